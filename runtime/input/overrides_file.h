#pragma once
// The player's binding overrides on disk: a small JSON file in the user's
// config folder holding only what differs from the mods' defaults.
//
//   {"format": "tumble-bindings", "version": 1,
//    "overrides": {"throttle": ["key:I", "pad_axis:righttrigger"], "reset": []}}
//
// Each entry is an action's whole binding list (text form, binding.h); an
// empty list unbinds the action. Saving is atomic (write beside, rename), so
// a crash never leaves half a file; a file that cannot be read is reported
// and left untouched until the player saves again.
#include <string>

#include "core/result.h"
#include "input/input_system.h"

namespace tumble::input {

/// $TUMBLE_CONFIG_DIR/bindings.json, else $XDG_CONFIG_HOME/tumble/bindings.json,
/// else ~/.config/tumble/bindings.json. Empty if none of them is set.
std::string bindingsConfigPath();

/// A missing file is no overrides (not an error). A file that is not valid
/// JSON or not in the form above is an error naming the file and, where
/// known, the line and the field.
Result<Overrides> loadOverrides(const std::string& path);
/// Writes the overrides atomically, creating the folder if needed.
Status saveOverrides(const std::string& path, const Overrides& overrides);

}  // namespace tumble::input
