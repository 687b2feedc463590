// Type HeightMap: a scenario builds its own terrain in Lua with the terrain
// module's generators and filters, the same as `tumble terrain ...` offers,
// deterministic for a seed.
//
// The map exists only while the scenario's `terrain.build(map)` runs, before
// on_start: the app then turns it into the scene's terrain. The userdata
// points at a C++-owned map and is cut loose when build returns, so a map
// kept in a Lua variable can't be used later (a clear error, not a dangling
// pointer). Positions and extents are fractions of the map (0..1, so a
// script works at any size), heights fractions of the terrain's height
// range (`terrain.height`, metres from the lowest to the highest value).
#include "script/terrain_build.h"

#include <cmath>
#include <filesystem>

#include "script/internal/bind_common.h"
#include "terrain/filters.h"
#include "terrain/generators.h"

namespace tumble::script {

/// @module HeightMap
/// The height map a scenario builds in `terrain.build(map)`, before
/// on_start. It starts flat at 0, `terrain.size` samples per side. Positions
/// and extents are fractions of the map (x across its columns, z across its
/// rows, 0..1); heights are fractions of the terrain's height range
/// (`terrain.height` metres from value 0 to value 1). Everything is
/// deterministic for its seeds. --set terrain.heightmap or
/// terrain.generate on the command line replaces the built map.
/// @example terrain = {size = 513, height = 60, build = function(map)
/// @example   map:plasma{seed = 3, roughness = 0.55}
/// @example   map:ridge{from = {0.2, 0.3}, to = {0.8, 0.6}, height = 0.3, width = 0.06, seed = 4}
/// @example   map:smooth(2)
/// @example end}

namespace {

constexpr const char* kHeightMapMeta = "tumble.HeightMap";

struct MapBox {
  terrain::HeightMap* map = nullptr;  // null once build has returned
  std::string modDir;
};

terrain::HeightMap& checkMap(lua_State* L, int idx) {
  auto* box = static_cast<MapBox*>(luaL_testudata(L, idx, kHeightMapMeta));
  if (!box) throw LuaArgError(std::string("expected a HeightMap (call it as map:smooth(), with a colon), got ") +
                              luaL_typename(L, idx));
  if (!box->map) throw LuaArgError("this HeightMap can only be changed inside terrain.build(map)");
  return *box->map;
}

std::uint64_t seedField(lua_State* L, int idx) {
  const double s = optNumberField(L, idx, "seed", 1);
  if (!std::isfinite(s) || s < 0 || s > 9.0e15 || s != std::floor(s))
    throw LuaArgError("seed must be a whole number from 0 to 9e15, got " + std::to_string(s));
  return std::uint64_t(s);
}

double fractionField(lua_State* L, int idx, const char* key, double fallback, double lo, double hi) {
  const double v = optNumberField(L, idx, key, fallback);
  if (!std::isfinite(v) || v < lo || v > hi)
    throw LuaArgError(std::string(key) + " must be a number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                      ", got " + std::to_string(v));
  return v;
}

/// {x, z} as fractions of the map -> sample coordinates.
void pointField(lua_State* L, int idx, const char* key, const terrain::HeightMap& m, double* x, double* z) {
  rawGetField(L, idx, key);
  if (!lua_istable(L, -1)) {
    lua_pop(L, 1);
    throw LuaArgError(std::string(key) + " must be {x, z}, fractions of the map (0..1)");
  }
  lua_rawgeti(L, -1, 1);
  lua_rawgeti(L, -2, 2);
  const double fx = lua_tonumber(L, -2), fz = lua_tonumber(L, -1);
  const bool ok = lua_isnumber(L, -2) && lua_isnumber(L, -1) && std::isfinite(fx) && std::isfinite(fz);
  lua_pop(L, 3);
  if (!ok) throw LuaArgError(std::string(key) + " must be {x, z} with two finite numbers");
  *x = fx * (m.width() - 1);
  *z = fz * (m.height() - 1);
}

void requireTable(lua_State* L, int idx, const char* example) {
  if (!lua_istable(L, idx)) throw LuaArgError(std::string("expected a table, e.g. ") + example);
}

/// @function HeightMap:width
/// Samples across (along X).
/// @return integer
int mapWidth(lua_State* L) {
  lua_pushinteger(L, checkMap(L, 1).width());
  return 1;
}

/// @function HeightMap:height
/// Samples down (along Z).
/// @return integer
int mapHeight(lua_State* L) {
  lua_pushinteger(L, checkMap(L, 1).height());
  return 1;
}

int checkIndex(lua_State* L, int idx, int size, const char* what) {
  const double v = checkNumber(L, idx, what);
  if (v != std::floor(v) || v < 0 || v >= size)
    throw LuaArgError(std::string(what) + " must be a whole number from 0 to " + std::to_string(size - 1) + ", got " +
                      std::to_string(v));
  return int(v);
}

/// @function HeightMap:get
/// Height of one sample, as a fraction of the height range.
/// @param i integer column, 0 .. width - 1
/// @param j integer row, 0 .. height - 1
/// @return number 0..1
int mapGet(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  const int i = checkIndex(L, 2, m.width(), "i"), j = checkIndex(L, 3, m.height(), "j");
  lua_pushnumber(L, m.at(i, j) / 65535.0);
  return 1;
}

std::uint16_t toValue(double h) { return std::uint16_t(std::lround(std::clamp(h, 0.0, 1.0) * 65535.0)); }

/// @function HeightMap:set
/// Sets one sample (clamped to 0..1).
/// @param i integer column
/// @param j integer row
/// @param h number height, fraction of the range
int mapSet(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  const int i = checkIndex(L, 2, m.width(), "i"), j = checkIndex(L, 3, m.height(), "j");
  const double h = checkNumber(L, 4, "h");
  if (!std::isfinite(h)) throw LuaArgError("h must be a finite number (a fraction of the height range)");
  m.set(i, j, toValue(h));
  return 0;
}

/// @function HeightMap:fill
/// Every sample to one height.
/// @param h number fraction of the range (clamped to 0..1)
int mapFill(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  const double h = checkNumber(L, 2, "h");
  if (!std::isfinite(h)) throw LuaArgError("h must be a finite number");
  std::fill(m.samples().begin(), m.samples().end(), toValue(h));
  return 0;
}

// Filters run in C++, outside the instruction count: each charges its work
// to the callback's instruction budget first (one unit per sample it
// touches per pass, about what a Lua instruction costs), so a loop of
// filters is stopped like a loop of Lua.
void chargeFilter(lua_State* L, double samples, const char* fn) {
  if (ScenarioHost* host = ScenarioHost::from(L)) host->chargeWork(L, samples, fn);
}

double samplesOf(const terrain::HeightMap& m) { return double(m.width()) * double(m.height()); }

/// @function HeightMap:plasma
/// Replaces the map with a plasma fractal (diamond-square), normalised to the full range.
/// @param p table {seed = integer, roughness = number (0.01..1; 0.3 rolling, 0.5 natural, 0.7 craggy)}
int mapPlasma(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  if (lua_isnoneornil(L, 2)) lua_newtable(L), lua_replace(L, 2);
  requireTable(L, 2, "map:plasma{seed = 3, roughness = 0.5}");
  terrain::PlasmaParams p;
  p.seed = seedField(L, 2);
  p.roughness = fractionField(L, 2, "roughness", 0.5, 0.01, 1);
  chargeFilter(L, samplesOf(m), "map:plasma");
  m = terrain::generatePlasma(m.width(), m.height(), p);
  return 0;
}

/// @function HeightMap:bump
/// Adds plasma to a rectangle, fading to nothing at its border (no cliff); negative amplitude digs.
/// @param p table {x, z, width, depth: the rectangle (fractions of the map); amplitude: -1..1 of the range; seed; roughness}
int mapBump(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  requireTable(L, 2, "map:bump{x = 0.4, z = 0.4, width = 0.2, depth = 0.2, amplitude = 0.2, seed = 5}");
  const double x = fractionField(L, 2, "x", 0, 0, 1), z = fractionField(L, 2, "z", 0, 0, 1);
  const double w = fractionField(L, 2, "width", 0.25, 0, 1), d = fractionField(L, 2, "depth", 0.25, 0, 1);
  const double amp = fractionField(L, 2, "amplitude", 0.1, -1, 1);
  terrain::PlasmaParams p;
  p.seed = seedField(L, 2);
  p.roughness = fractionField(L, 2, "roughness", 0.5, 0.01, 1);
  chargeFilter(L, samplesOf(m), "map:bump");
  terrain::addPlasmaRegion(m, int(std::lround(x * (m.width() - 1))), int(std::lround(z * (m.height() - 1))),
                           std::max(2, int(std::lround(w * m.width()))), std::max(2, int(std::lround(d * m.height()))),
                           amp * 65535.0, p);
  return 0;
}

/// @function HeightMap:ridge
/// Adds a ridge (or, with a negative height, a ditch) along a midpoint-displaced line.
/// @param p table {from = {x, z}, to = {x, z} (fractions); height: -1..1 of the range; width: half width, fraction of the map's width; jaggedness: sideways wander 0..1; seed}
int mapRidge(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  requireTable(L, 2, "map:ridge{from = {0.2, 0.3}, to = {0.8, 0.6}, height = 0.3, width = 0.05}");
  terrain::RidgeParams r;
  pointField(L, 2, "from", m, &r.fromX, &r.fromZ);
  pointField(L, 2, "to", m, &r.toX, &r.toZ);
  r.height = fractionField(L, 2, "height", 0.2, -1, 1) * 65535.0;
  r.halfWidth = std::max(1.0, fractionField(L, 2, "width", 0.05, 0, 1) * (m.width() - 1));
  r.jaggedness = fractionField(L, 2, "jaggedness", 0.2, 0, 1);
  r.seed = seedField(L, 2);
  chargeFilter(L, samplesOf(m), "map:ridge");
  terrain::addRidge(m, r);
  return 0;
}

/// @function HeightMap:smooth
/// Smooths with the 3 x 3 binomial kernel.
/// Like every filter, its work (one unit per sample per pass) counts
/// against the callback's instruction budget.
/// @param passes? integer 1..64 (default 1)
int mapSmooth(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  const double passes = lua_isnoneornil(L, 2) ? 1 : checkNumber(L, 2, "passes");
  if (passes != std::floor(passes) || passes < 1 || passes > 64)
    throw LuaArgError("passes must be a whole number from 1 to 64");
  chargeFilter(L, samplesOf(m) * passes, "map:smooth");
  m = terrain::smooth(m, int(passes));
  return 0;
}

/// @function HeightMap:sharpen
/// Sharpens with a Laplacian kernel.
/// @param amount? number 0..4 (default 0.5)
int mapSharpen(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  const double amount = lua_isnoneornil(L, 2) ? 0.5 : checkNumber(L, 2, "amount");
  if (!std::isfinite(amount) || amount < 0 || amount > 4) throw LuaArgError("amount must be a number from 0 to 4");
  chargeFilter(L, samplesOf(m), "map:sharpen");
  m = terrain::sharpen(m, amount);
  return 0;
}

/// @function HeightMap:convolve
/// Convolves with a custom square kernel (odd size; weights row by row, normalised by their sum when it is not 0).
/// @param weights table a sequence of size * size numbers (9 for 3 x 3, 25 for 5 x 5, ...)
int mapConvolve(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  requireTable(L, 2, "map:convolve{0, 1, 0, 1, 4, 1, 0, 1, 0}");
  const lua_Integer n = rawLength(L, 2);
  std::vector<double> weights;
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, 2, i);
    const bool ok = lua_isnumber(L, -1);
    const double v = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!ok || !std::isfinite(v)) throw LuaArgError("weight " + std::to_string(i) + " is not a finite number");
    weights.push_back(v);
  }
  double sum = 0;
  for (double w : weights) sum += w;
  if (sum != 0)
    for (double& w : weights) w /= sum;  // a blur keeps heights; a zero-sum (edge) kernel stays as given
  const int size = int(std::lround(std::sqrt(double(weights.size()))));
  auto kernel = terrain::makeKernel(size, weights, "weights");
  if (!kernel) throw LuaArgError(kernel.error());
  chargeFilter(L, samplesOf(m) * double(weights.size()), "map:convolve");
  m = terrain::convolve(m, kernel.value());
  return 0;
}

