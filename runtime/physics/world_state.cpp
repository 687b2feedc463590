// World::saveState / restoreState: the world's whole simulated state as exact
// bits, for snapshots of a running scene (app/scene_state.h) and for
// world.snapshot() / world.restore() in scripts.
//
// A snapshot goes back into a world with the same bodies (made by the same
// scenario), so each slot's liveness, generation, type and shape are
// compared. Where they differ, the saved slot wins: a body removed since is
// removed again, and a body the script made after on_start (projectiles, a
// rag-doll, a dropped rock) is made again in its slot: a sphere, box,
// capsule, cylinder or plane from its saved size, a convex hull or compound
// from its saved polyhedron and children, stored whole (vertices, faces,
// edges, mass data as computed when it was made: computing a hull again
// from its own vertices gives another face and vertex order in 451 of 500
// random clouds, and the run would then differ). Those are checked as they
// are read (sizes, indices, finite numbers), so damaged bytes are refused,
// never followed. A static triangle mesh (a model placed by a script) is
// stored as built: its node tree and its triangles with their boxes and
// active edges, so a mesh placed after on_start, or removed since a
// world.snapshot(), comes back bit for bit without its model file; bodies
// in slots the saved world did not have yet are removed. Everything that
// changes while the world steps is stored: each body's pose, velocities, accumulated force and
// torque, mass and inertia, material and sleep state; the contact cache
// with its warm-start impulses (without it the next step solves the stack
// from zero and the run differs); the broad phase's sort order (it decides
// the order of the pairs, hence of the contacts the solver visits); sleep
// islands, the collision filter, island links, springs, the settings and
// the error bookkeeping.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <type_traits>


#include "core/byte_stream.h"
#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/internal/broad_phase.h"
#include "physics/internal/height_field_collision.h"
#include "physics/internal/manifold.h"
#include "physics/mesh_shape.h"
#include "physics/world.h"

