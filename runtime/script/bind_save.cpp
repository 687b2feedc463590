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
#include <regex>
#include <sstream>

#include "core/file_util.h"
#include "script/internal/bind_common.h"

namespace tumble::script {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::size_t kMaxSaveBytes = 1u << 20;

fs::path dataDir(lua_State* L) {
  if (const std::string& d = ScenarioHost::from(L)->options().saveDir; !d.empty()) return d;
  if (const char* d = std::getenv("TUMBLE_SAVE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x && *x) return fs::path(x) / "tumble" / "saves";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".local" / "share" / "tumble" / "saves";
  return fs::current_path() / "tumble-saves";
}

fs::path savePath(lua_State* L, const char* fn) {
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError(std::string(fn) + ": expected a save name (a string)");
  const std::string name = lua_tostring(L, 1);
  static const std::regex valid("^[A-Za-z0-9_-]{1,64}$");
  if (!std::regex_match(name, valid))
    throw LuaArgError(std::string(fn) + ": save name \"" + name +
                      "\" must be 1 to 64 letters, digits, '_' or '-' (it becomes a file name)");
  return dataDir(L) / ScenarioHost::from(L)->mod().name / (name + ".json");
}

json toJson(lua_State* L, int idx, int depth) {
  idx = lua_absindex(L, idx);
  if (depth > 32) throw LuaArgError("save.write: the table is nested more than 32 levels deep");
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
      const lua_Integer n = lua_Integer(lua_rawlen(L, idx));
      std::size_t count = 0;
      lua_pushnil(L);
      while (lua_next(L, idx) != 0) ++count, lua_pop(L, 1);
      if (n > 0 && std::size_t(n) == count) {
        json a = json::array();
        for (lua_Integer i = 1; i <= n; ++i) {
          lua_rawgeti(L, idx, i);
          a.push_back(toJson(L, -1, depth + 1));
          lua_pop(L, 1);
        }
        return a;
      }
      json o = json::object();
      lua_pushnil(L);
      while (lua_next(L, idx) != 0) {
        if (lua_type(L, -2) != LUA_TSTRING)
          throw LuaArgError("save.write: table keys must be strings (or the table a list 1..n)");
        o[lua_tostring(L, -2)] = toJson(L, -1, depth + 1);
        lua_pop(L, 1);
      }
      return o;
    }
    default:
      throw LuaArgError(std::string("save.write: cannot save a ") + luaL_typename(L, idx) +
                        " (only tables, strings, numbers and booleans)");
  }
}

void pushJson(lua_State* L, const json& j) {
  switch (j.type()) {
    case json::value_t::boolean: lua_pushboolean(L, j.get<bool>()); break;
    case json::value_t::string: lua_pushstring(L, j.get<std::string>().c_str()); break;
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: lua_pushinteger(L, j.get<lua_Integer>()); break;
    case json::value_t::number_float: lua_pushnumber(L, j.get<double>()); break;
    case json::value_t::array: {
      lua_createtable(L, int(j.size()), 0);
      lua_Integer i = 1;
      for (const json& e : j) pushJson(L, e), lua_rawseti(L, -2, i++);
      break;
    }
    case json::value_t::object: {
      lua_createtable(L, 0, int(j.size()));
      for (const auto& [k, v] : j.items()) pushJson(L, v), lua_setfield(L, -2, k.c_str());
      break;
    }
    default: lua_pushnil(L); break;
  }
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
  auto text = readTextFile(path.string());
  if (!text) {
    lua_pushnil(L);
    lua_pushstring(L, text.error().c_str());
    return 2;
  }
  json j = json::parse(text.value(), nullptr, false);
  if (j.is_discarded()) {
    lua_pushnil(L);
    lua_pushstring(L, (path.string() + ": not valid JSON; it will be replaced by the next save.write").c_str());
    return 2;
  }
  pushJson(L, j);
  return 1;
}

/// @function save.write
/// Saves a table (strings, numbers, booleans, nested tables) atomically.
/// @param name string 1 to 64 letters, digits, '_' or '-'
/// @param data table what to save (at most 1 MB as JSON)
/// @example save.write("time_trial", {best_s = 61.4, car = "base:buggy"})
int saveWrite(lua_State* L) {
  const fs::path path = savePath(L, "save.write");
  if (!lua_istable(L, 2)) throw LuaArgError("save.write: expected a table to save as the second argument");
  const std::string text = toJson(L, 2, 0).dump(2) + "\n";
  if (text.size() > kMaxSaveBytes) throw LuaArgError("save.write: the data is larger than 1 MB as JSON");
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) throw LuaArgError("save.write: cannot create " + path.parent_path().string() + ": " + ec.message());
  if (auto s = writeFileAtomic(path.string(), text); !s) throw LuaArgError("save.write: " + s.error());
  return 0;
}

const luaL_Reg kFunctions[] = {{"read", guarded<saveRead>}, {"write", guarded<saveWrite>}, {nullptr, nullptr}};

}  // namespace

void openSaveBindings(lua_State* L, int envIndex) {
  registerModule(L, envIndex, "save", kFunctions);
}

}  // namespace tumble::script
