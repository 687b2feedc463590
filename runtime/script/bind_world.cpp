// Lua table `world`: create bodies, gravity, queries.
//
//   world.box{size = {1, 1, 1}, position = {0, 2, 0}, mass = 1}
//   world.sphere{radius = 0.5, position = {0, 5, 0}, restitution = 0.6}
//   world.capsule{radius = 0.3, length = 1.0, ...}   -- length: core segment, m
//   world.plane{normal = {0, 1, 0}, point = {0, 0, 0}}   -- static ground
//
// Common fields: position {x,y,z} m, rotation {x,y,z} rotation vector (axis
// times angle, rad) or orientation {w=,x=,y=,z=}, velocity m/s,
// angular_velocity rad/s, mass kg (or density kg/m^3), friction,
// restitution (0..1), rolling_resistance (C_rr, e.g. 0.02), linear_damping and angular_damping 1/s,
// type "dynamic" | "static" | "kinematic", color {r,g,b} 0..1, sleep (bool).
// Unknown fields are refused, so a typo is an error, not a silent default.
#include <set>

#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module world
/// The physics world of the scenario: create and remove bodies, set gravity,
/// cast rays. Units are SI (m, kg, s, rad); Y is up and the ground is y = 0.

namespace {

physics::World& worldOf(lua_State* L) { return ScenarioHost::from(L)->world(); }

const std::set<std::string> kCommonFields = {"position", "rotation", "orientation", "velocity", "angular_velocity",
                                             "mass", "density", "friction", "restitution", "rolling_resistance", "linear_damping",
                                             "angular_damping", "type", "color", "sleep"};

void checkFields(lua_State* L, int t, const char* fn, std::initializer_list<const char*> shapeFields) {
  lua_pushnil(L);
  while (lua_next(L, t) != 0) {
    lua_pop(L, 1);  // value
    if (lua_type(L, -1) != LUA_TSTRING) {
      lua_pop(L, 1);
      throw LuaArgError(std::string(fn) + ": fields must be named (key = value)");
    }
    std::string key = lua_tostring(L, -1);
    bool known = kCommonFields.count(key) > 0;
    for (const char* f : shapeFields) known |= key == f;
    if (!known) {
      lua_pop(L, 1);
      std::string valid;
      for (const char* f : shapeFields) valid += std::string(f) + ", ";
      for (const auto& f : kCommonFields) valid += f + ", ";
      valid.resize(valid.size() - 2);
      throw LuaArgError(std::string(fn) + ": unknown field '" + key + "' (valid: " + valid + ")");
    }
  }
}

physics::BodyDef readCommon(lua_State* L, int t, const char* fn) {
  physics::BodyDef d;
  try {
    optVec3Field(L, t, "position", &d.position_m);
    Vec3 rv;
    if (optVec3Field(L, t, "rotation", &rv)) {
      Real angle = rv.norm();
      if (angle > 0) d.orientation = Quat(Eigen::AngleAxis<Real>(angle, rv / angle));
    }
    if (lua_getfield(L, t, "orientation") == LUA_TTABLE) {
      Quat q(Real(optNumberField(L, -1, "w", 1)), Real(optNumberField(L, -1, "x", 0)),
             Real(optNumberField(L, -1, "y", 0)), Real(optNumberField(L, -1, "z", 0)));
      if (q.norm() < Real(1e-6)) throw LuaArgError("field 'orientation': quaternion must not be zero");
      d.orientation = q.normalized();
    }
    lua_pop(L, 1);
    optVec3Field(L, t, "velocity", &d.linearVelocity_mps);
    optVec3Field(L, t, "angular_velocity", &d.angularVelocity_radps);
    d.mass_kg = Real(optNumberField(L, t, "mass", 0));
    if (d.mass_kg < 0) throw LuaArgError("field 'mass' must be >= 0 kg (0 = from density), got " +
                                         std::to_string(d.mass_kg));
    d.density_kgpm3 = Real(optNumberField(L, t, "density", d.density_kgpm3));
    d.friction = Real(optNumberField(L, t, "friction", d.friction));
    d.restitution = Real(optNumberField(L, t, "restitution", d.restitution));
    d.rollingResistance = Real(optNumberField(L, t, "rolling_resistance", d.rollingResistance));
    d.linearDamping_per_s = Real(optNumberField(L, t, "linear_damping", 0));
    d.angularDamping_per_s = Real(optNumberField(L, t, "angular_damping", 0));
    d.allowSleep = optBoolField(L, t, "sleep", true);
    std::string type = optStringField(L, t, "type", "dynamic");
    if (type == "dynamic") d.type = physics::BodyType::Dynamic;
    else if (type == "static") d.type = physics::BodyType::Static;
    else if (type == "kinematic") d.type = physics::BodyType::Kinematic;
    else throw LuaArgError("field 'type' must be \"dynamic\", \"static\" or \"kinematic\", got \"" + type + "\"");
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  return d;
}

Eigen::Vector3f readColor(lua_State* L, int t, const char* fn, const Eigen::Vector3f& fallback) {
  Vec3 c;
  try {
    if (!optVec3Field(L, t, "color", &c)) return fallback;
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what() + " (colour {r, g, b}, each 0..1)");
  }
  return c.cast<float>().cwiseMax(0.0f).cwiseMin(1.0f);
}

int create(lua_State* L, physics::BodyDef d, const char* fn, const Eigen::Vector3f& color) {
  auto r = worldOf(L).createBody(d);
  if (!r) throw LuaArgError(std::string(fn) + ": " + r.error());
  ScenarioHost::from(L)->setColor(*r, color);
  pushBody(L, *r);
  return 1;
}

void checkTable(lua_State* L, const char* fn, const char* example) {
  if (!lua_istable(L, 1))
    throw LuaArgError(std::string(fn) + ": expected a table of fields, e.g. " + fn + example);
}

/// @class BodyDef
/// Fields shared by world.box, world.sphere, world.capsule and world.plane.
/// Unknown fields are refused, so a typo is an error, not a silent default.
/// @field position? Vec3Arg centre of mass, m (default {0, 0, 0})
/// @field rotation? Vec3Arg rotation vector: axis times angle, rad
/// @field orientation? Quat unit quaternion {w=, x=, y=, z=} (instead of rotation)
/// @field velocity? Vec3Arg m/s
/// @field angular_velocity? Vec3Arg rad/s, world frame
/// @field mass? number kg; 0 or absent: from density and volume
/// @field density? number kg/m^3 (default 1000, water)
/// @field friction? number Coulomb coefficient >= 0 (default 0.6); a pair uses sqrt(fa*fb)
/// @field restitution? number 0..1 (default 0); a pair uses the larger
/// @field rolling_resistance? number C_rr, e.g. 0.02 (default 0)
/// @field linear_damping? number 1/s (default 0)
/// @field angular_damping? number 1/s (default 0)
/// @field type? string "dynamic" (default), "static" or "kinematic"
/// @field color? Vec3Arg display colour {r, g, b}, each 0..1
/// @field sleep? boolean may the body fall asleep when at rest (default true)

/// @class BoxDef: BodyDef
/// @field size? Vec3Arg full size along x, y, z, m (default {1, 1, 1})
/// @field half_extents? Vec3Arg half the size, m (instead of size)

/// @class SphereDef: BodyDef
/// @field radius? number m (default 0.5)

/// @class CapsuleDef: BodyDef
/// @field radius? number m (default 0.3)
/// @field length? number length of the core segment along the local Y axis, m (default 1)
/// @field half_height? number half the core segment, m (instead of length)

/// @class PlaneDef: BodyDef
/// @field normal? Vec3Arg the plane's normal (default {0, 1, 0})
/// @field point? Vec3Arg a point on the plane, m (default {0, 0, 0})

/// @function world.box
/// Creates a box.
/// @param def BoxDef size and common body fields
/// @return Body the new body
/// @example local crate = world.box{size = {1, 1, 1}, position = {0, 2, 0}, mass = 10}
int worldBox(lua_State* L) {
  checkTable(L, "world.box", "{size = {1, 1, 1}, position = {0, 2, 0}}");
  checkFields(L, 1, "world.box", {"size", "half_extents"});
  physics::BodyDef d = readCommon(L, 1, "world.box");
  Vec3 size = Vec3::Ones();
  try {
    Vec3 half;
    if (optVec3Field(L, 1, "half_extents", &half)) size = 2 * half;
    optVec3Field(L, 1, "size", &size);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("world.box: ") + e.what());
  }
  d.shape = physics::Shape::box(size / 2);
  return create(L, d, "world.box", readColor(L, 1, "world.box", {0.85f, 0.45f, 0.25f}));
}