namespace tumble::physics {

namespace {

constexpr std::uint32_t kStateMagic = 0x54574c44;  // "TWLD"
// 2: WorldSettings::maxContactPairsPerBody and ErrorStats::contactPairsSkipped
// (both stored as bytes). 3: hull and compound shapes after their slot.
// 4: triangle meshes after their slot too.
constexpr std::uint32_t kStateVersion = 4;
constexpr std::size_t kMaxSlots = std::size_t(1) << 24;

static_assert(kBitwise<Manifold>);
static_assert(kBitwise<HullFace>);
static_assert(kBitwise<HullEdge>);
static_assert(kBitwise<WorldSettings>);
static_assert(kBitwise<ErrorStats>);

/// The part of a body that is structure, not state: it must match.
struct SlotShape {
  std::uint32_t generation = 0;
  std::uint8_t alive = 0, type = 0, shape = 0;
  Real radius_m = 0, halfHeight_m = 0;
  Vec3 halfExtents_m = Vec3::Zero();
};

SlotShape shapeOf(const Body& b) {
  SlotShape s;
  s.generation = b.generation;
  s.alive = b.alive;
  s.type = std::uint8_t(b.type);
  s.shape = std::uint8_t(b.shape.type);
  s.radius_m = b.shape.radius_m;
  s.halfHeight_m = b.shape.halfHeight_m;
  s.halfExtents_m = b.shape.halfExtents_m;
  return s;
}

/// The part of a body that changes while the world runs.
struct SlotState {
  Vec3 position_m, linearVelocity_mps, angularVelocity_radps, force_N, torque_Nm;
  Quat orientation;
  Real mass_kg, invMass_per_kg;
  Vec3 invInertiaLocal, inertiaLocal_kgm2;
  Mat3 invInertiaWorld;
  Real friction, restitution, rollingResistance, linearDamping_per_s, angularDamping_per_s, sleepTime_s;
  std::uint64_t userData;
  std::uint8_t soundMaterial, awake, allowSleep, frozen;
};
static_assert(kBitwise<SlotState>);

SlotState stateOf(const Body& b) {
  return SlotState{b.position_m, b.linearVelocity_mps, b.angularVelocity_radps, b.force_N, b.torque_Nm,
                   b.orientation, b.mass_kg, b.invMass_per_kg, b.invInertiaLocal, b.inertiaLocal_kgm2,
                   b.invInertiaWorld, b.friction, b.restitution, b.rollingResistance, b.linearDamping_per_s,
                   b.angularDamping_per_s, b.sleepTime_s, b.userData, b.soundMaterial, b.awake, b.allowSleep,
                   b.frozen};
}

void applyState(const SlotState& s, Body& b) {
  b.position_m = s.position_m;
  b.linearVelocity_mps = s.linearVelocity_mps;
  b.angularVelocity_radps = s.angularVelocity_radps;
  b.force_N = s.force_N;
  b.torque_Nm = s.torque_Nm;
  b.orientation = s.orientation;
  b.mass_kg = s.mass_kg;
  b.invMass_per_kg = s.invMass_per_kg;
  b.invInertiaLocal = s.invInertiaLocal;
  b.inertiaLocal_kgm2 = s.inertiaLocal_kgm2;
  b.invInertiaWorld = s.invInertiaWorld;
  b.friction = s.friction;
  b.restitution = s.restitution;
  b.rollingResistance = s.rollingResistance;
  b.linearDamping_per_s = s.linearDamping_per_s;
  b.angularDamping_per_s = s.angularDamping_per_s;
  b.sleepTime_s = s.sleepTime_s;
  b.userData = s.userData;
  b.soundMaterial = s.soundMaterial;
  b.awake = s.awake;
  b.allowSleep = s.allowSleep;
  b.frozen = s.frozen;
}

/// Shapes whose whole data is in SlotShape.
bool primitive(const SlotShape& s) {
  switch (ShapeType(s.shape)) {
    case ShapeType::Sphere:
    case ShapeType::Box:
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
    case ShapeType::Plane: return true;
    default: return false;
  }
}

bool validSize(const SlotShape& s) {
  return std::isfinite(s.radius_m) && s.radius_m > 0 && std::isfinite(s.halfHeight_m) && s.halfHeight_m >= 0 &&
         s.halfExtents_m.allFinite() && (s.halfExtents_m.array() > 0).all();
}

Shape primitiveShape(const SlotShape& s) {
  switch (ShapeType(s.shape)) {
    case ShapeType::Sphere: return Shape::sphere(s.radius_m);
    case ShapeType::Box: return Shape::box(s.halfExtents_m);
    case ShapeType::Capsule: return Shape::capsule(s.radius_m, s.halfHeight_m);
    case ShapeType::Cylinder: return Shape::cylinder(s.radius_m, s.halfHeight_m);
    default: return Shape::plane();
  }
}

bool sameShape(const SlotShape& a, const SlotShape& b) {
  return a.generation == b.generation && a.alive == b.alive && a.type == b.type && a.shape == b.shape &&
         a.radius_m == b.radius_m && a.halfHeight_m == b.halfHeight_m && a.halfExtents_m == b.halfExtents_m;
}

// ---- hull and compound shapes ----------------------------------------------------

bool finite(Real v) { return std::isfinite(v); }

void writeHull(ByteWriter& w, const ConvexHull& h) {
  w.vec(h.vertices_m);
  w.vec(h.faces);
  w.vec(h.faceVertices);
  w.vec(h.edges);
  w.vec(h.triangles);
  w.pod(h.volume_m3);
  w.pod(h.centroid_m);
  w.pod(h.unitInertia_m2);
  w.pod(h.boundsLo_m);
  w.pod(h.boundsHi_m);
  w.pod(h.boundingRadius_m);
  w.pod(h.innerRadius_m);
}

/// A hull as writeHull wrote it, or an error: every index inside its array,
/// every number finite, the sizes those computeConvexHull can make.
Result<std::shared_ptr<const ConvexHull>> readHull(ByteReader& r) {
  constexpr std::size_t kMax = kMaxHullPoints;
  ConvexHull h;
  h.vertices_m = r.vec<Vec3>(kMax);
  h.faces = r.vec<HullFace>(2 * kMax);
  h.faceVertices = r.vec<std::uint32_t>(6 * kMax);
  h.edges = r.vec<HullEdge>(3 * kMax);
  h.triangles = r.vec<std::array<std::uint32_t, 3>>(2 * kMax);
  h.volume_m3 = r.pod<Real>();
  h.centroid_m = r.pod<Vec3>();
  h.unitInertia_m2 = r.pod<Mat3>();
  h.boundsLo_m = r.pod<Vec3>();
  h.boundsHi_m = r.pod<Vec3>();
  h.boundingRadius_m = r.pod<Real>();
  h.innerRadius_m = r.pod<Real>();
  const auto damaged = [] { return makeError("world state: damaged (a hull)"); };
  if (!r.ok() || h.vertices_m.size() < 4 || h.faces.size() < 4 || h.edges.size() < 6 || h.triangles.size() < 4)
    return damaged();
  const std::uint32_t nv = std::uint32_t(h.vertices_m.size()), nf = std::uint32_t(h.faces.size());
  for (const Vec3& v : h.vertices_m)
    if (!v.allFinite()) return damaged();
  for (const HullFace& f : h.faces)
    if (!f.normal.allFinite() || !finite(f.offset_m) || f.count < 3 || f.first > h.faceVertices.size() ||
        f.count > h.faceVertices.size() - f.first)
      return damaged();
  for (std::uint32_t i : h.faceVertices)
    if (i >= nv) return damaged();
  for (const HullEdge& e : h.edges)
    if (e.v0 >= nv || e.v1 >= nv || e.face0 >= nf || e.face1 >= nf) return damaged();
  for (const auto& t : h.triangles)
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) return damaged();
  if (!(h.volume_m3 > 0) || !finite(h.volume_m3) || !h.centroid_m.allFinite() || !h.unitInertia_m2.allFinite() ||
      !h.boundsLo_m.allFinite() || !h.boundsHi_m.allFinite() || !finite(h.boundingRadius_m) ||
      !finite(h.innerRadius_m))
    return damaged();
  return std::shared_ptr<const ConvexHull>(std::make_shared<const ConvexHull>(std::move(h)));
}

// ---- triangle meshes --------------------------------------------------------------

/// A MeshNode and a MeshTriangle as stored: the same fields without padding
/// bytes (in float and in double builds), so that equal meshes give equal bytes.
struct SavedMeshNode {
  std::uint32_t firstTriangle, triangleCount, subtreeEnd, unused;
  Vec3 tightLo_m, tightHi_m, coverLo_m, coverHi_m;
};
struct SavedMeshTriangle {
  Vec3 v[3], normal, lo_m, hi_m;
  std::uint32_t activeEdges, unused;
};
static_assert(sizeof(SavedMeshNode) == 4 * sizeof(std::uint32_t) + 4 * sizeof(Vec3));
static_assert(sizeof(SavedMeshTriangle) == 6 * sizeof(Vec3) + 2 * sizeof(std::uint32_t));

void writeMesh(ByteWriter& w, const MeshShape& m) {
  std::vector<SavedMeshNode> nodes;
  nodes.reserve(m.nodes.size());
  for (const MeshNode& n : m.nodes)
    nodes.push_back({n.firstTriangle, n.triangleCount, n.subtreeEnd, 0, n.tightLo_m, n.tightHi_m, n.coverLo_m,
                     n.coverHi_m});
  std::vector<SavedMeshTriangle> triangles;
  triangles.reserve(m.triangles.size());
  for (const MeshTriangle& t : m.triangles)
    triangles.push_back({{t.v[0], t.v[1], t.v[2]}, t.normal, t.lo_m, t.hi_m, t.activeEdges, 0});
  w.vec(nodes);
  w.vec(triangles);
}

/// A mesh as writeMesh wrote it, or an error. What the queries follow is
/// checked so that they stay inside the arrays and end (each node's
/// triangle range inside the triangles, its subtree end past itself and
/// within the nodes), every vertex is finite and no box holds a NaN; the
/// bounding radius is computed again from the triangles.
Result<std::shared_ptr<const MeshShape>> readMesh(ByteReader& r) {
  const auto damaged = [] { return makeError("world state: damaged (a triangle mesh)"); };
  auto nodes = r.vec<SavedMeshNode>(kMaxMeshTriangles);
  auto triangles = r.vec<SavedMeshTriangle>(kMaxMeshTriangles);
  if (!r.ok() || nodes.empty() || triangles.empty()) return damaged();
  MeshShape m;
  m.nodes.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const SavedMeshNode& n = nodes[i];
    // A node without triangles of its own has an empty tight box (lo > hi: infinite bounds).
    if (std::uint64_t(n.firstTriangle) + n.triangleCount > triangles.size() || n.subtreeEnd <= i ||
        n.subtreeEnd > nodes.size() || n.tightLo_m.hasNaN() || n.tightHi_m.hasNaN() || n.coverLo_m.hasNaN() ||
        n.coverHi_m.hasNaN())
      return damaged();
    m.nodes.push_back({n.firstTriangle, n.triangleCount, n.subtreeEnd, n.tightLo_m, n.tightHi_m, n.coverLo_m,
                       n.coverHi_m});
  }
  if (m.nodes[0].subtreeEnd != nodes.size()) return damaged();  // the root's subtree is the whole tree
  m.triangles.reserve(triangles.size());
  for (const SavedMeshTriangle& t : triangles) {
    if (!t.v[0].allFinite() || !t.v[1].allFinite() || !t.v[2].allFinite() || !t.normal.allFinite() ||
        std::abs(t.normal.norm() - 1) > Real(1e-3) || !t.lo_m.allFinite() || !t.hi_m.allFinite() || t.activeEdges > 7)
      return damaged();
    MeshTriangle tri;
    for (int k = 0; k < 3; ++k) {
      tri.v[k] = t.v[k];
      m.boundingRadius_m = std::max(m.boundingRadius_m, t.v[k].norm());
    }
    tri.normal = t.normal;
    tri.lo_m = t.lo_m;
    tri.hi_m = t.hi_m;
    tri.activeEdges = std::uint8_t(t.activeEdges);
    m.triangles.push_back(tri);
  }
  if (!std::isfinite(m.boundingRadius_m)) return damaged();
  return std::shared_ptr<const MeshShape>(std::make_shared<const MeshShape>(std::move(m)));
}

