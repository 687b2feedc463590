// core: Result, atomic file writes, the state hasher, math helpers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/file_util.h"
#include "core/hash.h"
#include "core/math.h"
#include "core/result.h"

namespace tumble {

namespace {
std::filesystem::path tempDir(const char* name) {
  auto dir = std::filesystem::temp_directory_path() / ("tumble_core_test_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}
}  // namespace

TEST(Result, HoldsAValueOrAMessage) {
  Result<int> good = 3;
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(*good, 3);
  Result<int> bad = makeError("height.png: not a PNG file");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "height.png: not a PNG file");
}

TEST(FileUtil, AtomicWriteReplacesTheWholeFileAndLeavesNoTemporary) {
  auto dir = tempDir("atomic");
  std::string path = (dir / "save.json").string();
  ASSERT_TRUE(writeFileAtomic(path, std::string("first version, longer than the second")).ok());
  ASSERT_TRUE(writeFileAtomic(path, std::string("second")).ok());
  EXPECT_EQ(*readTextFile(path), "second");
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1) << "no temporary file is left behind";
}

TEST(FileUtil, FailuresNameTheFileAndKeepTheOldContents) {
  auto dir = tempDir("failures");
  auto missing = readTextFile((dir / "nope.txt").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().find("nope.txt"), std::string::npos);
  auto st = writeFileAtomic((dir / "no/such/dir/out.txt").string(), std::string("x"));
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().find("out.txt"), std::string::npos);
  // A failed replacement (target is a directory) keeps what was there.
  std::filesystem::create_directories(dir / "target");
  EXPECT_FALSE(writeFileAtomic((dir / "target").string(), std::string("x")).ok());
  EXPECT_TRUE(std::filesystem::is_directory(dir / "target"));
}

TEST(Hasher, AnyBitChangesTheDigest) {
  Hasher a, b, c;
  float x = 1.0f, y = std::nextafter(1.0f, 2.0f);
  a.value(x);
  b.value(x);
  c.value(y);
  EXPECT_EQ(a.digest(), b.digest());
  EXPECT_NE(a.digest(), c.digest());
  EXPECT_EQ(a.hex().size(), 16u);
}

TEST(Math, SkewIsTheCrossProductMatrix) {
  Vec3 a(1, -2, 3), b(4, 5, -6);
  EXPECT_TRUE((skew(a) * b - a.cross(b)).norm() < 1e-5);
}

}  // namespace tumble
