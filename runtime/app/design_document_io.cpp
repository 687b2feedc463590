// Saving a design as a mod scenario and opening it again (design_document.h).
//
// A save is all or nothing: every file is first written (atomically) into a
// staging folder inside the mod; only when all of them are written are the
// files of an earlier save moved to backup/<scenario>/ and the new ones
// renamed into place (renames within one file system cannot run out of
// space). A failure before that point removes the staging folder and leaves
// the earlier save untouched; a failed rename puts the moved files back.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <thread>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "app/design_document.h"
#include "app/paths.h"
#include "app/scene_models.h"
#include "app/terrain_scene.h"
#include "render/model.h"
#include "core/file_util.h"
#include "script/mods.h"
#include "script/presentation.h"
#include "terrain/png_io.h"

namespace tumble::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// 2: the sky (version 1 files have none and get DesignSky's defaults).
constexpr int kDesignFormatVersion = 2;
constexpr terrain::PngEncoding kFastPng{1, 2, true};

// ---- names and numbers ---------------------------------------------------------------

/// Mod and scenario names: what `tumble play MOD:SCENARIO` accepts.
Status checkName(const std::string& what, const std::string& name) {
  const bool ok = !name.empty() && name.size() <= script::kMaxModNameChars &&
                  std::all_of(name.begin(), name.end(), [](char c) {
                    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                           c == '-';
                  });
  if (ok) return Ok{};
  std::string shown = name.size() > 80 ? name.substr(0, 80) + "..." : name;
  return makeError(what + " \"" + shown + "\": use 1 to " + std::to_string(script::kMaxModNameChars) +
                   " letters, digits, '_' or '-' (no path separators, no '..'; it becomes a folder or file name)");
}

/// The shortest text that reads back as the same number (Lua and JSON).
template <typename T>
std::string num(T v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  if (s == "-0") s = "0";
  return s;
}

std::string vec(const Vec3& v) {
  std::string s = "{";
  s.append(num(v.x())).append(", ").append(num(v.y())).append(", ").append(num(v.z())).append("}");
  return s;
}

std::string luaString(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += char(c);
    else if (c == '\n') out += "\\n";
    else if (c < 32 || c == 127) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\%03u", unsigned(c));
      out += buf;
    } else {
      out += char(c);
    }
  }
  return out + "\"";
}

/// One line of a Lua comment (no newlines can end it early).
std::string commentLine(const std::string& s) {
  std::string out = s;
  std::replace(out.begin(), out.end(), '\n', ' ');
  std::replace(out.begin(), out.end(), '\r', ' ');
  return out;
}

// ---- the generated scenario ----------------------------------------------------------------

std::vector<std::pair<std::uint32_t, PlacedObject>> gatesInOrder(const DesignMeta& meta) {
  std::vector<std::pair<std::uint32_t, PlacedObject>> gates;
  for (const auto& [id, o] : meta.objects)
    if (o.kind == PlacedKind::Gate) gates.emplace_back(id, o);
  std::stable_sort(gates.begin(), gates.end(), [](const auto& a, const auto& b) { return a.second.order < b.second.order; });
  return gates;
}

std::string objectLine(std::uint32_t id, const PlacedObject& o) {
  const Vec3& p = o.position_m;
  const std::string rot = "{0, " + num(o.yaw_rad) + ", 0}";
  std::ostringstream s;
  switch (o.kind) {
    case PlacedKind::Model:
      s << "    world.add_static_model(" << luaString(o.asset) << ", {position = " << vec(p) << ", rotation = " << rot
        << ", scale = " << vec(o.scale) << ", collision = " << luaString(o.collision) << "})";
      break;
    case PlacedKind::Box: {
      Vec3 centre = p;
      centre.y() += o.scale.y() / 2;
      s << "    world.box{size = " << vec(o.scale) << ", position = " << vec(centre) << ", rotation = " << rot
        << (o.mass_kg > 0 ? ", mass = " + num(o.mass_kg) : ", density = 600") << "}";
      break;
    }
    case PlacedKind::Barrel:
      s << "    barrel(" << vec(p) << ", " << num(o.yaw_rad) << ", " << num(o.scale.x()) << ", " << num(o.scale.y()) << ", "
        << num(o.mass_kg) << ")";
      break;
    case PlacedKind::Ragdoll:
      s << "    spawn_ragdoll{position = " << vec(p) << ", rotation = " << rot << ", scale = " << num(o.scale.x()) << "}";
      break;
    case PlacedKind::Trigger: {
      Vec3 centre = p;
      centre.y() += o.scale.y() / 2;
      s << "    trigger.box{center = " << vec(centre) << ", size = " << vec(o.scale) << ", rotation = " << rot
        << ", on_enter = function(body)\n      if car and body == car:body() then game.message(\"trigger " << id
        << "\", 3) end\n    end}";
      break;
    }
    case PlacedKind::Emitter:
      s << "    particles.spawn(" << luaString(o.asset) << ", {position = " << vec(p) << "})";
      break;
    case PlacedKind::Gate: break;  // in GATES
  }
  s << "  -- " << placedKindName(o.kind) << " " << id << "\n";
  return s.str();
}

