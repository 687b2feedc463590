// The tuning panel's wiring (app/tuning.h): the panel shows the tunables'
// live values, an edit in the panel changes the tunable at once, and Save
// writes an overrides file that the next session loads.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "app/tuning.h"

namespace tumble::app {

namespace {
script::Tunables sample() {
  script::Tunables t;
  script::Tunable g;
  g.name = "gravity";
  g.defaultValue = 9.81;
  g.min = 0;
  g.max = 20;
  g.unit = "m/s^2";
  EXPECT_TRUE(t.declare(g));
  script::Tunable mode;
  mode.name = "mode";
  mode.kind = script::Tunable::Kind::Choice;
  mode.choices = {"easy", "hard"};
  EXPECT_TRUE(t.declare(mode));
  return t;
}
}  // namespace

TEST(TuningWiring, PanelShowsLiveValuesAndEditsApplyAtOnce) {
  script::Tunables t = sample();
  render::TuningPanel panel;
  fillTuningPanel(t, panel);
  ASSERT_EQ(panel.items.size(), 2u);
  EXPECT_EQ(panel.items[0].name, "gravity");
  EXPECT_EQ(panel.items[0].unit, "m/s^2");
  EXPECT_DOUBLE_EQ(panel.items[0].value, 9.81);
  EXPECT_EQ(panel.items[0].max, 20);
  EXPECT_EQ(panel.items[1].kind, render::TuningItem::Kind::Choice);
  EXPECT_EQ(render::tuningValueText(panel.items[1]), "easy");

  // What the slider and the drop-down do during a frame:
  panel.items[0].value = 3.7;
  panel.items[0].edited = true;
  panel.items[1].value = 1;
  panel.items[1].edited = true;
  applyTuningPanel(panel, t, "mymod");
  EXPECT_DOUBLE_EQ(t[0].value(), 3.7);
  EXPECT_EQ(t[1].valueText(), "hard");
  EXPECT_FALSE(panel.items[0].edited) << "requests are consumed";
  fillTuningPanel(t, panel);
  EXPECT_TRUE(panel.items[0].userSet);

  panel.items[0].resetRequested = true;
  applyTuningPanel(panel, t, "mymod");
  EXPECT_DOUBLE_EQ(t[0].value(), 9.81);
  EXPECT_EQ(t[1].valueText(), "hard") << "reset is per item";
}

TEST(TuningWiring, SaveWritesTheOverridesTheNextSessionLoads) {
  auto dir = std::filesystem::temp_directory_path() / ("tumble_tuning_wiring_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  script::Tunables t = sample();
  render::TuningPanel panel;
  panel.overridesPath = (dir / "tune" / "mymod.json").string();
  fillTuningPanel(t, panel);
  panel.items[0].value = 12;
  panel.items[0].edited = true;
  panel.saveRequested = true;
  applyTuningPanel(panel, t, "mymod");
  EXPECT_EQ(panel.status, "saved to " + panel.overridesPath);

  script::Tunables next;
  ASSERT_TRUE(next.loadOverrides(panel.overridesPath));
  script::Tunables declared = sample();  // declarations in a fresh session...
  ASSERT_TRUE(next.declare(declared[0]));
  EXPECT_DOUBLE_EQ(next[0].value(), 12) << "...pick up the saved value";

  // A folder that cannot be created: the panel says why, nothing crashes.
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "file") << "x";
  panel.overridesPath = (dir / "file" / "tune" / "mymod.json").string();
  panel.saveRequested = true;
  applyTuningPanel(panel, t, "mymod");
  EXPECT_EQ(panel.status.rfind("not saved: ", 0), 0u) << panel.status;
  std::filesystem::remove_all(dir);
}

}  // namespace tumble::app
