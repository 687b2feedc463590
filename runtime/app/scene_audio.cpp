#include "app/scene_audio.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "app/scene_sky.h"
#include "core/log.h"
#include "render/sky.h"
#include "vehicle/vehicle_system.h"
#ifdef TUMBLE_HAVE_TERRAIN
#include "app/terrain_scene.h"
#include "terrain/material_map.h"
#endif

namespace tumble::app {

namespace {

using audio::TyreSurface;

#ifdef TUMBLE_HAVE_TERRAIN
/// The terrain's sound layer (terrain/material_map.h) as one of the four tyre sounds.
TyreSurface tyreSurfaceOf(std::uint8_t layerValue) {
  using terrain::SurfaceSound;
  switch (SurfaceSound(layerValue)) {
    case SurfaceSound::Grass:
    case SurfaceSound::Snow: return TyreSurface::Grass;
    case SurfaceSound::Gravel:
    case SurfaceSound::Sand: return TyreSurface::Gravel;
    case SurfaceSound::Mud:
    case SurfaceSound::Water: return TyreSurface::Mud;
    default: return TyreSurface::Asphalt;  // asphalt, rock, wood, metal and values past the list
  }
}
#endif

/// What the tyre touches: the terrain's sound layer under the contact, or
/// asphalt (the ground plane, a body, a terrain without material maps is
/// grass as the layer's default).
TyreSurface surfaceUnder(const Scene& scene, const vehicle::WheelTelemetry& w) {
#ifdef TUMBLE_HAVE_TERRAIN
  if (w.ground.isNull() && scene.terrainScene()) {
    const terrain::Terrain& t = scene.terrainScene()->terrain();
    const terrain::MaterialMaps* maps = t.materials();
    if (!maps) return tyreSurfaceOf(terrain::MaterialDefaults{}.sound);
    int bi = 0, bj = 0;
    t.blockAt(w.contactPoint_m.x(), w.contactPoint_m.z(), bi, bj);
    return tyreSurfaceOf(maps->get(terrain::MaterialLayer::Sound, bi, bj));
  }
#else
  (void)scene;
  (void)w;
#endif
  return TyreSurface::Asphalt;
}

#ifdef TUMBLE_HAVE_TERRAIN
/// The terrain's sound layer as what an impact on it sounds like.
audio::ImpactMaterial impactMaterialOf(std::uint8_t layerValue) {
  using terrain::SurfaceSound;
  using audio::ImpactMaterial;
  switch (SurfaceSound(layerValue)) {
    case SurfaceSound::Gravel: return ImpactMaterial::Gravel;
    case SurfaceSound::Mud:
    case SurfaceSound::Water: return ImpactMaterial::Mud;
    case SurfaceSound::Rock:
    case SurfaceSound::Asphalt: return ImpactMaterial::Rock;
    case SurfaceSound::Wood: return ImpactMaterial::Wood;
    case SurfaceSound::Metal: return ImpactMaterial::Metal;
    default: return ImpactMaterial::Soil;  // grass, sand, snow and values past the list
  }
}
#endif

/// What a contact's side sounds like: the body's sound material; unset, a
/// vehicle's chassis is metal, a plane (the ground) rock, anything else a
/// thud. The terrain (a null body): its sound layer at the point.
audio::ImpactMaterial impactMaterialAt(const Scene& scene, physics::BodyId body, const Vec3& point_m,
                                       const std::vector<physics::BodyId>& chassis) {
  using audio::ImpactMaterial;
  if (body.isNull()) {
#ifdef TUMBLE_HAVE_TERRAIN
    if (const TerrainScene* ts = scene.terrainScene()) {
      const terrain::Terrain& t = ts->terrain();
      const terrain::MaterialMaps* maps = t.materials();
      if (!maps) return impactMaterialOf(terrain::MaterialDefaults{}.sound);
      int bi = 0, bj = 0;
      t.blockAt(point_m.x(), point_m.z(), bi, bj);
      return impactMaterialOf(maps->get(terrain::MaterialLayer::Sound, bi, bj));
    }
#else
    (void)point_m;
#endif
    return ImpactMaterial::Rock;
  }
  if (!scene.world().isValid(body)) return ImpactMaterial::Thud;
  const physics::Body& b = scene.world().body(body);
  if (b.soundMaterial != 0) return ImpactMaterial(b.soundMaterial);
  if (std::find(chassis.begin(), chassis.end(), body) != chassis.end()) return ImpactMaterial::Metal;
  if (b.shape.type == physics::ShapeType::Plane) return ImpactMaterial::Rock;
  return ImpactMaterial::Thud;
}

/// Impacts of the step's new contacts, by the materials that met.
void soundImpacts(Scene& scene, audio::AudioSystem& a) {
  const auto& events = scene.world().contactEvents();
  if (events.empty()) return;
  std::vector<physics::BodyId> chassis;
  if (vehicle::VehicleSystem* vs = scene.vehiclesIfAny()) vs->forEach([&](vehicle::VehicleId id) { chassis.push_back(vs->chassis(id)); });
  for (const physics::ContactEvent& e : events)
    a.impact(e.point_m, float(e.impulse_Ns), impactMaterialAt(scene, e.a, e.point_m, chassis),
             impactMaterialAt(scene, e.b, e.point_m, chassis));
}

/// Rain intensity of the weather, 0..1: a storm pours (1); clear and cloudy skies are dry.
float rainIntensity(const script::EnvironmentRequest& environment) { return environment.weather == "storm" ? 1.0f : 0.0f; }

void soundVehicles(Scene& scene, audio::AudioSystem& a, vehicle::VehicleSystem& vs) {
  const physics::World& world = scene.world();
  static std::set<std::string> badSamples;  // say each broken sample once
  audio::VehicleSoundInput in;
  vs.forEach([&](vehicle::VehicleId id) {
    const vehicle::VehicleDef& def = vs.def(id);
    const vehicle::VehicleTelemetry& t = vs.telemetry(id);
    const physics::Body& chassis = world.body(vs.chassis(id));
    in.position_m = chassis.position_m;
    in.velocity_mps = chassis.linearVelocity_mps;
    in.rpm = float(t.rpm);
    const Real fullTorque = def.engine.torque.eval(t.rpm);
    in.load = fullTorque > 0 ? float(std::clamp(t.engineTorque_Nm / fullTorque, Real(0), Real(1))) : 0.0f;
    in.shifting = t.shifting;
    in.speed_mps = float(chassis.linearVelocity_mps.norm());
    in.cylinders = int(def.sound.cylinders);
    in.volume = float(def.sound.volume);
    in.sampleRpm = float(def.sound.sampleRpm);
    in.tyreSlipThreshold_mps = float(def.sound.tyreSlipThreshold_mps);
    in.engineSample = 0;
    if (!def.sound.engineSamplePath.empty() && !badSamples.count(def.sound.engineSamplePath)) {
      auto clip = a.clipFromFile(def.sound.engineSamplePath);
      if (clip) in.engineSample = *clip;
      else badSamples.insert(def.sound.engineSamplePath), log::warn("audio: " + clip.error() + "; the engine is synthesised");
    }
    in.wheels.resize(std::size_t(vs.wheelCount(id)));
    for (int i = 0; i < vs.wheelCount(id); ++i) {
      const vehicle::WheelTelemetry& w = vs.wheel(id, i);
      in.wheels[std::size_t(i)] = {w.contact, float(w.slipSpeed_mps), surfaceUnder(scene, w)};
    }
    a.updateVehicle((std::uint64_t(id.index) << 32) | id.generation, in);
  });
}

/// Behind and above the first vehicle, facing its way (the chase camera's
/// place, render/camera_rig.h), for runs without a camera.
Scene::Listener listenerWithoutCamera(Scene& scene, Vec3& velocity_mps) {
  Scene::Listener l;
  velocity_mps = Vec3::Zero();
  if (vehicle::VehicleSystem* vs = scene.vehiclesIfAny()) {
    bool found = false;
    vs->forEach([&](vehicle::VehicleId id) {
      if (found) return;
      found = true;
      const physics::Body& b = scene.world().body(vs->chassis(id));
      l.position_m = b.position_m + b.orientation * Vec3(0, Real(2.2), Real(-6.5));
      l.forward = b.orientation * Vec3::UnitZ();
      velocity_mps = b.linearVelocity_mps + b.angularVelocity_radps.cross(l.position_m - b.position_m);  // riding with it
    });
  }
  return l;
}

}  // namespace

Scene::Listener listenerAtCamera(const render::Camera& c) {
  Scene::Listener l;
  Eigen::Vector3f eye = c.eye_m, up = c.up;
  if (c.mode == render::CameraMode::Orbit || c.mode == render::CameraMode::Follow) {
    eye = c.target + c.distance_m * Eigen::Vector3f(std::cos(c.pitch_rad) * std::sin(c.yaw_rad), std::sin(c.pitch_rad),
                                                    std::cos(c.pitch_rad) * std::cos(c.yaw_rad));
    up = Eigen::Vector3f::UnitY();
  }
  const Eigen::Vector3f look = c.target - eye;
  l.position_m = eye.cast<Real>();
  if (look.norm() > 1e-6f) l.forward = look.normalized().cast<Real>();
  if (up.norm() > 1e-6f) l.up = up.normalized().cast<Real>();
  return l;
}

void stepAudio(Scene& scene, double start_s, double dt_s) {
  audio::AudioSystem* a = scene.audioIfAny();
  vehicle::VehicleSystem* vehicles = scene.vehiclesIfAny();
  // The storm's lightning (the schedule the renderer draws): thunder for
  // each flash of this step, heard distance / 343 m/s later.
  const std::vector<render::LightningStrike> strikes =
      render::lightningStrikes(skySettingsOf(scene.host().presentation().environment), start_s, start_s + dt_s);
  const float rain = rainIntensity(scene.host().presentation().environment);
  if (!a) {
    if (scene.options().audioOutput == audio::AudioOutput::Silent) return;
    if (!(vehicles && vehicles->count() > 0) && scene.world().contactEvents().empty() && strikes.empty() && rain == 0)
      return;
    a = &scene.audio();
  }
  const bool mixing = a->output() != audio::AudioOutput::Silent;
  if (mixing) {
    Vec3 velocity_mps = Vec3::Zero();
    const Scene::Listener l = scene.listener() ? *scene.listener() : listenerWithoutCamera(scene, velocity_mps);
    // The camera's velocity from its movement; without a camera the listener rides with the first vehicle.
    if (scene.listener()) velocity_mps = scene.listenerMotion().update(l.position_m, start_s);
    a->setListener(l.position_m, l.forward, l.up, velocity_mps);
    if (vehicles) soundVehicles(scene, *a, *vehicles);
    soundImpacts(scene, *a);
    for (const render::LightningStrike& s : strikes) a->thunder(s.ground_m.cast<Real>());
  }
  a->setRain(rain);
  // Script sounds on bodies: moved, or stopped when their body is gone.
  auto& follows = scene.soundBodies();
  for (auto it = follows.begin(); it != follows.end();) {
    if (!a->isPlaying(it->first)) {
      it = follows.erase(it);
    } else if (!scene.world().isValid(it->second)) {
      a->stop(it->first);
      it = follows.erase(it);
    } else {
      const physics::Body& b = scene.world().body(it->second);
      a->setPosition(it->first, b.position_m);
      a->setVelocity(it->first, b.linearVelocity_mps);
      ++it;
    }
  }
  a->update(dt_s);
}

}  // namespace tumble::app
