#pragma once
// The tuning panel's wiring: script tunables -> render::TuningPanel (plain
// data the renderer draws) -> edits back into the tunables, at once, and
// "Save" writes the mod's overrides file (script/tunables.h).
#include <string>

#include "render/renderer.h"
#include "script/tunables.h"

namespace tumble::app {

/// Copies every tunable into panel.items (title, path and status are kept).
void fillTuningPanel(const script::Tunables& tunables, render::TuningPanel& panel);

/// Applies what the panel asked for during the last frame: edited values,
/// per-item and global resets, and Save (to panel.overridesPath, atomically,
/// under `mod`). Clears the requests; a save's outcome goes to panel.status.
void applyTuningPanel(render::TuningPanel& panel, script::Tunables& tunables, const std::string& mod);

}  // namespace tumble::app
