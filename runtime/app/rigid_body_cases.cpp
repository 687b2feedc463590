#include "app/rigid_body_cases.h"

#include <cmath>
#include <functional>
#include <memory>
#include <random>

#include "physics/world.h"

namespace tumble::app {

namespace {

using physics::BodyDef;
using physics::BodyId;
using physics::BodyType;
using physics::Shape;
using physics::World;

// The rigid-body world integrates with semi-implicit (symplectic) Euler;
// the other methods of the numerics lab are not available to it yet.
constexpr numerics::Method kWorldMethod = numerics::Method::SymplecticEuler;

Status onlyWorldMethod(numerics::Method m) {
  if (m == kWorldMethod) return Ok{};
  return makeError(std::string("the rigid-body world integrates with ") + numerics::methodName(kWorldMethod) +
                   " only");
}

BodyId addPlane(World& w, const Vec3& at = Vec3::Zero()) {
  BodyDef d;
  d.type = BodyType::Static;
  d.shape = Shape::plane();
  d.position_m = at;
  return w.createBody(d).value();
}

BodyId addBox(World& w, const Vec3& half, const Vec3& p, Real mass) {
  BodyDef d;
  d.shape = Shape::box(half);
  d.position_m = p;
  d.mass_kg = mass;
  return w.createBody(d).value();
}

// Steps a world and classifies the run. `check` returns a drift measure
// (checked against driftLimit) and may flag a blow-up itself.
struct Monitor {
  double speedLimit_mps = 100;  ///< any body faster than this: blew up
  double driftLimit = 0;        ///< drift measure above this: drifting
};

numerics::StabilityRow runWorld(const std::string& name, World& w, double dt, double seconds, const Monitor& mon,
                                const std::function<double(World&)>& drift) {
  numerics::StabilityRow row;
  row.caseName = name;
  row.method = numerics::methodName(kWorldMethod);
  row.dt_s = dt;
  w.resetErrorStats();
  double e0 = w.totalEnergy();
  long steps = std::lround(seconds / dt);
  double worstDrift = 0;
  for (long i = 0; i < steps; ++i) {
    w.step(Real(dt));
    double fastest = 0;
    w.forEachBody([&](BodyId, const physics::Body& b) {
      fastest = std::max<double>(fastest, b.linearVelocity_mps.norm());
    });
    double e = w.totalEnergy();
    bool blown = w.errorStats().nanEvents > 0 || !std::isfinite(e) || fastest > mon.speedLimit_mps;
    if (blown) {
      row.outcome = numerics::Outcome::BlewUp;
      row.timeToFailure_s = double(i + 1) * dt;
      row.energyGrowth = std::isfinite(e) ? (e - e0) / std::max(std::abs(e0), 1e-12) : INFINITY;
      break;
    }
    worstDrift = std::max(worstDrift, drift(w));
  }
  if (row.outcome != numerics::Outcome::BlewUp) {
    row.energyGrowth = (w.totalEnergy() - e0) / std::max(std::abs(e0), 1e-12);
    if (worstDrift > mon.driftLimit) row.outcome = numerics::Outcome::Drifting;
  }
  row.penetrationMax_m = w.errorStats().penetrationMax_m;
  row.nanEvents = w.errorStats().nanEvents;
  return row;
}

// A stack of `n` cubes of edge `size` at `origin`; drift = largest
// horizontal offset of any box, relative to the edge (1 = a whole box).
numerics::StabilityCase stackCase(const std::string& name, const std::string& description, Real size, int n,
                                  const Vec3& origin, double driftFraction) {
  numerics::StabilityCase c;
  c.name = name;
  c.description = description;
  c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
  c.methods = {kWorldMethod};
  c.run = [=](numerics::Method, double dt, bool quick) {
    World w;
    addPlane(w, origin);
    std::vector<BodyId> boxes;
    for (int i = 0; i < n; ++i)
      boxes.push_back(addBox(w, Vec3::Constant(size / 2), origin + Vec3(0, size * (Real(0.5) + i), 0),
                             size * size * size * 500));
    Monitor mon;
    mon.speedLimit_mps = 100 * std::max<double>(size, 1);
    mon.driftLimit = driftFraction;
    return runWorld(name, w, dt, quick ? 2 : 10, mon, [&](World& world) {
      double worst = 0;
      for (BodyId b : boxes) {
        Vec3 d = world.body(b).position_m - origin;
        worst = std::max<double>(worst, std::hypot(d.x(), d.z()) / size);
      }
      return worst;
    });
  };
  return c;
}

numerics::StabilityCase massRatioCase(Real ratio) {
  numerics::StabilityCase c;
  c.name = "mass_ratio_1_" + std::to_string(int(ratio));
  c.description = "a 1 kg box under a " + std::to_string(int(ratio)) + " kg box; drifting if the top moves > 3 cm";
  c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
  c.methods = {kWorldMethod};
  c.run = [=](numerics::Method, double dt, bool quick) {
    World w;
    addPlane(w);
    addBox(w, Vec3::Constant(Real(0.5)), Vec3(0, Real(0.5), 0), 1);
    BodyId heavy = addBox(w, Vec3::Constant(Real(0.5)), Vec3(0, Real(1.5), 0), ratio);
    Monitor mon;
    mon.driftLimit = 0.03;
    return runWorld(c.name, w, dt, quick ? 2 : 10, mon, [&](World& world) {
      return (world.body(heavy).position_m - Vec3(0, Real(1.5), 0)).norm();
    });
  };
  return c;
}

}  // namespace

std::vector<numerics::StabilityCase> rigidBodyStabilityCases() {
  std::vector<numerics::StabilityCase> cases;
  cases.push_back(massRatioCase(100));
  cases.push_back(massRatioCase(1000));
  cases.push_back(stackCase("stack_far_from_origin", "5 one-metre boxes stacked 10 km from the origin (float state)",
                            1, 5, Vec3(10000, 0, 10000), 0.01));
  cases.push_back(stackCase("stack_1cm_boxes", "5 boxes of 1 cm stacked; drifting past 10% of a box", Real(0.01), 5,
                            Vec3::Zero(), 0.1));
  cases.push_back(stackCase("stack_100m_boxes", "5 boxes of 100 m stacked; drifting past 1% of a box", 100, 5,
                            Vec3::Zero(), 0.01));
  {
    numerics::StabilityCase c;
    c.name = "projectile_500mps";
    c.description = "a 0.1 m sphere at 500 m/s at a 0.1 m wall; drifting if it passes the wall";
    c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
    c.methods = {kWorldMethod};
    c.run = [](numerics::Method, double dt, bool quick) {
      World w;
      w.settings().gravity_mps2 = Vec3::Zero();
      BodyDef wall;
      wall.type = BodyType::Static;
      wall.shape = Shape::box(Vec3(Real(0.05), 5, 5));
      wall.position_m = Vec3(20, 0, 0);
      w.createBody(wall).value();
      BodyDef ball;
      ball.shape = Shape::sphere(Real(0.05));
      ball.position_m = Vec3(Real(0.37), Real(0.1), 0);
      ball.mass_kg = Real(0.01);
      ball.linearVelocity_mps = Vec3(500, 0, 0);
      BodyId b = w.createBody(ball).value();
      Monitor mon;
      mon.speedLimit_mps = 1000;
      mon.driftLimit = 0;  // any passage is a failure
      return runWorld("projectile_500mps", w, dt, quick ? 0.5 : 2, mon, [&](World& world) {
        return world.body(b).position_m.x() > 20 ? 1.0 : 0.0;
      });
    };
    cases.push_back(c);
  }
  {
    numerics::StabilityCase c;
    c.name = "overlap_50_boxes";
    c.description = "50 one-metre boxes spawned interpenetrating; blew up past 20 m/s, drifting past 10 m/s";
    c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
    c.methods = {kWorldMethod};
    c.run = [](numerics::Method, double dt, bool quick) {
      World w;
      addPlane(w);
      std::mt19937 rng(7);
      for (int i = 0; i < 50; ++i)
        addBox(w, Vec3::Constant(Real(0.5)),
               Vec3(Real(rng() % 1000) / 500 - 1, Real(0.5) + Real(rng() % 1000) / 400, Real(rng() % 1000) / 500 - 1),
               1);
      Monitor mon;
      mon.speedLimit_mps = 20;
      mon.driftLimit = 10;
      return runWorld("overlap_50_boxes", w, dt, quick ? 2 : 6, mon, [](World& world) {
        double fastest = 0;
        world.forEachBody([&](BodyId, const physics::Body& b) {
          fastest = std::max<double>(fastest, b.linearVelocity_mps.norm());
        });
        return fastest;
      });
    };
    cases.push_back(c);
  }
  {
    numerics::StabilityCase c;
    c.name = "top_100radps";
    c.description = "a capsule spinning at 100 rad/s on its tip, tilted 0.1 rad; drifting if it falls over";
    c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
    c.methods = {kWorldMethod};
    c.run = [](numerics::Method, double dt, bool quick) {
      World w;
      w.settings().enableSleep = false;
      addPlane(w);
      BodyDef d;
      d.shape = Shape::capsule(Real(0.1), Real(0.05));
      Quat tilt(Eigen::AngleAxis<Real>(Real(0.1), Vec3::UnitX()));
      d.orientation = tilt;
      d.position_m = tilt * Vec3(0, Real(0.15), 0) + Vec3(0, Real(0.001), 0);
      d.angularVelocity_radps = tilt * Vec3(0, 100, 0);
      d.mass_kg = 1;
      d.friction = Real(0.3);
      BodyId top = w.createBody(d).value();
      Monitor mon;
      mon.speedLimit_mps = 50;
      mon.driftLimit = 0.5;  // axis more than 60 degrees from vertical
      return runWorld("top_100radps", w, dt, quick ? 1 : 5, mon, [&](World& world) {
        return 1 - double((world.body(top).orientation * Vec3::UnitY()).y());
      });
    };
    cases.push_back(c);
  }
  return cases;
}

namespace {

// A work-precision problem on the rigid-body world: `runOnce(dt)` simulates
// from scratch to t_end and returns the error; the report times it.
numerics::PrecisionProblem worldProblem(std::string name, std::string description, const char* unit,
                                        double tEnd_s, double dtMin_s, double dtMax_s,
                                        std::function<double(double dt)> runOnce) {
  numerics::PrecisionProblem p;
  p.name = std::move(name);
  p.description = std::move(description);
  p.errorUnit = unit;
  p.tEnd_s = tEnd_s;
  p.dtMin_s = dtMin_s;
  p.dtMax_s = dtMax_s;
  p.prepare = [runOnce](numerics::Method m, double dt) -> Result<numerics::PreparedRun> {
    if (auto s = onlyWorldMethod(m); !s) return makeError(s.error());
    auto error = std::make_shared<double>(0);
    numerics::PreparedRun run;
    run.dt_s = dt;
    run.integrate = [dt, error, runOnce] { *error = runOnce(dt); };
    run.error = [error] { return *error; };
    return run;
  };
  return p;
}

// Torque-free box spinning near its intermediate axis (it flips): energy and
// |L| are conserved exactly, so their largest relative change is the error.
double freeBodyInvariantError(double dt) {
  World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  w.settings().enableSleep = false;
  w.settings().substeps = 1;
  BodyDef d;
  d.shape = Shape::box(Vec3(Real(0.1), Real(0.4), Real(1.0)));
  d.mass_kg = 1;
  d.angularVelocity_radps = Vec3(Real(0.01), 6, Real(0.01));
  BodyId id = w.createBody(d).value();
  auto invariants = [&] {
    const physics::Body& b = w.body(id);
    Vec3 wl = b.orientation.conjugate() * b.angularVelocity_radps;
    Vec3 L = b.inertiaLocal_kgm2.cwiseProduct(wl);
    return std::make_pair(0.5 * double(wl.dot(L)), double(L.norm()));
  };
  auto [e0, l0] = invariants();
  double worst = 0;
  long steps = std::lround(10.0 / dt);
  for (long i = 0; i < steps; ++i) {
    w.step(Real(dt));
    auto [e, l] = invariants();
    worst = std::max({worst, std::abs(e - e0) / e0, std::abs(l - l0) / l0});
  }
  return worst;
}

// Ten stacked boxes for 5 s: the largest horizontal drift of any box (m).
double stackDrift(double dt) {
  World w;
  w.settings().enableSleep = false;
  addPlane(w);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 10; ++i) boxes.push_back(addBox(w, Vec3::Constant(Real(0.5)), Vec3(0, Real(0.5) + i, 0), 1));
  long steps = std::lround(5.0 / dt);
  double worst = 0;
  for (long i = 0; i < steps; ++i) {
    w.step(Real(dt));
    for (BodyId b : boxes) {
      const Vec3& p = w.body(b).position_m;
      worst = std::max<double>(worst, std::hypot(p.x(), p.z()));
    }
  }
  return worst;
}

}  // namespace

std::vector<numerics::PrecisionProblem> rigidBodyPrecisionProblems() {
  return {
      worldProblem("free_rigid_body",
                   "free box 0.2 x 0.8 x 2 m spinning near its intermediate axis for 10 s; error = max relative "
                   "change of kinetic energy and |L|",
                   "1", 10, 1.0 / 960, 1.0 / 15, freeBodyInvariantError),
      worldProblem("box_stack_drift",
                   "10 one-metre boxes stacked on a plane for 5 s; error = largest horizontal drift of any box", "m",
                   5, 1.0 / 240, 1.0 / 20, stackDrift),
  };
}

}  // namespace tumble::app
