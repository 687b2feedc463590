#include "app/physics_settings.h"

#include <sstream>
#include <type_traits>

namespace tumble::app {

namespace {

template <typename T>
Status parseSetting(const std::string& key, const std::string& text, T* out) {
  std::istringstream in(text);
  T v{};
  if constexpr (std::is_same_v<T, bool>) {
    if (text == "true" || text == "1") v = true;
    else if (text == "false" || text == "0") v = false;
    else return makeError("--set " + key + "=" + text + ": expected true or false");
  } else {
    in >> v;
    if (!in || !in.eof()) return makeError("--set " + key + "=" + text + ": expected a number");
  }
  *out = v;
  return Ok{};
}

}  // namespace

Status applyPhysicsSetting(physics::WorldSettings& s, const std::string& key, const std::string& value) {
  const std::string k = key.substr(std::string("physics.").size());
  Status st = Ok{};
  double d = 0;
  int i = 0;
  bool b = false;
  if (k == "substeps") {
    if (!(st = parseSetting(key, value, &i))) return st;
    if (i < 1 || i > 1000) return makeError("--set " + key + ": substeps must be 1..1000");
    s.substeps = i;
  } else if (k == "iterations") {
    if (!(st = parseSetting(key, value, &i))) return st;
    if (i < 1 || i > 1000) return makeError("--set " + key + ": iterations must be 1..1000");
    s.velocityIterations = i;
  } else if (k == "relax_iterations") {
    if (!(st = parseSetting(key, value, &i))) return st;
    if (i < 0 || i > 1000) return makeError("--set " + key + ": relax_iterations must be 0..1000");
    s.relaxIterations = i;
  } else if (k == "threads") {
    if (!(st = parseSetting(key, value, &i))) return st;
    if (i < 1 || i > 64) return makeError("--set " + key + ": threads must be 1..64");
    s.threads = i;
  } else if (k == "soft_contacts") {
    if (!(st = parseSetting(key, value, &b))) return st;
    s.softContacts = b;
  } else if (k == "sleep") {
    if (!(st = parseSetting(key, value, &b))) return st;
    s.enableSleep = b;
  } else if (k == "baumgarte") {
    if (!(st = parseSetting(key, value, &d))) return st;
    if (!(d > 0 && d <= 1)) return makeError("--set " + key + ": baumgarte must be in (0, 1]");
    s.baumgarte = Real(d);
  } else if (k == "solver_tolerance") {
    if (!(st = parseSetting(key, value, &d))) return st;
    if (!(d >= 0 && d < 1)) return makeError("--set " + key + ": solver_tolerance must be in [0, 1)");
    s.solverTolerance = Real(d);
  } else if (k == "gravity") {
    if (!(st = parseSetting(key, value, &d))) return st;
    s.gravity_mps2 = Vec3(0, Real(-d), 0);
  } else {
    return makeError("--set " + key +
                     ": unknown physics setting (known: physics.substeps, physics.iterations, "
                     "physics.relax_iterations, physics.threads, physics.soft_contacts, physics.sleep, physics.baumgarte, "
                     "physics.solver_tolerance, physics.gravity, physics.joint_solver)");
  }
  return Ok{};
}

}  // namespace tumble::app