/// The data of a hull, compound or mesh shape (children: their size or hull
/// and their pose). Other shapes have none beyond SlotShape.
void writeShapeData(ByteWriter& w, const Shape& s) {
  if (s.type == ShapeType::Hull) writeHull(w, *s.hull);
  if (s.type == ShapeType::Mesh) writeMesh(w, *s.mesh);
  if (s.type != ShapeType::Compound) return;
  const CompoundShape& c = *s.compound;
  w.pod(std::uint32_t(c.children.size()));
  for (const CompoundChild& child : c.children) {
    w.pod(std::uint8_t(child.shape.type));
    w.pod(child.shape.radius_m);
    w.pod(child.shape.halfHeight_m);
    w.pod(child.shape.halfExtents_m);
    if (child.shape.type == ShapeType::Hull) writeHull(w, *child.shape.hull);
    w.pod(child.position_m);
    w.pod(child.orientation);
  }
  w.pod(c.volume_m3);
  w.pod(c.unitInertia_m2);
  w.pod(c.boundingRadius_m);
  w.pod(c.innerRadius_m);
}

bool storesShapeData(const Body& b) {
  return b.alive && ((b.shape.type == ShapeType::Hull && b.shape.hull) ||
                     (b.shape.type == ShapeType::Compound && b.shape.compound) ||
                     (b.shape.type == ShapeType::Mesh && b.shape.mesh));
}

