// `tumble terrain ...` (tools/terrain) end to end, in process: generate -> filter -> info.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "tools/terrain/terrain_commands.h"
#include "core/file_util.h"
#include "terrain/height_map.h"
#include "terrain/terrain.h"
#include "test_util.h"

using namespace tumble;
using namespace tumble::terrain;
using namespace tumble::terrain::test;

namespace {

struct CliRun {
  int exitCode = 0;
  std::string out, err;
};

// Parses `tumble terrain ...` as the tool's main() would, with the leading
// "terrain" as a subcommand: a parse error exits 2 (CLI11's convention is non-zero).
CliRun runCli(std::vector<std::string> args) {
  CLI::App app{"test"};
  app.require_subcommand(1);
  CliRun run;
  tools::addTerrainCommands(*app.add_subcommand("terrain", "height maps"), run.exitCode);
  args.insert(args.begin(), "tumble");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    run.exitCode = e.get_exit_code() == 0 ? 0 : 2;
  }
  std::cout.flush();
  std::fflush(stdout);
  run.out = testing::internal::GetCapturedStdout();
  run.err = testing::internal::GetCapturedStderr();
  return run;
}

std::string bytesOf(const std::string& path) { return *readTextFile(path); }

}  // namespace

TEST(TerrainCli, GenIsDeterministicAndInfoReportsRuntimeMemory) {
  const std::string a = tempFile("cli_a.png"), b = tempFile("cli_b.png"), c = tempFile("cli_c.png");
  ASSERT_EQ(runCli({"terrain", "gen", "--size", "257", "--seed", "42", "--out", a}).exitCode, 0);
  ASSERT_EQ(runCli({"terrain", "gen", "--size", "257", "--seed", "42", "--out", b}).exitCode, 0);
  ASSERT_EQ(runCli({"terrain", "gen", "--size", "257", "--seed", "43", "--roughness", "0.7", "--out", c}).exitCode, 0);
  EXPECT_EQ(bytesOf(a), bytesOf(b));
  EXPECT_NE(bytesOf(a), bytesOf(c));

  const CliRun info = runCli({"terrain", "info", a, "--json"});
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["width"], 257);
  EXPECT_EQ(j["height"], 257);
  EXPECT_EQ(j["bytes_heights"], 257 * 257 * 2);
  EXPECT_GT(j["bytes_tree"].get<double>(), 0);
  EXPECT_LE(j["bytes_per_sample"].get<double>(), 2.1);
  // Not the file size: that is a compressed PNG.
  EXPECT_NE(j["bytes_heights"].get<std::uintmax_t>(), std::filesystem::file_size(a));

  const CliRun human = runCli({"terrain", "info", a});
  EXPECT_EQ(human.exitCode, 0);
  EXPECT_NE(human.out.find("257 x 257"), std::string::npos) << human.out;
}