std::string scenarioLua(const DesignMeta& meta, const std::string& modName, const std::string& scenario) {
  const auto gates = gatesInOrder(meta);
  std::ostringstream s;
  s << "-- " << commentLine(meta.title) << "\n"
    << "-- Made in Tumble's scenario designer; `tools/tumble design " << modName << ":" << scenario << "` opens it\n"
    << "-- again (from designs/" << scenario << ".design.json: saving from the designer replaces this\n"
    << "-- file and keeps the previous one in backup/" << scenario << "/). Everything below is the\n"
    << "-- Lua API modders use (docs/lua-api.md, docs/designer.md): edit it by hand as you like.\n"
    << "-- The player drives from the start (drive.player); with --set autopilot=1\n"
    << "-- and gates, the autopilot drives through them in order.\n"
    << "-- Expectations: the car stands on its wheels at the end; on autopilot\n"
    << "-- every gate is passed in order.\n"
    << "--\n"
    << "--   tumble play " << modName << ":" << scenario << " --set car=base:truck\n"
    << "--   tumble run " << modName << ":" << scenario << " --set autopilot=1\n"
    << "local drive = require \"tumble.drive\"\n\n"
    << "-- The ground point under the car's centre (m) and its heading (rad, 0 faces +Z).\n"
    << "local START = {x = " << num(meta.start.position_m.x()) << ", y = " << num(meta.start.position_m.y())
    << ", z = " << num(meta.start.position_m.z()) << ", heading = " << num(meta.start.heading_rad) << "}\n"
    << "-- Gates in driving order: centre (m), heading of the way through (rad),\n"
    << "-- width between the posts (m), post height (m).\n"
    << "local GATES = {\n";
  for (const auto& [id, g] : gates)
    s << "  {x = " << num(g.position_m.x()) << ", z = " << num(g.position_m.z()) << ", heading = " << num(g.yaw_rad)
      << ", width = " << num(g.scale.x()) << ", height = " << num(g.scale.y()) << "},  -- gate " << id << "\n";
  s << "}\n\n"
    << "local car, pilot, player\n"
    << "local next_gate, lap_time, finished = 1, 0, false\n\n"
    << "local function ground(x, z)\n"
    << "  return (vehicle.surface(x, z)) or 0\n"
    << "end\n\n"
    << "-- A barrel standing at (x, y, z): a 16-sided upright cylinder; mass 0 = wood's density.\n"
    << "local function barrel(at, yaw, diameter, height, mass)\n"
    << "  local points = {}\n"
    << "  for k = 0, 15 do\n"
    << "    local a = k / 16 * 2 * math.pi\n"
    << "    local x, z = math.cos(a) * diameter / 2, math.sin(a) * diameter / 2\n"
    << "    points[#points + 1] = {x, 0, z}\n"
    << "    points[#points + 1] = {x, height, z}\n"
    << "  end\n"
    << "  return world.hull{points = points, position = at, rotation = {0, yaw, 0},\n"
    << "                    mass = mass > 0 and mass or nil, density = 600}\n"
    << "end\n\n"
    << "-- Two posts across the way and a trigger between them; the gates count in order.\n"
    << "local function gate(i, g)\n"
    << "  local ax, az = math.cos(g.heading), -math.sin(g.heading)  -- across the way\n"
    << "  for _, side in ipairs({-0.5, 0.5}) do\n"
    << "    local px, pz = g.x + ax * g.width * side, g.z + az * g.width * side\n"
    << "    world.box{type = \"static\", size = {0.3, g.height, 0.3}, position = {px, ground(px, pz) + g.height / 2, pz},\n"
    << "              color = i == #GATES and {0.9, 0.9, 0.9} or {0.95, 0.6, 0.1}}\n"
    << "  end\n"
    << "  trigger.box{center = {g.x, ground(g.x, g.z) + 1.5, g.z}, size = {g.width * 0.75, 4, g.width * 0.75},\n"
    << "    rotation = {0, g.heading, 0},\n"
    << "    on_enter = function(body)\n"
    << "      if finished or not car or body ~= car:body() or i ~= next_gate then return end\n"
    << "      next_gate = next_gate + 1\n"
    << "      if next_gate > #GATES then\n"
    << "        finished = true\n"
    << "        game.message((\"Lap %.2f s\"):format(lap_time), 5)\n"
    << "        game.win((\"lap %.2f s\"):format(lap_time))\n"
    << "      end\n"
    << "    end}\n"
    << "end\n\n"
    << "return {\n"
    << "  title = " << luaString(meta.title) << ",\n"
    << "  duration = 30,\n"
    << "  -- 16-bit heights; spacing, height scale and origin in the .png.json beside\n"
    << "  -- it; the painted layers (texture, bump, friction, sound, softness) too.\n"
    << "  terrain = {heightmap = \"maps/" << scenario << ".png\"},\n"
    << "  params = {\n"
    << "    car = {default = " << luaString(meta.vehicle)
    << ", description = \"the vehicle definition, MOD:NAME (the menu's vehicle picker sets it)\"},\n"
    << "    autopilot = {default = 0, description = \"0: the player drives; 1: the autopilot drives through the gates\"},\n"
    << "    speed = {default = 12, unit = \"m/s\", description = \"the autopilot's cruising speed\"},\n"
    << "  },\n\n"
    << "  on_start = function(ctx)\n"
    << "    environment.set{time_of_day = " << num(meta.sky.timeOfDay_h) << ", weather = " << luaString(meta.sky.weather)
    << ", clouds = " << num(meta.sky.cloudCover) << "}\n";
  for (const auto& [id, o] : meta.objects)
    if (o.kind != PlacedKind::Gate) s << objectLine(id, o);
  s << "    for i, g in ipairs(GATES) do gate(i, g) end\n"
    << "    local waypoints = {}\n"
    << "    for i, g in ipairs(GATES) do waypoints[i] = {g.x, g.z} end\n"
    << "    if #GATES > 0 then hud.set_gates(waypoints) end\n"
    << "    car = vehicle.spawn(param(\"car\"), {position = {START.x, START.y, START.z}, heading = START.heading})\n"
    << "    drive.show(car)\n"
    << "    if param(\"autopilot\") ~= 0 and #GATES > 0 then\n"
    << "      pilot = drive.autopilot(car, {waypoints = waypoints, speed = param(\"speed\"), loop = false, radius = 4})\n"
    << "    else\n"
    << "      player = drive.player(car)\n"
    << "    end\n"
    << "  end,\n\n"
    << "  on_update = function(ctx, dt)\n"
    << "    if not car then return end\n"
    << "    if not finished then lap_time = lap_time + dt end\n"
    << "    if pilot then pilot:update(dt) else player:update(dt) end\n"
    << "    if #GATES > 0 then\n"
    << "      hud.set_lap{time = lap_time, gate = math.min(next_gate, #GATES), gates = #GATES, finished = finished}\n"
    << "    end\n"
    << "  end,\n\n"
    << "  on_finish = function(ctx)\n"
    << "    if not car then return end\n"
    << "    -- Wheels touch only once the world has stepped (contacts come from a step).\n"
    << "    local touching = 0\n"
    << "    for _, w in ipairs(car:telemetry().wheels) do\n"
    << "      if w.contact then touching = touching + 1 end\n"
    << "    end\n"
    << "    expect(\"wheels on the ground at the end\", touching, {min = 3})\n"
    << "    expect(\"car upright at the end (chassis up.y)\", car:body():up().y, {min = 0.5})\n"
    << "    if pilot then expect(\"gates passed in order\", next_gate - 1, {min = #GATES, max = #GATES}) end\n"
    << "  end,\n"
    << "}\n";
  return s.str();
}