/// Reads what writeShapeData wrote for a slot saved with this shape type
/// into `shape` (type, hull, compound or mesh), checked as it goes.
Status readShapeData(ByteReader& r, ShapeType type, Shape& shape) {
  shape.type = type;
  if (type == ShapeType::Mesh) {
    auto mesh = readMesh(r);
    if (!mesh) return makeError(mesh.error());
    shape.mesh = mesh.value();
    if (!validateShape(shape)) return makeError("world state: damaged (a triangle mesh)");
    return Ok{};
  }
  if (type == ShapeType::Hull) {
    auto hull = readHull(r);
    if (!hull) return makeError(hull.error());
    shape.hull = hull.value();
    if (!validateShape(shape)) return makeError("world state: damaged (a hull)");
    return Ok{};
  }
  if (type != ShapeType::Compound) return Ok{};
  const auto damaged = [] { return makeError("world state: damaged (a compound)"); };
  const auto count = r.pod<std::uint32_t>();
  if (!r.ok() || count == 0 || count > std::uint32_t(kMaxCompoundChildren)) return damaged();
  CompoundShape c;
  for (std::uint32_t i = 0; i < count; ++i) {
    CompoundChild child;
    const auto childType = r.pod<std::uint8_t>();
    child.shape.radius_m = r.pod<Real>();
    child.shape.halfHeight_m = r.pod<Real>();
    child.shape.halfExtents_m = r.pod<Vec3>();
    if (!r.ok()) return damaged();
    switch (ShapeType(childType)) {
      case ShapeType::Sphere:
      case ShapeType::Box:
      case ShapeType::Capsule:
      case ShapeType::Cylinder: child.shape.type = ShapeType(childType); break;
      case ShapeType::Hull: {
        child.shape.type = ShapeType::Hull;
        auto hull = readHull(r);
        if (!hull) return makeError(hull.error());
        child.shape.hull = hull.value();
        break;
      }
      default: return damaged();
    }
    if (!validateShape(child.shape)) return damaged();
    child.position_m = r.pod<Vec3>();
    child.orientation = r.pod<Quat>();
    if (!r.ok() || !child.position_m.allFinite() || !child.orientation.coeffs().allFinite() ||
        std::abs(child.orientation.norm() - 1) > Real(1e-3))
      return damaged();
    c.children.push_back(std::move(child));
  }
  c.volume_m3 = r.pod<Real>();
  c.unitInertia_m2 = r.pod<Vec3>();
  c.boundingRadius_m = r.pod<Real>();
  c.innerRadius_m = r.pod<Real>();
  if (!r.ok() || !(c.volume_m3 > 0) || !finite(c.volume_m3) || !c.unitInertia_m2.allFinite() ||
      !finite(c.boundingRadius_m) || !finite(c.innerRadius_m))
    return damaged();
  shape.compound = std::make_shared<const CompoundShape>(std::move(c));
  if (!validateShape(shape)) return damaged();
  return Ok{};
}

}  // namespace

