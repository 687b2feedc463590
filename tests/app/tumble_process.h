#pragma once
// Runs build/bin/tumble as a user would and captures what it prints.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace tumble::test {

struct ProcessResult {
  int exitCode = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs a shell command and captures its stdout and stderr together.
inline ProcessResult runCommand(const std::string& command) {
  const std::string cmd = "(" + command + ") 2>&1";
  ProcessResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  int status = pclose(p);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// envPrefix is put before the command, e.g. "env -u DISPLAY ".
inline ProcessResult runTumble(const std::string& args, const std::string& envPrefix = "") {
  return runCommand(envPrefix + std::string(TUMBLE_BINARY) + " " + args);
}

inline std::string testMods() { return std::string("--mods ") + TUMBLE_TEST_MODS; }

/// A fresh output folder per test.
inline std::string outDir(const std::string& name) {
  std::filesystem::path dir = std::filesystem::path(TUMBLE_TEST_OUT) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

/// An environment prefix for runTumble that puts the player's folders in
/// `dir`: home (the user's mods, ~/.local/share/tumble/mods), config
/// (settings, bindings), data (saves) and cache (thumbnails). A test then
/// never reads or changes the real player's settings, mods, saves or
/// thumbnails.
inline std::string isolated(const std::string& dir) {
  return "env HOME=" + dir + "/home TUMBLE_CONFIG_DIR=" + dir + "/config XDG_DATA_HOME=" + dir +
         "/data TUMBLE_CACHE_DIR=" + dir + "/cache ";
}

}  // namespace tumble::test