std::string manifestLua(const std::string& modName, const std::set<std::string>& usedMods) {
  std::ostringstream s;
  s << "-- " << modName << ": scenarios made in Tumble's scenario designer (docs/designer.md).\n"
    << "return {\n"
    << "  name = " << luaString(modName) << ",\n"
    << "  version = \"1.0.0\",\n"
    << "  title = " << luaString(modName + " (designed in Tumble)") << ",\n"
    << "  api = 1,\n"
    << "  depends = {\"base >= 1.0\"";
  for (const std::string& m : usedMods)
    if (m != "base" && m != modName) s << ", " << luaString(m);
  s << "},\n}\n";
  return s.str();
}

// ---- the design file -------------------------------------------------------------------------

json vec3Json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json designJson(const DesignMeta& meta, const std::string& scenario) {
  json objects = json::array();
  for (const auto& [id, o] : meta.objects)
    objects.push_back({{"id", id},
                       {"kind", placedKindName(o.kind)},
                       {"asset", o.asset},
                       {"position_m", vec3Json(o.position_m)},
                       {"yaw_rad", o.yaw_rad},
                       {"scale", vec3Json(o.scale)},
                       {"collision", o.collision},
                       {"order", o.order},
                       {"mass_kg", o.mass_kg}});
  return {{"format", "tumble-design"},
          {"version", kDesignFormatVersion},
          {"title", meta.title},
          {"vehicle", meta.vehicle},
          {"heightmap", "maps/" + scenario + ".png"},
          {"scenario", "scenarios/" + scenario + ".lua"},
          {"start", {{"position_m", vec3Json(meta.start.position_m)}, {"heading_rad", meta.start.heading_rad}}},
          {"next_id", meta.nextId},
          {"sky", {{"time_of_day_h", meta.sky.timeOfDay_h}, {"weather", meta.sky.weather}, {"clouds", meta.sky.cloudCover}}},
          {"objects", objects}};
}