/// @function HeightMap:resample
/// Bicubic resampling to a new size (corners stay put).
/// @param width integer samples across, 2..4097
/// @param height integer samples down, 2..4097
int mapResample(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  const double w = checkNumber(L, 2, "width"), h = checkNumber(L, 3, "height");
  if (auto st = terrain::checkHeightMapSize(int(w), int(h), "resample"); w != std::floor(w) || h != std::floor(h) || !st)
    throw LuaArgError("resample: width and height must be whole numbers from " +
                      std::to_string(terrain::kMinHeightMapSide) + " to " + std::to_string(terrain::kMaxHeightMapSide));
  chargeFilter(L, w * h * 16, "map:resample");  // 4 x 4 samples per output sample
  m = terrain::resampleBicubic(m, int(w), int(h));
  return 0;
}

/// @function HeightMap:import
/// Replaces the map with an image from the mod's folder (8- or 16-bit grey, or RGB as luminance), at its own size.
/// @param path string inside the mod, e.g. "assets/valley.png"
int mapImport(lua_State* L) {
  terrain::HeightMap& m = checkMap(L, 1);
  auto* box = static_cast<MapBox*>(luaL_testudata(L, 1, kHeightMapMeta));
  const std::string rel = luaL_checkstring(L, 2);
  namespace fs = std::filesystem;
  const fs::path root = fs::weakly_canonical(fs::path(box->modDir));
  const fs::path path = fs::weakly_canonical(root / rel);
  const fs::path inside = path.lexically_relative(root);
  if (inside.empty() || *inside.begin() == "..")
    throw LuaArgError("import: \"" + rel + "\" leaves the mod's folder; paths stay inside it");
  auto loaded = terrain::loadHeightMapPng(path.string());
  if (!loaded) throw LuaArgError("import: " + loaded.error());
  chargeFilter(L, samplesOf(loaded.value()), "map:import");
  m = std::move(loaded.value());
  return 0;
}

