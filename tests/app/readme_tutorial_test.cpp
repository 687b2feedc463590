// The README's tutorial ("Your first mod in ten minutes") as a user follows
// it: the mod files and the commands are read from README.md itself, so the
// README cannot drift from what the program does. The shell blocks run with
// bash in a fresh folder whose tools/tumble runs this build's binary with
// --mods pointing at the folder's mods/. Each command must exit as its
// comment says (`# exits 2: ...`; 0 without one); a block followed by
// "prints `...`" must print that line (the wall time aside); the report
// excerpt (a ``` block after a --report command) must match the report.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tumble_process.h"

namespace tumble::test {
namespace {

namespace fs = std::filesystem;

struct Block {
  std::string language;  ///< after the opening ```: "sh", "lua", "" ...
  std::string text;      ///< the lines inside, each ending in '\n'
  std::string after;     ///< the prose up to the next block
};

std::string readme() {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  std::ifstream in(fs::path(source ? source : ".") / "README.md");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The section's text, from its "## " heading to the next one.
std::string section(const std::string& doc, const std::string& heading) {
  const std::size_t start = doc.find("\n## " + heading + "\n");
  if (start == std::string::npos) return "";
  const std::size_t end = doc.find("\n## ", start + 1);
  return doc.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

std::vector<Block> fencedBlocks(const std::string& text) {
  std::vector<Block> blocks;
  std::istringstream in(text);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      if (!inside) blocks.push_back({line.substr(3), "", ""});
      inside = !inside;
    } else if (inside) {
      blocks.back().text += line + "\n";
    } else if (!blocks.empty()) {
      blocks.back().after += line + "\n";
    }
  }
  return blocks;
}

std::string collapseSpaces(const std::string& s) { return std::regex_replace(s, std::regex("\\s+"), " "); }

// "in 0.03 s;" -> "in # s;": the wall time differs between runs.
std::string withoutWallTime(const std::string& s) {
  return std::regex_replace(s, std::regex("in [0-9]+\\.[0-9]+ s;"), "in # s;");
}

int expectedExit(const std::string& command) {
  std::smatch m;
  if (std::regex_search(command, m, std::regex("#\\s*exits ([0-9]+)"))) return std::stoi(m[1]);
  return 0;
}

ProcessResult runIn(const fs::path& dir, const std::string& script) {
  const fs::path file = dir / "step.sh";
  std::ofstream(file) << script;
  return runCommand("cd '" + dir.string() + "' && bash -e '" + file.string() + "'");
}

// An excerpt value matches the report's: equal, or, where the README shows
// "9.61...", a number whose decimals begin so.
void expectExcerptMatches(const nlohmann::json& shown, const nlohmann::json& actual, const std::string& where) {
  if (shown.is_string() && shown.get<std::string>().rfind("~", 0) == 0) {
    ASSERT_TRUE(actual.is_number()) << where << ": " << actual.dump();
    const std::string prefix = shown.get<std::string>().substr(1);
    const int decimals = int(prefix.size() - prefix.find('.') - 1);
    char printed[64];
    std::snprintf(printed, sizeof printed, "%.*f", decimals + 3, actual.get<double>());
    EXPECT_EQ(std::string(printed).substr(0, prefix.size()), prefix) << where << ": the README shows " << prefix
                                                                     << "..., the report has " << actual.dump();
  } else if (shown.is_object()) {
    for (const auto& [key, value] : shown.items()) {
      ASSERT_TRUE(actual.is_object() && actual.contains(key)) << where << "." << key << " is not in the report";
      expectExcerptMatches(value, actual[key], where + "." + key);
    }
  } else if (shown.is_array()) {
    ASSERT_TRUE(actual.is_array() && actual.size() == shown.size()) << where << ": " << actual.dump();
    for (std::size_t i = 0; i < shown.size(); ++i)
      expectExcerptMatches(shown[i], actual[i], where + "[" + std::to_string(i) + "]");
  } else {
    EXPECT_EQ(shown, actual) << where;
  }
}

TEST(ReadmeTutorial, TheTowerModRunsAsTheReadmeSays) {
  const std::string text = section(readme(), "Your first mod in ten minutes");
  ASSERT_FALSE(text.empty()) << "README.md has no section \"Your first mod in ten minutes\"";
  const std::vector<Block> blocks = fencedBlocks(text);

  const fs::path dir = outDir("readme_tutorial");
  fs::create_directories(dir / "tools");
  const fs::path shim = dir / "tools/tumble";
  std::ofstream(shim) << "#!/bin/sh\nexec '" << TUMBLE_BINARY << "' --mods '" << (dir / "mods").string()
                      << "' \"$@\"\n";
  fs::permissions(shim, fs::perms::owner_all);

  int files = 0, commands = 0, printedLines = 0, excerpts = 0;
  std::string lastReport;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Block& block = blocks[b];
    if (block.language == "sh" && block.text.find("<<'EOF'") != std::string::npos) {
      // Writes the mod's files.
      const ProcessResult r = runIn(dir, block.text);
      ASSERT_EQ(r.exitCode, 0) << block.text << r.output;
      ++files;
      continue;
    }
    if (block.language == "sh") {
      std::istringstream lines(block.text);
      std::string command;
      ProcessResult last;
      while (std::getline(lines, command)) {
        if (command.empty() || command[0] == '#') continue;
        // play opens a window (or runs offscreen for seconds); the
        // tutorial's headless steps are what can be checked here.
        if (command.rfind("tools/tumble play", 0) == 0) continue;
        last = runIn(dir, command + "\n");
        EXPECT_EQ(last.exitCode, expectedExit(command)) << command << "\n" << last.output;
        ++commands;
        std::smatch m;
        if (std::regex_search(command, m, std::regex("--report ([^ ]+)"))) lastReport = m[1];
      }
      // "prints `LINE`" right after the block: the command's output line.
      std::smatch m;
      const std::string after = collapseSpaces(block.after);
      if (std::regex_search(after, m, std::regex("^ ?prints `([^`]*)`"))) {
        const std::string shown = withoutWallTime(m[1].str());
        EXPECT_NE(withoutWallTime(last.output).find(shown), std::string::npos)
            << "the README says the command prints\n  " << m[1].str() << "\nit printed\n  " << last.output;
        ++printedLines;
      }
      continue;
    }
    if (block.language.empty() && !lastReport.empty()) {
      // A report excerpt: lines of "key": value, (numbers shown as 9.61...).
      std::ifstream in(dir / lastReport);
      ASSERT_TRUE(in) << lastReport << " was not written";
      const nlohmann::json report = nlohmann::json::parse(in);
      std::string body = block.text;
      while (!body.empty() && (body.back() == '\n' || body.back() == ',')) body.pop_back();
      body = std::regex_replace(body, std::regex("([0-9]+\\.[0-9]+)\\.\\.\\."), "\"~$1\"");
      const nlohmann::json shown = nlohmann::json::parse("{" + body + "}", nullptr, false);
      ASSERT_FALSE(shown.is_discarded()) << "the report excerpt in the README is not JSON lines:\n" << block.text;
      expectExcerptMatches(shown, report, lastReport);
      ++excerpts;
      lastReport.clear();
    }
  }
  // The tutorial as written today: mod.lua and tower.lua, then check, run,
  // run at wind 10 and 20, run with a report; one printed line, one excerpt.
  EXPECT_EQ(files, 2);
  EXPECT_EQ(commands, 5);
  EXPECT_EQ(printedLines, 1);
  EXPECT_EQ(excerpts, 1);
}

}  // namespace
}  // namespace tumble::test
