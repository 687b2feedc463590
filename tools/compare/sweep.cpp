// Work-precision comparison (see sweep.h). Each engine runs over its own
// accuracy settings, every other input held equal (scenes.cpp builds one
// scene for all), and each run gives one point: CPU time per step (the
// median over the run, CLOCK_THREAD_CPUTIME_ID) against four quality
// figures. The headline compares the engines on their Pareto fronts, never
// at one hand-picked setting.
//
// Settings swept:
//   tumble: substeps {1,2,4,8,16} x solve iterations {1,2,4,8} x early exit
//           {solverTolerance 1e-4 (default), 0 = every iteration}; relax
//           iterations and everything else at the defaults.
//   bullet: internal steps {1,2,4,8} per dt (stepSimulation(dt, k, dt/k):
//           collision and solver each time) x iterations {5,10,20,40,80} x
//           residual threshold {0 (Bullet's default: every iteration),
//           1e-6 (m/s)^2: stop once no row's velocity changes by 1 mm/s};
//           split impulse on (its default).
//   ode (scenes with joints only, as the Lagrange-multiplier peer):
//           dWorldStep x {1,2,4,8} substeps, and dWorldQuickStep x
//           {1,2,4,8} substeps x iterations {5,10,20,40,80}.
// Both Tumble and Bullet may stop their iterations early, each by its own
// rule; both with early exit off are in the sweep too.
//
// Quality figures (lower is better):
//   stack_drift_m       largest horizontal displacement of a body at the end
//   penetration_max_m   deepest overlap the narrow phase reported
//   joint_error_max_m   largest separation of a joint's anchors after a step
//   energy_rel_change   |KE_end / KE_start - 1| when the scene starts moving
//                       (highspeed_1000: elastic, frictionless, so 0 is exact)
//   kinetic_energy_end_Jpkg  kinetic energy left at the end per kg of
//                       dynamic mass (scenes that start at rest and settle)
#include "sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare_report.h"
#include "core/file_util.h"

using nlohmann::json;

