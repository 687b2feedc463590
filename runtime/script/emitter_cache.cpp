#include "script/emitter_cache.h"
#include "script/internal/raw_access.h"

#include <cctype>
#include <filesystem>

#include "script/internal/emitter_table.h"
#include "script/lua_vm.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace fs = std::filesystem;

namespace tumble::script {

bool isPlainName(const std::string& name) {
  if (name.empty()) return false;
  for (unsigned char c : name)
    if (!std::isalnum(c) && c != '_' && c != '-') return false;
  return true;
}

EmitterCache::EmitterCache(LuaVm& vm, const ModInfo& mod, const std::vector<ModInfo>& mods)
    : m_vm(vm), m_mod(mod), m_mods(mods) {
  lua_newtable(vm.state());
  m_tablesRef = luaL_ref(vm.state(), LUA_REGISTRYINDEX);
}

const ModInfo* EmitterCache::findMod(const std::string& name) const {
  if (name == m_mod.name) return &m_mod;
  for (const ModInfo& info : m_mods)
    if (info.name == name) return &info;
  return nullptr;
}

Result<particles::EmitterDef> EmitterCache::definition(const std::string& ref, int overridesIdx) {
  lua_State* L = m_vm.state();
  if (overridesIdx) overridesIdx = lua_absindex(L, overridesIdx);
  std::string modName, name = ref;
  if (auto colon = ref.find(':'); colon != std::string::npos) {
    modName = ref.substr(0, colon);
    name = ref.substr(colon + 1);
  }
  if (!isPlainName(name) || (!modName.empty() && !isPlainName(modName)))
    return makeError("emitter \"" + ref + "\" is not of the form MOD:NAME or NAME (for example \"base:dust\")");
  std::vector<const ModInfo*> candidates;
  if (!modName.empty()) {
    if (const ModInfo* m = findMod(modName)) candidates.push_back(m);
    else return makeError("emitter \"" + ref + "\": no mod named \"" + modName + "\" is loaded");
  } else {
    candidates.push_back(&m_mod);
    if (const ModInfo* base = findMod("base"); base && base != &m_mod) candidates.push_back(base);
  }
  const ModInfo* mod = nullptr;
  for (const ModInfo* m : candidates)
    if (fs::exists(fs::path(m->dir) / "emitters" / (name + ".lua"))) {
      mod = m;
      break;
    }
  if (!mod) {
    std::string known;
    for (const ModInfo* m : candidates)
      for (const std::string& e : ModRegistry::listLua(*m, "emitters")) known += (known.empty() ? "" : ", ") + m->name + ":" + e;
    return makeError("emitter \"" + ref + "\" not found (emitters/" + name + ".lua; known: " +
                     (known.empty() ? std::string("none") : known) + ")");
  }
  const std::string key = mod->name + ":" + name;
  const std::string path = (fs::path(mod->dir) / "emitters" / (name + ".lua")).string();
  const std::string file = "emitters/" + name + ".lua";
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_tablesRef);
  if (rawGetField(L, -1, key.c_str()) != LUA_TTABLE) {
    lua_pop(L, 1);
    std::string error;
    int line = 0;
    if (!runEmitterChunk(m_vm, path, mod->name, &error, &line)) {
      lua_pop(L, 1);
      return makeError("mod " + mod->name + ": " + file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + error);
    }
    lua_pushvalue(L, -1);
    rawSetField(L, -3, key.c_str());
  }
  // The file's fields, then the overrides on top, into a fresh table.
  lua_newtable(L);
  for (int src : {-2, overridesIdx}) {
    if (src == 0) continue;
    int from = src < 0 ? lua_gettop(L) - 1 : src;
    lua_pushnil(L);
    while (lua_next(L, from) != 0) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_rawset(L, -4);
    }
  }
  particles::EmitterDef def;
  std::vector<std::string> problems;
  readEmitterTable(L, -1, def, problems);
  lua_pop(L, 3);
  if (problems.empty()) return def;
  std::string msg;
  for (const std::string& p : problems) msg += (msg.empty() ? "" : "; ") + p;
  return makeError("mod " + mod->name + ": " + file + (overridesIdx ? " (with overrides)" : "") + ": " + msg);
}

void EmitterCache::rememberSource(particles::EmitterId id, const std::string& ref, int overridesIdx,
                                  const particles::ParticleSystem& particles) {
  lua_State* L = m_vm.state();
  // Drop the sources of emitters that are gone (bounded: one entry per live emitter).
  std::erase_if(m_sources, [&](const Source& e) {
    if (particles.isValid(e.id)) return false;
    if (e.overridesRef) luaL_unref(L, LUA_REGISTRYINDEX, e.overridesRef);
    return true;
  });
  Source source{id, ref, 0};
  if (overridesIdx) {
    overridesIdx = lua_absindex(L, overridesIdx);
    lua_newtable(L);  // a shallow copy: the script may change its table later
    lua_pushnil(L);
    while (lua_next(L, overridesIdx) != 0) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_rawset(L, -4);
    }
    source.overridesRef = luaL_ref(L, LUA_REGISTRYINDEX);
  }
  m_sources.push_back(std::move(source));
}

Status EmitterCache::reloadFile(const std::string& relPath, particles::ParticleSystem* particles) {
  // "emitters/smoke.lua" -> "smoke"
  const std::string name = fs::path(relPath).stem().string();
  forget();
  // Read it now, so a broken file is reported at once (and nothing changes).
  const std::string qualified = m_mod.name + ":" + name;
  if (auto def = definition(qualified, 0); !def) return makeError(def.error());
  if (!particles) return Ok{};
  lua_State* L = m_vm.state();
  for (const Source& e : m_sources) {
    if (!particles->isValid(e.id)) continue;
    // "name" means this mod first, so it resolves to this file too.
    if (e.ref != qualified && e.ref != name) continue;
    int idx = 0;
    if (e.overridesRef) {
      lua_rawgeti(L, LUA_REGISTRYINDEX, e.overridesRef);
      idx = lua_gettop(L);
    }
    auto def = definition(e.ref, idx);
    if (idx) lua_pop(L, 1);
    if (!def) return makeError(def.error());
    particles->redefine(e.id, *def);
  }
  return Ok{};
}

void EmitterCache::forget() {
  lua_State* L = m_vm.state();
  lua_newtable(L);
  lua_rawseti(L, LUA_REGISTRYINDEX, m_tablesRef);
}

}  // namespace tumble::script
