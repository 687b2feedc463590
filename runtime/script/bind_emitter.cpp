// Lua table `particles` and type Emitter: particle emitters defined in
// mods/<mod>/emitters/<name>.lua (script/emitter_files.h), spawned at a point
// or attached to a body. The particle system is created by the first spawn,
// so a scenario without emitters has no particle pools.
#include <set>

#include "script/emitter_files.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module particles
/// Particle emitters: dust, smoke, fire, rain, sparks ... Each is defined in
/// a mod's emitters/NAME.lua (fields in docs/emitters.md) and spawned here,
/// at a point or attached to a body. Particles are simulated after physics
/// every step and drawn as camera-facing billboards; they never push bodies.

namespace {

constexpr const char* kEmitterMeta = "tumble.Emitter";

struct EmitterRef {
  std::uint32_t index, generation;
};

particles::EmitterId idOf(const EmitterRef& r) { return particles::EmitterId{r.index, r.generation}; }

EmitterRef* testRef(lua_State* L, int idx) { return static_cast<EmitterRef*>(luaL_testudata(L, idx, kEmitterMeta)); }

// The emitter at idx, refusing anything else and emitters that are gone.
particles::EmitterId checkEmitter(lua_State* L, int idx, const char* fn) {
  EmitterRef* ref = testRef(L, idx);
  if (!ref)
    throw LuaArgError(std::string(fn) + ": expected an Emitter (call methods with a colon, e:stop()), got " +
                      luaL_typename(L, idx));
  particles::ParticleSystem* ps = ScenarioHost::from(L)->scene().particlesIfAny();
  particles::EmitterId id = idOf(*ref);
  if (!ps || !ps->isValid(id))
    throw LuaArgError(std::string(fn) +
                      ": this emitter is gone (removed with :remove(), or stopped and its last particle died); "
                      "e:alive() tells");
  return id;
}

void pushEmitter(lua_State* L, particles::EmitterId id) {
  auto* ref = static_cast<EmitterRef*>(lua_newuserdatauv(L, sizeof(EmitterRef), 0));
  ref->index = id.index;
  ref->generation = id.generation;
  luaL_setmetatable(L, kEmitterMeta);
}

struct Placement {
  Vec3 position = Vec3::Zero();
  physics::BodyId body;
  bool attached = false;
  Vec3 offset = Vec3::Zero();
};

// The `at` table: {position = {x, y, z}} or {body = b, offset = {x, y, z}}.
Placement readPlacement(lua_State* L, int t, const char* fn) {
  if (!lua_istable(L, t))
    throw LuaArgError(std::string(fn) + ": argument 'at' must be a table, {position = {x, y, z}} or {body = b, "
                                        "offset = {x, y, z}}; got " + luaL_typename(L, t));
  checkFields(L, t, std::string(fn) + ": 'at'", {"position", "body", "offset"});
  Placement p;
  try {
    bool hasPosition = optVec3Field(L, t, "position", &p.position);
    optVec3Field(L, t, "offset", &p.offset);
    rawGetField(L, t, "body");
    if (!lua_isnil(L, -1)) {
      p.body = checkBody(L, -1);
      p.attached = true;
    }
    lua_pop(L, 1);
    if (hasPosition && p.attached)
      throw LuaArgError("give either position (a fixed point) or body with an offset, not both");
    if (!hasPosition && !p.attached) throw LuaArgError("needs position = {x, y, z} or body = b");
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  return p;
}

// Emitters alive at once: each costs work every step in C++, outside the
// instruction budget (20 000 made the step take 43 s); 1000 is ten times
// what the busiest base scenario keeps alive.
constexpr int kMaxLiveEmitters = 1000;

particles::EmitterId spawnAt(lua_State* L, const char* fn, int nameIdx, int atIdx, int overridesIdx) {
  ScenarioHost* host = ScenarioHost::from(L);
  if (host->scene().particles().emitterCount() >= kMaxLiveEmitters)
    throw LuaArgError(std::string(fn) + ": " + std::to_string(kMaxLiveEmitters) +
                      " emitters are alive (the emitter limit); remove some (emitter:remove) or reuse them");
  if (lua_type(L, nameIdx) != LUA_TSTRING)
    throw LuaArgError(std::string(fn) + ": argument 'name' must be an emitter name like \"base:dust\", got " +
                      luaL_typename(L, nameIdx));
  const std::string name = lua_tostring(L, nameIdx);
  if (overridesIdx && !lua_isnil(L, overridesIdx) && !lua_istable(L, overridesIdx))
    throw LuaArgError(std::string(fn) + ": argument 'overrides' must be a table of emitter fields, got " +
                      luaL_typename(L, overridesIdx));
  Placement at = readPlacement(L, atIdx, fn);
  auto def = host->emitters().definition(name, overridesIdx && lua_istable(L, overridesIdx) ? overridesIdx : 0);
  if (!def) throw LuaArgError(std::string(fn) + "(\"" + name + "\"): " + def.error());
  particles::ParticleSystem& ps = host->scene().particles();
  Eigen::Vector3f position = at.position.cast<float>();
  Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();
  if (at.attached) {
    const physics::Body& b = host->world().body(at.body);
    rotation = b.orientation.cast<float>();
    position = b.position_m.cast<float>() + rotation * at.offset.cast<float>();
  }
  particles::EmitterId id = ps.create(*def, position, rotation);
  if (at.attached) {
    ps.attach(id, emitterAnchorOf(at.body), at.offset.cast<float>());
    const physics::Body& b = host->world().body(at.body);
    ps.setAnchorState(id, b.position_m.cast<float>(), rotation, b.linearVelocity_mps.cast<float>(),
                      b.angularVelocity_radps.cast<float>());
  }
  return id;
}

/// @class EmitterAt
/// Where an emitter sits: a fixed point, or a body (it then moves and turns
/// with the body, and its `direction` is in the body's frame).
/// @field position? Vec3Arg a fixed point in the world, m
/// @field body? Body the body to attach to
/// @field offset? Vec3Arg with body: the point in the body's frame, m (default its centre)

/// @function particles.spawn
/// Starts an emitter from a definition file. It runs until :stop() (or its
/// `duration` runs out) and :remove(). Fields in `overrides` replace the
/// file's (same names and units, e.g. {rate = 0, color = {1, 0, 0}}).
/// @param name string "mod:name" (mods/<mod>/emitters/<name>.lua), or "name" (this mod, then base)
/// @param at EmitterAt {position = {x, y, z}} or {body = b, offset = {x, y, z}}
/// @param overrides? table emitter fields to change for this emitter
/// @return Emitter the emitter
/// @example local smoke = particles.spawn("base:smoke", {position = {0, 0.5, 0}})
/// @example local dust = particles.spawn("base:dust", {body = car, offset = {0.8, -0.3, 1.2}}, {rate = 0})
/// @example dust:set_rate(40 * slip)   -- per step, from the wheel's slip
int particlesSpawn(lua_State* L) {
  const int overridesIdx = lua_gettop(L) >= 3 && lua_istable(L, 3) ? 3 : 0;
  const particles::EmitterId id = spawnAt(L, "particles.spawn", 1, 2, overridesIdx);
  ScenarioHost* host = ScenarioHost::from(L);
  host->emitters().rememberSource(id, lua_tostring(L, 1), overridesIdx, host->scene().particles());  // for hot reload
  pushEmitter(L, id);
  return 1;
}

/// @function particles.burst
/// A one-shot: `count` particles at once, then the emitter stops and frees
/// itself when they are gone (sparks from an impact). The definition's own
/// rate and bursts are not used.
/// @param name string "mod:name" or "name", as for particles.spawn
/// @param count integer particles to emit (>= 0)
/// @param at EmitterAt where, as for particles.spawn
/// @param overrides? table emitter fields to change
/// @return Emitter the emitter (alive until its last particle dies)
/// @example particles.burst("base:sparks", 40, {position = point})
int particlesBurst(lua_State* L) {
  lua_Integer count = 0;
  if (!lua_isinteger(L, 2) || (count = lua_tointeger(L, 2)) < 0 || count > particles::kMaxParticlesPerEmitter)
    throw LuaArgError("particles.burst: argument 'count' must be an integer 0.." +
                      std::to_string(particles::kMaxParticlesPerEmitter));
  particles::EmitterId id = spawnAt(L, "particles.burst", 1, 3, lua_gettop(L) >= 4 ? 4 : 0);
  particles::ParticleSystem& ps = ScenarioHost::from(L)->scene().particles();
  particles::Emitter* e = ps.get(id);
  e->def.bursts.clear();
  e->rate_per_s = 0;
  ps.burst(id, int(count), /*thenStop=*/true);
  pushEmitter(L, id);
  return 1;
}

/// @function particles.count
/// @return integer live particles of every emitter (0 before the first spawn)
int particlesCount(lua_State* L) {
  particles::ParticleSystem* ps = ScenarioHost::from(L)->scene().particlesIfAny();
  lua_pushinteger(L, ps ? ps->particleCount() : 0);
  return 1;
}

/// @class Emitter
/// A handle returned by particles.spawn / particles.burst. Methods on an
/// emitter that is gone raise an error, except :alive() and :count().

/// @function Emitter:set_rate
/// Particles per second from now on (the fraction carries between steps).
/// @param per_s number rate, 1/s (>= 0)
/// @example dust:set_rate(math.min(60, 80 * slip))
int emitterSetRate(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:set_rate");
  double rate = checkNumber(L, 2, "Emitter:set_rate: argument 'per_s'");
  if (rate < 0 || rate > 1e6) throw LuaArgError("Emitter:set_rate: rate must be 0..1e6 particles per second");
  ScenarioHost::from(L)->scene().particles().setRate(id, float(rate));
  return 0;
}

/// @function Emitter:rate
/// @return number the current rate, particles per second
int emitterRate(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:rate");
  lua_pushnumber(L, ScenarioHost::from(L)->scene().particles().get(id)->rate_per_s);
  return 1;
}

/// @function Emitter:burst
/// n particles at once, born at the start of the next step.
/// @param n integer how many (>= 0)
int emitterBurst(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:burst");
  if (!lua_isinteger(L, 2) || lua_tointeger(L, 2) < 0 || lua_tointeger(L, 2) > particles::kMaxParticlesPerEmitter)
    throw LuaArgError("Emitter:burst: argument 'n' must be an integer 0.." +
                      std::to_string(particles::kMaxParticlesPerEmitter));
  ScenarioHost::from(L)->scene().particles().burst(id, int(lua_tointeger(L, 2)));
  return 0;
}

/// @function Emitter:set_position
/// Moves a free emitter to a world point (particles born during the next
/// step are spread along the way), or, for an attached one, sets its offset
/// in the body's frame.
/// @param p Vec3Arg m
int emitterSetPosition(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:set_position");
  Vec3 p = checkVec3(L, 2, "Emitter:set_position: argument 'p'");
  particles::ParticleSystem& ps = ScenarioHost::from(L)->scene().particles();
  particles::Emitter* e = ps.get(id);
  if (e->anchor != particles::kNoAnchor) e->anchorOffset_m = p.cast<float>();
  else ps.setPose(id, p.cast<float>(), e->rotation);
  return 0;
}

/// @function Emitter:position
/// @return Vec3 where the emitter is now (world, m)
int emitterPosition(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:position");
  pushVec3(L, ScenarioHost::from(L)->scene().particles().get(id)->position_m.cast<Real>());
  return 1;
}

/// @function Emitter:bounds
/// The box around its live particles, in the world (for checks and game
/// logic: how high the smoke went, where the rain ends).
/// @return Vec3? lowest corner, m (nil when it has no particles)
/// @return Vec3? highest corner, m
/// @example local lo, hi = smoke:bounds()
/// @example if hi then hud_text(("smoke top: %.1f m"):format(hi.y)) end
int emitterBounds(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:bounds");
  const particles::Emitter* e = ScenarioHost::from(L)->scene().particles().get(id);
  const particles::ParticlePool& p = e->pool;
  if (p.count == 0) {
    lua_pushnil(L);
    lua_pushnil(L);
    return 2;
  }
  const bool local = e->def.space == particles::SimSpace::Local;
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = -lo;
  for (std::uint32_t i = 0; i < p.count; ++i) {
    Eigen::Vector3f x(p.px[i], p.py[i], p.pz[i]);
    if (local) x = e->rotation * x + e->position_m;
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  pushVec3(L, lo.cast<Real>());
  pushVec3(L, hi.cast<Real>());
  return 2;
}

/// @function Emitter:set_direction
/// The main direction particles fly in: world frame for a free emitter, the
/// body's frame for an attached one.
/// @param d Vec3Arg any non-zero length
int emitterSetDirection(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:set_direction");
  Vec3 d = checkVec3(L, 2, "Emitter:set_direction: argument 'd'");
  if (d.norm() < 1e-6) throw LuaArgError("Emitter:set_direction: the direction must not be zero");
  ScenarioHost::from(L)->scene().particles().setDirection(id, d.cast<float>());
  return 0;
}

/// @function Emitter:stop
/// Stops emitting; live particles finish their lives, then the emitter is gone.
int emitterStop(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:stop");
  ScenarioHost::from(L)->scene().particles().stop(id);
  return 0;
}

/// @function Emitter:remove
/// Removes the emitter and its particles at once.
int emitterRemove(lua_State* L) {
  particles::EmitterId id = checkEmitter(L, 1, "Emitter:remove");
  ScenarioHost::from(L)->scene().particles().remove(id);
  return 0;
}

/// @function Emitter:count
/// @return integer its live particles (0 once it is gone)
int emitterCount(lua_State* L) {
  EmitterRef* ref = testRef(L, 1);
  if (!ref) throw LuaArgError(std::string("Emitter:count: expected an Emitter, got ") + luaL_typename(L, 1));
  particles::ParticleSystem* ps = ScenarioHost::from(L)->scene().particlesIfAny();
  lua_pushinteger(L, ps ? ps->count(idOf(*ref)) : 0);
  return 1;
}

/// @function Emitter:alive
/// @return boolean false once removed, or stopped with no particles left
int emitterAlive(lua_State* L) {
  EmitterRef* ref = testRef(L, 1);
  if (!ref) throw LuaArgError(std::string("Emitter:alive: expected an Emitter, got ") + luaL_typename(L, 1));
  particles::ParticleSystem* ps = ScenarioHost::from(L)->scene().particlesIfAny();
  lua_pushboolean(L, ps && ps->isValid(idOf(*ref)));
  return 1;
}

int emitterToString(lua_State* L) {
  auto* ref = static_cast<EmitterRef*>(luaL_checkudata(L, 1, kEmitterMeta));
  lua_pushfstring(L, "Emitter(%d:%d)", int(ref->index), int(ref->generation));
  return 1;
}

int emitterEq(lua_State* L) {
  EmitterRef* a = testRef(L, 1);
  EmitterRef* b = testRef(L, 2);
  lua_pushboolean(L, a && b && a->index == b->index && a->generation == b->generation);
  return 1;
}

const luaL_Reg kParticles[] = {
    {"spawn", guarded<particlesSpawn>},
    {"burst", guarded<particlesBurst>},
    {"count", guarded<particlesCount>},
    {nullptr, nullptr},
};
const luaL_Reg kMethods[] = {
    {"set_rate", guarded<emitterSetRate>},
    {"rate", guarded<emitterRate>},
    {"burst", guarded<emitterBurst>},
    {"set_position", guarded<emitterSetPosition>},
    {"position", guarded<emitterPosition>},
    {"bounds", guarded<emitterBounds>},
    {"set_direction", guarded<emitterSetDirection>},
    {"stop", guarded<emitterStop>},
    {"remove", guarded<emitterRemove>},
    {"count", guarded<emitterCount>},
    {"alive", guarded<emitterAlive>},
    {nullptr, nullptr},
};

}  // namespace

void openEmitterBindings(lua_State* L, int envIndex) {
  registerType(L, {kEmitterMeta, kMethods, emitterToString, emitterEq});
  registerModule(L, envIndex, "particles", kParticles);
}

}  // namespace tumble::script