namespace tumble::compare {

namespace {

constexpr double kTumbleDefaultTolerance = 1e-4;  // WorldSettings::solverTolerance
constexpr double kBulletEarlyExit_m2ps2 = 1e-6;
constexpr double kPlotFloor = 1e-9;  // log axes: zeros are drawn here

struct Point {
  std::string engine;
  std::string label;  ///< the setting, short, for the CSV
  json settings;
  double cpuMs = 0, wallMs = 0;
  std::map<std::string, double> quality;  ///< NaN when a figure does not apply
  bool valid = true;
  std::string failure;
};

const std::vector<std::string>& metricNames() {
  static const std::vector<std::string> names = {"stack_drift_m", "penetration_max_m", "joint_error_max_m",
                                                 "energy_rel_change", "kinetic_energy_end_Jpkg"};
  return names;
}

double dynamicMass(const SceneSpec& scene) {
  double m = 0;
  for (const BodySpec& b : scene.bodies) m += b.mass_kg;
  return m;
}

Point makePoint(const SceneSpec& scene, std::string engine, std::string label, json settings, const RunResult& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Point p;
  p.engine = std::move(engine);
  p.label = std::move(label);
  p.settings = std::move(settings);
  p.cpuMs = median(r.stepCpuMs);
  p.wallMs = median(r.stepMs);
  p.quality["stack_drift_m"] = r.stackDrift_m;
  p.quality["penetration_max_m"] = r.penetrationMax_m;
  p.quality["joint_error_max_m"] = scene.joints.empty() ? nan : r.jointErrorMax_m;
  p.quality["energy_rel_change"] =
      r.kineticEnergyStart_J > 0 ? std::abs(r.kineticEnergyEnd_J / r.kineticEnergyStart_J - 1) : nan;
  p.quality["kinetic_energy_end_Jpkg"] = r.kineticEnergyEnd_J / dynamicMass(scene);
  if (r.nanEvents > 0) {
    p.valid = false;
    p.failure = std::to_string(r.nanEvents) + " bodies frozen for non-finite state";
  }
  for (const auto& [name, v] : p.quality)
    if (std::isinf(v) || (std::isnan(v) && name != "joint_error_max_m" && name != "energy_rel_change")) {
      p.valid = false;
      p.failure = name + " is not finite: the run blew up";
    }
  if (scene.containHalf_m > 0 && r.escaped > 0) {
    // A body outside the box makes every other figure meaningless.
    p.valid = false;
    p.failure = std::to_string(r.escaped) + " bodies escaped the container";
  }
  return p;
}

bool applies(const std::vector<Point>& pts, const std::string& metric) {
  for (const Point& p : pts)
    if (!std::isnan(p.quality.at(metric))) return true;
  return false;
}

/// Valid points of one engine on its Pareto front for a metric: sorted by
/// time; each strictly better than every faster one.
std::vector<const Point*> front(const std::vector<Point>& pts, const std::string& engine, const std::string& metric) {
  std::vector<const Point*> mine;
  for (const Point& p : pts)
    if (p.engine == engine && p.valid && !std::isnan(p.quality.at(metric))) mine.push_back(&p);
  std::sort(mine.begin(), mine.end(), [&](const Point* a, const Point* b) {
    return a->cpuMs != b->cpuMs ? a->cpuMs < b->cpuMs : a->quality.at(metric) < b->quality.at(metric);
  });
  std::vector<const Point*> out;
  double best = std::numeric_limits<double>::infinity();
  for (const Point* p : mine)
    if (p->quality.at(metric) < best) {
      best = p->quality.at(metric);
      out.push_back(p);
    }
  return out;
}

/// Best quality an engine reaches within a time budget (NaN when none).
double bestWithin(const std::vector<const Point*>& f, double ms, const std::string& metric) {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (const Point* p : f)
    if (p->cpuMs <= ms) best = p->quality.at(metric);  // the front improves with time
  return best;
}

/// Least time an engine needs to reach a quality (NaN when it never does).
double timeToReach(const std::vector<const Point*>& f, double q, const std::string& metric) {
  for (const Point* p : f)
    if (p->quality.at(metric) <= q) return p->cpuMs;
  return std::numeric_limits<double>::quiet_NaN();
}

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

/// Headline for one peer on one metric: time to the peer's best quality, and
/// quality at the peer's times.
json headline(const std::vector<Point>& pts, const std::string& peer, const std::string& metric) {
  const auto tf = front(pts, "tumble", metric);
  const auto pf = front(pts, peer, metric);
  json h;
  h["metric"] = metric;
  if (tf.empty() || pf.empty()) {
    h["note"] = "no valid run of " + std::string(tf.empty() ? "tumble" : peer);
    return h;
  }
  const double peerBest = pf.back()->quality.at(metric);
  const double peerTime = pf.back()->cpuMs;
  const double tumbleTime = timeToReach(tf, peerBest, metric);
  h["peer_best_quality"] = num(peerBest);
  h["peer_best_setting"] = pf.back()->label;
  h["peer_time_at_best_ms"] = num(peerTime);
  h["tumble_time_to_peer_best_ms"] = num(tumbleTime);
  h["tumble_speedup_at_peer_best"] = num(peerTime / tumbleTime);  // > 1: Tumble reaches it faster
  const double tumbleBest = tf.back()->quality.at(metric);
  h["tumble_best_quality"] = num(tumbleBest);
  h["tumble_best_setting"] = tf.back()->label;
  h["peer_time_to_tumble_best_ms"] = num(timeToReach(pf, tumbleBest, metric));
  json equal = json::array();
  for (const Point* p : pf) {
    json e;
    e["cpu_ms_per_step"] = p->cpuMs;
    e["peer_setting"] = p->label;
    e["peer_quality"] = num(p->quality.at(metric));
    e["tumble_quality"] = num(bestWithin(tf, p->cpuMs, metric));
    equal.push_back(e);
  }
  h["quality_at_equal_time"] = equal;
  return h;
}

void writeOrThrow(const std::string& path, const std::string& text) {
  if (auto s = writeFileAtomic(path, text); !s) throw std::runtime_error(s.error());
}

std::string fmt(double v) {
  if (std::isnan(v)) return "";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string csv(const std::vector<Point>& pts) {
  std::string out = "engine,setting,step_cpu_ms_median,step_ms_median";
  for (const std::string& m : metricNames()) {
    out += ',';
    out += m;
  }
  out += ",valid,failure\n";
  for (const Point& p : pts) {
    out += p.engine + "," + p.label + "," + fmt(p.cpuMs) + "," + fmt(p.wallMs);
    for (const std::string& m : metricNames()) {
      out += ',';
      out += fmt(p.quality.at(m));
    }
    out += std::string(",") + (p.valid ? "1" : "0") + "," + p.failure + "\n";
  }
  return out;
}

/// Points as gnuplot data: time and the metric (zeros at the plot floor).
std::string dat(const std::vector<const Point*>& pts, const std::string& metric) {
  std::string out = "# step_cpu_ms_median " + metric + " setting\n";
  for (const Point* p : pts)
    out += fmt(p->cpuMs) + " " + fmt(std::max(p->quality.at(metric), kPlotFloor)) + " " + p->label + "\n";
  return out;
}

}  // namespace

json runSweep(const SceneSpec& scene, int steps, double dt, const SweepOptions& o) {
  std::vector<Point> pts;
  auto progress = [&](const std::string& engine, const std::string& label) {
    std::fprintf(stderr, "  %-6s %-28s ...\n", engine.c_str(), label.c_str());
  };

  // Tumble.
  const std::vector<int> tSub = o.quick ? std::vector<int>{1, 8} : std::vector<int>{1, 2, 4, 8, 16};
  const std::vector<int> tIt = o.quick ? std::vector<int>{1, 4} : std::vector<int>{1, 2, 4, 8};
  for (double tol : {kTumbleDefaultTolerance, 0.0})
    for (int sub : tSub)
      for (int it : tIt) {
        if (o.quick && tol == 0) continue;
        TumbleConfig c;
        c.substeps = sub;
        c.iterations = it;
        c.tolerance = tol;
        c.jointSolver = o.jointSolver;
        c.threads = o.threads;
        const std::string label = "sub" + std::to_string(sub) + "_it" + std::to_string(it) +
                                  (tol > 0 ? "_exit" : "_noexit");
        progress("tumble", label);
        pts.push_back(makePoint(scene, "tumble", label, tumbleSettings(c), runTumble(scene, steps, dt, c)));
      }

  // Bullet.
  const std::vector<int> bSub = o.quick ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 4, 8};
  const std::vector<int> bIt = o.quick ? std::vector<int>{10, 40} : std::vector<int>{5, 10, 20, 40, 80};
  for (double thr : {0.0, kBulletEarlyExit_m2ps2})
    for (int sub : bSub)
      for (int it : bIt) {
        if (o.quick && thr > 0) continue;
        BulletConfig c;
        c.substeps = sub;
        c.iterations = it;
        c.residualThreshold_m2ps2 = thr;
        const std::string label = "sub" + std::to_string(sub) + "_it" + std::to_string(it) +
                                  (thr > 0 ? "_exit" : "_noexit");
        progress("bullet", label);
        pts.push_back(makePoint(scene, "bullet", label, bulletSettings(scene, c), runBullet(scene, steps, dt, c)));
      }