std::string World::saveState() const {
  TUMBLE_ASSERT(!m_inStep, "saveState inside a step");
  ByteWriter w;
  w.pod(kStateMagic);
  w.pod(kStateVersion);
  w.pod(m_settings);
  w.pod(std::uint64_t(m_bodies.size()));
  for (const Body& b : m_bodies) {
    w.pod(shapeOf(b));
    w.pod(stateOf(b));
    if (storesShapeData(b)) writeShapeData(w, b.shape);
  }
  w.vec(m_freeList);
  w.pod(std::int32_t(m_bodyCount));
  w.vec(m_manifolds);
  w.vec(m_stepStartPosition);
  w.vec(m_stepStartOrientation);
  w.vec(m_sleepIsland);
  w.pod(m_nextIsland);
  w.vec(m_noCollide);
  w.vec(m_islandLinks);
  w.pod(std::int32_t(m_lastContactPoints));
  w.pod(m_error);
  w.pod(m_energy0);
  w.pod(m_energyScale);
  w.pod(m_externalWork);
  w.pod(m_momentum0);
  w.pod(m_externalImpulse);
  w.pod(m_momentumScale);
  w.pod(std::uint8_t(m_trackingStarted));
  w.vec(m_broad->order());
  w.pod(std::int32_t(m_broad->axis()));
  w.pod(std::uint64_t(m_broad->lastSwaps()));
  m_integration->saveSprings(w);
  return w.take();
}

