// Lua table `deformable` and type Deformable: ropes and cloth
// (physics/deformable.h), created in the scene's DeformableSystem, stepped
// by the app right after each World::step and drawn as lines.
//
//   local rope = deformable.rope{from = {0, 4, 0}, to = {3, 4, 0}, stiffness = 2e4}
//   local flag = deformable.cloth{origin = {0, 3, 0}, u = {0, -1, 0}, v = {1.5, 0, 0}, wind = {0, 0, 8}}
#include <algorithm>
#include <cmath>

#include "physics/deformable.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module deformable
/// Mass-spring ropes and cloth. Each is stepped with implicit (backward)
/// Euler, one linearised step per substep solved by sparse conjugate
/// gradients (Baraff & Witkin), so stiff springs stay stable at 60 Hz.
/// They collide with the ground, static and kinematic shapes and the
/// terrain (one way: bodies do not feel them), and are drawn as lines.
/// Particle indices start at 1; cloth particle (col, row) is
/// row * columns + col + 1 with col, row from 0 (see Deformable:index).
/// A scene's ropes and cloth together hold at most 16 384 particles x
/// substeps (a 128 x 64 cloth at the default 2 substeps); making one past
/// that is an error, so that no script makes a step take seconds.

namespace {

constexpr const char* kDeformableMeta = "tumble.Deformable";

struct DeformableRef {
  int id;
};

physics::Deformable& checkDeformable(lua_State* L, int idx) {
  auto* ref = static_cast<DeformableRef*>(luaL_testudata(L, idx, kDeformableMeta));
  if (!ref) throw LuaArgError(std::string("expected a Deformable, got ") + luaL_typename(L, idx));
  physics::DeformableSystem* sys = ScenarioHost::from(L)->scene().deformablesIfAny();
  physics::Deformable* d = sys ? sys->get(ref->id) : nullptr;
  if (!d) throw LuaArgError("this Deformable was removed");
  return *d;
}

int checkParticle(lua_State* L, const physics::Deformable& d, int idx, const char* fn) {
  const double i = checkNumber(L, idx, "particle index");
  if (i != std::floor(i) || i < 1 || i > d.particleCount())
    throw LuaArgError(std::string(fn) + ": particle index must be an integer in 1.." + std::to_string(d.particleCount()));
  return int(i) - 1;
}


physics::DeformableMaterial readMaterial(lua_State* L, physics::DeformableMaterial m) {
  m.stiffness_Npm = Real(optNumberField(L, 1, "stiffness", m.stiffness_Npm));
  m.shearStiffness_Npm = Real(optNumberField(L, 1, "shear", m.shearStiffness_Npm));
  m.bendStiffness_Npm = Real(optNumberField(L, 1, "bend", m.bendStiffness_Npm));
  m.damping_Nspm = Real(optNumberField(L, 1, "damping", m.damping_Nspm));
  m.airDrag_Nspm = Real(optNumberField(L, 1, "air_drag", m.airDrag_Nspm));
  m.dragCoefficient = Real(optNumberField(L, 1, "drag", m.dragCoefficient));
  m.airDensity_kgpm3 = Real(optNumberField(L, 1, "air_density", m.airDensity_kgpm3));
  m.friction = Real(optNumberField(L, 1, "friction", m.friction));
  m.radius_m = Real(optNumberField(L, 1, "radius", m.radius_m));
  const double sub = optNumberField(L, 1, "substeps", m.substeps);
  if (sub != std::floor(sub)) throw LuaArgError("field 'substeps' must be an integer in 1..64");
  m.substeps = int(sub);
  return m;
}

// What one step of a scene's ropes and cloth may cost, in particles times
// substeps over all of them: each particle-substep is a block row of a
// conjugate-gradient solve of up to 400 iterations. Measured in a release
// build on the 2-core machine the project runs on: a 128 x 128 cloth at 2
// substeps (32 768) took 0.45 s a step, a 256 x 256 one at 1 substep 0.6 s,
// so the largest cloth at 64 substeps would take some 40 s a step (found by
// the scenario fuzzer as a run that never finished). The cap keeps a step's
// ropes and cloth near a fifth of a second at most.
constexpr long long kMaxParticleSubsteps = 16384;

long long particleSubsteps(const physics::Deformable& d) {
  return (long long)d.particleCount() * std::max(1, d.material().substeps);
}

int pushNew(lua_State* L, Result<std::unique_ptr<physics::Deformable>> made, const char* fn) {
  if (!made) throw LuaArgError(std::string(fn) + ": " + made.error());
  ScenarioHost& host = *ScenarioHost::from(L);
  physics::Deformable& d = *made.value();
  long long total = particleSubsteps(d);
  if (physics::DeformableSystem* sys = host.scene().deformablesIfAny())
    sys->forEach([&](int, const physics::Deformable& other) { total += particleSubsteps(other); });
  if (total > kMaxParticleSubsteps)
    throw LuaArgError(std::string(fn) + ": the scene's ropes and cloth would hold " + std::to_string(total) +
                      " particles x substeps, more than the " + std::to_string(kMaxParticleSubsteps) +
                      " one step may cost; use fewer particles or substeps, or remove a rope or cloth first");
  Vec3 wind = Vec3::Zero();
  if (optVec3Field(L, 1, "wind", &wind)) d.setWind(wind);
  Vec3 color = d.kind() == physics::Deformable::Kind::Rope ? Vec3(0.9f, 0.6f, 0.2f) : Vec3(0.4f, 0.7f, 1.0f);
  optVec3Field(L, 1, "color", &color);
  const int id = host.scene().deformables().add(std::move(made.value()));
  host.presentation().setDeformableColor(id, color.cast<float>());
  auto* ref = static_cast<DeformableRef*>(lua_newuserdatauv(L, sizeof(DeformableRef), 0));
  ref->id = id;
  luaL_setmetatable(L, kDeformableMeta);
  return 1;
}

/// @class RopeDef
/// @field from Vec3Arg first particle (m)
/// @field to Vec3Arg last particle (m)
/// @field segments? integer springs along the rope, 1..4096 (default 20)
/// @field mass? number total mass, kg (default 1)
/// @field stiffness? number each segment's spring, N/m (default 2e4)
/// @field bend? number springs over two segments, N/m (default stiffness / 1000)
/// @field damping? number along each spring, N s/m (default 0.5)
/// @field air_drag? number per particle against the wind-relative velocity, N s/m (default 0.01)
/// @field friction? number against the ground and shapes (default 0.5)
/// @field radius? number collision radius of the particles, m (default 0.02)
/// @field substeps? integer implicit steps per physics step, 1..64 (default 2)
/// @field pin_start? boolean hold the first particle where it is (default true)
/// @field pin_end? boolean hold the last particle where it is (default false)
/// @field wind? Vec3Arg wind velocity, m/s (default none)
/// @field color? Vec3Arg line colour, linear RGB 0..1

/// @function deformable.rope
/// A rope: a chain of springs between equal particles.
/// @param def RopeDef
/// @return Deformable the rope
/// @example local rope = deformable.rope{from = {0, 4, 0}, to = {3, 4, 0}, segments = 30, mass = 1.5}
int ropeNew(lua_State* L) {
  const char* fn = "deformable.rope";
  if (!lua_istable(L, 1)) throw LuaArgError("deformable.rope: expected a table, e.g. deformable.rope{from = {0, 4, 0}, to = {3, 4, 0}}");
  checkFields(L, 1, fn, {"from", "to", "segments", "mass", "stiffness", "bend", "damping", "air_drag", "friction",
                      "radius", "substeps", "pin_start", "pin_end", "wind", "color"});
  physics::RopeDef def;
  try {
    if (!optVec3Field(L, 1, "from", &def.start_m)) throw LuaArgError("field 'from' is required ({x, y, z}, m)");
    if (!optVec3Field(L, 1, "to", &def.end_m)) throw LuaArgError("field 'to' is required ({x, y, z}, m)");
    const double seg = optNumberField(L, 1, "segments", def.segments);
    if (seg != std::floor(seg) || seg < 1 || seg > 4096) throw LuaArgError("field 'segments' must be an integer in 1..4096");
    def.segments = int(seg);
    def.mass_kg = Real(optNumberField(L, 1, "mass", def.mass_kg));
    def.pinStart = optBoolField(L, 1, "pin_start", def.pinStart);
    def.pinEnd = optBoolField(L, 1, "pin_end", def.pinEnd);
    def.material = readMaterial(L, def.material);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  return pushNew(L, physics::Deformable::rope(def), fn);
}

/// @class ClothDef
/// @field origin Vec3Arg the corner particle 1 (m)
/// @field u? Vec3Arg the first row, from origin to its last particle (m, default {2, 0, 0})
/// @field v? Vec3Arg the first column, from origin to its last particle (m, default {0, -1.5, 0})
/// @field columns? integer particles per row, 2..256 (default 16)
/// @field rows? integer particles per column, 2..256 (default 12)
/// @field mass? number total mass, kg (default 0.5)
/// @field stiffness? number structural springs, N/m (default 2e4)
/// @field shear? number diagonal springs, N/m (default stiffness / 4)
/// @field bend? number springs over two particles, N/m (default stiffness / 1000)
/// @field damping? number along each spring, N s/m (default 0.5)
/// @field drag? number pressure drag coefficient per triangle (default 1.2)
/// @field air_density? number kg/m^3 (default 1.2)
/// @field air_drag? number per particle, N s/m (default 0.01)
/// @field friction? number against the ground and shapes (default 0.5)
/// @field radius? number collision radius (thickness), m (default 0.02)
/// @field substeps? integer implicit steps per physics step (default 2)
/// @field pins? string "top" (the first row, default), "corners" (its two ends) or "none"
/// @field wind? Vec3Arg wind velocity, m/s
/// @field color? Vec3Arg line colour, linear RGB 0..1

/// @function deformable.cloth
/// A cloth: a grid of particles with structural, shear and bend springs.
/// @param def ClothDef
/// @return Deformable the cloth
/// @example local flag = deformable.cloth{origin = {0, 4, 0}, u = {0, -1, 0}, v = {1.5, 0, 0}, wind = {0, 0, 8}}
int clothNew(lua_State* L) {
  const char* fn = "deformable.cloth";
  if (!lua_istable(L, 1)) throw LuaArgError("deformable.cloth: expected a table, e.g. deformable.cloth{origin = {0, 3, 0}}");
  checkFields(L, 1, fn, {"origin", "u", "v", "columns", "rows", "mass", "stiffness", "shear", "bend", "damping", "drag",
                      "air_density", "air_drag", "friction", "radius", "substeps", "pins", "wind", "color"});
  physics::ClothDef def;
  try {
    if (!optVec3Field(L, 1, "origin", &def.origin_m)) throw LuaArgError("field 'origin' is required ({x, y, z}, m)");
    optVec3Field(L, 1, "u", &def.edgeU_m);
    optVec3Field(L, 1, "v", &def.edgeV_m);
    const double c = optNumberField(L, 1, "columns", def.columns), r = optNumberField(L, 1, "rows", def.rows);
    if (c != std::floor(c) || r != std::floor(r) || c < 2 || r < 2 || c > 256 || r > 256)
      throw LuaArgError("fields 'columns' and 'rows' must be integers in 2..256");
    def.columns = int(c);
    def.rows = int(r);
    def.mass_kg = Real(optNumberField(L, 1, "mass", def.mass_kg));
    const std::string pins = optStringField(L, 1, "pins", "top");
    if (pins == "top") def.pins = physics::ClothPins::TopEdge;
    else if (pins == "corners") def.pins = physics::ClothPins::TopCorners;
    else if (pins == "none") def.pins = physics::ClothPins::None;
    else throw LuaArgError("field 'pins' must be \"top\", \"corners\" or \"none\", got \"" + pins + "\"");
    def.material = readMaterial(L, def.material);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  return pushNew(L, physics::Deformable::cloth(def), fn);
}

/// @class Deformable
/// A rope or cloth made by deformable.rope / deformable.cloth.

/// @function Deformable:count
/// @return integer the number of particles
int dCount(lua_State* L) {
  lua_pushinteger(L, checkDeformable(L, 1).particleCount());
  return 1;
}

/// @function Deformable:index
/// Cloth particle index from its column and row (both from 0).
/// @param col integer 0..columns-1
/// @param row integer 0..rows-1
/// @return integer the particle index (from 1)
int dIndex(lua_State* L) {
  const physics::Deformable& d = checkDeformable(L, 1);
  const int cols = d.columns(), rows = d.particleCount() / cols;
  const double c = checkNumber(L, 2, "col"), r = checkNumber(L, 3, "row");
  if (c != std::floor(c) || r != std::floor(r) || c < 0 || r < 0 || c >= cols || r >= rows)
    throw LuaArgError("Deformable:index: col must be in 0.." + std::to_string(cols - 1) + " and row in 0.." +
                      std::to_string(rows - 1));
  lua_pushinteger(L, lua_Integer(r) * cols + lua_Integer(c) + 1);
  return 1;
}

/// @function Deformable:position
/// @param i integer particle index (from 1)
/// @return Vec3 its position (m)
int dPosition(lua_State* L) {
  const physics::Deformable& d = checkDeformable(L, 1);
  pushVec3(L, d.position(checkParticle(L, d, 2, "Deformable:position")));
  return 1;
}

/// @function Deformable:velocity
/// @param i integer particle index (from 1)
/// @return Vec3 its velocity (m/s)
int dVelocity(lua_State* L) {
  const physics::Deformable& d = checkDeformable(L, 1);
  pushVec3(L, d.velocity(checkParticle(L, d, 2, "Deformable:velocity")));
  return 1;
}

/// @function Deformable:pin
/// Holds a particle at a world point, or at the point of a body where it is
/// now (it then moves with the body).
/// @param i integer particle index (from 1)
/// @param target Body|Vec3Arg a body or a point (m)
int dPin(lua_State* L) {
  physics::Deformable& d = checkDeformable(L, 1);
  const int i = checkParticle(L, d, 2, "Deformable:pin");
  physics::BodyId body;
  if (testBody(L, 3, &body)) {
    if (!d.pinToBody(i, ScenarioHost::from(L)->world(), checkBody(L, 3)))
      throw LuaArgError("Deformable:pin: the body was removed");
  } else {
    d.pinToPoint(i, checkVec3(L, 3, "Deformable:pin target (a Body or {x, y, z})"));
  }
  return 0;
}

/// @function Deformable:unpin
/// @param i integer particle index (from 1)
/// @return boolean true if it was pinned
int dUnpin(lua_State* L) {
  physics::Deformable& d = checkDeformable(L, 1);
  lua_pushboolean(L, d.unpin(checkParticle(L, d, 2, "Deformable:unpin")));
  return 1;
}

/// @function Deformable:set_wind
/// @param wind Vec3Arg wind velocity (m/s)
int dSetWind(lua_State* L) {
  checkDeformable(L, 1).setWind(checkVec3(L, 2, "wind"));
  return 0;
}

/// @function Deformable:energy
/// Kinetic + gravitational (from y = 0) + spring energy.
/// @return number J
int dEnergy(lua_State* L) {
  lua_pushnumber(L, checkDeformable(L, 1).energy(ScenarioHost::from(L)->world().settings().gravity_mps2));
  return 1;
}

/// @function Deformable:length
/// @return number the summed length of the structural springs now (m)
/// @return number their summed rest length (m)
int dLength(lua_State* L) {
  const physics::Deformable& d = checkDeformable(L, 1);
  lua_pushnumber(L, d.structuralLength());
  lua_pushnumber(L, d.structuralRestLength());
  return 2;
}

/// @function Deformable:lowest
/// @return number the lowest particle surface, min of y - radius (m)
int dLowest(lua_State* L) {
  lua_pushnumber(L, checkDeformable(L, 1).lowestPoint());
  return 1;
}

/// @function Deformable:stats
/// @return table {cg_iterations_max, cg_failures, nan_events, steps}
int dStats(lua_State* L) {
  const physics::DeformableStats& s = checkDeformable(L, 1).stats();
  lua_createtable(L, 0, 4);
  lua_pushinteger(L, s.cgIterationsMax);
  rawSetField(L, -2, "cg_iterations_max");
  lua_pushinteger(L, s.cgFailures);
  rawSetField(L, -2, "cg_failures");
  lua_pushinteger(L, s.nanEvents);
  rawSetField(L, -2, "nan_events");
  lua_pushinteger(L, s.steps);
  rawSetField(L, -2, "steps");
  return 1;
}

/// @function Deformable:remove
/// @return boolean true if it was still there
int dRemove(lua_State* L) {
  auto* ref = static_cast<DeformableRef*>(luaL_testudata(L, 1, kDeformableMeta));
  if (!ref) throw LuaArgError(std::string("expected a Deformable, got ") + luaL_typename(L, 1));
  physics::DeformableSystem* sys = ScenarioHost::from(L)->scene().deformablesIfAny();
  lua_pushboolean(L, sys && sys->remove(ref->id));
  return 1;
}

int dToString(lua_State* L) {
  auto* ref = static_cast<DeformableRef*>(luaL_checkudata(L, 1, kDeformableMeta));
  lua_pushfstring(L, "Deformable(%d)", ref->id);
  return 1;
}

const luaL_Reg kDeformable[] = {
    {"rope", guarded<ropeNew>},
    {"cloth", guarded<clothNew>},
    {nullptr, nullptr},
};
const luaL_Reg kMethods[] = {
    {"count", guarded<dCount>},       {"index", guarded<dIndex>},       {"position", guarded<dPosition>},
    {"velocity", guarded<dVelocity>}, {"pin", guarded<dPin>},           {"unpin", guarded<dUnpin>},
    {"set_wind", guarded<dSetWind>},  {"energy", guarded<dEnergy>},     {"length", guarded<dLength>},
    {"lowest", guarded<dLowest>},     {"stats", guarded<dStats>},       {"remove", guarded<dRemove>},
    {nullptr, nullptr},
};

}  // namespace

void openDeformableBindings(lua_State* L, int envIndex) {
  registerType(L, {kDeformableMeta, kMethods, dToString});
  registerModule(L, envIndex, "deformable", kDeformable);
}

}  // namespace tumble::script
