// What the renderer reads of a scene each frame (Scene::snapshot): every
// body as its shape or model, interpolated between the last two fixed steps,
// vehicle wheels, particles, ropes, cloth and the lines scripts drew; and
// the collision view's wireframes.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "app/paths.h"
#include "app/scene.h"
#include "app/scene_models.h"
#include "app/scene_sky.h"
#include "particles/particle_system.h"
#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/deformable.h"
#include "physics/mesh_shape.h"
#include "vehicle/vehicle_system.h"
#if TUMBLE_HAVE_TERRAIN
#include "app/terrain_scene.h"
#endif

namespace tumble::app {

namespace {

// A rope segment from a to b as a capsule of the rope's radius (its local Y
// along the segment).
render::DrawShape ropeSegment(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius_m,
                              const Eigen::Vector3f& color) {
  render::DrawShape s;
  s.kind = render::ShapeKind::Capsule;
  s.position = 0.5f * (a + b);
  const Eigen::Vector3f d = b - a;
  const float length = d.norm();
  if (length > 0 && std::isfinite(length))
    s.orientation = Eigen::Quaternionf::FromTwoVectors(Eigen::Vector3f::UnitY(), d / length);
  s.halfHeight_m = std::isfinite(length) ? 0.5f * length : 0.0f;
  s.radius_m = radius_m;
  s.color = color;
  return s;
}

// A cloth's particle grid (row r, column c is particle r * columns + c) as
// two triangles per cell.
render::DrawSurface clothSurface(const physics::Deformable& cloth, const Eigen::Vector3f& color) {
  render::DrawSurface surface;
  surface.color = color;
  const int n = cloth.particleCount(), columns = cloth.columns();
  surface.positions.reserve(std::size_t(n));
  for (int i = 0; i < n; ++i) surface.positions.push_back(cloth.position(i).cast<float>());
  const int rows = columns > 0 ? n / columns : 0;
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < columns; ++c) {
      const std::uint32_t i00 = std::uint32_t(r * columns + c), i10 = i00 + 1, i01 = i00 + std::uint32_t(columns),
                          i11 = i01 + 1;
      surface.indices.insert(surface.indices.end(), {i00, i10, i11, i00, i11, i01});
    }
  return surface;
}

}  // namespace

void Scene::savePreviousState() {
  const auto& bodies = *m_world;
  std::size_t n = 0;
  bodies.forEachBody([&](physics::BodyId id, const physics::Body&) { n = std::max<std::size_t>(n, id.index + 1); });
  m_prevPosition.resize(n);
  m_prevOrientation.resize(n);
  bodies.forEachBody([&](physics::BodyId id, const physics::Body& b) {
    m_prevPosition[id.index] = b.position_m;
    m_prevOrientation[id.index] = b.orientation;
  });
}

std::optional<render::BodyPose> Scene::bodyPose(physics::BodyId id, double alpha) const {
  if (!m_world->isValid(id)) return std::nullopt;
  const physics::Body& b = m_world->body(id);
  Vec3 p = b.position_m;
  Quat q = b.orientation;
  if (id.index < m_prevPosition.size() && b.type != physics::BodyType::Static) {
    p = m_prevPosition[id.index] + Real(alpha) * (b.position_m - m_prevPosition[id.index]);
    q = m_prevOrientation[id.index].slerp(Real(alpha), b.orientation);
  }
  return render::BodyPose{p.cast<float>(), q.cast<float>()};
}

std::shared_ptr<const render::ConvexMeshData> Scene::meshOf(
    const std::shared_ptr<const physics::ConvexHull>& hull) const {
  auto it = m_hullMeshes.find(hull.get());
  if (it != m_hullMeshes.end()) return it->second.mesh;
  auto mesh = std::make_shared<render::ConvexMeshData>();
  mesh->id = m_hullMeshes.size() + 1;
  for (const Vec3& v : hull->vertices_m) mesh->vertices.push_back(v.cast<float>());
  for (const auto& t : hull->triangles) mesh->indices.insert(mesh->indices.end(), t.begin(), t.end());
  m_hullMeshes.emplace(hull.get(), HullMesh{hull, mesh});
  return mesh;
}