Status World::restoreState(const std::string& bytes) {
  TUMBLE_ASSERT(!m_inStep, "restoreState inside a step");
  ByteReader r(bytes);
  if (r.pod<std::uint32_t>() != kStateMagic || !r.ok()) return makeError("not a world state");
  if (const auto v = r.pod<std::uint32_t>(); v != kStateVersion)
    return makeError("world state version " + std::to_string(v) + ", this build reads " + std::to_string(kStateVersion));
  const auto settings = r.pod<WorldSettings>();
  const auto slots = r.pod<std::uint64_t>();
  // Each slot takes at least its SlotShape and SlotState bytes: a damaged
  // count cannot allocate more than the bytes could hold (a 3.5 kB state
  // whose count was changed by one byte asked for 16 million slots, 9 s of
  // allocation, before this check).
  if (!r.ok() || slots > kMaxSlots || slots > r.remaining() / (sizeof(SlotShape) + sizeof(SlotState)))
    return makeError("world state: damaged (body slots)");
  std::vector<SlotShape> shapes(slots);
  std::vector<SlotState> states(slots);
  std::vector<Shape> madeShapes(slots);  // hull, compound and mesh shapes for the slots made again
  for (std::size_t i = 0; i < slots; ++i) {
    shapes[i] = r.pod<SlotShape>();
    states[i] = r.pod<SlotState>();
    if (!r.ok()) return makeError("world state: damaged (body " + std::to_string(i) + ")");
    const SlotShape here = i < m_bodies.size() ? shapeOf(m_bodies[i]) : SlotShape{};
    const SlotShape& saved = shapes[i];
    const ShapeType type = ShapeType(saved.shape);
    if (saved.alive && (type == ShapeType::Hull || type == ShapeType::Compound || type == ShapeType::Mesh)) {
      Shape& made = madeShapes[i];
      made.radius_m = saved.radius_m;
      made.halfHeight_m = saved.halfHeight_m;
      made.halfExtents_m = saved.halfExtents_m;
      if (Status st = readShapeData(r, type, made); !st) return st;
      if (saved.type > std::uint8_t(BodyType::Dynamic) ||
          (type == ShapeType::Mesh && BodyType(saved.type) != BodyType::Static))  // as World::createBody refuses
        return makeError("world state: damaged (body " + std::to_string(i) + ")");
      continue;
    }
    if (saved.alive && !primitive(saved))
      return makeError("world state: damaged (body " + std::to_string(i) + ": shape type " +
                       std::to_string(int(saved.shape)) + ")");
    if (saved.alive && !sameShape(saved, here) &&
        (saved.type > std::uint8_t(BodyType::Dynamic) || !validSize(saved) ||
         (ShapeType(saved.shape) == ShapeType::Plane && BodyType(saved.type) != BodyType::Static)))
      return makeError("world state: damaged (body " + std::to_string(i) + ")");
  }
  auto freeList = r.vec<std::uint32_t>(kMaxSlots);
  const auto bodyCount = r.pod<std::int32_t>();
  auto manifolds = r.vec<Manifold>(kMaxSlots * 8);
  auto startPos = r.vec<Vec3>(kMaxSlots);
  auto startOri = r.vec<Quat>(kMaxSlots);
  auto sleepIsland = r.vec<std::uint32_t>(kMaxSlots);
  const auto nextIsland = r.pod<std::uint32_t>();
  auto noCollide = r.vec<BodyPair>(kMaxSlots * 8);
  auto islandLinks = r.vec<BodyPair>(kMaxSlots * 8);
  const auto lastContacts = r.pod<std::int32_t>();
  const auto error = r.pod<ErrorStats>();
  const auto energy0 = r.pod<double>(), energyScale = r.pod<double>(), externalWork = r.pod<double>();
  const auto momentum0 = r.pod<Eigen::Vector3d>(), externalImpulse = r.pod<Eigen::Vector3d>();
  const auto momentumScale = r.pod<double>();
  const auto tracking = r.pod<std::uint8_t>();
  auto order = r.vec<std::uint32_t>(kMaxSlots);
  const auto axis = r.pod<std::int32_t>();
  const auto swaps = r.pod<std::uint64_t>();
  if (!r.ok()) return makeError("world state: damaged (truncated)");
  if (startPos.size() != slots || startOri.size() != slots || sleepIsland.size() != slots || axis < 0 || axis > 2)
    return makeError("world state: damaged (per-slot arrays)");
  // Indices are checked against this world, so that damaged or hand-made
  // bytes cannot make the next step read outside its arrays.
  // (Old manifolds are only matched by index and child, never followed into
  // a body's shape, so a range check is enough for them.)
  for (const Manifold& m : manifolds)
    if (m.a >= slots || (m.b >= slots && m.b != kHeightFieldBody) || m.count < 0 || m.count > kMaxManifoldPoints ||
        !validBools(m.touchedBefore, m.roundA, m.roundB, m.rimA, m.rimB))
      return makeError("world state: damaged (contact cache)");
  if (Status st = validateWorldSettings(settings); !st) return makeError("world state: settings: " + st.error());
  for (std::uint32_t i : order)
    if (i >= slots) return makeError("world state: damaged (broad phase)");
  for (std::uint32_t i : freeList)
    if (i >= slots || shapes[i].alive) return makeError("world state: damaged (free slots)");
  if (!allDistinct(order) || !allDistinct(freeList)) return makeError("world state: damaged (repeated slots)");
  for (const auto* pairs : {&noCollide, &islandLinks})
    for (const BodyPair& p : *pairs)
      if (p.a >= slots || p.b >= slots) return makeError("world state: damaged (body pairs)");
  if (Status st = m_integration->restoreSprings(r, std::uint32_t(slots)); !st) return st;
  if (!r.atEnd()) return makeError("world state: damaged (bytes after the end)");
  m_settings = settings;
  m_bodies.resize(slots);
  for (std::size_t i = 0; i < slots; ++i) {
    Body& b = m_bodies[i];
    const SlotShape& saved = shapes[i];
    if (!sameShape(saved, shapeOf(b))) {
      // Made again from its saved size, or removed as in the saved run.
      b = Body{};
      b.generation = saved.generation;
      b.alive = saved.alive != 0;
      if (b.alive) {
        b.type = BodyType(saved.type);
        b.shape = primitive(saved) ? primitiveShape(saved) : std::move(madeShapes[i]);
      }
    }
    applyState(states[i], b);
  }
  m_freeList = std::move(freeList);
  m_bodyCount = bodyCount;
  m_manifolds = std::move(manifolds);
  m_stepStartPosition = std::move(startPos);
  m_stepStartOrientation = std::move(startOri);
  m_sleepIsland = std::move(sleepIsland);
  m_nextIsland = nextIsland;
  m_noCollide = std::move(noCollide);
  m_islandLinks = std::move(islandLinks);
  m_lastContactPoints = lastContacts;
  m_error = error;
  m_energy0 = energy0;
  m_energyScale = energyScale;
  m_externalWork = externalWork;
  m_momentum0 = momentum0;
  m_externalImpulse = externalImpulse;
  m_momentumScale = momentumScale;
  m_trackingStarted = tracking != 0;
  m_broad->restore(std::move(order), axis, swaps);
  m_events.clear();
  return Ok{};
}

}  // namespace tumble::physics