TEST(TerrainCli, NonSquareGenAndEveryFilterRoundTrips) {
  const std::string in = tempFile("cli_rect.png");
  ASSERT_EQ(runCli({"terrain", "gen", "--width", "130", "--height", "70", "--seed", "1", "--out", in}).exitCode, 0);
  auto map = loadHeightMapPng(in);
  ASSERT_TRUE(map.ok());
  EXPECT_EQ(map->width(), 130);
  EXPECT_EQ(map->height(), 70);

  // A sidecar on the input travels to the outputs; resample scales its spacing.
  ASSERT_TRUE(saveSidecar(in, {2.0, 0.005, 0, 0, 0}).ok());
  const std::string sm = tempFile("cli_smooth.png"), sh = tempFile("cli_sharp.png"), rs = tempFile("cli_rs.png"),
                    rg = tempFile("cli_ridge.png"), pv = tempFile("cli_preview.png"), bm = tempFile("cli_bump.png"),
                    cv = tempFile("cli_conv.png");
  EXPECT_EQ(runCli({"terrain", "smooth", in, "--out", sm, "--passes", "3"}).exitCode, 0);
  EXPECT_EQ(runCli({"terrain", "sharpen", in, "--out", sh}).exitCode, 0);
  EXPECT_EQ(runCli({"terrain", "convolve", in, "--kernel", "1,2,1,2,4,2,1,2,1", "--normalize", "--out", cv}).exitCode, 0);
  EXPECT_EQ(bytesOf(cv), bytesOf([&] {
              const std::string once = tempFile("cli_smooth1.png");
              runCli({"terrain", "smooth", in, "--out", once});
              return once;
            }()));
  EXPECT_EQ(runCli({"terrain", "resample", in, "--width", "259", "--height", "139", "--out", rs}).exitCode, 0);
  EXPECT_EQ(runCli({"terrain", "ridge", in, "--from", "20,20", "--to", "240,120", "--height", "30", "--width", "8",
                    "--out", rg}).exitCode, 0);
  EXPECT_EQ(runCli({"terrain", "ridge", rg, "--from", "20,120", "--to", "240,20", "--ditch", "--out", rg}).exitCode, 0);
  EXPECT_EQ(runCli({"terrain", "bump", in, "--region", "40,40,100,60", "--amplitude", "25", "--out", bm}).exitCode, 0);
  EXPECT_EQ(runCli({"terrain", "preview", rg, "--out", pv}).exitCode, 0);

  auto resampled = Terrain::loadPng(rs);
  ASSERT_TRUE(resampled.ok()) << resampled.error();
  EXPECT_EQ(resampled->heights().width(), 259);
  EXPECT_DOUBLE_EQ(resampled->desc().spacing_m, 1.0);  // 129 blocks * 2 m = 258 blocks * 1 m
  auto smoothed = Terrain::loadPng(sm);
  ASSERT_TRUE(smoothed.ok());
  EXPECT_DOUBLE_EQ(smoothed->desc().heightScale_m, 0.005);
  auto preview = readBinaryFile(pv);
  ASSERT_TRUE(preview.ok());
  EXPECT_GT(preview->size(), 1000u);
  // The preview is RGB, so as a height map it reads as luminance: still a valid image.
  EXPECT_TRUE(decodeHeightMapPng(*preview, pv).ok());
}

TEST(TerrainCli, ErrorsAreOneClearLineAndExitCodeOne) {
  const std::string junk = tempFile("cli_junk.png");
  ASSERT_TRUE(writeFileAtomic(junk, std::string("GIF89a not a png")).ok());
  CliRun r = runCli({"terrain", "info", junk});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("not a PNG file"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(junk), std::string::npos);

  r = runCli({"terrain", "smooth", tempFile("missing.png"), "--out", tempFile("x.png")});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("missing.png"), std::string::npos);

  r = runCli({"terrain", "gen", "--seed", "1", "--out", tempFile("nosize.png")});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;

  r = runCli({"terrain", "gen", "--size", "5000", "--seed", "1", "--out", tempFile("huge.png")});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("4097"), std::string::npos) << r.err;

  const std::string ok = tempFile("cli_ok.png");
  ASSERT_EQ(runCli({"terrain", "gen", "--size", "33", "--seed", "1", "--out", ok}).exitCode, 0);
  r = runCli({"terrain", "ridge", ok, "--from", "1;2", "--to", "3,4", "--out", ok});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--from"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(tempFile("nosize.png")));
}

TEST(TerrainCli, Info4097MapStaysUnder2Point1BytesPerSample) {
  const std::string big = tempFile("cli_4097.png");
  ASSERT_EQ(runCli({"terrain", "gen", "--size", "4097", "--seed", "5", "--out", big}).exitCode, 0);
  const CliRun info = runCli({"terrain", "info", big, "--json"});
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["width"], 4097);
  EXPECT_EQ(j["bytes_heights"], 4097LL * 4097LL * 2LL);
  EXPECT_LE(j["bytes_per_sample"].get<double>(), 2.1);
  std::cout << "[ info ] 4097^2: " << info.out;
}
