// Slow-motion levels step 1 -> 0.5 -> 0.25 -> 0.1 and stop at the ends; a
// single step also pauses.
#include <gtest/gtest.h>

#include "render/internal/time_scale.h"

namespace tumble::render {
namespace {

TEST(RenderTimeScale, SlowerWalksDownTheLevelsAndStops) {
  float s = 1.0f;
  s = slowerTimeScale(s);
  EXPECT_FLOAT_EQ(s, 0.5f);
  s = slowerTimeScale(s);
  EXPECT_FLOAT_EQ(s, 0.25f);
  s = slowerTimeScale(s);
  EXPECT_FLOAT_EQ(s, 0.1f);
  EXPECT_FLOAT_EQ(slowerTimeScale(s), 0.1f);
}

TEST(RenderTimeScale, FasterWalksUpTheLevelsAndStops) {
  EXPECT_FLOAT_EQ(fasterTimeScale(0.1f), 0.25f);
  EXPECT_FLOAT_EQ(fasterTimeScale(0.25f), 0.5f);
  EXPECT_FLOAT_EQ(fasterTimeScale(0.5f), 1.0f);
  EXPECT_FLOAT_EQ(fasterTimeScale(1.0f), 1.0f);
}

TEST(RenderTimeScale, OffLevelValuesSnapToTheNearestLevel) {
  EXPECT_EQ(timeScaleIndex(0.3f), 2);  // 0.25
  EXPECT_EQ(timeScaleIndex(7.0f), 0);
  EXPECT_FLOAT_EQ(slowerTimeScale(0.9f), 0.5f);
}

TEST(RenderTimeScale, SingleStepPausesAndRequestsOneStep) {
  Controls controls;
  requestSingleStep(controls);
  EXPECT_TRUE(controls.paused);
  EXPECT_TRUE(controls.stepOnce);
}

}  // namespace
}  // namespace tumble::render
