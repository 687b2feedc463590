// Report fields shared by main.cpp and sweep.cpp (see compare_report.h).
#include "compare_report.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "physics/world.h"

using nlohmann::json;

namespace tumble::compare {

/// Nearest-rank percentile of a sample (p in [0, 1]).
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  std::size_t rank = std::size_t(std::ceil(p * double(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

json measured(const RunResult& r) {
  double total = 0;
  for (double t : r.stepMs) total += t;
  json j;
  j["steps_run"] = r.stepMs.size();
  j["step_ms_median"] = median(r.stepMs);
  j["step_ms_p99"] = percentile(r.stepMs, 0.99);
  j["step_ms_max"] = r.stepMs.empty() ? 0.0 : *std::max_element(r.stepMs.begin(), r.stepMs.end());
  j["step_cpu_ms_median"] = median(r.stepCpuMs);
  j["total_s"] = total / 1000;
  j["penetration_max_m"] = r.penetrationMax_m;
  j["escaped"] = r.escaped;
  j["stack_drift_m"] = r.stackDrift_m;
  j["kinetic_energy_end_J"] = r.kineticEnergyEnd_J;
  // End / start; null when the scene starts at rest.
  j["kinetic_energy_ratio"] = r.kineticEnergyStart_J > 0 ? json(r.kineticEnergyEnd_J / r.kineticEnergyStart_J) : json(nullptr);
  j["sleeping_at_end"] = r.sleepingAtEnd;
  j["joint_error_max_m"] = r.jointErrorMax_m;
  if (!r.contactSolverMs.empty()) {
    // The contact solver's cost per contact point and substep: each step's
    // solver time over its points times substeps, the median over the
    // steps that had contacts.
    std::vector<double> perPoint;
    for (std::size_t i = 0; i < r.contactSolverMs.size(); ++i)
      if (r.contactPoints[i] > 0 && r.substeps > 0)
        perPoint.push_back(r.contactSolverMs[i] * 1e6 / (r.contactPoints[i] * r.substeps));
    j["collide_ms_median"] = median(r.collideMs);
    j["contact_solver_ms_median"] = median(r.contactSolverMs);
    j["contact_points_median"] = median(r.contactPoints);
    j["contact_solver_ns_per_point_substep"] = perPoint.empty() ? json(nullptr) : json(median(perPoint));
    // Bodies the world froze for a non-finite state (Tumble's errorStats;
    // the peers do not count theirs).
    j["nan_events"] = r.nanEvents;
  }
  return j;
}

json tumbleSettings(const TumbleConfig& c) {
  tumble::physics::WorldSettings s;
  s.enableSleep = c.sleep;
  if (c.substeps > 0) s.substeps = c.substeps;
  if (c.iterations > 0) s.velocityIterations = c.iterations;
  if (c.tolerance >= 0) s.solverTolerance = Real(c.tolerance);
  json j;
  j["threads"] = c.threads;
  j["substeps"] = s.substeps;
  j["iterations"] = s.velocityIterations;
  j["relax_iterations"] = s.relaxIterations;
  j["sweeps_per_step"] = s.substeps * (s.velocityIterations + s.relaxIterations);
  j["solver_tolerance"] = s.solverTolerance;
  j["collision_passes_per_step"] = 1;
  j["position_correction"] = s.softContacts ? "soft_contacts" : "split_impulse";
  j["baumgarte"] = s.baumgarte;
  j["linear_slop_m"] = s.linearSlop_m;
  j["restitution_threshold_mps"] = s.restitutionThreshold_mps;
  j["ccd"] = "speculative contacts (always on), margin " + std::to_string(s.speculativeDistance_m) + " m + closing speed x dt";
  j["sleep"] = s.enableSleep ? "after " + std::to_string(s.timeToSleep_s) + " s below " +
                                   std::to_string(s.sleepLinearSpeed_mps) + " m/s and " +
                                   std::to_string(s.sleepAngularSpeed_radps) + " rad/s"
                             : "off";
  j["precision"] = sizeof(tumble::Real) == 4 ? "float" : "double";
  return j;
}

json bulletSettings(const SceneSpec& scene, const BulletConfig& c) {
  json j;
  j["substeps"] = c.substeps;
  j["iterations"] = c.iterations;
  j["sweeps_per_step"] = c.substeps * c.iterations;
  j["collision_passes_per_step"] = c.substeps;
  j["residual_threshold_m2ps2"] = c.residualThreshold_m2ps2;
  j["split_impulse"] = c.splitImpulse;
  j["erp2"] = 0.2;
  j["solver_mode"] = "SOLVER_USE_WARMSTARTING | SOLVER_SIMD (default)";
  j["restitution_threshold_mps"] = 1.0;
  j["broadphase"] = "btDbvtBroadphase";
  j["ccd"] = scene.fastBodies ? "on: ccd motion threshold = swept sphere radius = sphere radius" : "off";
  j["material_rule"] = "per-body sqrt(pair value); Bullet multiplies the two";
  j["sleep"] = c.sleep ? "default: after 2 s below 0.8 m/s and 1 rad/s" : "off (DISABLE_DEACTIVATION)";
  j["precision"] = bulletPrecision();
  return j;
}


json odeSettings(const OdeConfig& c) {
  json j;
  j["substeps"] = c.substeps;
  j["method"] = c.quickStep ? "dWorldQuickStep (SOR)" : "dWorldStep (direct factorisation per island)";
  if (c.quickStep) j["iterations"] = c.iterations;
  j["sweeps_per_step"] = c.quickStep ? c.substeps * c.iterations : 0;
  j["collision_passes_per_step"] = c.substeps;
  j["erp"] = 0.2;
  j["cfm"] = 1e-10;
  j["contact"] = "dContactApprox1 (friction pyramid scaled by the normal force), up to 8 points per pair, "
                 "no surface layer, no correcting-velocity limit";
  j["restitution_threshold_mps"] = 1.0;
  j["broadphase"] = "dHashSpace";
  j["cone_twist"] = "ball joint + Euler angular motor, each angle limited (square swing cone)";
  j["sleep"] = "off (auto-disable off)";
  j["precision"] = "double";
  j["version"] = odeVersion();
  return j;
}

}  // namespace tumble::compare
