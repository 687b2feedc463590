// tumble sweep's spec, checks and job bookkeeping, in process: what a spec
// expands to, the messages bad specs get before anything runs, resume and
// failures kept with their logs, and the Pareto front the summary draws.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tools/sweep/sweep_collect.h"
#include "tools/sweep/sweep_run.h"
#include "tools/sweep/sweep_spec.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace tumble::tools::sweep {
namespace {

const std::string kMods = std::string(TUMBLE_SWEEP_TEST_DIR) + "/mods";

fs::path tempDir(const std::string& name) {
  fs::path dir = fs::path(TUMBLE_SWEEP_TEST_OUT) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

json dropSpec() {
  return json{{"scenarios", {"sweeptest:drop"}},
              {"mods", {kMods}},
              {"grid", {{"height", {1, 3}}}},
              {"seeds", {1, 2, 3}},
              {"integrators", {"symplectic_euler", "rk4"}}};
}

Result<SweepSpec> fromJson(const json& j) { return specFromJson(j, "spec.json", "/"); }

std::string problems(const json& j, bool force = false) {
  auto spec = fromJson(j);
  if (!spec) return spec.error();
  auto st = validateSpec(*spec, force);
  return st ? std::string() : st.error();
}

}  // namespace

TEST(SweepSpec, AGridExpandsToItsCrossProductOneTumbleRunEach) {
  auto spec = fromJson(dropSpec());
  ASSERT_TRUE(spec) << spec.error();
  ASSERT_TRUE(validateSpec(*spec, false)) << validateSpec(*spec, false).error();
  const auto jobs = expandJobs(*spec);
  ASSERT_EQ(jobs.size(), 2u * 3u * 2u);
  EXPECT_EQ(jobCount(*spec), jobs.size());
  // The seed varies fastest, then the integrator, then the grid.
  EXPECT_EQ(jobs[0].seed, 1u);
  EXPECT_EQ(jobs[1].seed, 2u);
  EXPECT_EQ(jobs[3].integrator, "rk4");
  EXPECT_EQ(jobs[6].values[0].text, "3");
  const std::vector<std::string> expected = {"tumble", "run", "sweeptest:drop", "--seed", "1", "--integrator",
                                             "symplectic_euler", "--set", "height=1", "--mods", kMods,
                                             "--report", "runs/000000/report.json"};
  EXPECT_EQ(jobs[0].argv, expected);
  EXPECT_EQ(sweptKeys(*spec), (std::vector<std::string>{"height", "seed", "integrator"}));
}

TEST(SweepSpec, ALuaSpecReadsInTheSandboxAndMeansWhatTheSameJsonMeans) {
  const fs::path dir = tempDir("lua_spec");
  std::ofstream(dir / "drops.lua") << "local heights = {}\n"
                                      "for h = 1, 3, 2 do heights[#heights + 1] = h end\n"
                                      "return {scenarios = {'sweeptest:drop'}, mods = {'" + kMods + "'},\n"
                                      "  grid = {height = heights}, seeds = {1, 2, 3},\n"
                                      "  integrators = {'symplectic_euler', 'rk4'}}\n";
  auto lua = readSpec((dir / "drops.lua").string());
  ASSERT_TRUE(lua) << lua.error();
  auto js = fromJson(dropSpec());
  const auto a = expandJobs(*lua), b = expandJobs(*js);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].argv, b[i].argv);
  EXPECT_EQ(lua->name, "drops");

  std::ofstream(dir / "escape.lua") << "os.execute('touch /tmp/owned')\nreturn {}\n";
  auto escape = readSpec((dir / "escape.lua").string());
  ASSERT_FALSE(escape);
  EXPECT_NE(escape.error().find("escape.lua"), std::string::npos) << escape.error();
  EXPECT_NE(escape.error().find("os.execute"), std::string::npos) << escape.error();

  std::ofstream(dir / "broken.json") << "{\"scenarios\": [\"base:drop\"],}";
  auto broken = readSpec((dir / "broken.json").string());
  ASSERT_FALSE(broken);
  EXPECT_NE(broken.error().find("broken.json: not valid JSON"), std::string::npos) << broken.error();
}

