// environment.set from a scenario changes the picture `run --screenshot`
// takes (night and storm against the default day), and bad fields are
// script errors that name the field.
#include <gtest/gtest.h>

#include "screenshot_stats.h"
#include "tumble_process.h"

namespace tumble::test {

TEST(EnvironmentCli, SettingNightAndStormDarkensTheSky) {
  const std::string dir = outDir("environment");
  auto day = runTumble(testMods() + " run good:sky --screenshot " + dir + "/day.png --width 160 --height 120");
  ASSERT_EQ(day.exitCode, 0) << day.output;
  auto night = runTumble(testMods() + " run good:night_sky --screenshot " + dir + "/night.png --width 160 --height 120");
  ASSERT_EQ(night.exitCode, 0) << night.output;
  const double dayMean = meanBrightness(dir + "/day.png"), nightMean = meanBrightness(dir + "/night.png");
  ASSERT_GT(dayMean, 0);
  ASSERT_GE(nightMean, 0);
  EXPECT_LT(nightMean, 0.35 * dayMean) << "night " << nightMean << " vs day " << dayMean;
}

TEST(EnvironmentCli, AMisspeltFieldIsAScriptErrorNamingIt) {
  auto r = runTumble(testMods() + " run good:bad_environment");
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("environment.set"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("weathr"), std::string::npos) << r.output;
}

}  // namespace tumble::test
