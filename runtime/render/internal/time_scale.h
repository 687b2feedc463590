#pragma once
// The slow-motion levels and the single-step rule, shared by the keys and the
// HUD so both behave the same.
#include "render/renderer.h"

namespace tumble::render {

/// Index into kTimeScales of the level closest to `scale` (any value works,
/// so a time scale set by the app or a script snaps to the nearest level).
int timeScaleIndex(float scale);
/// Next slower / faster level; stays at the slowest / fastest.
float slowerTimeScale(float scale);
float fasterTimeScale(float scale);
/// Single step: pause (so the app stops after this step) and ask for one step.
void requestSingleStep(Controls& controls);

}  // namespace tumble::render