/// @function world.sphere
/// Creates a sphere.
/// @param def SphereDef radius and common body fields
/// @return Body the new body
/// @example local ball = world.sphere{radius = 0.5, position = {0, 5, 0}, restitution = 0.8}
int worldSphere(lua_State* L) {
  checkTable(L, "world.sphere", "{radius = 0.5, position = {0, 2, 0}}");
  checkFields(L, 1, "world.sphere", {"radius"});
  physics::BodyDef d = readCommon(L, 1, "world.sphere");
  try {
    d.shape = physics::Shape::sphere(Real(optNumberField(L, 1, "radius", 0.5)));
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("world.sphere: ") + e.what());
  }
  return create(L, d, "world.sphere", readColor(L, 1, "world.sphere", {0.3f, 0.6f, 0.9f}));
}

/// @function world.capsule
/// Creates a capsule: a segment along the local Y axis swept by a sphere.
/// @param def CapsuleDef radius, length and common body fields
/// @return Body the new body
/// @example world.capsule{radius = 0.3, length = 1, position = {0, 2, 0}, rotation = {0, 0, math.pi / 2}}
int worldCapsule(lua_State* L) {
  checkTable(L, "world.capsule", "{radius = 0.3, length = 1, position = {0, 2, 0}}");
  checkFields(L, 1, "world.capsule", {"radius", "length", "half_height"});
  physics::BodyDef d = readCommon(L, 1, "world.capsule");
  try {
    Real r = Real(optNumberField(L, 1, "radius", 0.3));
    Real hh = Real(optNumberField(L, 1, "half_height", 0.5));
    hh = Real(optNumberField(L, 1, "length", 2 * hh)) / 2;
    d.shape = physics::Shape::capsule(r, hh);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("world.capsule: ") + e.what());
  }
  return create(L, d, "world.capsule", readColor(L, 1, "world.capsule", {0.95f, 0.8f, 0.25f}));
}

