// Lua module `save`: small per-mod save data (best times, unlocked cars) as
// JSON files in the user's data folder, written atomically (a crash never
// leaves half a file). The folder is the scene's save folder if the app set
// one (`run` uses a throw-away folder, or --save-dir), else $TUMBLE_SAVE_DIR
// if set (TUMBLE_DATA_DIR already names where mods and scripts are found),
// else $XDG_DATA_HOME/tumble/saves, else ~/.local/share/tumble/saves; each
// mod has its own subfolder, so mods cannot read or overwrite each other's
// saves.
//
//   local best = (save.read("time_trial") or {}).best
//   save.write("time_trial", {best = 61.4})
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/file_util.h"
#include "core/text.h"
#include "script/internal/bind_common.h"
#include "script/tunables.h"

namespace tumble::script {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::size_t kMaxSaveBytes = 1u << 20;

// The scene's save folder (run's throw-away folder or --save-dir), else the player's.
fs::path dataDir(lua_State* L) {
  if (const std::string& d = ScenarioHost::from(L)->options().saveDir; !d.empty()) return d;
  return savesDir();
}

fs::path savePath(lua_State* L, const char* fn) {
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError(std::string(fn) + ": expected a save name (a string)");
  std::size_t length = 0;
  const char* text = lua_tolstring(L, 1, &length);
  const std::string name(text, length);  // a NUL inside the name is kept, and refused below
  const bool valid = !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
  if (!valid)
    throw LuaArgError(std::string(fn) + ": save name \"" + clipped(name) +
                      "\" must be 1 to 64 letters, digits, '_' or '-' (it becomes a file name)");
  return dataDir(L) / ScenarioHost::from(L)->mod().name / (name + ".json");
}

// Deepest nesting a save may have, in tables (save.write) and in JSON
// (save.read): each level is a C++ frame and a few Lua stack slots.
constexpr int kMaxSaveDepth = 32;
// Per-mod quota: the mod's save folder may hold at most this much in at most
// this many saves (a mod writing a new name every frame fills no disk).
constexpr std::uintmax_t kMaxModSaveBytes = 4u << 20;
constexpr std::size_t kMaxModSaveFiles = 64;

std::string depthMessage(const char* fn) {
  return std::string(fn) + ": the data is nested more than " + std::to_string(kMaxSaveDepth) + " levels deep";
}

// `path` holds the tables (lua_topointer) being converted, outermost first:
// a table met again on its own path is a cycle.
json toJson(lua_State* L, int idx, int depth, std::vector<const void*>& path) {
  idx = lua_absindex(L, idx);
  if (depth > kMaxSaveDepth) throw LuaArgError(depthMessage("save.write"));
  if (!lua_checkstack(L, 4)) throw LuaArgError("save.write: out of Lua stack space");
  switch (lua_type(L, idx)) {
    case LUA_TBOOLEAN: return bool(lua_toboolean(L, idx));
    case LUA_TSTRING: return std::string(lua_tostring(L, idx));
    case LUA_TNUMBER: {
      if (lua_isinteger(L, idx)) return lua_tointeger(L, idx);
      const double v = lua_tonumber(L, idx);
      if (!std::isfinite(v)) throw LuaArgError("save.write: numbers must be finite (got inf or nan)");
      return v;
    }
    case LUA_TTABLE: {
      const void* self = lua_topointer(L, idx);
      if (std::find(path.begin(), path.end(), self) != path.end())
        throw LuaArgError("save.write: the table contains itself (a cycle, " + std::to_string(depth) +
                          " levels down); only trees of tables can be saved");
      path.push_back(self);
      const lua_Integer n = lua_Integer(lua_rawlen(L, idx));
      std::size_t count = 0;
      lua_pushnil(L);
      while (lua_next(L, idx) != 0) ++count, lua_pop(L, 1);
      json out;
      if (n > 0 && std::size_t(n) == count) {
        out = json::array();
        for (lua_Integer i = 1; i <= n; ++i) {
          lua_rawgeti(L, idx, i);
          json value = toJson(L, -1, depth + 1, path);
          lua_pop(L, 1);
          out.push_back(std::move(value));
        }
      } else {
        out = json::object();
        lua_pushnil(L);
        while (lua_next(L, idx) != 0) {
          if (lua_type(L, -2) != LUA_TSTRING) {
            lua_pop(L, 2);
            throw LuaArgError("save.write: table keys must be strings (or the table a list 1..n)");
          }
          json value = toJson(L, -1, depth + 1, path);
          out[lua_tostring(L, -2)] = std::move(value);
          lua_pop(L, 1);
        }
      }
      path.pop_back();
      return out;
    }
    default:
      throw LuaArgError(std::string("save.write: cannot save a ") + luaL_typename(L, idx) +
                        " (only tables, strings, numbers and booleans)");
  }
}

// Pushes j; its depth was checked when it was parsed (at most kMaxSaveDepth).
void pushJson(lua_State* L, const json& j) {
  if (!lua_checkstack(L, 3)) throw LuaArgError("save.read: out of Lua stack space");
  switch (j.type()) {
    case json::value_t::boolean: lua_pushboolean(L, j.get<bool>()); break;
    case json::value_t::string: lua_pushlstring(L, j.get_ref<const std::string&>().data(), j.get_ref<const std::string&>().size()); break;
    case json::value_t::number_integer: lua_pushinteger(L, j.get<lua_Integer>()); break;
    case json::value_t::number_unsigned: lua_pushnumber(L, double(j.get<std::uint64_t>())); break;
    case json::value_t::number_float: lua_pushnumber(L, j.get<double>()); break;
    case json::value_t::array: {
      lua_createtable(L, int(std::min<std::size_t>(j.size(), 1u << 16)), 0);
      lua_Integer i = 1;
      for (const json& e : j) pushJson(L, e), lua_rawseti(L, -2, i++);
      break;
    }
    case json::value_t::object: {
      lua_createtable(L, 0, int(std::min<std::size_t>(j.size(), 1u << 16)));
      for (const auto& [k, v] : j.items()) {
        lua_pushlstring(L, k.data(), k.size());
        pushJson(L, v);
        lua_rawset(L, -3);
      }
      break;
    }
    default: lua_pushnil(L); break;
  }
}

// Bytes and files in the mod's save folder, not counting `except`.
std::pair<std::uintmax_t, std::size_t> folderUse(const fs::path& dir, const fs::path& except) {
  std::uintmax_t bytes = 0;
  std::size_t files = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path() == except || !entry.is_regular_file(ec)) continue;
    bytes += entry.file_size(ec);
    ++files;
  }
  return {bytes, files};
}