  // ODE, for the scenes with joints.
  const bool withOde = !scene.joints.empty();
  if (withOde) {
    const std::vector<int> oSub = o.quick ? std::vector<int>{1} : std::vector<int>{1, 2, 4, 8};
    const std::vector<int> oIt = o.quick ? std::vector<int>{10} : std::vector<int>{5, 10, 20, 40, 80};
    for (int sub : oSub) {
      OdeConfig c;
      c.quickStep = false;
      c.substeps = sub;
      const std::string label = "step_sub" + std::to_string(sub);
      progress("ode", label);
      pts.push_back(makePoint(scene, "ode", label, odeSettings(c), runOde(scene, steps, dt, c)));
      for (int it : oIt) {
        c.quickStep = true;
        c.iterations = it;
        const std::string ql = "quick_sub" + std::to_string(sub) + "_it" + std::to_string(it);
        progress("ode", ql);
        pts.push_back(makePoint(scene, "ode", ql, odeSettings(c), runOde(scene, steps, dt, c)));
      }
    }
  }

  std::vector<std::string> engines = {"tumble", "bullet"};
  if (withOde) engines.push_back("ode");
  std::vector<std::string> plotted;  // metrics that apply to this scene
  for (const std::string& m : metricNames())
    if (applies(pts, m) && (m != "kinetic_energy_end_Jpkg" || !applies(pts, "energy_rel_change"))) plotted.push_back(m);

