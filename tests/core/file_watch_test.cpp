// core/file_watch: a saved, new or deleted file is reported once, in path
// order; other files and unchanged ones are not.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "core/file_watch.h"

namespace tumble {

namespace {
namespace fs = std::filesystem;

fs::path watchDir(const char* name) {
  auto dir = fs::temp_directory_path() / ("tumble_watch_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// Editors may save twice within the clock's resolution; move the time on so
// the test does not depend on the file system's timestamp granularity.
void touchLater(const fs::path& p) { fs::last_write_time(p, fs::last_write_time(p) + std::chrono::seconds(1)); }
}  // namespace

TEST(FileWatch, ReportsSavedAddedAndRemovedFilesInPathOrder) {
  fs::path dir = watchDir("changes");
  write(dir / "mod.lua", "return {}");
  write(dir / "scenarios/a.lua", "return {}");
  write(dir / "assets/map.png", "not lua");
  FileWatch watch({dir.string()}, {".lua"});
  EXPECT_EQ(watch.fileCount(), 2u);
  EXPECT_TRUE(watch.poll().empty()) << "the state at construction is the baseline";

  write(dir / "scenarios/a.lua", "return {title = 'new'}");
  touchLater(dir / "scenarios/a.lua");
  write(dir / "scenarios/b.lua", "return {}");
  write(dir / "assets/map.png", "changed, but not watched");
  fs::remove(dir / "mod.lua");
  auto changes = watch.poll();
  ASSERT_EQ(changes.size(), 3u);
  EXPECT_EQ(changes[0].path, (dir / "mod.lua").lexically_normal().string());
  EXPECT_EQ(changes[0].kind, FileChange::Kind::Removed);
  EXPECT_EQ(changes[1].path, (dir / "scenarios/a.lua").lexically_normal().string());
  EXPECT_EQ(changes[1].kind, FileChange::Kind::Modified);
  EXPECT_EQ(changes[2].path, (dir / "scenarios/b.lua").lexically_normal().string());
  EXPECT_EQ(changes[2].kind, FileChange::Kind::Added);
  EXPECT_TRUE(watch.poll().empty()) << "each change is reported once";
}

TEST(FileWatch, SeesASaveThatKeepsTheTimeButChangesTheSize) {
  fs::path dir = watchDir("size");
  write(dir / "a.lua", "x = 1");
  auto t = fs::last_write_time(dir / "a.lua");
  FileWatch watch({dir.string()}, {".lua"});
  write(dir / "a.lua", "x = 100");
  fs::last_write_time(dir / "a.lua", t);
  ASSERT_EQ(watch.poll().size(), 1u);
}

TEST(FileWatch, AMissingRootIsWatchedForFilesThatAppear) {
  fs::path dir = watchDir("missing");
  FileWatch watch({(dir / "later").string()}, {});
  EXPECT_EQ(watch.fileCount(), 0u);
  write(dir / "later/bindings.lua", "return {}");
  auto changes = watch.poll();
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].kind, FileChange::Kind::Added);
}

TEST(FileWatch, PollIfDueScansAtMostOncePerPeriod) {
  fs::path dir = watchDir("period");
  write(dir / "a.lua", "x = 1");
  FileWatch watch({dir.string()}, {".lua"}, 0.25);
  EXPECT_TRUE(watch.pollIfDue(10.0).empty());  // first call scans: nothing changed yet
  write(dir / "a.lua", "x = 22");
  touchLater(dir / "a.lua");
  EXPECT_TRUE(watch.pollIfDue(10.1).empty()) << "0.1 s after the last scan: not due";
  EXPECT_EQ(watch.pollIfDue(10.25).size(), 1u) << "a quarter second later the save is seen";
}

}  // namespace tumble
