// ODE side of the comparison (Debian's libode-dev, double precision): the
// Lagrange-multiplier engine the rag-doll paper follows. A dWorld with the
// scene's bodies, a hash space of their geoms, and each dt stepped as
// `substeps` x (collision, contact joints, dWorldStep or dWorldQuickStep).
//
// Fairness choices:
// - Materials: one contact surface per pair with mu = the scene's pair
//   friction (dContactApprox1: the friction pyramid scaled by the normal
//   force, as Tumble's and Bullet's Coulomb cones are) and the scene's
//   restitution with Tumble's 1 m/s threshold (bounce_vel).
// - Everything else stays at ODE's defaults: ERP 0.2, CFM 1e-10 (double),
//   no contact surface layer, no limit on the correcting velocity, up to 8
//   contact points per geom pair (dCollide's count), auto-disable off.
// - Joints: ODE has no cone-twist joint. A cone-twist becomes a ball joint
//   plus an Euler angular motor whose three angles are limited: twist about
//   the joint axis to the larger of Tumble's two twist limits (symmetric, as
//   Bullet's is), each swing axis to the swing limit (so the cone is a square
//   pyramid, a little wider diagonally than Tumble's and Bullet's round
//   cone). A hinge is dHingeJoint with the same limits; ODE measures its
//   angle as body 1 relative to body 2, so the parent is attached first and
//   the angle is the parent's relative to the child, as Tumble's.
// - Capsules: ODE's lie along local Z, the scene's along Y: the geom gets an
//   offset rotation; the mass is dMassSetCapsuleTotal about Y.
#include <ode/ode.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "core/assert.h"
#include "scenes.h"

namespace tumble::compare {

namespace {

/// What the near callback needs.
struct OdeScene {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  double friction = 0.5;
  double restitution = 0;
  double deepest_m = 0;  ///< deepest contact depth seen since the last reset
};

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
  auto& s = *static_cast<OdeScene*>(data);
  dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
  if (!b1 && !b2) return;  // static against static
  if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;  // jointed pairs do not collide
  constexpr int kMaxContacts = 8;
  dContact contact[kMaxContacts];
  const int n = dCollide(o1, o2, kMaxContacts, &contact[0].geom, sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    dSurfaceParameters& surface = contact[i].surface;
    surface = dSurfaceParameters{};
    surface.mode = dContactApprox1;
    surface.mu = s.friction;
    if (s.restitution > 0) {
      surface.mode |= dContactBounce;
      surface.bounce = s.restitution;
      surface.bounce_vel = 1;  // Tumble's WorldSettings::restitutionThreshold_mps
    }
    s.deepest_m = std::max(s.deepest_m, double(contact[i].geom.depth));
    dJointID c = dJointCreateContact(s.world, s.contacts, &contact[i]);
    dJointAttach(c, b1, b2);
  }
}

void setPose(dGeomID g, dBodyID b, const BodySpec& s) {
  const dQuaternion q = {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()};
  if (b) {
    dBodySetPosition(b, s.position_m.x(), s.position_m.y(), s.position_m.z());
    dBodySetQuaternion(b, q);
  } else {
    dGeomSetPosition(g, s.position_m.x(), s.position_m.y(), s.position_m.z());
    dGeomSetQuaternion(g, q);
  }
}

double kineticEnergy(const std::vector<dBodyID>& bodies) {
  double e = 0;
  for (dBodyID b : bodies) {
    if (!b) continue;
    dMass m;
    dBodyGetMass(b, &m);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* w = dBodyGetAngularVel(b);  // world frame
    const dReal* R = dBodyGetRotation(b);    // 3x4, rows
    // Angular velocity in the body frame: R^T w; I is in the body frame.
    double wl[3];
    for (int c = 0; c < 3; ++c) wl[c] = R[0 * 4 + c] * w[0] + R[1 * 4 + c] * w[1] + R[2 * 4 + c] * w[2];
    double rot = 0;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) rot += wl[r] * m.I[r * 4 + c] * wl[c];
    e += 0.5 * m.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * rot;
  }
  return e;
}

