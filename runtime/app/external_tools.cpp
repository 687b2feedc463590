#include "app/external_tools.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace tumble::app {

namespace {

namespace fs = std::filesystem;

constexpr const char* kToolPrefix = "tumble-";

// The folder this binary was started from (/proc/self/exe on Linux).
fs::path ownFolder() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

bool isProgram(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && ::access(path.c_str(), X_OK) == 0;
}

}  // namespace

std::vector<std::string> externalTools() {
  std::vector<std::string> names;
  const fs::path dir = ownFolder();
  std::error_code ec;
  if (dir.empty()) return names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::string file = entry.path().filename().string();
    if (file.rfind(kToolPrefix, 0) == 0 && file.size() > std::strlen(kToolPrefix) && isProgram(entry.path()))
      names.push_back(file.substr(std::strlen(kToolPrefix)));
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::optional<int> runExternalTool(int argc, char** argv, const std::vector<std::string>& builtins) {
  if (argc < 2 || argv[1][0] == '-' || argv[1][0] == '\0') return std::nullopt;
  const std::string name = argv[1];
  if (std::find(builtins.begin(), builtins.end(), name) != builtins.end()) return std::nullopt;
  // A name with a slash or a dot could point outside the folder.
  if (name.find_first_of("/.") != std::string::npos) return std::nullopt;
  const fs::path tool = ownFolder() / (kToolPrefix + name);
  if (!isProgram(tool)) return std::nullopt;
  std::vector<char*> args;
  std::string program = tool.string();
  args.push_back(program.data());
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  std::fflush(stdout);
  ::execv(program.c_str(), args.data());
  std::fprintf(stderr, "tumble: cannot run %s: %s\n", program.c_str(), std::strerror(errno));
  return 1;
}

}  // namespace tumble::app
