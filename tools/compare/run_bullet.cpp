// Bullet side of the comparison: btDiscreteDynamicsWorld with the stock
// pieces (default collision configuration, DBVT broad phase, sequential
// impulse solver), one internal step of dt per stepSimulation() call
// (maxSubSteps = 0) or exactly `substeps` internal steps of dt / substeps,
// and the iteration count and residual threshold given by the caller.
//
// Fairness choices:
// - Materials: Bullet multiplies the two bodies' friction and restitution,
//   so every body gets sqrt(pair value) and the pair gets the scene's value.
// - Restitution threshold: Tumble's (1 m/s) instead of Bullet's 0.2 m/s.
// - Fast bodies: CCD on (motion threshold = swept-sphere radius = sphere
//   radius), as Bullet's manual advises for small fast objects.
// - Everything else stays at Bullet's defaults (split impulse on, erp2 0.2,
//   warm starting, deactivation after 2 s below 0.8 m/s and 1 rad/s).
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "scenes.h"

namespace tumble::compare {

namespace {

/// Owns one Bullet world; members are destroyed in reverse order, the world
/// first (after its bodies are removed), then solver, broad phase, dispatcher.
struct BulletWorld {
  std::unique_ptr<btDefaultCollisionConfiguration> config = std::make_unique<btDefaultCollisionConfiguration>();
  std::unique_ptr<btCollisionDispatcher> dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
  std::unique_ptr<btBroadphaseInterface> broadphase = std::make_unique<btDbvtBroadphase>();
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver = std::make_unique<btSequentialImpulseConstraintSolver>();
  std::unique_ptr<btDiscreteDynamicsWorld> world =
      std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(), config.get());
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btTypedConstraint>> constraints;

  ~BulletWorld() {
    for (auto& c : constraints) world->removeConstraint(c.get());
    for (auto& b : bodies) world->removeRigidBody(b.get());
  }
};

/// One shape per distinct size (Bullet shares shapes between bodies).
btCollisionShape* shapeFor(BulletWorld& bw, const BodySpec& s) {
  for (auto& sh : bw.shapes) {
    if (s.shape == BodyShape::Box && sh->getShapeType() == BOX_SHAPE_PROXYTYPE) {
      btVector3 h = static_cast<btBoxShape*>(sh.get())->getHalfExtentsWithMargin();
      if (h == btVector3(btScalar(s.halfExtents_m.x()), btScalar(s.halfExtents_m.y()), btScalar(s.halfExtents_m.z())))
        return sh.get();
    }
    if (s.shape == BodyShape::Sphere && sh->getShapeType() == SPHERE_SHAPE_PROXYTYPE &&
        static_cast<btSphereShape*>(sh.get())->getRadius() == btScalar(s.radius_m))
      return sh.get();
  }
  if (s.shape == BodyShape::Capsule)  // not shared: rag-doll parts differ in size anyway
    bw.shapes.push_back(std::make_unique<btCapsuleShape>(btScalar(s.radius_m), btScalar(2 * s.halfHeight_m)));
  else if (s.shape == BodyShape::Cylinder)  // axis Y, as the scene's; its margin lies inside the half extents
    bw.shapes.push_back(std::make_unique<btCylinderShape>(
        btVector3(btScalar(s.radius_m), btScalar(s.halfHeight_m), btScalar(s.radius_m))));
  else if (s.shape == BodyShape::Box)
    bw.shapes.push_back(std::make_unique<btBoxShape>(
        btVector3(btScalar(s.halfExtents_m.x()), btScalar(s.halfExtents_m.y()), btScalar(s.halfExtents_m.z()))));
  else
    bw.shapes.push_back(std::make_unique<btSphereShape>(btScalar(s.radius_m)));
  return bw.shapes.back().get();
}

/// Deepest overlap among the contact points the narrow phase produced this
/// step (btManifoldPoint::getDistance() < 0 is penetration).
double deepestOverlap(btCollisionDispatcher& d) {
  double deepest = 0;
  const int n = d.getNumManifolds();
  for (int i = 0; i < n; ++i) {
    const btPersistentManifold* m = d.getManifoldByIndexInternal(i);
    for (int p = 0; p < m->getNumContacts(); ++p) deepest = std::max(deepest, double(-m->getContactPoint(p).getDistance()));
  }
  return deepest;
}

double kineticEnergy(const BulletWorld& bw) {
  double e = 0;
  for (const auto& b : bw.bodies) {
    if (b->getInvMass() == 0) continue;
    const btVector3 v = b->getLinearVelocity(), w = b->getAngularVelocity();
    const btVector3 Iw = b->getInvInertiaTensorWorld().inverse() * w;
    e += 0.5 / b->getInvMass() * v.length2() + 0.5 * w.dot(Iw);
  }
  return e;
}

btTransform worldFrame(const V3& anchor, const Eigen::Quaterniond& q) {
  btTransform t;
  t.setOrigin(btVector3(btScalar(anchor.x()), btScalar(anchor.y()), btScalar(anchor.z())));
  t.setRotation(btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())));
  return t;
}

