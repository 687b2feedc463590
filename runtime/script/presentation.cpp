#include "script/presentation.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "script/mods.h"

namespace tumble::script {

namespace fs = std::filesystem;

Result<std::string> resolveModFile(const std::string& ref, const ModInfo& caller,
                                   const std::map<std::string, std::string>& modDirs) {
  std::string modName = caller.name, relative = ref;
  std::string modDir = caller.dir;
  if (const auto colon = ref.find(':'); colon != std::string::npos) {
    modName = ref.substr(0, colon);
    relative = ref.substr(colon + 1);
    if (modName != caller.name) {
      auto it = modDirs.find(modName);
      if (it == modDirs.end()) {
        return makeError("\"" + ref + "\": no mod named \"" + modName + "\" is installed (write \"MOD:path\", e.g. "
                         "\"base:assets/models/rock.obj\")");
      }
      modDir = it->second;
    }
  }
  if (relative.empty()) return makeError("\"" + ref + "\": the path inside the mod is empty");
  if (fs::path(relative).is_absolute()) {
    return makeError("\"" + ref + "\": absolute paths are not allowed; give a path inside a mod");
  }
  const fs::path root = fs::weakly_canonical(fs::path(modDir));
  const fs::path path = fs::weakly_canonical(root / relative);
  const fs::path rel = path.lexically_relative(root);
  if (rel.empty() || *rel.begin() == "..") {
    return makeError("\"" + ref + "\" leaves the folder of mod \"" + modName + "\"; paths stay inside it");
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    return makeError("\"" + ref + "\": no such file in mod \"" + modName + "\" (looked for " + path.string() + ")");
  }
  return path.string();
}

bool isFileInMods(const std::string& file, const std::map<std::string, std::string>& modDirs) {
  std::error_code ec;
  const fs::path path = fs::weakly_canonical(fs::path(file), ec);
  if (ec || !fs::is_regular_file(path, ec)) return false;
  for (const auto& [name, dir] : modDirs) {
    const fs::path rel = path.lexically_relative(fs::weakly_canonical(fs::path(dir), ec));
    if (!ec && !rel.empty() && *rel.begin() != "..") return true;
  }
  return false;
}

void Presentation::setColor(physics::BodyId id, const Eigen::Vector3f& rgb) {
  if (m_colors.size() <= id.index) m_colors.resize(id.index + 1, Eigen::Vector3f(-1, -1, -1));
  m_colors[id.index] = rgb;
}

Eigen::Vector3f Presentation::colorOf(physics::BodyId id) const {
  if (id.index < m_colors.size() && m_colors[id.index].x() >= 0) return m_colors[id.index];
  return Eigen::Vector3f(0.75f, 0.75f, 0.78f);
}

void Presentation::setGroundTexture(physics::BodyId id, int layer) {
  if (m_groundTextures.size() <= id.index) m_groundTextures.resize(id.index + 1, -1);
  m_groundTextures[id.index] = layer;
}

int Presentation::groundTextureOf(physics::BodyId id) const {
  return id.index < m_groundTextures.size() ? m_groundTextures[id.index] : -1;
}

Eigen::Vector3f Presentation::deformableColor(int id) const {
  auto it = m_deformableColors.find(id);
  return it == m_deformableColors.end() ? Eigen::Vector3f(0.9f, 0.6f, 0.2f) : it->second;
}

void Presentation::addScriptLine(const ScriptLine& line) {
  if (m_scriptLines.size() < kMaxScriptLines) m_scriptLines.push_back(line);
}

}  // namespace tumble::script

