// Rag-doll description, builder and the default human (see ragdoll.h).
//
// Anthropometry: D. A. Winter, "Biomechanics and Motor Control of Human
// Movement", 4th ed., Wiley 2009, Table 4.1 (segment mass as a fraction of
// total body mass, after Dempster 1955) and Figure 4.1 (segment lengths as a
// fraction of body height H, after Drillis and Contini 1966).
//   mass fractions: head and neck 0.081, thorax + abdomen 0.355, pelvis 0.142,
//     upper arm 0.028, forearm and hand 0.022, thigh 0.100, leg and foot 0.061
//     (11 parts: 0.081 + 0.355 + 0.142 + 2 (0.028 + 0.022 + 0.100 + 0.061) = 1).
//   heights: top of head 1.000 H, chin 0.870 H, shoulder 0.818 H, hip 0.530 H,
//     knee 0.285 H, ankle 0.039 H; lengths: upper arm 0.186 H, forearm
//     0.146 H, hand 0.108 H; shoulder width 0.259 H, hip width 0.191 H.
// Simplifications (ours): widths and radii are not in Winter's figure and
// are chosen so that no two parts overlap in the standing pose; joint-to-
// joint lengths follow Winter, but the capsules stop short of the parent's
// joint (see defaultHuman: adjacent parts cannot collide yet, the World has
// no collision filter); the hip joints sit closer together (0.10 H) than
// Winter's hip width so the thighs fit under a pelvis box; the arms hang
// beside the torso, so the shoulders are 0.236 H apart instead of 0.259 H.
#include "physics/joints/ragdoll.h"

#include <cmath>
#include <string>

