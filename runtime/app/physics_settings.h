#pragma once
// `--set physics.KEY=VALUE`: world settings from the command line, applied
// before the scenario runs (physics.joint_solver is the scene's, not the
// world's: app/scene.cpp reads it).
#include <string>

#include "core/result.h"
#include "physics/world.h"

namespace tumble::app {

/// Applies one physics.* setting; an error names the key, the value and
/// what is valid (and lists the known keys for an unknown one).
Status applyPhysicsSetting(physics::WorldSettings& settings, const std::string& key, const std::string& value);

}  // namespace tumble::app