const std::vector<Scene::WireEdge>& Scene::wireOf(const std::shared_ptr<const physics::MeshShape>& mesh) const {
  auto it = m_meshWires.find(mesh.get());
  if (it != m_meshWires.end()) return it->second.edges;
  // Each edge once: neighbours share an edge's two end points (the mesh
  // shape matched them bit for bit when it set the flags).
  std::map<std::array<float, 6>, bool> unique;
  for (const physics::MeshTriangle& t : mesh->triangles)
    for (int e = 0; e < 3; ++e) {
      Eigen::Vector3f a = t.v[e].cast<float>(), b = t.v[(e + 1) % 3].cast<float>();
      if (std::lexicographical_compare(b.data(), b.data() + 3, a.data(), a.data() + 3)) std::swap(a, b);
      const bool crease = (t.activeEdges >> e) & 1u;
      auto [slot, added] = unique.emplace(std::array<float, 6>{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}, crease);
      if (!added) slot->second = slot->second || crease;
    }
  MeshWire wire{mesh, {}};
  wire.edges.reserve(unique.size());
  for (const auto& [k, crease] : unique)
    wire.edges.push_back({Eigen::Vector3f(k[0], k[1], k[2]), Eigen::Vector3f(k[3], k[4], k[5]), crease});
  return m_meshWires.emplace(mesh.get(), std::move(wire)).first->second.edges;
}

void Scene::snapshot(render::FrameSnapshot& out, double alpha) const {
  out.shapes.clear();
  out.models.clear();
  out.lines.clear();  // ropes, cloth and script lines follow in snapshotVehiclesAndLines
  out.sky = skySettingsOf(m_host->presentation().environment);
  // Bodies drawn with a model (body:set_model, static models' collision
  // boxes) are not also drawn as their plain shape; in the collision view
  // the shapes are drawn and the models are not.
  std::vector<bool> hasModel;
  const script::Presentation& presentation = m_host->presentation();
  auto mark = [&](physics::BodyId id) {
    if (id.isNull() || !m_world->isValid(id)) return;
    if (hasModel.size() <= id.index) hasModel.resize(id.index + 1, false);
    hasModel[id.index] = true;
  };
  if (!m_collisionView) {
    for (const auto& a : presentation.attachments) mark(a.body);
    for (const auto& s : presentation.statics) mark(s.body);
    appendModelInstances(*this, alpha, out.models);
  }
#if TUMBLE_HAVE_TERRAIN
  out.terrain = m_terrain ? &m_terrain->surface() : nullptr;
#endif
  // One draw shape per simple shape; compounds give one per child.
  auto emit = [&](const physics::Shape& shape, render::DrawShape s) {
    switch (shape.type) {
      case physics::ShapeType::Box:
        s.kind = render::ShapeKind::Box;
        s.halfExtents = shape.halfExtents_m.cast<float>();
        break;
      case physics::ShapeType::Sphere:
        s.kind = render::ShapeKind::Sphere;
        s.radius_m = float(shape.radius_m);
        break;
      case physics::ShapeType::Capsule:
        s.kind = render::ShapeKind::Capsule;
        s.radius_m = float(shape.radius_m);
        s.halfHeight_m = float(shape.halfHeight_m);
        break;
      case physics::ShapeType::Cylinder:
        s.kind = render::ShapeKind::Cylinder;
        s.radius_m = float(shape.radius_m);
        s.halfHeight_m = float(shape.halfHeight_m);
        break;
      case physics::ShapeType::Hull:
        s.kind = render::ShapeKind::ConvexMesh;
        s.convexMesh = meshOf(shape.hull);
        break;
      case physics::ShapeType::Plane: s.kind = render::ShapeKind::Plane; break;
      case physics::ShapeType::Compound: return;  // children are emitted instead
      case physics::ShapeType::Mesh: {  // wireframe: creases and borders bright, flat seams dim
        static const Eigen::Vector3f kCrease(1.0f, 0.55f, 0.05f), kSeam(0.45f, 0.3f, 0.12f);
        for (const WireEdge& e : wireOf(shape.mesh))
          out.lines.push_back(render::DebugLine{s.position + s.orientation * e.a_m,
                                                s.position + s.orientation * e.b_m, e.crease ? kCrease : kSeam});
        return;
      }
    }
    out.shapes.push_back(std::move(s));
  };
  m_world->forEachBody([&](physics::BodyId id, const physics::Body& b) {
    if (id.index < hasModel.size() && hasModel[id.index]) return;
    render::DrawShape s;
    Vec3 p = b.position_m;
    Quat q = b.orientation;
    if (id.index < m_prevPosition.size() && b.type != physics::BodyType::Static) {
      p = m_prevPosition[id.index] + Real(alpha) * (b.position_m - m_prevPosition[id.index]);
      q = m_prevOrientation[id.index].slerp(Real(alpha), b.orientation);
    }
    s.position = p.cast<float>();
    s.orientation = q.cast<float>();
    s.color = presentation.colorOf(id);
    s.groundTexture = presentation.groundTextureOf(id);
    s.sleeping = !b.awake;
    if (b.shape.type != physics::ShapeType::Compound) return emit(b.shape, s);
    for (const physics::CompoundChild& c : b.shape.compound->children) {
      render::DrawShape part = s;
      part.position = (p + q * c.position_m).cast<float>();
      part.orientation = (q * c.orientation).cast<float>();
      emit(c.shape, part);
    }
  });
  snapshotParticles(out, alpha);
  snapshotVehiclesAndLines(out, alpha);
}

