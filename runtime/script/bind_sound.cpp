// Lua table `sound` and type Sound: mod sound files played at a point or on
// a body, and thunder. The scene's audio system does the playing (silent,
// with no device, in headless runs: files are still checked the same way).
#include <cmath>

#include "audio/audio_system.h"
#include "script/internal/bind_common.h"
#include "script/presentation.h"

namespace tumble::script {

/// @module sound
/// Sounds from the mod's files (WAV or Ogg Vorbis), placed in the world:
/// at a point, on a body (moving with it), or, with neither, at the
/// listener. The listener is the camera. At most 32 sounds play at once.
/// Headless runs and `--mute` play nothing but check files and fields the
/// same way, so a scenario behaves alike everywhere.

namespace {

constexpr const char* kSoundMeta = "tumble.Sound";

struct SoundRef {
  std::uint64_t id;
};

audio::AudioSystem& audioOf(lua_State* L) { return ScenarioHost::from(L)->scene().audio(); }

std::uint64_t checkSound(lua_State* L, int idx) {
  auto* ref = static_cast<SoundRef*>(luaL_testudata(L, idx, kSoundMeta));
  if (!ref) throw LuaArgError(std::string("expected a Sound, got ") + luaL_typename(L, idx));
  return ref->id;
}

double finiteField(lua_State* L, int t, const char* key, double fallback, double lo, bool loOpen, double hi,
                   const char* expected) {
  if (rawGetField(L, t, key) == LUA_TNIL) {
    lua_pop(L, 1);
    return fallback;
  }
  lua_pop(L, 1);
  const double v = optNumberField(L, t, key, fallback);
  if (!std::isfinite(v) || (loOpen ? v <= lo : v < lo) || v > hi)
    throw LuaArgError(std::string("'") + key + "' must be " + expected + ", got " + std::to_string(v));
  return v;
}

/// @class SoundPlay
/// @field file string "MOD:path/in/mod" or a path in this mod: a .wav or .ogg (Vorbis) file
/// @field position? Vec3Arg where the sound is, m (fixed)
/// @field body? Body the body the sound moves with (it stops when the body is removed)
/// @field volume? number gain, 0..4 (default 1)
/// @field pitch? number playback rate, 0.05..8 (default 1; 2 is an octave up)
/// @field loop? boolean play until stopped (default false)
/// @field distance? number full volume out to this distance, m, then falling as 1/distance (default 5)

/// @function sound.play
/// Plays a sound file of a mod. The file is read and checked on first use
/// (then kept): a missing, unreadable or corrupt file is an error naming it.
/// @param opts SoundPlay the file, where, how loud and how fast
/// @return Sound a handle to change or stop it
/// @example local horn = sound.play{file = "assets/sounds/horn.wav", body = car:body(), loop = true}
/// @example horn:set_pitch(1.2)
int soundPlay(lua_State* L) {
  const char* fn = "sound.play";
  if (!lua_istable(L, 1))
    throw LuaArgError(std::string(fn) + ": expected a table {file = \"assets/x.wav\", position = {x, y, z}}, got " +
                      luaL_typename(L, 1));
  checkFields(L, 1, fn, {"file", "position", "body", "volume", "pitch", "loop", "distance"});
  audio::SoundParams p;
  physics::BodyId body;
  bool hasBody = false, hasPosition = false;
  std::string file;
  try {
    if (rawGetField(L, 1, "file") != LUA_TSTRING) {
      const char* got = luaL_typename(L, -1);
      lua_pop(L, 1);
      throw LuaArgError(std::string("'file' must be a path such as \"assets/sounds/bang.wav\", got ") + got);
    }
    file = lua_tostring(L, -1);
    lua_pop(L, 1);
    hasPosition = optVec3Field(L, 1, "position", &p.position_m);
    rawGetField(L, 1, "body");
    if (!lua_isnil(L, -1)) {
      body = checkBody(L, -1);
      hasBody = true;
    }
    lua_pop(L, 1);
    if (hasPosition && hasBody) throw LuaArgError("give position or body, not both");
    p.volume = float(finiteField(L, 1, "volume", 1, 0, false, 4, "a number from 0 to 4"));
    p.pitch = float(finiteField(L, 1, "pitch", 1, 0.05, false, 8, "a number from 0.05 to 8"));
    p.referenceDistance_m = float(finiteField(L, 1, "distance", 5, 0, true, 1e5, "a number > 0 (m)"));
    p.loop = optBoolField(L, 1, "loop", false);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  ScenarioHost* host = ScenarioHost::from(L);
  auto path = resolveModFile(file, host->mod(), host->options().modDirs);
  if (!path) throw LuaArgError(std::string(fn) + ": " + path.error());
  audio::AudioSystem& a = audioOf(L);
  auto clip = a.clipFromFile(*path);
  if (!clip) throw LuaArgError(std::string(fn) + ": " + clip.error());
  p.clip = *clip;
  p.atListener = !hasPosition && !hasBody;
  if (hasBody) p.position_m = host->scene().world().body(body).position_m;
  auto id = a.play(p);
  if (!id) throw LuaArgError(std::string(fn) + ": " + id.error());
  if (hasBody) host->scene().attachSound(*id, body);
  auto* ref = static_cast<SoundRef*>(lua_newuserdatauv(L, sizeof(SoundRef), 0));
  ref->id = *id;
  luaL_setmetatable(L, kSoundMeta);
  return 1;
}

/// @class SoundThunder
/// @field position Vec3Arg where the lightning struck, m

/// @function sound.thunder
/// The thunder of a lightning flash at `position` now: it is heard when
/// the sound has travelled from there to the listener at 343 m/s.
/// @param opts SoundThunder where the flash was
/// @return number the delay until it is heard, s (distance / 343 m/s)
/// @example local delay = sound.thunder{position = {800, 300, -200}}
int soundThunder(lua_State* L) {
  const char* fn = "sound.thunder";
  if (!lua_istable(L, 1))
    throw LuaArgError(std::string(fn) + ": expected a table {position = {x, y, z}}, got " + luaL_typename(L, 1));
  checkFields(L, 1, fn, {"position"});
  Vec3 position;
  try {
    if (!optVec3Field(L, 1, "position", &position)) throw LuaArgError("needs position = {x, y, z}");
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  lua_pushnumber(L, audioOf(L).thunder(position));
  return 1;
}

/// @class Sound
/// A playing sound, returned by sound.play. Once it has finished (or was
/// stopped) its methods do nothing and playing() is false.

/// @function Sound:set_pitch
/// @param pitch number playback rate, 0.05..8
int soundSetPitch(lua_State* L) {
  const std::uint64_t id = checkSound(L, 1);
  const double v = checkNumber(L, 2, "Sound:set_pitch pitch");
  if (v < 0.05 || v > 8) throw LuaArgError("Sound:set_pitch: pitch must be from 0.05 to 8, got " + std::to_string(v));
  audioOf(L).setPitch(id, float(v));
  return 0;
}

/// @function Sound:set_volume
/// @param volume number gain, 0..4
int soundSetVolume(lua_State* L) {
  const std::uint64_t id = checkSound(L, 1);
  const double v = checkNumber(L, 2, "Sound:set_volume volume");
  if (v < 0 || v > 4) throw LuaArgError("Sound:set_volume: volume must be from 0 to 4, got " + std::to_string(v));
  audioOf(L).setVolume(id, float(v));
  return 0;
}

/// @function Sound:stop
/// Stops the sound now.
int soundStop(lua_State* L) {
  audioOf(L).stop(checkSound(L, 1));
  return 0;
}

/// @function Sound:playing
/// @return boolean true until it ends or is stopped (a loop plays until stopped)
int soundPlaying(lua_State* L) {
  lua_pushboolean(L, audioOf(L).isPlaying(checkSound(L, 1)));
  return 1;
}

int soundToString(lua_State* L) {
  auto* ref = static_cast<SoundRef*>(luaL_checkudata(L, 1, kSoundMeta));
  lua_pushfstring(L, "Sound(%d)", int(ref->id));
  return 1;
}

const luaL_Reg kSound[] = {
    {"play", guarded<soundPlay>},
    {"thunder", guarded<soundThunder>},
    {nullptr, nullptr},
};
const luaL_Reg kMethods[] = {
    {"set_pitch", guarded<soundSetPitch>},
    {"set_volume", guarded<soundSetVolume>},
    {"stop", guarded<soundStop>},
    {"playing", guarded<soundPlaying>},
    {nullptr, nullptr},
};

}  // namespace

void openSoundBindings(lua_State* L, int envIndex) {
  registerType(L, {kSoundMeta, kMethods, soundToString});
  registerModule(L, envIndex, "sound", kSound);
}

}  // namespace tumble::script