namespace tumble::script {

namespace {

constexpr std::uint32_t kPresentationMagic = 0x54505253;  // "TPRS"
constexpr std::size_t kMaxStatics = std::size_t(1) << 20;
constexpr std::size_t kMaxGates = 1000;       // hud.set_gates
constexpr int kGroundTextures = 8;            // world.plane's textures (bind_world.cpp)
constexpr std::size_t kMaxPath = 4096;
constexpr std::size_t kMaxWord = 64;

/// A zero T (Eigen's T{} is not initialised: its bytes would differ between saves).
template <typename T>
T zero() {
  if constexpr (requires { T::Zero(); }) return T::Zero();
  else return T{};
}

template <typename T>
void writeOptional(ByteWriter& w, const std::optional<T>& v) {
  w.pod(std::uint8_t(v.has_value()));
  w.pod(v ? *v : zero<T>());
}

/// An optional as writeOptional wrote it; false if its flag is not 0 or 1.
template <typename T>
bool readOptional(ByteReader& r, std::optional<T>& out) {
  const auto has = r.pod<std::uint8_t>();
  const T v = r.pod<T>();
  if (has > 1) return false;
  out = has ? std::optional<T>(v) : std::nullopt;
  return true;
}

template <typename M>
bool finite(const M& m) {
  if constexpr (std::is_arithmetic_v<M>) return std::isfinite(m);
  else return m.allFinite();
}
bool unitQuat(const Quat& q) { return q.coeffs().allFinite() && std::abs(q.norm() - 1) < Real(1e-3); }
bool colour01(const Eigen::Vector3f& c) { return c.allFinite() && c.minCoeff() >= 0 && c.maxCoeff() <= 1; }

}  // namespace

void Presentation::saveState(ByteWriter& w, const std::function<std::string(const std::string&)>& refOf) const {
  w.pod(kPresentationMagic);
  w.vec(m_colors);
  w.vec(m_groundTextures);
  w.pod(std::uint64_t(m_deformableColors.size()));
  for (const auto& [id, rgb] : m_deformableColors) {
    w.pod(std::int32_t(id));
    w.pod(rgb);
  }
  w.pod(std::uint64_t(attachments.size()));
  for (const ModelAttachment& a : attachments) {
    w.pod(a.body);
    w.text(refOf(a.file));
    w.pod(a.offset_m);
    w.pod(a.rotation);
    w.pod(a.scale);
  }
  w.pod(std::uint64_t(statics.size()));
  for (const StaticModel& m : statics) {
    w.text(refOf(m.file));
    w.pod(m.position_m);
    w.pod(m.rotation);
    w.pod(m.scale);
    w.pod(m.body);
  }
  const CameraRequest& c = camera;
  w.text(c.mode);
  writeOptional(w, c.target);
  writeOptional(w, c.offset_m);
  writeOptional(w, c.lookAt_m);
  writeOptional(w, c.eye_m);
  writeOptional(w, c.hoodEye_m);
  writeOptional(w, c.stiffness_per_s);
  writeOptional(w, c.distance_m);
  w.text(c.interiorFile.empty() ? std::string() : refOf(c.interiorFile));
  writeOptional(w, c.speedGauge_m);
  writeOptional(w, c.rpmGauge_m);
  w.pod(c.gaugeRadius_m);
  const EnvironmentRequest& e = environment;
  writeOptional(w, e.timeOfDay_h);
  writeOptional(w, e.sunDirection);
  writeOptional(w, e.fogDistance_m);
  w.pod(e.cloudCover);
  w.text(e.weather);
  w.pod(e.wind_mps);
  w.pod(std::uint8_t(lap.shown));
  w.pod(lap.time_s);
  writeOptional(w, lap.last_s);
  writeOptional(w, lap.best_s);
  w.pod(std::int32_t(lap.gate));
  w.pod(std::int32_t(lap.gates));
  w.pod(std::int32_t(lap.lap));
  w.pod(std::int32_t(lap.laps));
  w.pod(std::uint8_t(lap.finished));
  w.vec(gates_m);
}

Status Presentation::restoreState(ByteReader& r, const std::function<Result<std::string>(const std::string&)>& resolve,
                                  const std::function<bool(physics::BodyId)>& bodyKnown, std::size_t bodySlots) {
  auto damaged = [](const std::string& what) { return makeError("presentation: damaged (" + what + ")"); };
  if (r.pod<std::uint32_t>() != kPresentationMagic || !r.ok()) return damaged("header");
  auto colors = r.vec<Eigen::Vector3f>(bodySlots);
  auto groundTextures = r.vec<int>(bodySlots);
  if (!r.ok()) return damaged("body colours");
  for (const Eigen::Vector3f& c : colors)
    if (!colour01(c) && c != Eigen::Vector3f(-1, -1, -1)) return damaged("body colours");
  for (int t : groundTextures)
    if (t < -1 || t >= kGroundTextures) return damaged("ground textures");
  std::map<int, Eigen::Vector3f> deformableColors;
  const auto deformables = r.pod<std::uint64_t>();
  if (!r.ok() || deformables > kMaxStatics || deformables > r.remaining() / sizeof(Eigen::Vector3f))
    return damaged("rope and cloth colours");
  for (std::uint64_t i = 0; i < deformables; ++i) {
    const auto id = r.pod<std::int32_t>();
    const auto rgb = r.pod<Eigen::Vector3f>();
    if (!r.ok() || !colour01(rgb)) return damaged("rope and cloth colours");
    deformableColors[id] = rgb;
  }
  auto file = [&](const std::string& ref, const char* what) -> Result<std::string> {
    if (!r.ok()) return damaged(what);
    auto f = resolve(ref);
    if (!f) return makeError(std::string("presentation: ") + what + ": " + f.error());
    return f;
  };
  // Counts are checked against the bytes left (each entry takes at least
  // its fixed-size fields) before anything is allocated for them.
  const auto attachedCount = r.pod<std::uint64_t>();
  if (!r.ok() || attachedCount > bodySlots || attachedCount > r.remaining() / sizeof(physics::BodyId))
    return damaged("models on bodies");
  std::vector<ModelAttachment> attached(attachedCount);
  for (ModelAttachment& a : attached) {
    a.body = r.pod<physics::BodyId>();
    auto f = file(r.text(kMaxPath), "models on bodies");
    if (!f) return makeError(f.error());
    a.file = f.value();
    a.offset_m = r.pod<Vec3>();
    a.rotation = r.pod<Quat>();
    a.scale = r.pod<Vec3>();
    if (!r.ok() || !bodyKnown(a.body) || !finite(a.offset_m) || !unitQuat(a.rotation) || !finite(a.scale))
      return damaged("models on bodies");
  }
  const auto placedCount = r.pod<std::uint64_t>();
  if (!r.ok() || placedCount > kMaxStatics || placedCount > r.remaining() / sizeof(Vec3))
    return damaged("static models");
  std::vector<StaticModel> placed(placedCount);
  for (StaticModel& m : placed) {
    auto f = file(r.text(kMaxPath), "static models");
    if (!f) return makeError(f.error());
    m.file = f.value();
    m.position_m = r.pod<Vec3>();
    m.rotation = r.pod<Quat>();
    m.scale = r.pod<Vec3>();
    m.body = r.pod<physics::BodyId>();
    if (!r.ok() || !finite(m.position_m) || !unitQuat(m.rotation) || !finite(m.scale) ||
        !(m.body.isNull() || bodyKnown(m.body)))
      return damaged("static models");
  }
  CameraRequest c;
  c.mode = r.text(kMaxWord);
  bool ok = readOptional(r, c.target) && readOptional(r, c.offset_m) && readOptional(r, c.lookAt_m) &&
            readOptional(r, c.eye_m) && readOptional(r, c.hoodEye_m) && readOptional(r, c.stiffness_per_s) &&
            readOptional(r, c.distance_m);
  const std::string interior = r.text(kMaxPath);
  ok = ok && readOptional(r, c.speedGauge_m) && readOptional(r, c.rpmGauge_m);
  c.gaugeRadius_m = r.pod<Real>();
  auto finiteOr = [](const auto& o) { return !o || finite(*o); };
  if (!r.ok() || !ok || (c.mode != "orbit" && c.mode != "follow" && c.mode != "chase" && c.mode != "hood" &&
                         c.mode != "cockpit") ||
      (c.target && !bodyKnown(*c.target)) || !finiteOr(c.offset_m) || !finiteOr(c.lookAt_m) || !finiteOr(c.eye_m) ||
      !finiteOr(c.hoodEye_m) || !finiteOr(c.stiffness_per_s) || !finiteOr(c.distance_m) ||
      !finiteOr(c.speedGauge_m) || !finiteOr(c.rpmGauge_m) || !(c.gaugeRadius_m > 0 && c.gaugeRadius_m <= 1))
    return damaged("camera");
  if (!interior.empty()) {
    auto f = file(interior, "camera");
    if (!f) return makeError(f.error());
    c.interiorFile = f.value();
  }
  EnvironmentRequest e;
  ok = readOptional(r, e.timeOfDay_h) && readOptional(r, e.sunDirection) && readOptional(r, e.fogDistance_m);
  e.cloudCover = r.pod<double>();
  e.weather = r.text(kMaxWord);
  e.wind_mps = r.pod<Eigen::Vector2d>();
  if (!r.ok() || !ok || (e.timeOfDay_h && !(*e.timeOfDay_h >= 0 && *e.timeOfDay_h <= 24)) ||
      (e.sunDirection && !(finite(*e.sunDirection) && e.sunDirection->norm() > Real(0.5))) ||
      (e.fogDistance_m && !(*e.fogDistance_m >= 0 && std::isfinite(*e.fogDistance_m))) ||
      !(e.cloudCover >= 0 && e.cloudCover <= 1) ||
      (e.weather != "clear" && e.weather != "cloudy" && e.weather != "storm") || !finite(e.wind_mps))
    return damaged("environment");
  LapDisplay l;
  const auto shown = r.pod<std::uint8_t>();
  l.time_s = r.pod<double>();
  ok = readOptional(r, l.last_s) && readOptional(r, l.best_s);
  l.gate = r.pod<std::int32_t>();
  l.gates = r.pod<std::int32_t>();
  l.lap = r.pod<std::int32_t>();
  l.laps = r.pod<std::int32_t>();
  const auto finished = r.pod<std::uint8_t>();
  auto count = [](int n) { return n >= 0 && n <= 1000000; };
  auto seconds = [](const std::optional<double>& s) { return !s || (*s >= 0 && std::isfinite(*s)); };
  if (!r.ok() || !ok || shown > 1 || finished > 1 || !(l.time_s >= 0 && std::isfinite(l.time_s)) ||
      !seconds(l.last_s) || !seconds(l.best_s) || !count(l.gate) || !count(l.gates) || !count(l.lap) ||
      !count(l.laps) || l.gate > l.gates)
    return damaged("lap display");
  l.shown = shown != 0;
  l.finished = finished != 0;
  auto gates = r.vec<Vec3>(kMaxGates);
  if (!r.ok() || !std::all_of(gates.begin(), gates.end(), [](const Vec3& g) { return finite(g); }))
    return damaged("gates");
  m_colors = std::move(colors);
  m_groundTextures = std::move(groundTextures);
  m_deformableColors = std::move(deformableColors);
  attachments = std::move(attached);
  statics = std::move(placed);
  c.revision = camera.revision + 1;
  camera = std::move(c);
  e.revision = environment.revision + 1;
  environment = std::move(e);
  lap = l;
  gates_m = std::move(gates);
  ++revision;
  return Ok{};
}

}  // namespace tumble::script