void Scene::snapshotParticles(render::FrameSnapshot& out, double alpha) const {
  out.particles.clear();
  out.additiveParticles.clear();
  const particles::ParticleSystem* ps = m_particles.get();
  if (!ps) return;
  // Positions are the step's end; back them up along the velocity to the
  // interpolated time (alpha = 1: the step's end).
  const float back_s = float((1.0 - alpha) * m_options.dt_s);
  ps->forEach([&](particles::EmitterId, const particles::Emitter& e) {
    const particles::ParticlePool& p = e.pool;
    const particles::EmitterDef& d = e.def;
    std::vector<render::DrawParticle>& dst =
        d.blend == particles::BlendMode::Additive ? out.additiveParticles : out.particles;
    const bool local = d.space == particles::SimSpace::Local;
    const Eigen::Matrix3f rot = e.rotation.toRotationMatrix();
    for (std::uint32_t i = 0; i < p.count; ++i) {
      const float life = std::min(1.0f, p.age_s[i] * p.invLifetime[i]);
      render::DrawParticle q;
      q.size_m = d.size_m.eval(life);
      const float a = d.alpha.eval(life);
      if (q.size_m <= 0 || a <= 0) continue;
      Eigen::Vector3f pos(p.px[i] - p.vx[i] * back_s, p.py[i] - p.vy[i] * back_s, p.pz[i] - p.vz[i] * back_s);
      q.position = local ? Eigen::Vector3f(rot * pos + e.position_m) : pos;
      const Eigen::Vector3f rgb = d.color.eval(life);
      q.color = Eigen::Vector4f(rgb.x(), rgb.y(), rgb.z(), a);
      q.angle_rad = p.angle_rad[i] - p.spin_radps[i] * back_s;
      if (d.stretch_s > 0) {
        const Eigen::Vector3f v(p.vx[i], p.vy[i], p.vz[i]);
        q.stretch_m = (local ? Eigen::Vector3f(rot * v) : v) * d.stretch_s;
      }
      dst.push_back(q);
    }
  });
}