/// Field readers that name the file and the field in every error.
struct JsonReader {
  std::string file;
  std::string error;

  bool fail(const std::string& field, const std::string& expected) {
    if (error.empty()) error = file + ": field '" + field + "': expected " + expected;
    return false;
  }
  const json* get(const json& obj, const std::string& key, const std::string& field) {
    auto it = obj.find(key);
    if (it == obj.end()) {
      fail(field, "a value (it is missing)");
      return nullptr;
    }
    return &*it;
  }
  bool number(const json& obj, const std::string& key, const std::string& field, double* out) {
    const json* v = get(obj, key, field);
    if (!v) return false;
    if (!v->is_number() || !std::isfinite(v->get<double>())) return fail(field, "a finite number");
    *out = v->get<double>();
    return true;
  }
  bool integer(const json& obj, const std::string& key, const std::string& field, long long lo, long long hi,
               long long* out) {
    const json* v = get(obj, key, field);
    if (!v) return false;
    if (!v->is_number_integer() || v->get<long long>() < lo || v->get<long long>() > hi)
      return fail(field, "a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    *out = v->get<long long>();
    return true;
  }
  bool text(const json& obj, const std::string& key, const std::string& field, std::string* out) {
    const json* v = get(obj, key, field);
    if (!v) return false;
    if (!v->is_string()) return fail(field, "a string");
    *out = v->get<std::string>();
    return true;
  }
  bool vec3(const json& obj, const std::string& key, const std::string& field, Vec3* out) {
    const json* v = get(obj, key, field);
    if (!v) return false;
    if (!v->is_array() || v->size() != 3) return fail(field, "an array of 3 numbers");
    for (int k = 0; k < 3; ++k) {
      if (!(*v)[k].is_number() || !std::isfinite((*v)[k].get<double>())) return fail(field, "an array of 3 finite numbers");
      (*out)[k] = (*v)[k].get<Real>();
    }
    return true;
  }
};

Result<DesignMeta> parseDesign(const std::string& text, const std::string& file, std::string* heightmap) {
  json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return makeError(file + ": not a JSON object (is the file complete?)");
  JsonReader r{file, ""};
  DesignMeta meta;
  std::string format;
  long long version = 0, nextId = 0;
  double heading = 0;
  if (!r.text(j, "format", "format", &format) || format != "tumble-design")
    return makeError(r.error.empty() ? file + ": field 'format': expected \"tumble-design\"" : r.error);
  if (!r.integer(j, "version", "version", 1, kDesignFormatVersion, &version) ||
      !r.text(j, "title", "title", &meta.title) || !r.text(j, "vehicle", "vehicle", &meta.vehicle) ||
      !r.text(j, "heightmap", "heightmap", heightmap) || !r.integer(j, "next_id", "next_id", 1, 0xFFFFFFFFll, &nextId))
    return makeError(r.error);
  meta.nextId = std::uint32_t(nextId);
  const json* start = r.get(j, "start", "start");
  if (!start || !start->is_object()) return makeError(r.error.empty() ? file + ": field 'start': expected an object" : r.error);
  if (!r.vec3(*start, "position_m", "start.position_m", &meta.start.position_m) ||
      !r.number(*start, "heading_rad", "start.heading_rad", &heading))
    return makeError(r.error);
  meta.start.heading_rad = heading;
  if (version >= 2) {
    const json* sky = r.get(j, "sky", "sky");
    if (!sky || !sky->is_object()) return makeError(r.error.empty() ? file + ": field 'sky': expected an object" : r.error);
    if (!r.number(*sky, "time_of_day_h", "sky.time_of_day_h", &meta.sky.timeOfDay_h) ||
        !r.text(*sky, "weather", "sky.weather", &meta.sky.weather) ||
        !r.number(*sky, "clouds", "sky.clouds", &meta.sky.cloudCover))
      return makeError(r.error);
    if (const std::string bad = checkSky(meta.sky); !bad.empty()) return makeError(file + ": field " + bad);
  }
  const json* objects = r.get(j, "objects", "objects");
  if (!objects || !objects->is_array()) return makeError(r.error.empty() ? file + ": field 'objects': expected an array" : r.error);
  for (std::size_t k = 0; k < objects->size(); ++k) {
    const json& o = (*objects)[k];
    const std::string at = "objects[" + std::to_string(k) + "]";
    if (!o.is_object()) return makeError(file + ": field '" + at + "': expected an object");
    long long id = 0, order = 0;
    std::string kind;
    PlacedObject p;
    if (!r.integer(o, "id", at + ".id", 1, 0xFFFFFFFFll, &id) || !r.text(o, "kind", at + ".kind", &kind) ||
        !r.text(o, "asset", at + ".asset", &p.asset) || !r.vec3(o, "position_m", at + ".position_m", &p.position_m) ||
        !r.number(o, "yaw_rad", at + ".yaw_rad", &p.yaw_rad) || !r.vec3(o, "scale", at + ".scale", &p.scale) ||
        !r.text(o, "collision", at + ".collision", &p.collision) ||
        !r.integer(o, "order", at + ".order", -1000000, 1000000, &order) ||
        !r.number(o, "mass_kg", at + ".mass_kg", &p.mass_kg))
      return makeError(r.error);
    bool known = false;
    for (PlacedKind pk : {PlacedKind::Model, PlacedKind::Box, PlacedKind::Barrel, PlacedKind::Ragdoll, PlacedKind::Gate,
                          PlacedKind::Trigger, PlacedKind::Emitter})
      if (kind == placedKindName(pk)) p.kind = pk, known = true;
    if (!known)
      return makeError(file + ": field '" + at + ".kind': \"" + kind +
                       "\" is not one of model, box, barrel, ragdoll, gate, trigger, emitter");
    if (!(p.scale.array() > 0).all()) return makeError(file + ": field '" + at + ".scale': expected 3 numbers > 0");
    if (p.mass_kg < 0) return makeError(file + ": field '" + at + ".mass_kg': expected a mass >= 0 (0: from the size)");
    p.order = int(order);
    if (!meta.objects.emplace(std::uint32_t(id), p).second)
      return makeError(file + ": field '" + at + ".id': " + std::to_string(id) + " is used twice");
    if (std::uint32_t(id) >= meta.nextId) return makeError(file + ": field 'next_id': must be above every object id");
  }
  return meta;
}

// ---- checks before writing ---------------------------------------------------------------------

/// What a saved scenario names must exist: models that load, emitters, the car.
Status checkReferences(const DesignMeta& meta, const script::ModRegistry& registry, const script::ModInfo& self) {
  std::map<std::string, std::string> modDirs;
  for (const script::ModInfo& m : registry.mods()) modDirs[m.name] = m.dir;
  auto definition = [&](const std::string& ref, const char* folder) -> Status {
    const auto colon = ref.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == ref.size())
      return makeError("\"" + ref + "\": expected MOD:NAME, e.g. base:hatchback");
    const std::string mod = ref.substr(0, colon), name = ref.substr(colon + 1);
    auto it = modDirs.find(mod);
    if (it == modDirs.end()) return makeError("\"" + ref + "\": no mod named \"" + mod + "\" is installed");
    if (name.find('/') != std::string::npos || name.find("..") != std::string::npos ||
        !fs::is_regular_file(fs::path(it->second) / folder / (name + ".lua")))
      return makeError("\"" + ref + "\": no " + folder + "/" + name + ".lua in mod " + mod);
    return Ok{};
  };
  if (Status st = definition(meta.vehicle, "vehicles"); !st) return makeError("vehicle " + st.error());
  ModelCache models;
  for (const auto& [id, o] : meta.objects) {
    const std::string what = std::string(placedKindName(o.kind)) + " " + std::to_string(id);
    if (o.kind == PlacedKind::Emitter) {
      if (Status st = definition(o.asset, "emitters"); !st) return makeError(what + ": emitter " + st.error());
    } else if (o.kind == PlacedKind::Model) {
      if (o.collision != "mesh" && o.collision != "box" && o.collision != "none")
        return makeError(what + ": collision \"" + o.collision + "\": expected mesh, box or none");
      auto file = script::resolveModFile(o.asset, self, modDirs);
      if (!file) return makeError(what + ": model " + file.error());
      if (o.collision == "mesh") {
        auto shape = models.meshShape(*file, o.scale);
        if (!shape) return makeError(what + ": model \"" + o.asset + "\" (" + *file + "): " + shape.error());
      } else {
        auto box = models.bounds(*file);
        if (!box) return makeError(what + ": model \"" + o.asset + "\" (" + *file + "): " + box.error());
      }
    }
  }
  return Ok{};
}