TEST(SweepSpec, AnUnknownParameterIsNamedWithTheOnesTheScenarioDeclares) {
  json j = dropSpec();
  j["grid"] = {{"heigth", {1, 2}}};
  const std::string p = problems(j);
  EXPECT_NE(p.find("spec.json: --set heigth=1: sweeptest:drop has no parameter 'heigth' (its parameters: explode, height"),
            std::string::npos)
      << p;
  j["grid"] = {{"height", {1, "tall"}}};
  EXPECT_NE(problems(j).find("'height' is a number in m"), std::string::npos) << problems(j);
  j["grid"] = {{"physics.iterations", {0}}};
  EXPECT_NE(problems(j).find("iterations must be 1..1000"), std::string::npos) << problems(j);
  j["grid"] = {{"tune.wind", {1, 2}}};
  EXPECT_NE(problems(j).find("a tunable is declared while the scenario runs"), std::string::npos) << problems(j);
  // terrain.* settings are checked as a run checks them, for any scenario.
  j["grid"] = {{"terrain.generate", {1, 2}}, {"terrain.size", {65, 129}}, {"terrain.style", {"hills", "island"}}};
  EXPECT_EQ(problems(j), "");
  j["grid"] = {{"terrain.size", {65, 1}}};
  EXPECT_NE(problems(j).find("--set terrain.size=1: expected a number in ["), std::string::npos) << problems(j);
  j["grid"] = {{"terrain.styl", {"hills"}}};
  EXPECT_NE(problems(j).find("--set terrain.styl: unknown terrain setting"), std::string::npos) << problems(j);
  j["grid"] = {{"terrain.style", {"dunes"}}};
  EXPECT_NE(problems(j).find("terrain.style=dunes: expected hills or island"), std::string::npos) << problems(j);
  // base:drop declares no parameters: nothing can be checked, so it is refused.
  j["scenarios"] = {"base:pyramid"};
  j["grid"] = {{"base", {3, 4}}};
  EXPECT_NE(problems(j).find("base:pyramid declares no parameters"), std::string::npos) << problems(j);
  j = dropSpec();
  j["integrators"] = {"rk5"};
  EXPECT_NE(problems(j).find("field 'integrators'"), std::string::npos) << problems(j);
  j = dropSpec();
  j["scenarios"] = {"sweeptest:nope"};
  EXPECT_NE(problems(j).find("no such scenario"), std::string::npos) << problems(j);
  j = dropSpec();
  j["collect"] = {"error.energy"};
  EXPECT_NE(problems(j).find("'error.energy' is not a number the run report has"), std::string::npos) << problems(j);
  j = dropSpec();
  j["grdi"] = json::object();
  EXPECT_NE(problems(j).find("field 'grdi' is not a spec field"), std::string::npos) << problems(j);
}

TEST(SweepSpec, AnEmptyGridIsRefused) {
  json j = dropSpec();
  j["grid"] = json::object();
  EXPECT_NE(problems(j).find("field 'grid' is empty"), std::string::npos) << problems(j);
  j["grid"] = {{"height", json::array()}};
  EXPECT_NE(problems(j).find("field 'grid.height' is an empty list"), std::string::npos) << problems(j);
  j = dropSpec();
  j["seeds"] = json::array();
  EXPECT_NE(problems(j).find("field 'seeds' is empty"), std::string::npos) << problems(j);
  j = dropSpec();
  j["scenarios"] = json::array();
  EXPECT_NE(problems(j).find("field 'scenarios' is empty"), std::string::npos) << problems(j);
}

TEST(SweepSpec, ASweepAboveTheLimitNeedsForce) {
  json j = dropSpec();
  j["grid"] = {{"height", {1, 2}}};
  j["integrators"] = {"rk4"};
  j["seeds"] = int(kMaxJobsWithoutForce / 2) + 1;  // 2 x 5001 = 10 002 jobs
  const std::string p = problems(j);
  EXPECT_NE(p.find("the sweep has 10002 jobs, more than 10000; check the grid, or pass --force"), std::string::npos) << p;
  EXPECT_EQ(problems(j, true), "");
  j["seeds"] = int(kMaxJobsWithoutForce / 2);  // exactly the limit
  EXPECT_EQ(problems(j), "");
}