const luaL_Reg kMethods[] = {
    {"width", guarded<mapWidth>},     {"height", guarded<mapHeight>},   {"get", guarded<mapGet>},
    {"set", guarded<mapSet>},         {"fill", guarded<mapFill>},       {"plasma", guarded<mapPlasma>},
    {"bump", guarded<mapBump>},       {"ridge", guarded<mapRidge>},     {"smooth", guarded<mapSmooth>},
    {"sharpen", guarded<mapSharpen>}, {"convolve", guarded<mapConvolve>}, {"resample", guarded<mapResample>},
    {"import", guarded<mapImport>},   {nullptr, nullptr},
};

}  // namespace

Result<terrain::HeightMap> buildScenarioTerrain(ScenarioHost& host, int width, int height) {
  if (auto st = terrain::checkHeightMapSize(width, height, "terrain.build"); !st) return makeError(st.error());
  terrain::HeightMap map(width, height);
  lua_State* L = host.luaState();
  if (luaL_getmetatable(L, kHeightMapMeta) == LUA_TNIL) registerType(L, {kHeightMapMeta, kMethods});
  lua_pop(L, 1);
  MapBox* box = nullptr;
  ScriptError err;
  const bool ok = host.callTerrainBuild(
      [&](lua_State* S) {
        box = new (lua_newuserdatauv(S, sizeof(MapBox), 0)) MapBox{&map, host.mod().dir};
        luaL_setmetatable(S, kHeightMapMeta);
      },
      &err);
  // Cut the userdata loose: the map moves to the terrain now. (MapBox holds
  // a std::string; the userdata has no __gc, so release it here.)
  if (box) {
    box->map = nullptr;
    std::string().swap(box->modDir);
  }
  if (!ok) return makeError(err.summary());
  return map;
}

}  // namespace tumble::script