/// @module save
/// Per-mod save data as JSON in the user's data folder ($TUMBLE_SAVE_DIR,
/// else $XDG_DATA_HOME/tumble/saves, else ~/.local/share/tumble/saves), one
/// folder per mod, written atomically. `tumble run` keeps saves in a
/// throw-away folder (removed at exit) unless given --save-dir, so headless
/// runs never change what the player's game shows.

/// @function save.read
/// @param name string 1 to 64 letters, digits, '_' or '-'
/// @return table? the saved table, or nil when nothing was saved yet
/// @return string? why it could not be read (a broken file), else nil
/// @example local best = (save.read("time_trial") or {}).best_s
int saveRead(lua_State* L) {
  const fs::path path = savePath(L, "save.read");
  if (!fs::exists(path)) return 0;
  auto text = readTextFile(path.string(), kMaxSaveBytes);
  if (!text) {
    lua_pushnil(L);
    lua_pushstring(L, text.error().c_str());
    return 2;
  }
  // Depth is checked while parsing (a hand-made file nested 100 000 deep
  // never becomes a tree), and out-of-range numbers (1e400) are refused.
  json j;
  std::string why;
  try {
    j = json::parse(text.value(), [](int depth, json::parse_event_t, json&) {
      if (depth > kMaxSaveDepth) throw std::length_error("too deep");
      return true;
    });
  } catch (const std::length_error&) {
    why = "nested more than " + std::to_string(kMaxSaveDepth) + " levels deep";
  } catch (const json::exception& e) {
    why = std::string("not valid JSON (") + e.what() + ")";
  }
  if (!why.empty()) {
    lua_pushnil(L);
    lua_pushstring(L, (path.string() + ": " + why + "; it will be replaced by the next save.write").c_str());
    return 2;
  }
  pushJson(L, j);
  return 1;
}

/// @function save.write
/// Saves a table (strings, numbers, booleans, nested tables) atomically.
/// @param name string 1 to 64 letters, digits, '_' or '-'
/// A table that contains itself is refused (a cycle), as is nesting deeper
/// than 32 levels. Each mod may keep at most 64 saves using 4 MB in all
/// (its quota); a write past it is an error that says so.
/// @param data table what to save (at most 1 MB as JSON)
/// @example save.write("time_trial", {best_s = 61.4, car = "base:buggy"})
int saveWrite(lua_State* L) {
  const fs::path path = savePath(L, "save.write");
  if (!lua_istable(L, 2)) throw LuaArgError("save.write: expected a table to save as the second argument");
  std::vector<const void*> tables;
  const std::string text = toJson(L, 2, 0, tables).dump(2) + "\n";
  if (text.size() > kMaxSaveBytes) throw LuaArgError("save.write: the data is larger than 1 MB as JSON");
  const auto [bytes, files] = folderUse(path.parent_path(), path);
  if (bytes + text.size() > kMaxModSaveBytes || files + 1 > kMaxModSaveFiles)
    throw LuaArgError("save.write: the mod's saves would exceed its quota of " + std::to_string(kMaxModSaveFiles) +
                      " saves and 4 MB (" + std::to_string(files) + " other saves use " + std::to_string(bytes) +
                      " bytes in " + path.parent_path().string() + "); reuse a name or save less");
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) throw LuaArgError("save.write: cannot create " + path.parent_path().string() + ": " + ec.message());
  if (auto s = writeFileAtomic(path.string(), text); !s) throw LuaArgError("save.write: " + s.error());
  return 0;
}

const luaL_Reg kFunctions[] = {{"read", guarded<saveRead>}, {"write", guarded<saveWrite>}, {nullptr, nullptr}};

}  // namespace

std::string savesDir() {
  if (const char* d = std::getenv("TUMBLE_SAVE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x && *x) return (fs::path(x) / "tumble" / "saves").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".local" / "share" / "tumble" / "saves").string();
  return (fs::current_path() / "tumble-saves").string();
}

void openSaveBindings(lua_State* L, int envIndex) {
  registerModule(L, envIndex, "save", kFunctions);
}

}  // namespace tumble::script