namespace tumble::physics {

void BodyIntegration::saveSprings(ByteWriter& w) const {
  static_assert(kBitwise<Slot>);
  w.vec(m_springs);
  w.vec(m_free);
  w.pod(std::int32_t(m_springCount));
  w.pod(std::int64_t(m_newtonFailures));
}

Status BodyIntegration::restoreSprings(ByteReader& r, std::uint32_t slotCount) {
  auto springs = r.vec<Slot>(kMaxSlots);
  auto freeSlots = r.vec<std::uint32_t>(kMaxSlots);
  const auto count = r.pod<std::int32_t>();
  const auto failures = r.pod<std::int64_t>();
  if (!r.ok()) return makeError("world state: damaged (springs)");
  for (const Slot& s : springs) {
    if (!validBools(s.alive)) return makeError("world state: damaged (springs)");
    if (s.alive && (s.def.a.index >= slotCount || s.def.b.index >= slotCount))
      return makeError("world state: damaged (a spring on a body slot the world does not have)");
  }
  for (std::uint32_t i : freeSlots)
    if (i >= springs.size()) return makeError("world state: damaged (spring free slots)");
  m_springs = std::move(springs);
  m_free = std::move(freeSlots);
  m_springCount = count;
  m_newtonFailures = long(failures);
  return Ok{};
}

}  // namespace tumble::physics
