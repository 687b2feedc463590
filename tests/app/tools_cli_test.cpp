// Offline tools through the tumble binary (tools/README.md): `tumble TOOL
// ARGS...` runs tumble-TOOL beside it with ARGS, its output and exit status
// are the tool's, --help lists the tools, and a command that is neither a
// built-in nor a tool says what there is.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tumble_process.h"

namespace tumble::test {

TEST(ToolsCli, HelpListsTheToolsBesideTheBinary) {
  const ProcessResult r = runTumble("--help");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  for (const char* command : {"play", "run", "check", "list"})
    EXPECT_NE(r.output.find(command), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Tools (programs beside this one"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("meshgen, report, sweep, terrain"), std::string::npos) << r.output;
}

TEST(ToolsCli, AToolGetsTheRestOfTheCommandLineAndItsExitStatusIsTumbles) {
  const std::string dir = outDir("tools_cli");
  const std::string map = dir + "/m.png";
  ProcessResult r = runTumble("terrain gen --width 20 --height 12 --seed 4 --out " + map);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runTumble("terrain info " + map + " --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json info = nlohmann::json::parse(r.output);
  EXPECT_EQ(info["width"], 20);
  EXPECT_EQ(info["height"], 12);
  // The tool's own errors and usage errors come back as they are.
  r = runTumble("terrain info " + dir + "/missing.png");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("tumble terrain info: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing.png"), std::string::npos) << r.output;
  r = runTumble("report precision");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("--out"), std::string::npos) << "names the missing option: " << r.output;
  // A tool's help is its own, under the name users type.
  r = runTumble("meshgen --help");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("tumble meshgen"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
}

TEST(ToolsCli, MeshgenWritesTheRuntimesAndTheBaseModsFolders) {
  const std::string dir = outDir("tools_cli_meshgen");
  const ProcessResult r = runTumble("meshgen --out " + dir);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/assets/models/wheel.obj")) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/assets/models/tyre.png")) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/mods/base/assets/models/hatchback.obj")) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/mods/base/assets/models/wheel.obj")) << r.output;
}

TEST(ToolsCli, AnUnknownCommandNamesTheCommandsAndTools) {
  const ProcessResult r = runTumble("nosuchcommand --x");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("'nosuchcommand' is not a command"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("play, design, run, check, list"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("meshgen, report, sweep, terrain"), std::string::npos) << r.output;
  // A path is never taken for a tool name.
  EXPECT_EQ(runTumble("../bin/tumble --help").exitCode, 1);
}

}  // namespace tumble::test
