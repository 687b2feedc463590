#pragma once
// mods/<mod>/bindings.lua: a mod's input actions with their default
// bindings, read into plain input::BindingSet data.
//
//   return {
//     contexts = {
//       vehicle = {priority = 10, enabled = false, actions = {
//         throttle = {type = "button", label = "Throttle", bindings = {"key:W", "pad_axis:righttrigger"}},
//         steer = {type = "axis", dead_zone = 0.1,
//                  bindings = {"keys:A/D", {"pad_axis:leftx", dead_zone = 0.15, curve = 1.5}}},
//       }},
//     },
//   }
//
// Binding texts are input/binding.h's (key:, keys:, mouse:, mouse_axis:,
// wheel:, pad:, pad_axis:). An action's dead_zone / curve / invert / scale
// apply to each of its bindings that does not set its own.
//
// Several mods (in load order) merge (input::mergeBindings): contexts by
// name; base declares plain action names; any other mod names its new
// actions "<mod>.<name>" (["mymod.fire"] = {...}) so two mods never collide,
// and may re-declare an existing action (same type and context) to change
// its default bindings.
#include <string>
#include <vector>

#include "input/binding.h"
#include "script/mods.h"

namespace tumble::script {

struct ModBindings {
  input::BindingSet set;
  std::vector<ModProblem> problems;  ///< each names bindings.lua, the line where known, the field
  bool present = false;              ///< the mod has a bindings.lua
};

/// Reads <mod.dir>/bindings.lua (none: an empty, problem-free result).
/// Everything valid is kept; each invalid context, action or binding is a
/// problem and left out.
ModBindings loadModBindings(const ModInfo& mod);
/// The bindings of `mods`, merged in the given (load) order, with the
/// namespacing rule above checked.
ModBindings loadBindings(const std::vector<ModInfo>& mods);

}  // namespace tumble::script
