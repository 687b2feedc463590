// The attack suite: every file in tests/attacks/ is one probe, a mod or a
// file made the way an attacker would make it (long strings, metamethods,
// runaway work, paths out of the mod, bad numbers, special files). Each probe
// runs build/bin/tumble as a user would, in a fresh folder, and must end
// with the exit status it names (below 128: never a signal), print the
// clear message it names, and write nothing outside its own mod's saves and
// the run's report.
//
// A probe file:
//
//   attack: what the probe tries, in a sentence
//   command: run probe:probe --steps 3        (default; {root} is the folder;
//                                              "tool terrain ..." runs a tool)
//   exit: 3                                   (required)
//   output: text the output must contain      (any number of these)
//   ---- scenarios/probe.lua                  (a file of the mod "probe" ...)
//   return {on_start = function() error(string.rep("x", 50000)) end}
//   ---- @config/bindings.json                (... or of the user's folders:
//   {"format": "tumble-bindings", ...}          @config, @saves, @root)
//
// A file's text may contain {{rep N TEXT}} (TEXT N times) and is otherwise
// taken as written; "@fifo" as the whole text makes a FIFO, "@symlink
// TARGET" a symbolic link, "@copy FILE" a copy of FILE of the source tree. Without a mod.lua section the mod gets a valid
// manifest.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tumble_process.h"

namespace fs = std::filesystem;

namespace {

struct ProbeFile {
  std::string path, text;
};

struct Probe {
  std::string name, attack, command = "run probe:probe --steps 3";
  int exitCode = -1;
  std::vector<std::string> outputs;
  std::vector<ProbeFile> files;
};

std::string expand(const std::string& text) {
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t open = text.find("{{rep ", pos);
    if (open == std::string::npos) break;
    const std::size_t close = text.find("}}", open);
    if (close == std::string::npos) break;
    out += text.substr(pos, open - pos);
    std::istringstream spec(text.substr(open + 6, close - open - 6));
    std::size_t n = 0;
    spec >> n;
    std::string piece;
    std::getline(spec, piece);
    if (!piece.empty() && piece[0] == ' ') piece.erase(0, 1);
    for (std::size_t i = 0; i < n; ++i) out += piece;
    pos = close + 2;
  }
  return out + text.substr(pos);
}

Probe readProbe(const fs::path& file) {
  Probe p;
  p.name = file.stem().string();
  std::ifstream in(file);
  std::string line;
  ProbeFile* current = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind("---- ", 0) == 0) {
      p.files.push_back({line.substr(5), ""});
      current = &p.files.back();
    } else if (current) {
      current->text += line + "\n";
    } else if (auto colon = line.find(": "); colon != std::string::npos) {
      const std::string key = line.substr(0, colon), value = line.substr(colon + 2);
      if (key == "attack") p.attack = value;
      else if (key == "command") p.command = value;
      else if (key == "exit") p.exitCode = std::stoi(value);
      else if (key == "output") p.outputs.push_back(value);
    }
  }
  return p;
}

std::vector<std::string> probeNames() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(TUMBLE_ATTACKS_DIR))
    if (e.path().extension() == ".probe") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::set<std::string> filesUnder(const fs::path& root) {
  std::set<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); it != fs::recursive_directory_iterator(); it.increment(ec))
    if (!it->is_directory(ec)) out.insert(fs::relative(it->path(), root).string());
  return out;
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) s.replace(p, from.size(), to);
  return s;
}

class AttackProbe : public ::testing::TestWithParam<std::string> {};

TEST_P(AttackProbe, EndsWithAClearMessageAndWritesNothingOutsideTheMod) {
  const Probe probe = readProbe(fs::path(TUMBLE_ATTACKS_DIR) / (GetParam() + ".probe"));
  ASSERT_FALSE(probe.attack.empty()) << probe.name << ": no 'attack:' line";
  ASSERT_GE(probe.exitCode, 0) << probe.name << ": no 'exit:' line";
  ASSERT_LT(probe.exitCode, 128) << probe.name << ": a probe expects a clean exit";
  const fs::path root = tumble::test::outDir("attacks/" + probe.name);
  const fs::path mod = root / "mods" / "probe";
  for (const char* d : {"mods/probe/scenarios", "config", "saves", "home", "xdg", "cwd", "out"})
    fs::create_directories(root / d);
  bool manifest = false;
  for (const ProbeFile& f : probe.files) {
    fs::path target;
    if (f.path.rfind("@config/", 0) == 0) target = root / "config" / f.path.substr(8);
    else if (f.path.rfind("@saves/", 0) == 0) target = root / "saves" / f.path.substr(7);
    else if (f.path.rfind("@root/", 0) == 0) target = root / f.path.substr(6);
    else target = mod / f.path, manifest = manifest || f.path == "mod.lua";
    fs::create_directories(target.parent_path());
    if (f.text == "@fifo\n") {
      ASSERT_EQ(::mkfifo(target.c_str(), 0600), 0) << target;
    } else if (f.text.rfind("@copy ", 0) == 0) {
      fs::copy_file(fs::path(TUMBLE_SOURCE_DIR) / f.text.substr(6, f.text.size() - 7), target);
    } else if (f.text.rfind("@symlink ", 0) == 0) {
      fs::create_symlink(f.text.substr(9, f.text.size() - 10), target);
    } else {
      std::ofstream(target, std::ios::binary) << expand(f.text);
    }
  }
  if (!manifest)
    std::ofstream(mod / "mod.lua") << "return {name = \"probe\", version = \"1.0.0\", title = \"Probe\", api = 1}\n";
  const std::set<std::string> before = filesUnder(root);
  const std::string env = "cd " + (root / "cwd").string() + " && env HOME=" + (root / "home").string() +
                          " TUMBLE_CONFIG_DIR=" + (root / "config").string() + " TUMBLE_SAVE_DIR=" +
                          (root / "saves").string() + " XDG_DATA_HOME=" + (root / "xdg").string() +
                          " XDG_CONFIG_HOME=" + (root / "config").string() + " timeout 120 ";
  std::string command = replaceAll(probe.command, "{root}", root.string());
  // `run` keeps saves in a throw-away folder unless told: the probes' saves
  // (and their hand-made save files) are in root/saves.
  if (command.rfind("run ", 0) == 0) command += " --save-dir " + (root / "saves").string();
  // "tool terrain ..." runs an offline tool (no --mods: tools take their own arguments).
  const bool tool = command.rfind("tool ", 0) == 0;
  const auto r = tumble::test::runTumble(tool ? command.substr(5) : "--mods " + (root / "mods").string() + " " + command, env);
  const std::string shown = r.output.size() > 3000 ? r.output.substr(0, 3000) + "..." : r.output;
  EXPECT_EQ(r.exitCode, probe.exitCode) << probe.name << " (" << probe.attack << ")\n" << shown;
  for (const std::string& text : probe.outputs)
    EXPECT_NE(r.output.find(text), std::string::npos) << probe.name << ": output lacks \"" << text << "\"\n" << shown;
  for (const std::string& file : filesUnder(root)) {
    if (before.count(file) || file.rfind("saves/probe/", 0) == 0 || file.rfind("out/", 0) == 0) continue;
    ADD_FAILURE() << probe.name << " wrote " << file << " outside its mod's saves";
  }
}

INSTANTIATE_TEST_SUITE_P(Attacks, AttackProbe, ::testing::ValuesIn(probeNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(AttackSuite, HasAtLeast150Probes) { EXPECT_GE(probeNames().size(), 150u); }

}  // namespace