/// The scene's joints as Bullet's RagdollDemo builds them: btConeTwistConstraint
/// (twist about the frame's X, swing spans about Y and Z) and
/// btHingeConstraint (hinge about the frame's Z). Frames are the joint frame
/// at the start pose expressed in each body; the linked pair does not collide
/// (addConstraint(c, true)). Differences: Bullet's twist limit is symmetric,
/// so it gets the larger of |twist_lower| and twist_upper.
void addJoints(BulletWorld& bw, const SceneSpec& scene) {
  for (const JointSpec& j : scene.joints) {
    btRigidBody& A = *bw.bodies[j.a];
    btRigidBody& B = *bw.bodies[j.b];
    const Eigen::Quaterniond frame = Eigen::Quaterniond::FromTwoVectors(V3::UnitX(), j.axis);
    std::unique_ptr<btTypedConstraint> c;
    if (j.type == JointSpec::Type::ConeTwist) {
      const btTransform f = worldFrame(j.anchor_m, frame);
      auto ct = std::make_unique<btConeTwistConstraint>(A, B, A.getWorldTransform().inverse() * f,
                                                        B.getWorldTransform().inverse() * f);
      ct->setLimit(btScalar(j.swingLimit_rad), btScalar(j.swingLimit_rad),
                   btScalar(std::max(-j.twistLower_rad, j.twistUpper_rad)));
      c = std::move(ct);
    } else {
      // Bullet's hinge axis is the frame's Z: (X', Y', Z') = (Y, Z, X) of ours,
      // which keeps the angle's sign (both measure B relative to A).
      Eigen::Matrix3d m;
      const Eigen::Matrix3d F = frame.toRotationMatrix();
      m << F.col(1), F.col(2), F.col(0);
      const btTransform f = worldFrame(j.anchor_m, Eigen::Quaterniond(m));
      auto h = std::make_unique<btHingeConstraint>(A, B, A.getWorldTransform().inverse() * f,
                                                   B.getWorldTransform().inverse() * f);
      h->setLimit(btScalar(j.lower_rad), btScalar(j.upper_rad));
      c = std::move(h);
    }
    bw.world->addConstraint(c.get(), true);
    bw.constraints.push_back(std::move(c));
  }
}

/// Largest separation of the two frames' origins over every joint, m.
double jointError(const BulletWorld& bw) {
  double worst = 0;
  for (const auto& c : bw.constraints) {
    btTransform fa, fb;
    if (c->getConstraintType() == CONETWIST_CONSTRAINT_TYPE) {
      auto* ct = static_cast<const btConeTwistConstraint*>(c.get());
      fa = ct->getRigidBodyA().getWorldTransform() * ct->getAFrame();
      fb = ct->getRigidBodyB().getWorldTransform() * ct->getBFrame();
    } else {
      auto* h = static_cast<const btHingeConstraint*>(c.get());
      fa = h->getRigidBodyA().getWorldTransform() * h->getAFrame();
      fb = h->getRigidBodyB().getWorldTransform() * h->getBFrame();
    }
    worst = std::max(worst, double((fa.getOrigin() - fb.getOrigin()).length()));
  }
  return worst;
}

}  // namespace

