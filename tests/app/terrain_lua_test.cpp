// A scenario shapes its own terrain in Lua (terrain.build(map)
// item 2): the heights it sets are where physics finds the ground, the
// generators are deterministic, a command-line map replaces the built one,
// and mistakes give clear messages naming the file and line.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tumble_process.h"

namespace tumble::test {
namespace {

/// A mod "lt" in `dir` with one scenario file; returns the --mods argument.
std::string writeMod(const std::string& dir, const std::string& scenario) {
  std::filesystem::create_directories(dir + "/lt/scenarios");
  std::ofstream(dir + "/lt/mod.lua") << "return {name = \"lt\", version = \"1.0.0\", title = \"terrain in Lua\", api = 1}\n";
  std::ofstream(dir + "/lt/scenarios/t.lua") << scenario;
  return "--mods " + dir;
}

// Ground height under (x, z) from a ray cast, in the scenario.
const char* kGround = R"(
local function ground(x, z)
  for _, hit in ipairs(world.raycast_all({x, 1000, z}, {0, -1, 0}, 3000)) do
    if not hit.body:is_valid() then return hit.point.y end
  end
end
)";

TEST(TerrainLua, HeightsSetInBuildAreWherePhysicsFindsTheGround) {
  const std::string dir = outDir("terrain_lua_heights");
  // 33 x 33 samples 2 m apart, 100 m of relief, centred: x, z in -32..32 m.
  // Flat at 0.25 (25 m), one 3 x 3 plateau at 0.75 (75 m) around sample (8, 24).
  const std::string mods = writeMod(dir, std::string(kGround) + R"(
return {
  terrain = {size = 33, spacing = 2, height = 100, build = function(map)
    expect("map is 33 samples wide", map:width() == 33 and map:height() == 33)
    map:fill(0.25)
    for i = 7, 9 do for j = 23, 25 do map:set(i, j, 0.75) end end
    expect("get reads what set wrote", math.abs(map:get(8, 24) - 0.75) < 1e-4)
  end},
  on_start = function()
    expect("flat ground at 25 m", ground(-20.5, -10.3), {min = 24.999, max = 25.001})
    -- sample (8, 24) is at x = -32 + 16 = -16, z = -32 + 48 = 16
    expect("plateau at 75 m", ground(-16.2, 15.9), {min = 74.999, max = 75.001})
  end,
}
)");
  auto r = runTumble(mods + " run lt:t --steps 1");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(TerrainLua, GeneratorsAreDeterministicAndTheSeedMatters) {
  const std::string dir = outDir("terrain_lua_seed");
  const std::string mods = writeMod(dir, std::string(kGround) + R"(
return {
  terrain = {size = 129, height = 40, build = function(map)
    map:plasma{seed = param("seed_a", 5), roughness = 0.6}
    map:ridge{from = {0.1, 0.2}, to = {0.9, 0.7}, height = 0.3, width = 0.05, seed = 2}
    map:bump{x = 0.2, z = 0.5, width = 0.3, depth = 0.3, amplitude = -0.2, seed = 3}
    map:sharpen(0.3)
    map:convolve{1, 2, 1, 2, 4, 2, 1, 2, 1}
    map:smooth(1)
  end},
  on_start = function()
    local sum = 0
    for k = 1, 20 do sum = sum + ground(-60 + 6 * k, 50 - 5 * k) end
    expect("ground sum", sum, {min = -1e9, max = 1e9})  -- the value is compared by the test
  end,
}
)");
  auto value = [&](const std::string& extra) {
    const std::string report = dir + "/r.json";
    auto r = runTumble(mods + " run lt:t --steps 1 --report " + report + extra);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    auto j = nlohmann::json::parse(std::ifstream(report));
    return j["expectations"][0]["value"].get<double>();
  };
  const double a = value(""), b = value(""), c = value(" --set seed_a=6");
  EXPECT_EQ(a, b) << "same seeds, same terrain";
  EXPECT_NE(a, c) << "another plasma seed, another terrain";
}

TEST(TerrainLua, CommandLineMapReplacesTheBuiltOne) {
  const std::string dir = outDir("terrain_lua_override");
  const std::string mods = writeMod(dir, std::string(kGround) + R"(
return {
  terrain = {size = 17, height = 100, build = function(map) map:fill(0.5) end},
  on_start = function() expect("ground", ground(1.3, 2.1), {min = -1e4, max = 1e4}) end,
}
)");
  const std::string report = dir + "/r.json";
  ASSERT_EQ(runTumble(mods + " run lt:t --steps 1 --report " + report).exitCode, 0);
  EXPECT_NEAR(nlohmann::json::parse(std::ifstream(report))["expectations"][0]["value"].get<double>(), 50, 1e-3);
  auto r = runTumble(mods + " run lt:t --steps 1 --set terrain.generate=4 --set terrain.size=65 --report " + report);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_GT(std::abs(nlohmann::json::parse(std::ifstream(report))["expectations"][0]["value"].get<double>() - 50), 1e-3);
}

TEST(TerrainLua, MistakesNameTheFileLineAndWhatIsExpected) {
  struct Case {
    const char* build;
    const char* expected;
  } cases[] = {
      {"map:ridge{from = {0.1}, to = {0.9, 0.9}}", "from must be {x, z}"},
      {"map:plasma{seed = 1, roughness = 3}", "roughness must be a number from"},
      {"map:set(40, 0, 0.5)", "i must be a whole number from 0 to 16"},
      {"map:import(\"../../secret.png\")", "leaves the mod's folder"},
      {"map:import(\"assets/none.png\")", "none.png"},
      {"map:smooth(0)", "passes must be a whole number"},
      {"error(\"my own mistake\")", "my own mistake"},
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string dir = outDir("terrain_lua_bad_" + std::to_string(n++));
    const std::string mods = writeMod(dir, std::string("return {\n  terrain = {size = 17, build = function(map)\n    ") +
                                               c.build + "\n  end},\n}\n");
    auto r = runTumble(mods + " run lt:t --steps 1");
    EXPECT_EQ(r.exitCode, 1) << c.build << "\n" << r.output;
    EXPECT_NE(r.output.find("scenarios/t.lua:3"), std::string::npos) << c.build << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.build << "\n" << r.output;
  }
  // Keeping the map for later is refused, not a dangling pointer.
  const std::string dir = outDir("terrain_lua_kept");
  const std::string mods = writeMod(dir, R"(
local kept
return {
  terrain = {size = 17, build = function(map) kept = map end},
  on_start = function() kept:fill(0.3) end,
}
)");
  auto r = runTumble(mods + " run lt:t --steps 1");
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("only be changed inside terrain.build"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace tumble::test