TEST(SweepSpec, ARandomDesignIsReproducibleAndInsideItsRanges) {
  json j = dropSpec();
  j.erase("grid");
  j["random"] = {{"samples", 50}, {"seed", 7}, {"ranges", {{"height", {0.5, 4.5}}}}};
  auto spec = fromJson(j);
  ASSERT_TRUE(spec) << spec.error();
  ASSERT_TRUE(validateSpec(*spec, false));
  const auto a = expandJobs(*spec), b = expandJobs(*spec);
  ASSERT_EQ(a.size(), 50u * 3u * 2u);
  double lo = 10, hi = -10;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].argv, b[i].argv);
    const double h = std::stod(a[i].values[0].text);
    lo = std::min(lo, h), hi = std::max(hi, h);
  }
  EXPECT_GE(lo, 0.5);
  EXPECT_LT(hi, 4.5);
  EXPECT_LT(lo, 1.0);  // 50 uniform draws cover the range
  EXPECT_GT(hi, 4.0);
}

TEST(SweepRun, AFailedRunKeepsItsLogAndReasonAndAFinishedOneIsSkipped) {
  const fs::path dir = tempDir("exec");
  auto spec = fromJson(dropSpec());
  ASSERT_TRUE(writeSweepFolder(*spec, expandJobs(*spec), dir.string(), WriteOptions{}));
  auto sweep = readSweepFolder(dir.string());
  ASSERT_TRUE(sweep) << sweep.error();
  // A "tumble" that cannot run the scenario: exit 1, no report.
  EXPECT_FALSE(execJob(*sweep, 0, "/bin/false"));
  EXPECT_FALSE(jobFinished(*sweep, 0));
  std::ifstream statusFile(dir / "runs/000000/status.json");
  json status = json::parse(statusFile);
  EXPECT_EQ(status["exit"], 1);
  EXPECT_NE(status["reason"].get<std::string>().find("exit 1 without a report"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "runs/000000/log.txt"));
  auto rows = gatherRows(*sweep);
  EXPECT_EQ(rows[0].status, "failed");
  EXPECT_EQ(rows[1].status, "not_run");
  // A report present means finished: exec does not run it again.
  std::ofstream(dir / "runs/000000/report.json") << R"({"state_hash": "0123456789abcdef", "expectations": [], "script_errors": []})";
  EXPECT_TRUE(execJob(*sweep, 0, "/bin/false"));
  EXPECT_EQ(gatherRows(*sweep)[0].status, "passed");
  // The folder of another sweep is not overwritten.
  json other = dropSpec();
  other["seeds"] = {9};
  auto otherSpec = fromJson(other);
  auto st = writeSweepFolder(*otherSpec, expandJobs(*otherSpec), dir.string(), WriteOptions{});
  ASSERT_FALSE(st);
  EXPECT_NE(st.error().find("holds another sweep"), std::string::npos) << st.error();
  // Chunks for Slurm array tasks cover every job once.
  sweep->chunkSize = 5;
  std::size_t covered = 0;
  for (std::size_t c = 0; chunkRange(*sweep, c).first < sweep->jobs.size(); ++c) {
    auto [b, e] = chunkRange(*sweep, c);
    EXPECT_EQ(b, covered);
    covered = e;
  }
  EXPECT_EQ(covered, sweep->jobs.size());
}

TEST(SweepCollect, TheParetoFrontKeepsTheRunsNoOtherBeatsOnTimeAndError) {
  // (time, error): (1, 5) (2, 3) (3, 4) (4, 1) (5, 1) and one without error.
  std::vector<std::optional<double>> t = {3, 1, 2, 4, 5, 0.5}, e = {4, 5, 3, 1, 1, std::nullopt};
  EXPECT_EQ(paretoFront(t, e), (std::vector<std::size_t>{1, 2, 3}));
}

}  // namespace tumble::tools::sweep