  // Files: CSV, one data file per engine (all points) and per front, the plot.
  const std::string base = o.outDir + "/" + scene.name + "_sweep";
  writeOrThrow(base + ".csv", csv(pts));
  std::string gp = "# Generated by `tumble compare " + scene.name +
                   " --sweep`; rerun with: gnuplot " + scene.name + "_sweep.gp (in this folder)\n";
  gp += "set terminal pngcairo size 1200,900 noenhanced font ',10'\nset output '" + scene.name + "_sweep.png'\n";
  const std::string setup = (scene.joints.empty() ? std::string() : ", Tumble's " + o.jointSolver + " joint solver") +
                            (o.threads > 1 ? ", Tumble on " + std::to_string(o.threads) + " threads" : "");
  gp += "set multiplot layout 2,2 title '" + scene.name + setup + ": quality against CPU time per step (" +
        std::to_string(steps) + " steps of " + fmt(dt) + " s); lines: Pareto fronts; values below " +
        fmt(kPlotFloor) + " drawn at it'\n";
  gp += "set logscale xy\nset grid\nset key top right\nset xlabel 'CPU ms per step (median)'\n";
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c"};
  for (const std::string& m : plotted) {
    gp += "set ylabel '" + m + "'\nplot ";
    for (std::size_t e = 0; e < engines.size(); ++e) {
      std::vector<const Point*> all;
      for (const Point& p : pts)
        if (p.engine == engines[e] && p.valid && !std::isnan(p.quality.at(m))) all.push_back(&p);
      const std::string allFile = scene.name + "_sweep_" + engines[e] + "_" + m + ".dat";
      const std::string frontFile = scene.name + "_sweep_" + engines[e] + "_" + m + "_front.dat";
      writeOrThrow(o.outDir + "/" + allFile, dat(all, m));
      writeOrThrow(o.outDir + "/" + frontFile, dat(front(pts, engines[e], m), m));
      if (e) gp += ", ";
      gp += "'" + allFile + "' using 1:2 with points pt 7 ps 0.6 lc rgb '" + colours[e] + "' title '" + engines[e] +
            "', '" + frontFile + "' using 1:2 with lines lw 2 lc rgb '" + colours[e] + "' notitle";
    }
    gp += "\n";
  }
  gp += "unset multiplot\n";
  writeOrThrow(base + ".gp", gp);
  bool plottedPng = false;
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string cmd = "cd '" + o.outDir + "' && gnuplot '" + scene.name + "_sweep.gp'";
    plottedPng = std::system(cmd.c_str()) == 0;
  }

  json report;
  report["scene"] = scene.name;
  report["description"] = scene.description;
  report["steps"] = steps;
  report["dt"] = dt;
  report["bodies"] = scene.bodies.size();
  report["joints"] = scene.joints.size();
  report["threads"] = o.threads;  // Tumble's; the peers run on one
  if (!scene.joints.empty()) report["joint_solver"] = o.jointSolver;  // Tumble's
  report["quality_metric"] = scene.qualityMetric;
  report["time_measure"] = o.threads > 1 ? "median over the run of each step's CPU time, ms (Tumble: the process's "
                                           "CPU clock over its threads; the peers: their one thread's)"
                                         : "median over the run of each step's thread CPU time (CLOCK_THREAD_CPUTIME_ID), ms";
  report["files"] = {{"csv", base + ".csv"}, {"gnuplot", base + ".gp"},
                     {"png", plottedPng ? json(base + ".png") : json(nullptr)}};
  if (!plottedPng) report["note"] = "gnuplot not found or failed: run the .gp file with gnuplot to draw the PNG";
  json runs = json::array();
  for (const Point& p : pts) {
    json r;
    r["engine"] = p.engine;
    r["setting"] = p.label;
    r["settings"] = p.settings;
    r["step_cpu_ms_median"] = p.cpuMs;
    r["step_ms_median"] = p.wallMs;
    for (const auto& [k, v] : p.quality) r[k] = num(v);
    r["valid"] = p.valid;
    if (!p.valid) r["failure"] = p.failure;
    runs.push_back(r);
  }
  report["runs"] = runs;
  json fronts;
  for (const std::string& e : engines)
    for (const std::string& m : plotted) {
      json f = json::array();
      for (const Point* p : front(pts, e, m)) f.push_back({{"setting", p->label}, {"cpu_ms", p->cpuMs}, {m, p->quality.at(m)}});
      fronts[e][m] = f;
    }
  report["pareto_fronts"] = fronts;
  json heads;
  for (std::size_t e = 1; e < engines.size(); ++e) {
    json perMetric;
    for (const std::string& m : plotted) perMetric[m] = headline(pts, engines[e], m);
    heads[engines[e]] = perMetric;
  }
  report["headline"] = heads;
  return report;
}

}  // namespace tumble::compare
