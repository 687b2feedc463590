#pragma once
// The emitter definitions one scenario uses (particles.spawn), by "mod:name":
// each emitters/<name>.lua is run once and its table kept, and every
// emitter spawned from a file remembers the file and its spawn overrides,
// so that a saved emitter file changes the emitters already running from it
// (hot reload). emitter_files.h reads and validates the tables.
#include <string>
#include <vector>

#include "core/result.h"
#include "particles/emitter_def.h"
#include "particles/particle_system.h"
#include "script/mods.h"

struct lua_State;

namespace tumble::script {

class LuaVm;

class EmitterCache {
 public:
  /// `mod` is the scenario's mod (searched first); `mods` every loadable one.
  EmitterCache(LuaVm& vm, const ModInfo& mod, const std::vector<ModInfo>& mods);

  /// The definition "mod:name" (or "name": this mod, then base) with the
  /// fields of the table at overridesIdx (0: none) on top. Error: file,
  /// field and what is expected.
  Result<particles::EmitterDef> definition(const std::string& ref, int overridesIdx);
  /// Remembers which file (and a copy of the overrides) an emitter came from.
  void rememberSource(particles::EmitterId id, const std::string& ref, int overridesIdx,
                      const particles::ParticleSystem& particles);
  /// Hot reload of emitters/<name>.lua of the scenario's mod: the file is
  /// read again and every running emitter spawned from it takes the new
  /// definition (with its overrides on top). A broken file changes nothing.
  Status reloadFile(const std::string& relPath, particles::ParticleSystem* particles);
  /// Forgets the files read, so the next spawn reads them again.
  void forget();

 private:
  struct Source {
    particles::EmitterId id;
    std::string ref;       ///< as given to particles.spawn
    int overridesRef = 0;  ///< registry ref of a copy of the overrides table, 0 = none
  };
  const ModInfo* findMod(const std::string& name) const;

  LuaVm& m_vm;
  const ModInfo& m_mod;
  const std::vector<ModInfo>& m_mods;
  int m_tablesRef = 0;  ///< registry table: "mod:name" -> the file's returned table
  std::vector<Source> m_sources;
};

/// True for a name made of letters, digits, '_' and '-' (no path parts).
bool isPlainName(const std::string& name);

}  // namespace tumble::script