struct PendingFile {
  std::string relative;  // inside the mod folder
  std::vector<std::uint8_t> bytes;
};

std::vector<std::uint8_t> toBytes(const std::string& s) { return {s.begin(), s.end()}; }

void removeAllQuiet(const fs::path& p) {
  std::error_code ec;
  fs::remove_all(p, ec);
}

/// Staging folders ".saving-SCENARIO-PID" left by a save whose process died
/// (a crash, a kill) are removed; a live process's folder is left alone.
void removeOrphanedStaging(const fs::path& modDir, const std::string& scenario) {
  const std::string prefix = ".saving-" + scenario + "-";
  std::error_code ec;
  for (auto it = fs::directory_iterator(modDir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string pid = name.substr(prefix.size());
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    if (::kill(pid_t(std::stol(pid)), 0) != 0 && errno == ESRCH) removeAllQuiet(it->path());
  }
}

/// Makes the renames into `dir` durable (as writeFileAtomic does for its own).
void syncFolder(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

// ---- palettes ----------------------------------------------------------------------------------

std::vector<std::string> listModelAssets(const std::vector<std::string>& modFolders) {
  std::vector<std::string> out;
  const script::ModRegistry registry = script::ModRegistry::discover(modFolders);
  for (const script::ModInfo& mod : registry.mods()) {
    const fs::path assets = fs::path(mod.dir) / "assets";
    std::error_code ec;
    if (!fs::is_directory(assets, ec)) continue;
    for (auto it = fs::recursive_directory_iterator(assets, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (it->is_regular_file(ec) && render::hasModelExtension(it->path().string()))
        out.push_back(mod.name + ":" + fs::relative(it->path(), mod.dir, ec).generic_string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> listEmitters(const std::vector<std::string>& modFolders) {
  std::vector<std::string> out;
  const script::ModRegistry registry = script::ModRegistry::discover(modFolders);
  for (const script::ModInfo& mod : registry.mods())
    for (const std::string& name : script::ModRegistry::listLua(mod, "emitters")) out.push_back(mod.name + ":" + name);
  std::sort(out.begin(), out.end());
  return out;
}

// ---- saving ------------------------------------------------------------------------------------

Status DesignDocument::saveAsMod(const std::string& modsDir, const std::string& modName, const std::string& scenario) {
  return saveAsMod(modsDir, modName, scenario, [](const std::string& path, const void* data, std::size_t size) {
    return writeFileAtomic(path, data, size);
  });
}

Status DesignDocument::saveAsMod(const std::string& modsDir, const std::string& modName, const std::string& scenario,
                                 const WriteFileFn& writeFile) {
  endStroke();
  if (Status st = checkName("mod name", modName); !st) return st;
  if (Status st = checkName("scenario name", scenario); !st) return st;
  const fs::path modDir = fs::path(modsDir) / modName;
  std::error_code ec;
  fs::create_directories(modDir, ec);
  if (ec || !fs::is_directory(modDir))
    return makeError(modDir.string() + ": cannot make the mod's folder (" + (ec ? ec.message() : "not a folder") + ")");

  // The mod's manifest: kept if it is there (a modder may have edited it).
  const terrain::Terrain& t = terrain();
  const DesignMeta& meta = this->meta();
  std::set<std::string> usedMods{"base"};
  for (const auto& [id, o] : meta.objects)
    if (auto colon = o.asset.find(':'); colon != std::string::npos) usedMods.insert(o.asset.substr(0, colon));
  std::vector<PendingFile> files;
  script::ModInfo self;
  self.name = modName;
  self.dir = fs::absolute(modDir).string();
  if (fs::exists(modDir / "mod.lua")) {
    auto manifest = script::loadManifest(modDir.string());
    if (!manifest) return makeError((modDir / "mod.lua").string() + ": " + manifest.error() + " (fix it or save under another mod name)");
  } else {
    files.push_back({"mod.lua", toBytes(manifestLua(modName, usedMods))});
  }
  std::vector<std::string> folders = modFolders();
  folders.push_back(modsDir);
  const script::ModRegistry registry = script::ModRegistry::discover(folders);
  if (Status st = checkReferences(meta, registry, self); !st) return makeError("not saved: " + st.error());

  // Encode the maps, the heights on a thread of their own. One filter for
  // every row (Up: the row above) and zlib's run-length matching: on a
  // plasma 4097^2 map 3x faster than the default at 3 % more bytes for the
  // heights, and smaller for the layers (long runs of one material).
  const std::string map = "maps/" + scenario + ".png";
  const terrain::MaterialMaps* mats = t.materials();
  std::vector<std::uint8_t> heightBytes;
  std::string heightError;
  std::thread encoder([&] {
    auto png = terrain::encodePngGrey16(t.heights().samples().data(), t.heights().width(), t.heights().height(), kFastPng);
    if (png) heightBytes.swap(png.value());
    else heightError = png.error();
  });
  std::vector<PendingFile> layers;
  std::string layerError;
  if (mats) {
    for (int l = 0; l < terrain::kMaterialLayerCount && layerError.empty(); ++l) {
      const auto layer = terrain::MaterialLayer(l);
      auto png = terrain::encodePngGrey8(mats->layer(layer).data(), mats->blocksX(), mats->blocksZ(), kFastPng);
      if (png) layers.push_back({materialLayerPath(map, layer), std::move(*png)});
      else layerError = materialLayerPath(map, layer) + ": " + png.error();
    }
  }
  encoder.join();
  if (!layerError.empty()) return makeError(layerError);
  if (!heightError.empty()) return makeError(map + ": " + heightError);
  files.push_back({map, std::move(heightBytes)});
  files.push_back({map + ".json", toBytes(terrain::terrainDescToJson(t.desc()))});
  for (PendingFile& f : layers) files.push_back(std::move(f));
  files.push_back({"scenarios/" + scenario + ".lua", toBytes(scenarioLua(meta, modName, scenario))});
  files.push_back({"designs/" + scenario + ".design.json", toBytes(designJson(meta, scenario).dump(2) + "\n")});

  // 1. Everything into a staging folder.
  const fs::path staging = modDir / (".saving-" + scenario + "-" + std::to_string(::getpid()));
  removeAllQuiet(staging);
  removeOrphanedStaging(modDir, scenario);
  for (const PendingFile& f : files) {
    const fs::path target = staging / f.relative;
    fs::create_directories(target.parent_path(), ec);
    if (ec) {
      removeAllQuiet(staging);
      return makeError((modDir / f.relative).string() + ": not saved, cannot make a folder (" + ec.message() +
                       "); the earlier save is unchanged");
    }
    if (Status st = writeFile(target.string(), f.bytes.data(), f.bytes.size()); !st) {
      removeAllQuiet(staging);
      return makeError((modDir / f.relative).string() + ": not saved (" + st.error() + "); the earlier save is unchanged");
    }
  }
  // 2. The earlier save's files to backup/<scenario>/ (the backup before it is dropped).
  const fs::path backup = modDir / "backup" / scenario;
  std::vector<std::string> backedUp;
  bool anyOld = false;
  for (const PendingFile& f : files) anyOld = anyOld || (f.relative != "mod.lua" && fs::exists(modDir / f.relative));
  auto restore = [&] {
    for (const std::string& rel : backedUp) {
      std::error_code e;
      fs::rename(backup / rel, modDir / rel, e);
    }
  };
  if (anyOld) {
    removeAllQuiet(backup);
    for (const PendingFile& f : files) {
      if (f.relative == "mod.lua" || !fs::exists(modDir / f.relative)) continue;
      fs::create_directories((backup / f.relative).parent_path(), ec);
      if (!ec) fs::rename(modDir / f.relative, backup / f.relative, ec);
      if (ec) {
        restore();
        removeAllQuiet(staging);
        return makeError((backup / f.relative).string() + ": cannot keep the earlier save there (" + ec.message() +
                         "); nothing was changed");
      }
      backedUp.push_back(f.relative);
    }
  }
  // 3. The new files into place.
  std::vector<std::string> placed;
  for (const PendingFile& f : files) {
    fs::create_directories((modDir / f.relative).parent_path(), ec);
    if (!ec) fs::rename(staging / f.relative, modDir / f.relative, ec);
    if (ec) {
      for (const std::string& rel : placed) {
        std::error_code e;
        fs::remove(modDir / rel, e);
      }
      restore();
      removeAllQuiet(staging);
      return makeError((modDir / f.relative).string() + ": cannot put the new file in place (" + ec.message() +
                       "); the earlier save is back");
    }
    placed.push_back(f.relative);
  }
  removeAllQuiet(staging);
  std::set<fs::path> written{modDir};
  for (const PendingFile& f : files) written.insert((modDir / f.relative).parent_path());
  for (const std::string& rel : backedUp) written.insert((backup / rel).parent_path());
  for (const fs::path& dir : written) syncFolder(dir);
  return Ok{};
}

// ---- opening -------------------------------------------------------------------------------------

Result<DesignDocument> DesignDocument::open(const std::string& modDir, const std::string& scenario) {
  if (Status st = checkName("scenario name", scenario); !st) return makeError(st.error());
  const std::string file = (fs::path(modDir) / "designs" / (scenario + ".design.json")).string();
  auto text = readTextFile(file, std::size_t(64) << 20);
  if (!text) return makeError(text.error());
  std::string heightmap;
  auto meta = parseDesign(*text, file, &heightmap);
  if (!meta) return makeError(meta.error());
  // The height map stays inside the mod, as a scenario's terrain.heightmap must.
  const fs::path root = fs::weakly_canonical(fs::path(modDir));
  const fs::path map = fs::weakly_canonical(root / heightmap);
  const fs::path rel = map.lexically_relative(root);
  if (rel.empty() || *rel.begin() == "..")
    return makeError(file + ": field 'heightmap': \"" + heightmap + "\" leaves the mod's folder; paths stay inside it");
  auto loaded = terrain::Terrain::loadPng(map.string());
  if (!loaded) return makeError(file + ": field 'heightmap': " + loaded.error());
  auto t = std::make_unique<terrain::Terrain>(std::move(loaded.value()));
  const terrain::SurfaceMaterial& g = surfacePalette().front().material;
  t->createMaterials({g.texture, g.bump, g.friction, g.sound, g.softness});
  if (Status st = loadMaterialLayersBeside(*t, map.string()); !st) return makeError(file + ": " + st.error());
  return fromParts(std::move(t), std::move(*meta));
}

}  // namespace tumble::app