void Scene::snapshotVehiclesAndLines(render::FrameSnapshot& out, double alpha) const {
  const script::Presentation& presentation = m_host->presentation();
  // Vehicle wheels are ray casts, not bodies: drawn with the runtime's wheel
  // model (assets/models; axle along X, radius 0.35 m, width 0.25 m) at each
  // hub, steered and turned by its accumulated spin; as spheres if the model
  // is missing.
  std::shared_ptr<const render::Model> wheelModel;
  if (const vehicle::VehicleSystem* vehicles = m_vehicles.get(); vehicles && vehicles->count() > 0) {
    auto loaded = m_models->get(assetPath("models/wheel.obj"));
    if (loaded) wheelModel = loaded.value();
  }
  constexpr float kWheelModelRadius_m = 0.35f, kWheelModelWidth_m = 0.25f;
  if (const vehicle::VehicleSystem* vehicles = m_vehicles.get())
    vehicles->forEach([&](vehicle::VehicleId id) {
      // Hubs ride with the chassis' interpolated pose, so they do not lag it.
      const physics::BodyId c = vehicles->chassis(id);
      const physics::Body& b = m_world->body(c);
      Vec3 p = b.position_m;
      Quat q = b.orientation;
      if (c.index < m_prevPosition.size()) {
        p = m_prevPosition[c.index] + Real(alpha) * (b.position_m - m_prevPosition[c.index]);
        q = m_prevOrientation[c.index].slerp(Real(alpha), b.orientation);
      }
      for (int i = 0; i < vehicles->wheelCount(id); ++i) {
        const vehicle::WheelTelemetry& w = vehicles->wheel(id, i);
        const Vec3 hub = p + q * (b.orientation.conjugate() * (w.hub_m - b.position_m));
        if (wheelModel) {
          render::ModelInstance m;
          m.model = wheelModel;
          m.position = hub.cast<float>();
          const Quat turn = q * Quat(Eigen::AngleAxis<Real>(w.steer_rad, Vec3::UnitY())) *
                            Quat(Eigen::AngleAxis<Real>(w.rotation_rad, Vec3::UnitX()));
          m.orientation = turn.cast<float>();
          const float r = float(w.radius_m) / kWheelModelRadius_m;
          m.scale = Eigen::Vector3f(float(w.width_m) / kWheelModelWidth_m, r, r);
          out.models.push_back(std::move(m));
          continue;
        }
        render::DrawShape s;
        s.kind = render::ShapeKind::Sphere;
        s.position = hub.cast<float>();
        s.radius_m = float(w.radius_m);
        s.color = Eigen::Vector3f(0.12f, 0.12f, 0.13f);
        out.shapes.push_back(s);
      }
    });
  // Ropes as lit tubes (a capsule of the rope's thickness per segment, so
  // the joints are round), cloth as a surface lit on both sides; neither
  // interpolated (their particles are not bodies).
  out.surfaces.clear();
  if (const physics::DeformableSystem* d = m_deformables.get()) {
    d->forEach([&](int id, const physics::Deformable& def) {
      const Eigen::Vector3f color = presentation.deformableColor(id);
      if (def.kind() == physics::Deformable::Kind::Cloth) return out.surfaces.push_back(clothSurface(def, color));
      def.forEachStructuralSegment([&](const Vec3& a, const Vec3& b) {
        out.shapes.push_back(ropeSegment(a.cast<float>(), b.cast<float>(), float(def.material().radius_m), color));
      });
    });
  }
  // The lines scripts drew, after the collision view's mesh wireframes
  // (snapshot cleared the list).
  for (const auto& l : presentation.scriptLines())
    out.lines.push_back(render::DebugLine{l.a_m.cast<float>(), l.b_m.cast<float>(), l.color});
}


}  // namespace tumble::app
