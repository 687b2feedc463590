// Lua table `world`: create bodies, gravity, queries.
//
//   world.box{size = {1, 1, 1}, position = {0, 2, 0}, mass = 1}
//   world.sphere{radius = 0.5, position = {0, 5, 0}, restitution = 0.6}
//   world.capsule{radius = 0.3, length = 1.0, ...}   -- length: core segment, m
//   world.plane{normal = {0, 1, 0}, point = {0, 0, 0}}   -- static ground
//   world.hull{points = {{0,0,0}, {1,0,0}, {0,1,0}, {0,0,1}}, ...}   -- convex hull of the points
//   world.compound{children = {{shape = "box", size = {2, 0.2, 0.2}}, ...}, ...}
//   world.overlap{shape = "sphere", radius = 1, position = {...}}      -- bodies inside
//   world.shape_cast{shape = "sphere", radius = 0.3, position = {...}, direction = {0, -1, 0}}
//
// Common fields: position {x,y,z} m, rotation {x,y,z} rotation vector (axis
// times angle, rad) or orientation {w=,x=,y=,z=}, velocity m/s,
// angular_velocity rad/s, mass kg (or density kg/m^3), friction,
// restitution (0..1), rolling_resistance (C_rr, e.g. 0.02), linear_damping and angular_damping 1/s,
// type "dynamic" | "static" | "kinematic", color {r,g,b} 0..1, sleep (bool).
// Unknown fields are refused, so a typo is an error, not a silent default.
#include <optional>
#include <set>
#include <vector>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module world
/// The physics world of the scenario: create and remove bodies, set gravity,
/// cast rays. Units are SI (m, kg, s, rad); Y is up and the ground is y = 0.

