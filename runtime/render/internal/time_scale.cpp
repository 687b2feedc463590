#include "render/internal/time_scale.h"

#include <cmath>
#include <iterator>

namespace tumble::render {

namespace {
constexpr int kLevels = static_cast<int>(std::size(kTimeScales));
}

int timeScaleIndex(float scale) {
  int best = 0;
  for (int i = 1; i < kLevels; ++i) {
    if (std::abs(kTimeScales[i] - scale) < std::abs(kTimeScales[best] - scale)) best = i;
  }
  return best;
}

// kTimeScales runs from fastest to slowest.
float slowerTimeScale(float scale) {
  const int i = timeScaleIndex(scale);
  return kTimeScales[i + 1 < kLevels ? i + 1 : i];
}

float fasterTimeScale(float scale) {
  const int i = timeScaleIndex(scale);
  return kTimeScales[i > 0 ? i - 1 : 0];
}

void requestSingleStep(Controls& controls) {
  controls.paused = true;
  controls.stepOnce = true;
}

}  // namespace tumble::render
