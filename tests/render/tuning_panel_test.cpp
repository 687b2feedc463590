// The tuning panel (F2): which widget each tunable gets, how values print
// and snap, and that the panel is really drawn (offscreen) when visible,
// without pressing any of its buttons.
#include <SDL.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/renderer.h"
#include "render_test_util.h"

namespace tumble::render {
namespace {

TuningItem number(double value, double min, double max, const char* unit = "", double step = 0) {
  TuningItem item;
  item.name = "gravity";
  item.kind = TuningItem::Kind::Number;
  item.value = value;
  item.min = min;
  item.max = max;
  item.unit = unit;
  item.step = step;
  return item;
}

TuningPanel samplePanel() {
  TuningPanel panel;
  panel.title = "mymod:tower";
  panel.items.push_back(number(9.81, 0, 20, "m/s^2"));
  panel.items.back().userSet = true;  // drawn in the "changed" colour
  TuningItem wind;
  wind.name = "wind";
  wind.kind = TuningItem::Kind::Bool;
  panel.items.push_back(wind);
  TuningItem mode;
  mode.name = "mode";
  mode.kind = TuningItem::Kind::Choice;
  mode.choices = {"easy", "hard"};
  mode.value = 1;
  panel.items.push_back(mode);
  return panel;
}

}  // namespace

TEST(TuningPanel, EachKindGetsItsWidget) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(tuningWidgetFor(number(1, 0, 2)), TuningWidget::Slider);
  EXPECT_EQ(tuningWidgetFor(number(1, -inf, inf)), TuningWidget::Drag) << "no limits: no slider range";
  EXPECT_EQ(tuningWidgetFor(number(1, 0, inf)), TuningWidget::Drag);
  TuningPanel panel = samplePanel();
  EXPECT_EQ(tuningWidgetFor(panel.items[1]), TuningWidget::Checkbox);
  EXPECT_EQ(tuningWidgetFor(panel.items[2]), TuningWidget::Combo);
}

TEST(TuningPanel, ValuesPrintWithTheirUnitAndSnapToTheStep) {
  TuningPanel panel = samplePanel();
  EXPECT_EQ(tuningValueText(panel.items[0]), "9.81 m/s^2");
  EXPECT_EQ(tuningValueText(panel.items[1]), "off");
  EXPECT_EQ(tuningValueText(panel.items[2]), "hard");
  TuningItem stepped = number(1, 0.5, 3, "m", 0.25);
  EXPECT_DOUBLE_EQ(tuningSnap(stepped, 1.13), 1.25);  // 0.5 + 3 * 0.25
  EXPECT_DOUBLE_EQ(tuningSnap(stepped, 9), 3);
  EXPECT_DOUBLE_EQ(tuningSnap(stepped, -2), 0.5);
  EXPECT_DOUBLE_EQ(tuningSnap(number(1, 0, 2), 1.2345), 1.2345) << "step 0: continuous";
}

TEST(TuningPanel, IsDrawnOnlyWhenVisibleAndPressesNothing) {
  auto renderer = test::makeOffscreenRenderer(640, 360, /*hud=*/true);
  ASSERT_NE(renderer, nullptr);
  test::ScratchDir scratch;
  TuningPanel panel = samplePanel();
  renderer->setTuningPanel(&panel);
  Controls controls;
  HudStats stats;
  stats.scenario = "mymod:tower";
  const std::string hidden = scratch.file("hidden.png"), shown = scratch.file("shown.png");
  ASSERT_TRUE(renderer->drawFrame(FrameSnapshot{}, stats, controls, hidden.c_str()).ok());
  controls.tuningPanelVisible = true;
  ASSERT_TRUE(renderer->drawFrame(FrameSnapshot{}, stats, controls, shown.c_str()).ok());

  // The sky has no dark pixels; the panel (dark, top right) does, on the
  // very first frame it is visible, with the user-set value's name in amber.
  const auto dark = [](int r, int g, int b) { return r < 70 && g < 70 && b < 70; };
  const test::Image off = test::loadPng(hidden), on = test::loadPng(shown);
  EXPECT_EQ(test::countPixels(off, dark, 400, 0, 640, 200), 0);
  EXPECT_GT(test::countPixels(on, dark, 400, 0, 640, 200), 4000);
  EXPECT_GT(test::countPixels(on, test::isYellowish, 240, 0, 640, 200), 10);
  EXPECT_TRUE(controls.tuningPanelVisible);
  for (const TuningItem& item : panel.items) EXPECT_FALSE(item.edited || item.resetRequested) << item.name;
  EXPECT_FALSE(panel.saveRequested || panel.resetAllRequested);
}

TEST(TuningPanel, F2TogglesIt) {
  auto renderer = test::makeOffscreenRenderer(320, 240, /*hud=*/true);
  ASSERT_NE(renderer, nullptr);
  Controls controls;
  for (bool expected : {true, false}) {
    SDL_Event event{};
    event.type = SDL_KEYDOWN;
    event.key.state = SDL_PRESSED;
    event.key.keysym.sym = SDLK_F2;
    event.key.keysym.scancode = SDL_SCANCODE_F2;
    ASSERT_EQ(SDL_PushEvent(&event), 1) << SDL_GetError();
    renderer->processEvents(controls);
    EXPECT_EQ(controls.tuningPanelVisible, expected);
  }
}

}  // namespace tumble::render