double distance(const dVector3 a, const dVector3 b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/// Largest separation of a joint's two anchors (as each body carries it), m.
double jointError(const std::vector<dJointID>& joints) {
  double worst = 0;
  dVector3 a, b;
  for (dJointID j : joints) {
    switch (dJointGetType(j)) {
      case dJointTypeBall:
        dJointGetBallAnchor(j, a);
        dJointGetBallAnchor2(j, b);
        break;
      case dJointTypeHinge:
        dJointGetHingeAnchor(j, a);
        dJointGetHingeAnchor2(j, b);
        break;
      default:
        continue;
    }
    worst = std::max(worst, distance(a, b));
  }
  return worst;
}

}  // namespace

std::string odeVersion() {
#ifdef TUMBLE_ODE_VERSION
  return TUMBLE_ODE_VERSION;
#else
  return "unknown";
#endif
}

RunResult runOde(const SceneSpec& scene, int steps, double dt, const OdeConfig& cfg) {
  dInitODE2(0);
  OdeScene s;
  s.world = dWorldCreate();
  s.space = dHashSpaceCreate(nullptr);
  s.contacts = dJointGroupCreate(0);
  s.friction = scene.friction;
  s.restitution = scene.restitution;
  dWorldSetGravity(s.world, scene.gravity_mps2.x(), scene.gravity_mps2.y(), scene.gravity_mps2.z());
  dWorldSetQuickStepNumIterations(s.world, cfg.iterations);

  std::vector<dBodyID> bodies(scene.bodies.size(), nullptr);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    dGeomID g = nullptr;
    dMass m;
    switch (b.shape) {
      case BodyShape::Box:
        g = dCreateBox(s.space, 2 * b.halfExtents_m.x(), 2 * b.halfExtents_m.y(), 2 * b.halfExtents_m.z());
        if (!b.isStatic())
          dMassSetBoxTotal(&m, b.mass_kg, 2 * b.halfExtents_m.x(), 2 * b.halfExtents_m.y(), 2 * b.halfExtents_m.z());
        break;
      case BodyShape::Sphere:
        g = dCreateSphere(s.space, b.radius_m);
        if (!b.isStatic()) dMassSetSphereTotal(&m, b.mass_kg, b.radius_m);
        break;
      case BodyShape::Capsule:
        g = dCreateCapsule(s.space, b.radius_m, 2 * b.halfHeight_m);
        if (!b.isStatic()) dMassSetCapsuleTotal(&m, b.mass_kg, 2 /* y */, b.radius_m, 2 * b.halfHeight_m);
        break;
      case BodyShape::Cylinder:
        g = dCreateCylinder(s.space, b.radius_m, 2 * b.halfHeight_m);
        if (!b.isStatic()) dMassSetCylinderTotal(&m, b.mass_kg, 2 /* y */, b.radius_m, 2 * b.halfHeight_m);
        break;
    }
    if (!b.isStatic()) {
      dBodyID body = dBodyCreate(s.world);
      dBodySetMass(body, &m);
      dGeomSetBody(g, body);
      if (b.shape == BodyShape::Capsule || b.shape == BodyShape::Cylinder) {  // ODE's axis is local Z; the scene's is Y
        dMatrix3 R;
        dRFromAxisAndAngle(R, 1, 0, 0, -M_PI / 2);
        dGeomSetOffsetRotation(g, R);
      }
      dBodySetLinearVel(body, b.velocity_mps.x(), b.velocity_mps.y(), b.velocity_mps.z());
      bodies[i] = body;
    } else if (b.shape == BodyShape::Capsule || b.shape == BodyShape::Cylinder) {
      TUMBLE_ASSERT(false, "static capsules and cylinders are not used by any comparison scene");
    }
    setPose(g, bodies[i], b);
  }

  std::vector<dJointID> joints;
  for (const JointSpec& j : scene.joints) {
    dBodyID a = bodies[std::size_t(j.a)], b = bodies[std::size_t(j.b)];
    const V3 axis = j.axis.normalized();
    if (j.type == JointSpec::Type::Hinge) {
      dJointID h = dJointCreateHinge(s.world, nullptr);
      dJointAttach(h, b, a);  // parent first: the angle is the parent's relative to the child, as Tumble's
      dJointSetHingeAnchor(h, j.anchor_m.x(), j.anchor_m.y(), j.anchor_m.z());
      dJointSetHingeAxis(h, axis.x(), axis.y(), axis.z());
      dJointSetHingeParam(h, dParamLoStop, j.lower_rad);
      dJointSetHingeParam(h, dParamHiStop, j.upper_rad);
      joints.push_back(h);
    } else {
      dJointID ball = dJointCreateBall(s.world, nullptr);
      dJointAttach(ball, a, b);
      dJointSetBallAnchor(ball, j.anchor_m.x(), j.anchor_m.y(), j.anchor_m.z());
      joints.push_back(ball);
      // Euler motor: angle 0 about the twist axis (fixed in a), angle 2
      // about a perpendicular axis fixed in b, angle 1 about their cross.
      const V3 swing = axis.unitOrthogonal();
      dJointID motor = dJointCreateAMotor(s.world, nullptr);
      dJointAttach(motor, a, b);
      dJointSetAMotorMode(motor, dAMotorEuler);
      dJointSetAMotorAxis(motor, 0, 1, axis.x(), axis.y(), axis.z());
      dJointSetAMotorAxis(motor, 2, 2, swing.x(), swing.y(), swing.z());
      const double twist = std::max(-j.twistLower_rad, j.twistUpper_rad);
      dJointSetAMotorParam(motor, dParamLoStop, -twist);
      dJointSetAMotorParam(motor, dParamHiStop, twist);
      dJointSetAMotorParam(motor, dParamLoStop2, -j.swingLimit_rad);
      dJointSetAMotorParam(motor, dParamHiStop2, j.swingLimit_rad);
      dJointSetAMotorParam(motor, dParamLoStop3, -j.swingLimit_rad);
      dJointSetAMotorParam(motor, dParamHiStop3, j.swingLimit_rad);
    }
  }

  RunResult r;
  r.kineticEnergyStart_J = kineticEnergy(bodies);
  r.stepMs.reserve(steps);
  r.stepCpuMs.reserve(steps);
  const int substeps = std::max(1, cfg.substeps);
  const double h = dt / substeps;
  for (int i = 0; i < steps; ++i) {
    const double c0 = threadCpuMs();
    auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < substeps; ++k) {
      s.deepest_m = 0;
      dSpaceCollide(s.space, &s, nearCallback);
      if (cfg.quickStep)
        dWorldQuickStep(s.world, h);
      else
        dWorldStep(s.world, h);
      dJointGroupEmpty(s.contacts);
    }
    auto t1 = std::chrono::steady_clock::now();
    r.stepCpuMs.push_back(threadCpuMs() - c0);
    r.stepMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    // As Bullet's figure: the overlaps the last collision pass of the step saw.
    r.penetrationMax_m = std::max(r.penetrationMax_m, s.deepest_m);
    r.jointErrorMax_m = std::max(r.jointErrorMax_m, jointError(joints));
  }
  r.kineticEnergyEnd_J = kineticEnergy(bodies);
  std::vector<V3> end;
  end.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i]) {
      const dReal* p = dBodyGetPosition(bodies[i]);
      end.emplace_back(p[0], p[1], p[2]);
    } else {
      end.push_back(scene.bodies[i].position_m);
    }
  }
  measureEnd(scene, end, &r);
  dJointGroupDestroy(s.contacts);
  dSpaceDestroy(s.space);
  dWorldDestroy(s.world);
  dCloseODE();
  return r;
}

}  // namespace tumble::compare
