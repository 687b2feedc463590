#pragma once
// The player's volume settings: volume_master, volume_effects and
// volume_engine (each 0..1) in the player's settings file, a JSON object
// (the settings menu writes it; every other key there is ignored here).
#include <string>

#include "audio/audio_system.h"
#include "core/result.h"

namespace tumble::audio {

/// A missing file or key is the default (1). A file that is not a JSON
/// object, or one of the three keys that is not a number in [0, 1], is an
/// error naming the file and the key.
Result<AudioVolumes> readVolumes(const std::string& path);

}  // namespace tumble::audio