const char* bulletPrecision() { return sizeof(btScalar) == 4 ? "float" : "double"; }

RunResult runBullet(const SceneSpec& scene, int steps, double dt, const BulletConfig& cfg) {
  BulletWorld bw;
  btDiscreteDynamicsWorld& world = *bw.world;
  world.setGravity(btVector3(btScalar(scene.gravity_mps2.x()), btScalar(scene.gravity_mps2.y()),
                             btScalar(scene.gravity_mps2.z())));
  btContactSolverInfo& info = world.getSolverInfo();
  info.m_numIterations = cfg.iterations;
  info.m_leastSquaresResidualThreshold = btScalar(cfg.residualThreshold_m2ps2);
  info.m_splitImpulse = cfg.splitImpulse ? 1 : 0;
  info.m_restitutionVelocityThreshold = 1;  // Tumble's WorldSettings::restitutionThreshold_mps

  const btScalar friction = btScalar(std::sqrt(scene.friction));
  const btScalar restitution = btScalar(std::sqrt(scene.restitution));
  bw.bodies.reserve(scene.bodies.size());
  for (const BodySpec& s : scene.bodies) {
    btCollisionShape* shape = shapeFor(bw, s);
    const btScalar mass = btScalar(s.mass_kg);
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, shape, inertia);
    ci.m_startWorldTransform.setIdentity();
    ci.m_startWorldTransform.setOrigin(
        btVector3(btScalar(s.position_m.x()), btScalar(s.position_m.y()), btScalar(s.position_m.z())));
    ci.m_startWorldTransform.setRotation(btQuaternion(btScalar(s.orientation.x()), btScalar(s.orientation.y()),
                                                      btScalar(s.orientation.z()), btScalar(s.orientation.w())));
    ci.m_friction = friction;
    ci.m_restitution = restitution;
    auto body = std::make_unique<btRigidBody>(ci);
    body->setLinearVelocity(
        btVector3(btScalar(s.velocity_mps.x()), btScalar(s.velocity_mps.y()), btScalar(s.velocity_mps.z())));
    if (scene.fastBodies && mass > 0 && s.shape == BodyShape::Sphere) {
      body->setCcdMotionThreshold(btScalar(s.radius_m));
      body->setCcdSweptSphereRadius(btScalar(s.radius_m));
    }
    if (!cfg.sleep) body->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(body.get());
    bw.bodies.push_back(std::move(body));
  }

  addJoints(bw, scene);

  RunResult r;
  r.kineticEnergyStart_J = kineticEnergy(bw);
  r.stepMs.reserve(steps);
  r.stepCpuMs.reserve(steps);
  for (int i = 0; i < steps; ++i) {
    const double c0 = threadCpuMs();
    auto t0 = std::chrono::steady_clock::now();
    if (cfg.substeps <= 1)
      world.stepSimulation(btScalar(dt), 0);  // maxSubSteps 0: exactly one step of dt
    else  // exactly cfg.substeps internal steps of dt / substeps (no interpolation left over)
      world.stepSimulation(btScalar(dt), cfg.substeps, btScalar(dt / cfg.substeps));
    auto t1 = std::chrono::steady_clock::now();
    r.stepCpuMs.push_back(threadCpuMs() - c0);
    r.stepMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    r.penetrationMax_m = std::max(r.penetrationMax_m, deepestOverlap(*bw.dispatcher));
    r.jointErrorMax_m = std::max(r.jointErrorMax_m, jointError(bw));
  }
  r.kineticEnergyEnd_J = kineticEnergy(bw);
  std::vector<V3> end;
  end.reserve(bw.bodies.size());
  for (const auto& b : bw.bodies) {
    const btVector3& p = b->getWorldTransform().getOrigin();
    end.emplace_back(p.x(), p.y(), p.z());
    if (b->getInvMass() > 0 && !b->isActive()) ++r.sleepingAtEnd;
  }
  measureEnd(scene, end, &r);
  return r;
}

}  // namespace tumble::compare