namespace {

physics::World& worldOf(lua_State* L) { return ScenarioHost::from(L)->world(); }

const std::set<std::string> kCommonFields = {"position", "rotation", "orientation", "velocity", "angular_velocity",
                                             "mass", "density", "friction", "restitution", "rolling_resistance", "linear_damping",
                                             "angular_damping", "type", "color", "sleep", "inertia", "center_of_mass"};

// A body definition's fields: the common ones and the shape's own.
void checkBodyFields(lua_State* L, int t, const char* fn, std::initializer_list<const char*> shapeFields) {
  std::set<std::string> allowed = kCommonFields;
  allowed.insert(shapeFields.begin(), shapeFields.end());
  checkFields(L, t, fn, allowed);
}

physics::BodyDef readCommon(lua_State* L, int t, const char* fn) {
  physics::BodyDef d;
  try {
    optVec3Field(L, t, "position", &d.position_m);
    d.orientation = optRotationField(L, t);
    if (rawGetField(L, t, "orientation") == LUA_TTABLE) {
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

/// The definition's `inertia` field, checked: principal moments of a real
/// rigid body (finite, > 0, each at most the sum of the other two).
std::optional<Vec3> readInertia(lua_State* L, int t, const char* fn, const physics::BodyDef& d) {
  Vec3 I;
  try {
    if (!optVec3Field(L, t, "inertia", &I)) return std::nullopt;
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what() + " (principal moments {Ixx, Iyy, Izz}, kg m^2)");
  }
  const std::string got = " {" + std::to_string(I.x()) + ", " + std::to_string(I.y()) + ", " + std::to_string(I.z()) + "}";
  if (d.type != physics::BodyType::Dynamic)
    throw LuaArgError(std::string(fn) + ": field 'inertia' is for dynamic bodies (static and kinematic ones do not turn under forces)");
  if (!I.allFinite() || (I.array() <= 0).any())
    throw LuaArgError(std::string(fn) + ": field 'inertia' must be three finite moments > 0 kg m^2 {Ixx, Iyy, Izz}, got" + got);
  const char* axis[] = {"Ixx", "Iyy", "Izz"};
  for (int k = 0; k < 3; ++k) {
    const Real others = I[(k + 1) % 3] + I[(k + 2) % 3];
    if (I[k] > Real(1.0001) * others)
      throw LuaArgError(std::string(fn) + ": field 'inertia': " + axis[k] + " is larger than the sum of the other two" + got +
                        " (the triangle inequality every rigid body's principal moments satisfy)");
  }
  return I;
}

/// The definition's `center_of_mass` field: the centre of mass in the frame
/// the definition's position and rotation place (the shape's frame; for a
/// hull or compound the frame its points or children are given in, whose
/// own centre of mass `frame` gives). Moves the shape so the body's origin
/// is there (physics::offsetCentreOfMass), and the body with it.
void applyCentreOfMass(lua_State* L, int t, const char* fn, physics::BodyDef& d, const physics::ShapeFrame& frame) {
  Vec3 c;
  try {
    if (!optVec3Field(L, t, "center_of_mass", &c)) return;
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what() + " (the centre of mass {x, y, z} in the shape's frame, m)");
  }
  if (d.type != physics::BodyType::Dynamic)
    throw LuaArgError(std::string(fn) + ": field 'center_of_mass' is for dynamic bodies (static and kinematic ones are not moved by forces)");
  const Vec3 offset = frame.rotation.conjugate() * (c - frame.centre_m);
  auto shape = physics::offsetCentreOfMass(d.shape, offset);
  if (!shape) throw LuaArgError(std::string(fn) + ": field 'center_of_mass': " + shape.error());
  d.shape = shape.value();
  d.position_m += d.orientation * offset;
}

int create(lua_State* L, physics::BodyDef d, const char* fn, const Eigen::Vector3f& color,
           const physics::ShapeFrame& frame = {}) {
  if (lua_istable(L, 1)) applyCentreOfMass(L, 1, fn, d, frame);
  const std::optional<Vec3> inertia = lua_istable(L, 1) ? readInertia(L, 1, fn, d) : std::nullopt;
  ScenarioHost::from(L)->countBodiesCreated(1, fn);
  auto r = worldOf(L).createBody(d);
  if (!r) throw LuaArgError(std::string(fn) + ": " + r.error());
  if (inertia) {
    if (Status s = worldOf(L).setPrincipalInertia(*r, *inertia); !s) {
      worldOf(L).destroyBody(*r);
      throw LuaArgError(std::string(fn) + ": field 'inertia': " + s.error());
    }
  }
  ScenarioHost::from(L)->presentation().setColor(*r, color);
  pushBody(L, *r);
  return 1;
}

void checkTable(lua_State* L, const char* fn, const char* example) {
  if (!lua_istable(L, 1))
    throw LuaArgError(std::string(fn) + ": expected a table of fields, e.g. " + fn + example);
}

/// @class BodyDef
/// Fields shared by world.box, world.sphere, world.capsule, world.cylinder and world.plane.
/// Unknown fields are refused, so a typo is an error, not a silent default.
/// @field position? Vec3Arg the shape's centre, m (default {0, 0, 0}); the body's centre of mass unless center_of_mass moves it
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
/// @field inertia? Vec3Arg principal moments of inertia {Ixx, Iyy, Izz} about the body's own axes through its centre of mass, kg m^2 (default: from the shape and mass); each > 0 and at most the sum of the other two; dynamic bodies only
/// @field center_of_mass? Vec3Arg the centre of mass in the shape's own frame, m (default: the shape's centroid, uniform density): ballast low in a boat, a weighted toy. Inside the shape; the principal moments (computed or given by inertia) are taken about it; body:position() then reports it; dynamic bodies only

/// @class BoxDef: BodyDef
/// @field size? Vec3Arg full size along x, y, z, m (default {1, 1, 1})
/// @field half_extents? Vec3Arg half the size, m (instead of size)

/// @class SphereDef: BodyDef
/// @field radius? number m (default 0.5)

/// @class CapsuleDef: BodyDef
/// @field radius? number m (default 0.3)
/// @field length? number length of the core segment along the local Y axis, m (default 1)
/// @field half_height? number half the core segment, m (instead of length)

/// @class CylinderDef: BodyDef
/// @field radius? number m (default 0.3)
/// @field height? number full height along the local Y axis, cap to cap, m (default 1)
/// @field half_height? number half the height, m (instead of height)

/// @class PlaneDef: BodyDef
/// @field normal? Vec3Arg the plane's normal (default {0, 1, 0})
/// @field point? Vec3Arg a point on the plane, m (default {0, 0, 0})
/// @field texture? string what is drawn on it: "checker" (default, 1 m squares in color, for lab scenes) or a ground texture of the terrain's, tinted by color (default white): "grass", "rock", "sand", "mud", "snow", "gravel", "dirt", "moss". Drawn only: physics ignores it

/// @function world.box
/// Creates a box.
/// @param def BoxDef size and common body fields
/// @return Body the new body
/// @example local crate = world.box{size = {1, 1, 1}, position = {0, 2, 0}, mass = 10}
int worldBox(lua_State* L) {
  checkTable(L, "world.box", "{size = {1, 1, 1}, position = {0, 2, 0}}");
  checkBodyFields(L, 1, "world.box", {"size", "half_extents"});
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
  checkBodyFields(L, 1, "world.sphere", {"radius"});
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
  checkBodyFields(L, 1, "world.capsule", {"radius", "length", "half_height"});
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

/// @function world.cylinder
/// Creates a solid cylinder: its axis is the local Y axis, flat caps at +-height / 2.
/// @param def CylinderDef radius, height and common body fields
/// @return Body the new body
/// @example world.cylinder{radius = 0.4, height = 0.3, position = {0, 2, 0}, rotation = {math.pi / 2, 0, 0}}
int worldCylinder(lua_State* L) {
  checkTable(L, "world.cylinder", "{radius = 0.3, height = 1, position = {0, 2, 0}}");
  checkBodyFields(L, 1, "world.cylinder", {"radius", "height", "half_height"});
  physics::BodyDef d = readCommon(L, 1, "world.cylinder");
  try {
    const Real r = Real(optNumberField(L, 1, "radius", 0.3));
    Real hh = Real(optNumberField(L, 1, "half_height", 0.5));
    hh = Real(optNumberField(L, 1, "height", 2 * hh)) / 2;
    d.shape = physics::Shape::cylinder(r, hh);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("world.cylinder: ") + e.what());
  }
  return create(L, d, "world.cylinder", readColor(L, 1, "world.cylinder", {0.45f, 0.75f, 0.45f}));
}

/// @function world.plane
/// Creates an infinite static plane (the ground). Always static.
/// @param def? PlaneDef normal, point, friction, restitution, color
/// @return Body the new body
/// @example world.plane{}  -- the ground y = 0
int worldPlane(lua_State* L) {
  if (lua_isnoneornil(L, 1)) lua_newtable(L), lua_replace(L, 1);
  checkTable(L, "world.plane", "{normal = {0, 1, 0}, point = {0, 0, 0}}");
  checkBodyFields(L, 1, "world.plane", {"normal", "point", "texture"});
  // The ground textures in render::DrawShape::groundTexture's order.
  static const char* const kTextures[] = {"grass", "rock", "sand", "mud", "snow", "gravel", "dirt", "moss"};
  int texture = -1;
  if (rawGetField(L, 1, "texture") != LUA_TNIL) {
    const bool isString = lua_type(L, -1) == LUA_TSTRING;
    const std::string name = isString ? lua_tostring(L, -1) : "";
    for (int i = 0; i < int(std::size(kTextures)); ++i)
      if (name == kTextures[i]) texture = i;
    if (texture < 0 && name != "checker") {
      const std::string got = isString ? "\"" + (name.size() > 40 ? name.substr(0, 40) + "..." : name) + "\""
                                       : std::string(luaL_typename(L, -1));
      lua_pop(L, 1);
      throw LuaArgError("world.plane: field 'texture' must be \"checker\", \"grass\", \"rock\", \"sand\", \"mud\", "
                        "\"snow\", \"gravel\", \"dirt\" or \"moss\", got " + got);
    }
  }
  lua_pop(L, 1);
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
  const Eigen::Vector3f color = readColor(L, 1, "world.plane", texture >= 0 ? Eigen::Vector3f(1, 1, 1) : Eigen::Vector3f(0.55f, 0.57f, 0.6f));
  create(L, d, "world.plane", color);
  ScenarioHost::from(L)->presentation().setGroundTexture(checkBody(L, -1), texture);
  return 1;
}

/// Points {{x, y, z}, ...} of field `key` of the table at t.
std::vector<Vec3> readPoints(lua_State* L, int t, const char* key) {
  std::vector<Vec3> points;
  if (rawGetField(L, t, key) != LUA_TTABLE) {
    lua_pop(L, 1);
    throw LuaArgError(std::string("field '") + key + "' must be a list of at least 4 points {{x, y, z}, ...}");
  }
  const lua_Integer n = rawLength(L, -1);
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    const std::string what = std::string("field '") + key + "', point " + std::to_string(i);
    try {
      points.push_back(checkVec3(L, -1, what.c_str()));
    } catch (...) {
      lua_pop(L, 2);
      throw;
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return points;
}

/// The shape described by the table at t (field `shape` = "box", "sphere",
/// "capsule" or "hull" and that shape's size fields), with where its body
/// frame sits in the table's frame (hulls: centroid and principal axes).
physics::Shape readShapeDef(lua_State* L, int t, physics::ShapeFrame* frame) {
  *frame = {};
  const std::string kind = optStringField(L, t, "shape", "");
  if (kind == "box") {
    Vec3 size = Vec3::Ones(), half;
    if (optVec3Field(L, t, "half_extents", &half)) size = 2 * half;
    optVec3Field(L, t, "size", &size);
    return physics::Shape::box(size / 2);
  }
  if (kind == "sphere") return physics::Shape::sphere(Real(optNumberField(L, t, "radius", 0.5)));
  if (kind == "capsule") {
    Real hh = Real(optNumberField(L, t, "half_height", 0.5));
    hh = Real(optNumberField(L, t, "length", 2 * hh)) / 2;
    return physics::Shape::capsule(Real(optNumberField(L, t, "radius", 0.3)), hh);
  }
  if (kind == "cylinder") {
    Real hh = Real(optNumberField(L, t, "half_height", 0.5));
    hh = Real(optNumberField(L, t, "height", 2 * hh)) / 2;
    return physics::Shape::cylinder(Real(optNumberField(L, t, "radius", 0.3)), hh);
  }
  if (kind == "hull") {
    auto hull = physics::makeHullShape(readPoints(L, t, "points"), frame);
    if (!hull) throw LuaArgError(hull.error());
    return hull.value();
  }
  throw LuaArgError("field 'shape' must be \"box\", \"sphere\", \"capsule\", \"cylinder\" or \"hull\", got \"" + kind +
                    "\"");
}

/// Optional pose fields position / rotation of the table at t.
void readPose(lua_State* L, int t, Vec3* p, Quat* q) {
  *p = Vec3::Zero();
  *q = Quat::Identity();
  optVec3Field(L, t, "position", p);
  Vec3 rv;
  if (optVec3Field(L, t, "rotation", &rv) && rv.norm() > 0) *q = Quat(Eigen::AngleAxis<Real>(rv.norm(), rv.normalized()));
}

// A shape description's fields (world.compound children, query shapes) and `extra`.
void checkShapeFields(lua_State* L, int t, const std::string& fn, std::initializer_list<const char*> extra) {
  std::set<std::string> allowed = {"shape", "size", "half_extents", "radius", "length", "height", "half_height", "points",
                                   "position", "rotation"};
  allowed.insert(extra.begin(), extra.end());
  checkFields(L, t, fn, allowed);
}

/// Placed body frame from a pose of the given frame and the shape's own frame.
void placeBody(physics::BodyDef& d, const physics::ShapeFrame& frame) {
  d.position_m = d.position_m + d.orientation * frame.centre_m;
  d.orientation = (d.orientation * frame.rotation).normalized();
}

void refuseZeroMass(lua_State* L, const char* fn) {
  if (rawGetField(L, 1, "mass") != LUA_TNIL) {
    const double m = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!(m > 0)) throw LuaArgError(std::string(fn) + ": field 'mass' must be > 0 kg (leave it out to use density)");
    return;
  }
  lua_pop(L, 1);
}

/// @class HullDef: BodyDef
/// The body's centre of mass is the hull's centroid: position and rotation
/// place the frame the points are given in, and body:position() then reports
/// where the centroid went.
/// @field points Vec3Arg[] 4 to 4096 points, not all on one plane, m; the hull is their convex hull

/// @class ShapeDef
/// A shape with its pose: a compound's child (pose relative to the compound's
/// frame) or the shape of a query (pose in the world).
/// @field shape string "box", "sphere", "capsule", "cylinder" or "hull"
/// @field size? Vec3Arg box: full size, m (default {1, 1, 1})
/// @field half_extents? Vec3Arg box: half size, m (instead of size)
/// @field radius? number sphere (default 0.5), capsule or cylinder (default 0.3) radius, m
/// @field length? number capsule: core segment along local Y, m (default 1)
/// @field height? number cylinder: cap to cap along local Y, m (default 1)
/// @field half_height? number capsule: half the core segment; cylinder: half the height, m
/// @field points? Vec3Arg[] hull: at least 4 points spanning a volume, m
/// @field position? Vec3Arg the shape's origin, m (default {0, 0, 0})
/// @field rotation? Vec3Arg rotation vector (axis times angle), rad

/// @class CompoundDef: BodyDef
/// One rigid body made of several shapes. Mass spreads over the children at
/// one density; the centre of mass and principal axes are computed, so
/// body:position() is the centre of mass, not the frame origin the children
/// were given in (that frame is placed by position / rotation).
/// @field children ShapeDef[] 1 to 64 children (box, sphere, capsule, cylinder, hull)

/// @function world.hull
/// Creates a convex hull of a point cloud (rocks, wedges, dice, tops).
/// Refused with a clear error: fewer than 4 or more than 4096 points, points
/// all on one plane or line, non-finite coordinates, mass = 0.
/// @param def HullDef points and common body fields
/// @return Body the new body
/// @example local wedge = world.hull{points = {{0,0,0}, {2,0,0}, {0,0,1}, {2,0,1}, {0,1,0}, {0,1,1}}, position = {0, 1, 0}}
int worldHull(lua_State* L) {
  checkTable(L, "world.hull", "{points = {{0,0,0}, {1,0,0}, {0,1,0}, {0,0,1}}, position = {0, 2, 0}}");
  checkBodyFields(L, 1, "world.hull", {"points"});
  physics::BodyDef d = readCommon(L, 1, "world.hull");
  refuseZeroMass(L, "world.hull");
  physics::ShapeFrame frame;
  try {
    auto hull = physics::makeHullShape(readPoints(L, 1, "points"), &frame);
    if (!hull) throw LuaArgError(hull.error());
    d.shape = hull.value();
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("world.hull: ") + e.what());
  }
  placeBody(d, frame);
  return create(L, d, "world.hull", readColor(L, 1, "world.hull", {0.6f, 0.55f, 0.5f}), frame);
}

/// @function world.compound
/// Creates one rigid body from several child shapes at fixed poses.
/// @param def CompoundDef children and common body fields
/// @return Body the new body
/// @example local t = world.compound{children = {{shape = "box", size = {2, 0.2, 0.2}}, {shape = "capsule", radius = 0.1, length = 0.8, position = {0, 0, 0.6}, rotation = {math.pi / 2, 0, 0}}}, position = {0, 2, 0}}
int worldCompound(lua_State* L) {
  checkTable(L, "world.compound", "{children = {{shape = \"box\", size = {1, 1, 1}}}, position = {0, 2, 0}}");
  checkBodyFields(L, 1, "world.compound", {"children"});
  physics::BodyDef d = readCommon(L, 1, "world.compound");
  refuseZeroMass(L, "world.compound");
  if (rawGetField(L, 1, "children") != LUA_TTABLE)
    throw LuaArgError("world.compound: field 'children' must be a list of shapes {{shape = \"box\", ...}, ...}");
  std::vector<physics::CompoundChild> children;
  const lua_Integer n = rawLength(L, -1);
  for (lua_Integer i = 1; i <= n; ++i) {
    const std::string who = "world.compound: child " + std::to_string(i);
    if (lua_rawgeti(L, -1, i) != LUA_TTABLE) throw LuaArgError(who + ": expected a table {shape = \"box\", ...}");
    const int t = lua_absindex(L, -1);
    physics::CompoundChild c;
    try {
      checkShapeFields(L, t, who, {});
      physics::ShapeFrame frame;
      c.shape = readShapeDef(L, t, &frame);
      readPose(L, t, &c.position_m, &c.orientation);
      c.position_m += c.orientation * frame.centre_m;
      c.orientation = c.orientation * frame.rotation;
    } catch (const LuaArgError& e) {
      throw LuaArgError(who + ": " + e.what());
    }
    children.push_back(std::move(c));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  physics::ShapeFrame frame;
  auto shape = physics::makeCompoundShape(children, &frame);
  if (!shape) throw LuaArgError("world.compound: " + shape.error());
  d.shape = shape.value();
  placeBody(d, frame);
  return create(L, d, "world.compound", readColor(L, 1, "world.compound", {0.7f, 0.5f, 0.8f}), frame);
}

/// The query shape of world.overlap / world.shape_cast, placed in the world.
physics::Shape readQueryShape(lua_State* L, const char* fn, std::initializer_list<const char*> extra, Vec3* p,
                              Quat* q) {
  if (!lua_istable(L, 1))
    throw LuaArgError(std::string(fn) + ": expected a table, e.g. " + fn + "{shape = \"sphere\", radius = 1, position = {0, 1, 0}}");
  try {
    checkShapeFields(L, 1, fn, extra);
    physics::ShapeFrame frame;
    physics::Shape shape = readShapeDef(L, 1, &frame);
    if (auto st = physics::validateShape(shape); !st) throw LuaArgError(st.error());
    readPose(L, 1, p, q);
    *p += *q * frame.centre_m;
    *q = *q * frame.rotation;
    return shape;
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
}

/// @function world.overlap
/// Bodies whose shape overlaps a shape placed in the world (the height field
/// is not included). Touching within 1 mm counts.
/// @param def ShapeDef the shape and its pose in the world
/// @return Body[] the overlapping bodies, in creation-slot order
/// @example for _, b in ipairs(world.overlap{shape = "sphere", radius = 2, position = {0, 1, 0}}) do b:apply_impulse({0, 5, 0}) end
int worldOverlap(lua_State* L) {
  Vec3 p;
  Quat q;
  const physics::Shape shape = readQueryShape(L, "world.overlap", {}, &p, &q);
  const std::vector<physics::BodyId> ids = worldOf(L).overlapShape(shape, p, q);
  lua_createtable(L, int(ids.size()), 0);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    pushBody(L, ids[i]);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  return 1;
}

/// @class ShapeCastHit
/// @field body Body? the body hit; nil when the shape hit the terrain
/// @field distance number how far the shape moved along the unit direction before touching, m
/// @field point Vec3Arg contact point, m
/// @field normal Vec3Arg surface normal of what was hit, pointing back at the shape (unit)

/// @class ShapeCastDef: ShapeDef
/// @field direction Vec3Arg where to sweep (need not be unit, must not be zero)
/// @field max_distance? number m (default 1000)
/// @field ignore? Body a body to pass through (e.g. the car casting its own wheels)

/// @function world.shape_cast
/// Sweeps a shape along a straight line without turning it and returns the
/// first body or terrain it touches (a fat ray: wheels, feet, sweeps).
/// @param def ShapeCastDef the shape, its start pose, direction and limits
/// @return ShapeCastHit? the first hit, or nil
/// @example local hit = world.shape_cast{shape = "sphere", radius = 0.35, position = {0, 2, 0}, direction = {0, -1, 0}, max_distance = 1}
int worldShapeCast(lua_State* L) {
  Vec3 p;
  Quat q;
  const physics::Shape shape =
      readQueryShape(L, "world.shape_cast", {"direction", "max_distance", "ignore"}, &p, &q);
  Vec3 dir;
  double maxd = 1000;
  physics::BodyId ignore;
  try {
    if (!optVec3Field(L, 1, "direction", &dir)) throw LuaArgError("field 'direction' is required, e.g. {0, -1, 0}");
    if (dir.norm() == 0) throw LuaArgError("field 'direction' must not be zero");
    maxd = optNumberField(L, 1, "max_distance", maxd);
    if (maxd < 0) throw LuaArgError("field 'max_distance' must be >= 0 m");
    if (rawGetField(L, 1, "ignore") != LUA_TNIL && !testBody(L, -1, &ignore))
      throw LuaArgError(std::string("field 'ignore' must be a Body, got ") + luaL_typename(L, -1));
    lua_pop(L, 1);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("world.shape_cast: ") + e.what());
  }
  physics::ShapeCastHit hit;
  if (!worldOf(L).shapeCast(shape, p, q, dir, Real(maxd), &hit, ignore)) {
    lua_pushnil(L);
    return 1;
  }
  lua_createtable(L, 0, 4);
  if (!hit.body.isNull()) {
    pushBody(L, hit.body);
    rawSetField(L, -2, "body");
  }
  lua_pushnumber(L, hit.distance_m);
  rawSetField(L, -2, "distance");
  pushVec3(L, hit.point_m);
  rawSetField(L, -2, "point");
  pushVec3(L, hit.normal);
  rawSetField(L, -2, "normal");
  return 1;
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
  rawSetField(L, -2, "body");
  lua_pushnumber(L, hit.distance_m);
  rawSetField(L, -2, "distance");
  pushVec3(L, hit.point_m);
  rawSetField(L, -2, "point");
  pushVec3(L, hit.normal);
  rawSetField(L, -2, "normal");
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
    {"cylinder", guarded<worldCylinder>},
    {"plane", guarded<worldPlane>},
    {"hull", guarded<worldHull>},
    {"compound", guarded<worldCompound>},
    {"overlap", guarded<worldOverlap>},
    {"shape_cast", guarded<worldShapeCast>},
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
  registerModule(L, envIndex, "world", kWorld);
}

}  // namespace tumble::script
