// Models from Lua: body:set_model draws a body with a model file (its
// collision shape stays what it was); world.add_static_model places scenery
// (rocks, trees, buildings) that collide with their own triangles (through
// the model's object tree), with one box around them, or not at all.
//
//   crate:set_model("base:assets/models/barrier.obj", {offset = {0, -0.4, 0}})
//   world.add_static_model("base:assets/models/rock.obj", {position = {5, 0, 3}, scale = 1.5})
//
// Paths are "MOD:path/in/mod" or a path inside the calling mod. Files are
// .obj (+ .mtl), .gltf / .glb, .fbx, .dae or .3ds (render/model.h).
#include <algorithm>
#include <optional>
#include <set>
#include <tuple>

#include "physics/mass_properties.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

namespace {

// scale = 2 or scale = {1, 2, 1}; every factor finite and > 0.
Vec3 readScale(lua_State* L, int t) {
  Vec3 scale = Vec3::Ones();
  if (rawGetField(L, t, "scale") == LUA_TNUMBER) {
    scale = Vec3::Constant(Real(lua_tonumber(L, -1)));
    lua_pop(L, 1);
  } else {
    lua_pop(L, 1);
    optVec3Field(L, t, "scale", &scale);
  }
  if (!(scale.array() > 0).all() || !scale.allFinite()) {
    throw LuaArgError("option 'scale' must be a number > 0 or {x, y, z} with each > 0");
  }
  return scale;
}

std::string resolve(lua_State* L, int idx, const char* fn) {
  if (lua_type(L, idx) != LUA_TSTRING) {
    throw LuaArgError(std::string(fn) + ": expected a model path such as \"base:assets/models/rock.obj\", got " +
                      luaL_typename(L, idx));
  }
  ScenarioHost* host = ScenarioHost::from(L);
  auto file = resolveModFile(lua_tostring(L, idx), host->mod(), host->options().modDirs);
  if (!file) throw LuaArgError(std::string(fn) + ": " + file.error());
  return *file;
}

/// @class ModelOptions
/// Placement of a model on a body, in the body's frame.
/// @field offset? Vec3Arg model origin relative to the body's centre, m (default {0, 0, 0})
/// @field rotation? Vec3Arg rotation vector (axis times angle, rad) from model to body axes
/// @field scale? number|Vec3Arg factor per axis, > 0 (default 1): model file units to metres

/// @function Body:set_model
/// Draws the body with a model instead of its plain shape. The collision
/// shape stays what it was; only the picture changes. A second call
/// replaces the model. The file is checked now: a missing or unreadable
/// model is an error naming the file.
/// @param path string "MOD:path/in/mod" (e.g. "base:assets/models/hatchback.obj") or a path in this mod
/// @param options? ModelOptions offset, rotation and scale in the body's frame
/// @example car:set_model("base:assets/models/hatchback.obj", {offset = {0, -0.6, 0}})
int bodySetModel(lua_State* L) {
  const physics::BodyId id = checkBody(L, 1);
  const char* fn = "Body:set_model";
  ModelAttachment a;
  a.body = id;
  a.file = resolve(L, 2, fn);
  ScenarioHost* host = ScenarioHost::from(L);
  if (auto box = host->scene().modelBounds(a.file); !box) throw LuaArgError(std::string(fn) + ": " + box.error());
  if (!lua_isnoneornil(L, 3)) {
    if (!lua_istable(L, 3)) throw LuaArgError(std::string(fn) + ": options must be a table {offset=, rotation=, scale=}");
    checkFields(L, 3, fn, {"offset", "rotation", "scale"});
    try {
      optVec3Field(L, 3, "offset", &a.offset_m);
      a.rotation = optRotationField(L, 3);
      a.scale = readScale(L, 3);
    } catch (const LuaArgError& e) {
      throw LuaArgError(std::string(fn) + ": " + e.what());
    }
  }
  Presentation& p = host->presentation();
  // Forget models of removed bodies, so spawning and removing keeps no garbage.
  std::erase_if(p.attachments, [&](const ModelAttachment& m) { return !host->world().isValid(m.body); });
  auto it = std::find_if(p.attachments.begin(), p.attachments.end(),
                         [&](const ModelAttachment& m) { return m.body == id; });
  if (it != p.attachments.end()) *it = a;
  else p.attachments.push_back(a);
  ++p.revision;
  return 0;
}

/// @function Body:clear_model
/// Draws the body as its plain shape again.
/// @return boolean true if the body had a model
int bodyClearModel(lua_State* L) {
  const physics::BodyId id = checkBody(L, 1);
  Presentation& p = ScenarioHost::from(L)->presentation();
  const auto before = p.attachments.size();
  std::erase_if(p.attachments, [&](const ModelAttachment& m) { return m.body == id; });
  ++p.revision;
  lua_pushboolean(L, p.attachments.size() != before);
  return 1;
}

/// @class StaticModelDef
/// @field position? Vec3Arg where the model's origin goes, m (default {0, 0, 0})
/// @field rotation? Vec3Arg rotation vector (axis times angle, rad)
/// @field scale? number|Vec3Arg factor per axis, > 0 (default 1)
/// @field collision? string "mesh" (default): the model's own triangles; "box": one box around the model; "none": only drawn
/// @field friction? number of the collision body (default 0.6)
/// @field color? Vec3Arg colour of the collision body where models are not drawn (headless: unused)

/// @function world.add_static_model
/// Places a static model: scenery such as rocks, trees, buildings and
/// barriers. With collision = "mesh" (the default) bodies collide with the
/// model's own triangles, as drawn: a car drives under a tree's canopy and
/// hits its trunk, a ball rolls through an arch. The model's object tree
/// (each node's box and the box around its children) skips the parts a
/// body is not near, so a detailed model costs little. Triangles collide
/// from their front (outside) only: a model made of single flat quads (a
/// sign) stops bodies from its front side; use "box" for such props, or as
/// a cheap stand-in for a complicated model nobody reaches. collision =
/// "box" makes one static box around the model's bounds (its empty space
/// is solid too). Static bodies are never tested against each other and,
/// over a terrain, go into its tree of static objects. A model with no
/// triangles, or a vertex that is not a finite number, is an error naming
/// the file and the node.
/// @param path string "MOD:path/in/mod" or a path in this mod
/// @param def? StaticModelDef placement and collision
/// @return Body? the collision body, or nil with collision = "none"
/// @example world.add_static_model("base:assets/models/tree.obj", {position = {8, 0, -4}, rotation = {0, 1.2, 0}})
int worldAddStaticModel(lua_State* L) {
  const char* fn = "world.add_static_model";
  StaticModel s;
  s.file = resolve(L, 1, fn);
  std::string collision = "mesh";
  Real friction = Real(0.6);
  Eigen::Vector3f color(0.55f, 0.5f, 0.45f);
  if (!lua_isnoneornil(L, 2)) {
    if (!lua_istable(L, 2)) throw LuaArgError(std::string(fn) + ": the second argument must be a table {position=, ...}");
    checkFields(L, 2, fn, {"position", "rotation", "scale", "collision", "friction", "color"});
    try {
      optVec3Field(L, 2, "position", &s.position_m);
      s.rotation = optRotationField(L, 2);
      s.scale = readScale(L, 2);
      collision = optStringField(L, 2, "collision", "mesh");
      friction = Real(optNumberField(L, 2, "friction", friction));
      Vec3 c;
      if (optVec3Field(L, 2, "color", &c)) color = c.cast<float>().cwiseMax(0.0f).cwiseMin(1.0f);
    } catch (const LuaArgError& e) {
      throw LuaArgError(std::string(fn) + ": " + e.what());
    }
  }
  if (collision != "mesh" && collision != "box" && collision != "none") {
    throw LuaArgError(std::string(fn) + ": option 'collision' must be \"mesh\", \"box\" or \"none\", got \"" +
                      collision + "\"");
  }
  ScenarioHost* host = ScenarioHost::from(L);
  auto box = host->scene().modelBounds(s.file);
  if (!box) throw LuaArgError(std::string(fn) + ": " + box.error());
  if (collision == "mesh") {
    // One shape per (file, scale), shared by every placement of it: the
    // shape is immutable and in the model's frame, the body places it.
    auto shape = host->scene().modelMeshShape(s.file, s.scale);
    if (!shape) throw LuaArgError(std::string(fn) + ": " + shape.error());
    physics::BodyDef d;
    d.type = physics::BodyType::Static;
    d.shape = std::move(*shape);
    d.position_m = s.position_m;  // the body frame is the model's frame, placed
    d.orientation = s.rotation;
    d.friction = friction;
    host->countBodiesCreated(1, fn);
    auto body = host->world().createBody(d);
    if (!body) throw LuaArgError(std::string(fn) + ": " + body.error());
    s.body = *body;
    host->presentation().setColor(*body, color);
  } else if (collision == "box") {
    physics::BodyDef d;
    d.type = physics::BodyType::Static;
    const Vec3 half = (box->max_m - box->min_m).cwiseProduct(s.scale) / 2;
    const Vec3 centre = (box->max_m + box->min_m).cwiseProduct(s.scale) / 2;
    d.position_m = s.position_m + s.rotation * centre;
    d.orientation = s.rotation;
    d.friction = friction;
    // A flat model (a sign, a decal) still gets a box with some thickness.
    d.shape = physics::Shape::box(half.cwiseMax(Vec3::Constant(Real(0.005))));
    host->countBodiesCreated(1, fn);
    auto body = host->world().createBody(d);
    if (!body) throw LuaArgError(std::string(fn) + ": " + body.error());
    s.body = *body;
    host->presentation().setColor(*body, color);
  }
  host->presentation().statics.push_back(s);
  ++host->presentation().revision;
  if (!s.body.isNull()) pushBody(L, s.body);
  else lua_pushnil(L);
  return 1;
}

/// @class MeshMassProperties
/// @field mass number kg
/// @field volume number m^3
/// @field center Vec3 centre of mass in the model's frame (scaled), m
/// @field inertia table inertia about the centre of mass, kg m^2: {xx=, yy=, zz=, xy=, yz=, zx=}

/// @function world.model_mass_properties
/// Mass, volume, centre of mass and inertia of a model of uniform density,
/// computed from its closed triangle mesh (Mirtich's method). Every part
/// of the model must be a closed surface; an open one is an error.
/// @param path string "MOD:path/in/mod" or a path in this mod
/// @param options? table {density = kg/m^3 (default 1000), scale = number or {x, y, z} (default 1)}
/// @return MeshMassProperties the mass properties
/// @example local p = world.model_mass_properties("base:assets/models/rock.obj", {density = 2600})
/// @example print(p.mass, p.inertia.xx)
int worldModelMassProperties(lua_State* L) {
  const char* fn = "world.model_mass_properties";
  const std::string file = resolve(L, 1, fn);
  Real density = 1000;
  Vec3 scale = Vec3::Ones();
  if (!lua_isnoneornil(L, 2)) {
    if (!lua_istable(L, 2)) throw LuaArgError(std::string(fn) + ": options must be a table {density=, scale=}");
    checkFields(L, 2, fn, {"density", "scale"});
    try {
      density = Real(optNumberField(L, 2, "density", density));
      scale = readScale(L, 2);
    } catch (const LuaArgError& e) {
      throw LuaArgError(std::string(fn) + ": " + e.what());
    }
    if (!(density > 0)) throw LuaArgError(std::string(fn) + ": option 'density' must be > 0 kg/m^3");
  }
  auto mesh = ScenarioHost::from(L)->scene().modelTriangles(file);
  if (!mesh) throw LuaArgError(std::string(fn) + ": " + mesh.error());
  for (Vec3& v : mesh->vertices_m) v = v.cwiseProduct(scale);
  if (!physics::isClosedMesh(mesh->vertices_m, mesh->triangles)) {
    throw LuaArgError(std::string(fn) + ": " + file + " is not one closed surface (an edge with no partner or a "
                      "face wound the wrong way); mass properties need a closed mesh");
  }
  const physics::MassProperties p = physics::massPropertiesOfMesh(mesh->vertices_m, mesh->triangles, density);
  if (!p.valid) throw LuaArgError(std::string(fn) + ": " + file + " encloses no volume");
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, p.mass_kg);
  rawSetField(L, -2, "mass");
  lua_pushnumber(L, p.volume_m3);
  rawSetField(L, -2, "volume");
  pushVec3(L, p.centreOfMass_m);
  rawSetField(L, -2, "center");
  lua_createtable(L, 0, 6);
  const Mat3& I = p.inertia_kgm2;
  for (auto [name, r, c] : {std::tuple{"xx", 0, 0}, {"yy", 1, 1}, {"zz", 2, 2}, {"xy", 0, 1}, {"yz", 1, 2}, {"zx", 2, 0}}) {
    lua_pushnumber(L, I(r, c));
    rawSetField(L, -2, name);
  }
  rawSetField(L, -2, "inertia");
  return 1;
}

const luaL_Reg kBodyModelMethods[] = {
    {"set_model", guarded<bodySetModel>},
    {"clear_model", guarded<bodyClearModel>},
    {nullptr, nullptr},
};
const luaL_Reg kWorldModel[] = {
    {"add_static_model", guarded<worldAddStaticModel>},
    {"model_mass_properties", guarded<worldModelMassProperties>},
    {nullptr, nullptr},
};

}  // namespace

void openModelBindings(lua_State* L, int envIndex) {
  // Body methods: added to the Body metatable's method table.
  luaL_getmetatable(L, kBodyMeta);
  rawGetField(L, -1, "__index");
  registerFunctions(L, -1, kBodyModelMethods);
  lua_pop(L, 2);
  // world.add_static_model, world.model_mass_properties: into the env's world table.
  rawGetField(L, envIndex, "world");
  registerFunctions(L, -1, kWorldModel);
  lua_pop(L, 1);
}

}  // namespace tumble::script
