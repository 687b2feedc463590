// core: Result, atomic file writes, the state hasher, math helpers.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

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

TEST(FileUtil, ReadsOnlyRegularFilesUpToTheirLimit) {
  auto dir = tempDir("special");
  const std::string fifo = (dir / "pipe").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // A FIFO would block until a writer came; /dev/zero would never end.
  for (const std::string& path : {fifo, std::string("/dev/zero"), dir.string()}) {
    auto r = readTextFile(path);
    ASSERT_FALSE(r.ok()) << path;
    EXPECT_NE(r.error().find("not a regular file"), std::string::npos) << r.error();
    EXPECT_EQ(r.error().rfind(path, 0), 0u) << "the message starts with the file: " << r.error();
  }
  const std::string big = (dir / "big.txt").string();
  std::ofstream(big) << std::string(1000, 'x');
  EXPECT_TRUE(readTextFile(big, 1000).ok());
  auto tooBig = readTextFile(big, 999);
  ASSERT_FALSE(tooBig.ok());
  EXPECT_NE(tooBig.error().find("larger than the 999 bytes"), std::string::npos) << tooBig.error();
}

TEST(FileUtil, OrphanedTemporariesOfDeadWritersAreRemoved) {
  auto dir = tempDir("orphans");
  std::filesystem::create_directories(dir / "mod");
  // A writer killed mid-write leaves "<name>.tmp<pid>"; pid 2^22 + 1 is above
  // Linux's largest pid, so no process has it.
  const std::string dead = "save.json.tmp4194305";
  const std::string alive = "save.json.tmp" + std::to_string(::getpid());
  for (const std::string& name : {dead, alive, std::string("notes.tmp"), std::string("keep.json")})
    std::ofstream(dir / "mod" / name) << "x";
  EXPECT_EQ(removeOrphanedTemporaries(dir.string(), 0), 0u) << "depth 0 does not enter folders";
  EXPECT_EQ(removeOrphanedTemporaries(dir.string(), 1), 1u);
  EXPECT_FALSE(std::filesystem::exists(dir / "mod" / dead));
  EXPECT_TRUE(std::filesystem::exists(dir / "mod" / alive)) << "a running writer keeps its file";
  EXPECT_TRUE(std::filesystem::exists(dir / "mod" / "notes.tmp"));
  EXPECT_TRUE(std::filesystem::exists(dir / "mod" / "keep.json"));
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
