#include "app/scene_view.h"

#include <algorithm>

#include "app/terrain_scene.h"
#include "particles/particle_system.h"
#include "vehicle/vehicle_system.h"

namespace tumble::app {

int particleCount(Scene& scene) {
  const particles::ParticleSystem* ps = scene.particlesIfAny();
  return ps ? ps->particleCount() : 0;
}

void frameCamera(Scene& scene, render::Camera& cam) {
  // A scene with vehicles follows the first one from 12 m (until the chase
  // camera of the camera modes lands).
  if (const vehicle::VehicleSystem* vehicles = scene.vehiclesIfAny(); vehicles && vehicles->count() > 0) {
    bool first = true;
    vehicles->forEach([&](vehicle::VehicleId id) {
      if (!first) return;
      first = false;
      cam.target = scene.world().body(vehicles->chassis(id)).position_m.cast<float>();
      cam.distance_m = 12;
      cam.mode = render::CameraMode::Follow;
    });
    return;
  }
  Eigen::Vector3f lo(1e30f, 1e30f, 1e30f), hi = -lo;
  int n = 0;
  scene.world().forEachBody([&](physics::BodyId, const physics::Body& b) {
    if (b.type == physics::BodyType::Static) return;
    Eigen::Vector3f p = b.position_m.cast<float>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    ++n;
  });
  if (n == 0) return;
  cam.target = (lo + hi) / 2;
  // Half way down from the bodies' middle to the ground under it (y = 0 on
  // a plane, the terrain's height over a terrain), and at least 0.5 m up:
  // the view takes in what is falling and where it lands. Over a terrain
  // the ground is the terrain, or the view would aim under the hills.
  float ground_m = 0;
  if (const TerrainScene* terrain = scene.terrainScene()) {
    Real h = 0;
    Vec3 normal;
    if (terrain->heightField().surfaceAt(Real(cam.target.x()), Real(cam.target.z()), &h, &normal)) ground_m = float(h);
  }
  cam.target.y() = ground_m + std::max((cam.target.y() - ground_m) * 0.5f, 0.5f);
  cam.distance_m = std::clamp((hi - lo).norm() * 1.4f + 6.0f, 6.0f, 400.0f);
}

Eigen::Vector3f dynamicCentroid(Scene& scene) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  int n = 0;
  scene.world().forEachBody([&](physics::BodyId, const physics::Body& b) {
    if (b.type != physics::BodyType::Dynamic) return;
    sum += b.position_m.cast<float>();
    ++n;
  });
  return n ? Eigen::Vector3f(sum / float(n)) : Eigen::Vector3f(0, 1, 0);
}

render::HudStats hudStats(Scene& scene, double fps, const RunTimings& perFrame, double time_s) {
  render::HudStats h;
  h.scenario = scene.host().title();
  h.fps = fps;
  h.physics_ms = perFrame.physics_s * 1000;
  h.script_ms = perFrame.script_s * 1000;
  h.render_ms = perFrame.render_s * 1000;
  h.particles_ms = perFrame.particles_s * 1000;
  h.simTime_s = time_s;
  h.bodies = scene.world().bodyCount();
  h.contacts = scene.world().contactPointCount();
  for (const auto& e : scene.host().errors()) h.messages.push_back(e.summary());
  if (h.messages.size() > 5) h.messages.erase(h.messages.begin(), h.messages.end() - 5);
  for (const auto& line : scene.host().hudText()) h.messages.insert(h.messages.begin(), line);
  for (const auto& m : scene.host().activeMessages(time_s)) h.messages.insert(h.messages.begin(), m);
  if (scene.host().hasScore()) h.messages.insert(h.messages.begin(), "score: " + std::to_string(scene.host().score()));
  if (scene.host().outcome() != script::Outcome::None)
    h.messages.insert(h.messages.begin(), std::string(scene.host().outcome() == script::Outcome::Won ? "WON: " : "LOST: ") +
                                              scene.host().outcomeReason());
  return h;
}

Result<std::unique_ptr<render::Renderer>> makeRenderer(Scene& scene, int w, int h, bool offscreen, bool hud) {
  render::WindowConfig cfg;
  cfg.width = w;
  cfg.height = h;
  cfg.title = "Tumble - " + scene.name();
  cfg.forceOffscreen = offscreen;
  cfg.hud = hud;
  if (scene.hasTerrain()) cfg.msaaSamples = 1;  // terrain fill rate on llvmpipe (render/README.md)
  auto r = render::Renderer::create(cfg);
  if (!r) return makeError("cannot open a window or an offscreen GL context: " + r.error());
  scene.noteSubsystem("render");
  return r;
}

}  // namespace tumble::app
