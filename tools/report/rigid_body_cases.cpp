#include "tools/report/rigid_body_cases.h"

#include <cmath>
#include <functional>
#include <memory>
#include <algorithm>
#include <cstdio>
#include <random>

#include "physics/deformable.h"
#include "physics/joints/joint_system.h"
#include "physics/joints/ragdoll.h"
#include "physics/world.h"

namespace tumble::tools {

namespace {

using physics::BodyDef;
using physics::BodyId;
using physics::BodyType;
using physics::Shape;
using physics::World;

// The world's default integrator. Contact-dominated cases (stacks, mass
// ratios, projectiles, overlaps) run with it only: every method hands the
// same velocity-level contact solve its free step (physics/integrate.cpp),
// so there the choice changes little and would multiply the report's time.
// Cases and problems whose free motion is stiff or smooth (applied springs)
// run every method.
constexpr numerics::Method kWorldMethod = numerics::Method::SymplecticEuler;

/// The world's strategy of the same name (every numerics method has one).
physics::BodyIntegrator worldIntegrator(numerics::Method m) {
  return physics::parseBodyIntegrator(numerics::methodName(m)).value();
}

std::string describeBody(const World& w, BodyId id) {
  const physics::Body& b = w.body(id);
  char text[160];
  std::snprintf(text, sizeof text, "body %u (%s) at (%.3g %.3g %.3g) m", id.index,
                physics::shapeTypeName(b.shape.type), double(b.position_m.x()), double(b.position_m.y()),
                double(b.position_m.z()));
  return text;
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
                                const std::function<double(World&)>& drift,
                                numerics::Method method = kWorldMethod,
                                const std::function<void(Real)>& step = {}) {
  numerics::StabilityRow row;
  row.caseName = name;
  row.method = numerics::methodName(method);
  row.dt_s = dt;
  w.settings().integrator = worldIntegrator(method);
  w.resetErrorStats();
  double e0 = w.totalEnergy();
  long steps = std::lround(seconds / dt);
  double worstDrift = 0;
  for (long i = 0; i < steps; ++i) {
    if (step) step(Real(dt));
    else w.step(Real(dt));
    double fastest = 0;
    BodyId culprit;
    w.forEachBody([&](BodyId id, const physics::Body& b) {
      const double v = b.linearVelocity_mps.norm();
      if (b.frozen && culprit.isNull()) culprit = id;
      if (v > fastest) fastest = v;
      if (v > mon.speedLimit_mps && culprit.isNull()) culprit = id;
    });
    double e = w.totalEnergy();
    bool blown = w.errorStats().nanEvents > 0 || !std::isfinite(e) || fastest > mon.speedLimit_mps;
    if (blown) {
      row.outcome = numerics::Outcome::BlewUp;
      row.failedBody = culprit.isNull() ? std::string("(energy only)") : describeBody(w, culprit);
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

// ---- joint solvers ---------------------------------------------------------------

/// The lagrange joint solver on the public World API (physics/joints).
class LagrangeRig final : public JointRig {
 public:
  explicit LagrangeRig(World& w) : joints(w) {}
  void step(Real dt) override { joints.step(dt); }
  double anchorError_m() const override { return joints.anchorError_m(); }
  physics::JointSystem joints;
};

std::unique_ptr<JointRig> lagrangeChain(World& w, const std::vector<BodyId>& bodies, const std::vector<Vec3>& anchors) {
  auto rig = std::make_unique<LagrangeRig>(w);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyId other = i == 0 ? BodyId{} : bodies[i - 1];
    auto j = rig->joints.createJoint(physics::makeJointDef(w, physics::JointType::Ball, bodies[i], other, anchors[i]));
    TUMBLE_ASSERT(bool(j), "chain joint refused");
  }
  return rig;
}

/// The impulse joint solver: the same joints as velocity-level impulses solved
/// with the contacts inside the World's substeps (physics/joints/impulse_solver.cpp).
std::unique_ptr<JointRig> impulseChain(World& w, const std::vector<BodyId>& bodies, const std::vector<Vec3>& anchors) {
  auto rig = lagrangeChain(w, bodies, anchors);
  static_cast<LagrangeRig&>(*rig).joints.setSolver(physics::JointSolverKind::Impulse);
  return rig;
}

std::vector<JointSolverCase>& solverRegistry() {
  static std::vector<JointSolverCase> registry{{"lagrange", lagrangeChain}, {"impulse", impulseChain}};
  return registry;
}

/// A chain of `links` capsules (0.04 m radius, `linkLength` m each, 1 kg)
/// hanging from a fixed point at `top` and displaced sideways by `swing`
/// (rad) so it moves; each link joined to the previous at its end.
struct Chain {
  std::vector<BodyId> bodies;
  std::vector<Vec3> anchors;
};
Chain buildChain(World& w, int links, Real linkLength, const Vec3& top, Real swing) {
  Chain c;
  const Vec3 dir(std::sin(swing), -std::cos(swing), 0);
  const Quat q = Quat::FromTwoVectors(Vec3::UnitY(), -dir);
  for (int i = 0; i < links; ++i) {
    BodyDef d;
    d.shape = Shape::capsule(Real(0.04), linkLength / 2 - Real(0.04));
    d.position_m = top + dir * (linkLength * (Real(i) + Real(0.5)));
    d.orientation = q;
    d.mass_kg = 1;
    d.allowSleep = false;
    c.bodies.push_back(w.createBody(d).value());
    c.anchors.push_back(top + dir * (linkLength * Real(i)));
  }
  for (std::size_t i = 1; i < c.bodies.size(); ++i) w.disableCollision(c.bodies[i - 1], c.bodies[i]);
  return c;
}

// ---- cases: springs, chains, rag-dolls, cloth ---------------------------------------

// A 1 kg sphere on an anchor spring with k/m = 1e6 (omega = 1000 rad/s),
// pulled 0.1 m and released, gravity on, 8 substeps (omega h = 2.1 at
// 60 Hz): every world integrator. Blow-up: energy past 101x or a body
// faster than 1000 m/s; drifting: energy gained more than 5%.
numerics::StabilityCase worldSpringCase() {
  numerics::StabilityCase c;
  c.name = "world_spring_k1e6";
  c.description = "a 1 kg body on an applied spring with k/m = 1e6 in the world (8 substeps); "
                  "drifting if the energy grows more than 5%";
  c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
  c.methods = {};
  c.run = [name = c.name](numerics::Method m, double dt, bool quick) {
    World w;
    BodyDef d;
    d.shape = Shape::sphere(Real(0.05));
    d.position_m = Vec3(Real(0.1), 0, 0);
    d.mass_kg = 1;
    d.allowSleep = false;
    BodyId b = w.createBody(d).value();
    (void)w.addSpring({b, {}, Vec3::Zero(), Real(1e6), 0, 0});
    const double e0 = w.totalEnergy();
    Monitor mon;
    mon.speedLimit_mps = 1000;
    mon.driftLimit = 0.05;
    return runWorld(name, w, dt, quick ? 1 : 5, mon,
                    [e0](World& world) { return std::max(0.0, (world.totalEnergy() - e0) / std::abs(e0)); }, m);
  };
  return c;
}

// 100 links of 0.1 m hanging from a fixed point, released 0.3 rad from
// vertical. Drifting: a joint's anchors more than 1 cm apart.
numerics::StabilityCase hangingChainCase(const JointSolverCase& f) {
  numerics::StabilityCase c;
  c.name = "chain_100_links_" + f.name;
  c.description = "100 capsule links (0.1 m, 1 kg) hanging by ball joints (joint solver " + f.name +
                  "), released 0.3 rad from vertical; drifting past 1 cm of joint error";
  c.dts_s = {1.0 / 60, 1.0 / 120};
  c.methods = {kWorldMethod};
  c.run = [name = c.name, f](numerics::Method m, double dt, bool quick) {
    World w;
    Chain chain = buildChain(w, 100, Real(0.1), Vec3(0, 12, 0), Real(0.3));
    auto rig = f.chain(w, chain.bodies, chain.anchors);
    double worstJoint = 0;
    Monitor mon;
    mon.speedLimit_mps = 50;
    mon.driftLimit = 0.01;
    auto row = runWorld(
        name, w, dt, quick ? 0.5 : 4, mon,
        [&](World&) {
          worstJoint = std::max(worstJoint, rig->anchorError_m());
          return rig->anchorError_m();
        },
        m, [&](Real h) { rig->step(h); });
    row.jointErrorMax_m = worstJoint;
    return row;
  };
  return c;
}

// A rag-doll lying on the ground with a 1 m box of `boxMass` kg dropped on
// its torso from 1 m. Drifting: a joint's anchors more than 5 cm apart.
numerics::StabilityCase heavyOnRagdollCase() {
  numerics::StabilityCase c;
  c.name = "heavy_box_on_ragdoll";
  c.description = "a 500 kg box dropped from 1 m onto a 75 kg rag-doll lying on the ground (Lagrange joint solver); "
                  "drifting past 5 cm of joint error";
  c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
  c.methods = {kWorldMethod};
  c.run = [name = c.name](numerics::Method m, double dt, bool quick) {
    World w;
    addPlane(w);
    physics::JointSettings lagrangeSolver;
    lagrangeSolver.solver = physics::JointSolverKind::Lagrange;
    physics::JointSystem joints(w, lagrangeSolver);
    const Quat lying(Eigen::AngleAxis<Real>(-kPi / 2, Vec3::UnitX()));
    auto doll = physics::buildRagdoll(w, joints, physics::defaultHuman(), Vec3(0, Real(0.15), 0), lying);
    TUMBLE_ASSERT(bool(doll), "the default human builds");
    addBox(w, Vec3::Constant(Real(0.5)), Vec3(0, Real(1.8), Real(0.5)), 500);
    double worstJoint = 0;
    Monitor mon;
    mon.speedLimit_mps = 50;
    mon.driftLimit = 0.05;
    auto row = runWorld(
        name, w, dt, quick ? 1 : 4, mon,
        [&](World&) {
          worstJoint = std::max(worstJoint, joints.anchorError_m());
          return joints.anchorError_m();
        },
        m, [&](Real h) { joints.step(h); });
    row.jointErrorMax_m = worstJoint;
    return row;
  };
  return c;
}

// A 12 x 12 cloth whose particles have k/m = 1e6, pinned at two corners,
// one linearised backward-Euler step per World step (deformable.cpp).
// Its method is fixed (the row says implicit_euler); dt varies. Blew up: a
// non-finite state (undone and counted); drifting: a spring stretched more
// than 5% or a CG solve hit its cap.
numerics::StabilityCase stiffClothCase() {
  numerics::StabilityCase c;
  c.name = "cloth_k1e6";
  c.description = "12 x 12 cloth, structural k/m = 1e6, pinned at two corners, one implicit step per frame; "
                  "drifting past 5% stretch or a CG failure";
  c.dts_s = {1.0 / 30, 1.0 / 60, 1.0 / 120};
  c.methods = {numerics::Method::ImplicitEuler};
  c.run = [name = c.name](numerics::Method m, double dt, bool quick) {
    physics::ClothDef def;
    def.columns = 12;
    def.rows = 12;
    def.mass_kg = Real(0.144);  // 1 g per particle
    def.material.stiffness_Npm = 1000;
    def.material.substeps = 1;
    def.pins = physics::ClothPins::TopCorners;
    def.edgeV_m = Vec3(0, 0, Real(1.5));
    auto cloth = physics::Deformable::cloth(def);
    numerics::StabilityRow row;
    row.caseName = name;
    row.method = numerics::methodName(m);
    row.dt_s = dt;
    physics::DeformableEnvironment env;
    const double e0 = (*cloth)->energy(env.gravity_mps2);
    const long steps = std::lround((quick ? 1.0 : 5.0) / dt);
    double worstStretch = 0;
    for (long i = 0; i < steps; ++i) {
      (*cloth)->step(Real(dt), env);
      if ((*cloth)->stats().nanEvents > 0) {
        row.outcome = numerics::Outcome::BlewUp;
        row.timeToFailure_s = double(i + 1) * dt;
        row.failedBody = "cloth particle state";
        break;
      }
      worstStretch = std::max(worstStretch, (*cloth)->structuralLength() / (*cloth)->structuralRestLength() - 1);
    }
    row.energyGrowth = ((*cloth)->energy(env.gravity_mps2) - e0) / std::max(std::abs(e0), 1e-12);
    row.nanEvents = (*cloth)->stats().nanEvents;
    if (row.outcome != numerics::Outcome::BlewUp && (worstStretch > 0.05 || (*cloth)->stats().cgFailures > 0))
      row.outcome = numerics::Outcome::Drifting;
    return row;
  };
  return c;
}

}  // namespace

void registerJointSolver(JointSolverCase solver) {
  solverRegistry().push_back(std::move(solver));
}

const std::vector<JointSolverCase>& jointSolvers() { return solverRegistry(); }

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
  cases.push_back(worldSpringCase());
  for (const JointSolverCase& f : jointSolvers()) cases.push_back(hangingChainCase(f));
  cases.push_back(heavyOnRagdollCase());
  cases.push_back(stiffClothCase());
  return cases;
}

namespace {

// A work-precision problem on the rigid-body world: `runOnce(dt)` simulates
// from scratch to t_end and returns the error; the report times it.
numerics::PrecisionProblem worldProblem(std::string name, std::string description, const char* unit,
                                        double tEnd_s, double dtMin_s, double dtMax_s,
                                        std::function<double(numerics::Method, double dt)> runMethod,
                                        std::vector<numerics::Method> methods = {kWorldMethod}) {
  numerics::PrecisionProblem p;
  p.name = std::move(name);
  p.description = std::move(description);
  p.errorUnit = unit;
  p.tEnd_s = tEnd_s;
  p.dtMin_s = dtMin_s;
  p.dtMax_s = dtMax_s;
  p.prepare = [runMethod, methods](numerics::Method m, double dt) -> Result<numerics::PreparedRun> {
    if (!methods.empty() && std::find(methods.begin(), methods.end(), m) == methods.end())
      return makeError(std::string("problem runs ") + numerics::methodName(methods.front()) + " and a few others only");
    auto error = std::make_shared<double>(0);
    numerics::PreparedRun run;
    run.dt_s = dt;
    run.integrate = [dt, error, runMethod, m] { *error = runMethod(m, dt); };
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
double stackDrift(numerics::Method m, double dt) {
  World w;
  w.settings().enableSleep = false;
  w.settings().integrator = worldIntegrator(m);
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

// A 1 kg body on an anchor spring, k/m = 1e4 (omega = 100 rad/s), released
// 0.1 m out in zero gravity, one substep per step, for 1 s: error = largest
// distance from 0.1 cos(omega t) (m). The world's integrators on a smooth
// force; float state limits the error to ~1e-7 m.
double worldSpringError(numerics::Method m, double dt) {
  World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  w.settings().substeps = 1;
  w.settings().integrator = worldIntegrator(m);
  BodyDef d;
  d.shape = Shape::sphere(Real(0.05));
  d.position_m = Vec3(Real(0.1), 0, 0);
  d.mass_kg = 1;
  d.allowSleep = false;
  BodyId b = w.createBody(d).value();
  (void)w.addSpring({b, {}, Vec3::Zero(), Real(1e4), 0, 0});
  const long steps = std::lround(1.0 / dt);
  double worst = 0;
  for (long i = 1; i <= steps; ++i) {
    w.step(Real(dt));
    const double x = w.body(b).frozen ? INFINITY : double(w.body(b).position_m.x());
    worst = std::max(worst, std::abs(x - 0.1 * std::cos(100.0 * double(i) * dt)));
    if (!std::isfinite(worst)) return INFINITY;
  }
  return worst;
}

// A 10-link chain of 0.2 m links released horizontal (1.5 rad) for 1 s:
// error = largest joint anchor separation (m), the constraint drift.
double chainDrift(const JointSolverCase& f, double dt) {
  World w;
  Chain chain = buildChain(w, 10, Real(0.2), Vec3(0, 5, 0), Real(1.5));
  auto rig = f.chain(w, chain.bodies, chain.anchors);
  const long steps = std::lround(1.0 / dt);
  double worst = 0;
  for (long i = 0; i < steps; ++i) {
    rig->step(Real(dt));
    worst = std::max(worst, rig->anchorError_m());
  }
  return worst;
}

// The default human dropped from 1 m (head first, tilted) onto the ground
// for 2 s: error = largest joint anchor separation (m).
double ragdollDropDrift(double dt) {
  World w;
  addPlane(w);
  physics::JointSettings lagrangeSolver;
  lagrangeSolver.solver = physics::JointSolverKind::Lagrange;
  physics::JointSystem joints(w, lagrangeSolver);
  const Quat tilt(Eigen::AngleAxis<Real>(Real(2.5), Vec3(1, 0, Real(0.3)).normalized()));
  auto doll = physics::buildRagdoll(w, joints, physics::defaultHuman(), Vec3(0, Real(2.2), 0), tilt);
  TUMBLE_ASSERT(bool(doll), "the default human builds");
  const long steps = std::lround(2.0 / dt);
  for (long i = 0; i < steps; ++i) joints.step(Real(dt));
  return joints.maxAnchorError_m();
}

}  // namespace

std::vector<numerics::PrecisionProblem> rigidBodyPrecisionProblems() {
  std::vector<numerics::PrecisionProblem> problems{
      worldProblem("free_rigid_body",
                   "free box 0.2 x 0.8 x 2 m spinning near its intermediate axis for 10 s; error = max relative "
                   "change of kinetic energy and |L|",
                   "1", 10, 1.0 / 960, 1.0 / 15,
                   [](numerics::Method, double dt) { return freeBodyInvariantError(dt); }),
      worldProblem("box_stack_drift",
                   "10 one-metre boxes stacked on a plane for 5 s; error = largest horizontal drift of any box", "m",
                   5, 1.0 / 240, 1.0 / 20, [](numerics::Method m, double dt) { return stackDrift(m, dt); },
                   {kWorldMethod, numerics::Method::Rk4, numerics::Method::Sdirk2}),
  };
  std::vector<numerics::Method> every;
  for (const numerics::MethodInfo& info : numerics::methodTable()) every.push_back(info.method);
  problems.push_back(worldProblem("world_spring",
                                  "a 1 kg body on an applied spring in the world, k/m = 1e4, 1 s, one substep; "
                                  "error = largest distance from 0.1 cos(100 t)",
                                  "m", 1, 1.0 / 3840, 1.0 / 60, worldSpringError, every));
  for (const JointSolverCase& f : jointSolvers())
    problems.push_back(worldProblem("chain_10_links_" + f.name,
                                    "10 capsule links of 0.2 m on ball joints (joint solver " + f.name +
                                        ") released horizontal, 1 s; error = largest joint anchor separation",
                                    "m", 1, 1.0 / 480, 1.0 / 30,
                                    [f](numerics::Method, double dt) { return chainDrift(f, dt); }));
  problems.push_back(worldProblem("ragdoll_drop",
                                  "the default 75 kg human dropped head first from 1 m, 2 s (Lagrange joint solver); error = "
                                  "largest joint anchor separation",
                                  "m", 2, 1.0 / 480, 1.0 / 30,
                                  [](numerics::Method, double dt) { return ragdollDropDrift(dt); }));
  return problems;
}

}  // namespace tumble::tools