namespace tumble::physics {

namespace {

RagdollPart box(const char* name, Real mass, const Vec3& centre, const Vec3& half) {
  RagdollPart p;
  p.name = name;
  p.shape = RagdollShape::Box;
  p.mass_kg = mass;
  p.position_m = centre;
  p.halfExtents_m = half;
  return p;
}

/// A vertical capsule whose core runs from y = bottom to y = top at (x, ., 0).
RagdollPart capsule(const char* name, Real mass, Real x, Real bottom, Real top, Real radius) {
  RagdollPart p;
  p.name = name;
  p.shape = RagdollShape::Capsule;
  p.mass_kg = mass;
  p.position_m = Vec3(x, (bottom + top) / 2, 0);
  p.radius_m = radius;
  p.halfHeight_m = (top - bottom) / 2;
  return p;
}

RagdollJoint cone(const char* name, int child, int parent, const Vec3& anchor, const Vec3& axis, Real swing,
                  Real twist) {
  RagdollJoint j;
  j.name = name;
  j.type = JointType::ConeTwist;
  j.partA = child;
  j.partB = parent;
  j.anchor_m = anchor;
  j.axis = axis;
  j.swingLimit_rad = swing;
  j.twistLower_rad = -twist;
  j.twistUpper_rad = twist;
  return j;
}

RagdollJoint hinge(const char* name, int child, int parent, const Vec3& anchor, Real lower, Real upper) {
  RagdollJoint j;
  j.name = name;
  j.type = JointType::Hinge;
  j.partA = child;
  j.partB = parent;
  j.anchor_m = anchor;
  j.axis = Vec3::UnitX();
  j.lowerAngle_rad = lower;
  j.upperAngle_rad = upper;
  return j;
}

}  // namespace

RagdollDesc defaultHuman(Real H, Real M) {
  RagdollDesc d;
  auto& P = d.parts;
  enum { Pelvis, Torso, Head, UpperArmL, LowerArmL, UpperArmR, LowerArmR, UpperLegL, LowerLegL, UpperLegR, LowerLegR };
  // Joint heights (fractions of H): Winter's hip, knee, shoulder (0.80 H, the
  // joint centre below the acromion at 0.818 H), elbow = shoulder - upper
  // arm, wrist+hand below it; waist and neck are ours.
  const Real hip = Real(0.530), knee = Real(0.285), shoulder = Real(0.800), elbow = shoulder - Real(0.186);
  const Real hand = elbow - Real(0.146 + 0.108), waist = Real(0.660), neck = Real(0.866);
  const Real rUpperArm = Real(0.022), rLowerArm = Real(0.019), rThigh = Real(0.035), rShank = Real(0.028);
  const Real rHead = Real(0.045), armX = Real(0.118), legX = Real(0.05);
  // Every child capsule has its core end on its joint, and every parent
  // surface is at least the child's radius from the joint, so a limb turning
  // about its joint never touches its parent while it bends less than 90
  // degrees (the World cannot filter adjacent pairs yet; see noCollide).
  const Real pelvisBottom = hip + rThigh + Real(0.003), pelvisTop = waist - Real(0.015);
  const Real torsoBottom = waist + Real(0.015), torsoTop = Real(0.818);
  P.push_back(box("pelvis", Real(0.142) * M, Vec3(0, (pelvisBottom + pelvisTop) / 2, 0) * H,
                  Vec3(0.08f, (pelvisTop - pelvisBottom) / 2, 0.055f) * H));
  P.push_back(box("torso", Real(0.355) * M, Vec3(0, (torsoBottom + torsoTop) / 2, 0) * H,
                  Vec3(0.09f, (torsoTop - torsoBottom) / 2, 0.055f) * H));
  P.push_back(capsule("head", Real(0.081) * M, 0, neck * H, (1 - rHead) * H, rHead * H));
  for (Real side : {Real(1), Real(-1)}) {
    const bool left = side > 0;  // the figure faces +Z, so its left is +X
    P.push_back(capsule(left ? "upper_arm_l" : "upper_arm_r", Real(0.028) * M, side * armX * H,
                        (elbow + rUpperArm + rLowerArm) * H, shoulder * H, rUpperArm * H));
    P.push_back(capsule(left ? "lower_arm_l" : "lower_arm_r", Real(0.022) * M, side * armX * H,
                        (hand + rLowerArm) * H, elbow * H, rLowerArm * H));
  }
  for (Real side : {Real(1), Real(-1)}) {
    const bool left = side > 0;
    P.push_back(capsule(left ? "upper_leg_l" : "upper_leg_r", Real(0.100) * M, side * legX * H,
                        (knee + rThigh + rShank) * H, hip * H, rThigh * H));
    P.push_back(capsule(left ? "lower_leg_l" : "lower_leg_r", Real(0.061) * M, side * legX * H,
                        (Real(0.005) + rShank) * H, knee * H, rShank * H));
  }
  const Vec3 up = Vec3::UnitY(), down = -Vec3::UnitY();
  auto& J = d.joints;
  // Waist swing kept at 0.3 rad: the torso box's corners would reach the
  // pelvis beyond that (box against box, 0.03 H apart).
  J.push_back(cone("waist", Torso, Pelvis, Vec3(0, waist * H, 0), up, Real(0.3), Real(0.4)));
  J.push_back(cone("neck", Head, Torso, Vec3(0, neck * H, 0), up, Real(0.6), Real(0.8)));
  // Hinge angles are the parent's rotation relative to the child about +X:
  // elbows flex forward (positive), knees backward (negative). Limited to
  // 1.5 rad (86 deg) so adjacent capsules never touch; real joints reach
  // ~2.5 rad: raise the limits once World::disableCollision exists.
  const int arms[2][2] = {{UpperArmL, LowerArmL}, {UpperArmR, LowerArmR}};
  const int legs[2][2] = {{UpperLegL, LowerLegL}, {UpperLegR, LowerLegR}};
  for (int s = 0; s < 2; ++s) {
    const Real side = s == 0 ? Real(1) : Real(-1);
    J.push_back(cone(s == 0 ? "shoulder_l" : "shoulder_r", arms[s][0], Torso, Vec3(side * armX, shoulder, 0) * H,
                     down, Real(1.5), Real(0.8)));
    J.push_back(hinge(s == 0 ? "elbow_l" : "elbow_r", arms[s][1], arms[s][0], Vec3(side * armX, elbow, 0) * H, 0,
                      Real(1.5)));
  }
  for (int s = 0; s < 2; ++s) {
    const Real side = s == 0 ? Real(1) : Real(-1);
    J.push_back(cone(s == 0 ? "hip_l" : "hip_r", legs[s][0], Pelvis, Vec3(side * legX, hip, 0) * H, down, Real(1.4),
                     Real(0.5)));
    J.push_back(hinge(s == 0 ? "knee_l" : "knee_r", legs[s][1], legs[s][0], Vec3(side * legX, knee, 0) * H,
                      Real(-1.5), 0));
  }
  for (const RagdollJoint& j : J) d.noCollide.emplace_back(j.partA, j.partB);
  return d;
}

Status validateRagdoll(RagdollDesc& d) {
  const int n = int(d.parts.size());
  if (n == 0) return makeError("ragdoll field 'parts' must list at least one part");
  for (int i = 0; i < n; ++i) {
    const RagdollPart& p = d.parts[i];
    const std::string where = "ragdoll part " + std::to_string(i + 1) + " ('" + p.name + "')";
    if (!std::isfinite(p.mass_kg) || p.mass_kg <= 0) return makeError(where + ": 'mass' must be > 0 kg");
    if (!p.position_m.allFinite() || !p.orientation.coeffs().allFinite() || p.orientation.norm() < Real(1e-6))
      return makeError(where + ": 'position' and 'orientation' must be finite");
    if (p.shape == RagdollShape::Box && !(p.halfExtents_m.minCoeff() > 0 && p.halfExtents_m.allFinite()))
      return makeError(where + ": box 'size' must be > 0 m on every axis");
    if (p.shape == RagdollShape::Capsule &&
        !(std::isfinite(p.radius_m) && p.radius_m > 0 && std::isfinite(p.halfHeight_m) && p.halfHeight_m >= 0))
      return makeError(where + ": capsule 'radius' must be > 0 m and 'half_height' >= 0 m");
  }
  for (std::size_t k = 0; k < d.joints.size(); ++k) {
    const RagdollJoint& j = d.joints[k];
    const std::string where = "ragdoll joint " + std::to_string(k + 1) + " ('" + j.name + "')";
    if (j.partA < 0 || j.partA >= n || j.partB < 0 || j.partB >= n || j.partA == j.partB)
      return makeError(where + ": 'parts' must name two different parts (1.." + std::to_string(n) + ")");
    if (!j.anchor_m.allFinite() || !(j.axis.norm() > 0)) return makeError(where + ": 'anchor' and 'axis' must be finite, axis non-zero");
  }
  if (d.noCollide.empty())
    for (const RagdollJoint& j : d.joints) d.noCollide.emplace_back(j.partA, j.partB);
  return Ok{};
}

Result<Ragdoll> buildRagdoll(World& world, JointSystem& joints, RagdollDesc desc, const Vec3& position,
                             const Quat& orientation) {
  if (auto s = validateRagdoll(desc); !s) return makeError(s.error());
  Ragdoll r;
  const Quat R = orientation.normalized();
  auto fail = [&](const std::string& message) -> Result<Ragdoll> {
    destroyRagdoll(world, joints, r);
    return makeError(message);
  };
  for (const RagdollPart& p : desc.parts) {
    BodyDef b;
    b.shape = p.shape == RagdollShape::Box ? Shape::box(p.halfExtents_m) : Shape::capsule(p.radius_m, p.halfHeight_m);
    b.mass_kg = p.mass_kg;
    b.position_m = position + R * p.position_m;
    b.orientation = (R * p.orientation).normalized();
    b.friction = desc.friction;
    b.restitution = desc.restitution;
    b.rollingResistance = desc.rollingResistance;
    auto id = world.createBody(b);
    if (!id) return fail("ragdoll part '" + p.name + "': " + id.error());
    r.bodies.push_back(id.value());
  }
  for (const RagdollJoint& j : desc.joints) {
    JointDef def = makeJointDef(world, j.type, r.bodies[j.partA], r.bodies[j.partB], position + R * j.anchor_m,
                                R * j.axis);
    def.enableLimit = j.type == JointType::Hinge;
    def.lowerAngle_rad = j.lowerAngle_rad;
    def.upperAngle_rad = j.upperAngle_rad;
    def.swingLimit_rad = j.swingLimit_rad;
    def.twistLower_rad = j.twistLower_rad;
    def.twistUpper_rad = j.twistUpper_rad;
    def.breakForce_N = j.breakForce_N;
    auto id = joints.createJoint(def);
    if (!id) return fail("ragdoll joint '" + j.name + "': " + id.error());
    r.joints.push_back(id.value());
  }
  for (auto [a, b] : desc.noCollide)
    if (a >= 0 && b >= 0 && a < int(r.bodies.size()) && b < int(r.bodies.size()))
      r.noCollide.emplace_back(r.bodies[a], r.bodies[b]);
  for (auto [a, b] : r.noCollide) world.disableCollision(a, b);
  return r;
}

void destroyRagdoll(World& world, JointSystem& joints, const Ragdoll& r) {
  for (JointId j : r.joints) joints.destroyJoint(j);
  for (BodyId b : r.bodies) world.destroyBody(b);
}

}  // namespace tumble::physics