/// @function world.plane
/// Creates an infinite static plane (the ground). Always static.
/// @param def? PlaneDef normal, point, friction, restitution, color
/// @return Body the new body
/// @example world.plane{}  -- the ground y = 0
int worldPlane(lua_State* L) {
  if (lua_isnoneornil(L, 1)) lua_newtable(L), lua_replace(L, 1);
  checkTable(L, "world.plane", "{normal = {0, 1, 0}, point = {0, 0, 0}}");
  checkFields(L, 1, "world.plane", {"normal", "point"});
  physics::BodyDef d = readCommon(L, 1, "world.plane");
  d.type = physics::BodyType::Static;
  Vec3 n = Vec3::UnitY();
  try {
    optVec3Field(L, 1, "normal", &n);
    optVec3Field(L, 1, "point", &d.position_m);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("world.plane: ") + e.what());
  }
  if (n.norm() < Real(1e-6)) throw LuaArgError("world.plane: field 'normal' must not be zero");
  d.orientation = Quat::FromTwoVectors(Vec3::UnitY(), n.normalized());
  d.shape = physics::Shape::plane();
  return create(L, d, "world.plane", readColor(L, 1, "world.plane", {0.55f, 0.57f, 0.6f}));
}

/// @function world.set_gravity
/// Sets the gravity acceleration for every body.
/// @param g Vec3Arg m/s^2 (default {0, -9.81, 0})
/// @example world.set_gravity{0, -1.62, 0}  -- the Moon
int worldSetGravity(lua_State* L) {
  worldOf(L).settings().gravity_mps2 = checkVec3(L, 1, "world.set_gravity");
  return 0;
}
/// @function world.gravity
/// @return Vec3 the gravity acceleration, m/s^2
int worldGravity(lua_State* L) {
  pushVec3(L, worldOf(L).settings().gravity_mps2);
  return 1;
}
void pushHit(lua_State* L, const physics::RayHit& hit) {
  lua_createtable(L, 0, 4);
  pushBody(L, hit.body);
  lua_setfield(L, -2, "body");
  lua_pushnumber(L, hit.distance_m);
  lua_setfield(L, -2, "distance");
  pushVec3(L, hit.point_m);
  lua_setfield(L, -2, "point");
  pushVec3(L, hit.normal);
  lua_setfield(L, -2, "normal");
}

/// @class RayHit
/// @field body Body the body hit
/// @field distance number from the origin along the ray, m
/// @field point Vec3Arg where the ray hit, m
/// @field normal Vec3Arg surface normal at the hit (unit)

/// @function world.raycast
/// The closest body along a ray.
/// @param origin Vec3Arg start of the ray, m
/// @param dir Vec3Arg direction (need not be unit, must not be zero)
/// @param max_distance? number m (default 1000)
/// @return RayHit? the nearest hit, or nil
/// @example local hit = world.raycast({0, 10, 0}, {0, -1, 0})
/// @example if hit then print("ground at", hit.point.y) end
int worldRaycast(lua_State* L) {
  Vec3 o = checkVec3(L, 1, "world.raycast origin");
  Vec3 dir = checkVec3(L, 2, "world.raycast direction");
  double maxd = lua_isnoneornil(L, 3) ? 1000.0 : checkNumber(L, 3, "world.raycast max_distance");
  if (dir.norm() == 0) throw LuaArgError("world.raycast: direction must not be zero");
  physics::RayHit hit;
  if (!worldOf(L).rayCast(o, dir, Real(maxd), &hit)) {
    lua_pushnil(L);
    return 1;
  }
  pushHit(L, hit);
  return 1;
}
/// @function world.bodies
/// @return Body[] every body in the world, in creation-slot order
int worldBodies(lua_State* L) {
  lua_createtable(L, worldOf(L).bodyCount(), 0);
  int i = 0;
  worldOf(L).forEachBody([&](physics::BodyId id, const physics::Body&) {
    pushBody(L, id);
    lua_rawseti(L, -2, ++i);
  });
  return 1;
}
/// @function world.body_count
/// @return integer the number of bodies
int worldBodyCount(lua_State* L) {
  lua_pushinteger(L, worldOf(L).bodyCount());
  return 1;
}
/// @function world.energy
/// @return number kinetic plus gravitational potential energy of the dynamic bodies, J
int worldEnergy(lua_State* L) {
  lua_pushnumber(L, worldOf(L).totalEnergy());
  return 1;
}

/// @function world.raycast_all
/// Every body along a ray, nearest first.
/// @param origin Vec3Arg start of the ray, m
/// @param dir Vec3Arg direction (need not be unit, must not be zero)
/// @param max_distance? number m (default 1000)
/// @return RayHit[] the hits, nearest first (empty if none)
/// @example for _, hit in ipairs(world.raycast_all({-10, 1, 0}, {1, 0, 0})) do print(hit.body, hit.distance) end
int worldRaycastAll(lua_State* L) {
  Vec3 o = checkVec3(L, 1, "world.raycast_all origin");
  Vec3 dir = checkVec3(L, 2, "world.raycast_all direction");
  double maxd = lua_isnoneornil(L, 3) ? 1000.0 : checkNumber(L, 3, "world.raycast_all max_distance");
  if (dir.norm() == 0) throw LuaArgError("world.raycast_all: direction must not be zero");
  if (maxd < 0) throw LuaArgError("world.raycast_all: max_distance must be >= 0 m");
  std::vector<physics::RayHit> hits = worldOf(L).rayCastAll(o, dir, Real(maxd));
  lua_createtable(L, int(hits.size()), 0);
  for (std::size_t i = 0; i < hits.size(); ++i) {
    pushHit(L, hits[i]);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  return 1;
}

/// @function world.remove
/// Removes a body from the world; its handles become invalid (body:is_valid()
/// is false). Removing a body that is already gone does nothing.
/// @param body Body the body to remove
/// @return boolean true if the body was removed now, false if it was already gone
/// @example world.remove(crate)
int worldRemove(lua_State* L) {
  physics::BodyId id;
  if (!testBody(L, 1, &id)) throw LuaArgError(std::string("world.remove: expected a Body, got ") + luaL_typename(L, 1));
  lua_pushboolean(L, worldOf(L).destroyBody(id));
  return 1;
}

const luaL_Reg kWorld[] = {
    {"box", guarded<worldBox>},
    {"sphere", guarded<worldSphere>},
    {"capsule", guarded<worldCapsule>},
    {"plane", guarded<worldPlane>},
    {"set_gravity", guarded<worldSetGravity>},
    {"gravity", guarded<worldGravity>},
    {"raycast", guarded<worldRaycast>},
    {"raycast_all", guarded<worldRaycastAll>},
    {"remove", guarded<worldRemove>},
    {"bodies", guarded<worldBodies>},
    {"body_count", guarded<worldBodyCount>},
    {"energy", guarded<worldEnergy>},
    {nullptr, nullptr},
};

}  // namespace

void openWorldBindings(lua_State* L, int envIndex) {
  luaL_newlib(L, kWorld);
  lua_setfield(L, envIndex, "world");
}

}  // namespace tumble::script
