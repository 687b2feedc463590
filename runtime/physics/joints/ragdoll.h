#pragma once
// Rag-dolls: a plain-data description (parts and joints), a builder that
// creates the bodies and joints in a World, and a default human of 11 parts
// with anthropometric proportions (ragdoll.cpp cites the table).
//
// The description is in a model frame: Y up, the figure faces +Z, its feet
// on y = 0, standing. The builder places that frame at a position and
// orientation in the world. Scripts (spawn_ragdoll{...}) fill the same struct.
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "physics/joints/joint_system.h"
#include "physics/world.h"

namespace tumble::physics {

enum class RagdollShape { Box, Capsule };

struct RagdollPart {
  std::string name;
  RagdollShape shape = RagdollShape::Box;
  Vec3 halfExtents_m = Vec3::Constant(Real(0.1));  ///< Box: half size along the part's local axes
  Real radius_m = Real(0.05);                      ///< Capsule: radius
  Real halfHeight_m = Real(0.1);                   ///< Capsule: half length of the core along local Y
  Real mass_kg = 1;
  Vec3 position_m = Vec3::Zero();           ///< centre of mass in the model frame
  Quat orientation = Quat::Identity();      ///< part frame to model frame
};

struct RagdollJoint {
  std::string name;
  JointType type = JointType::ConeTwist;
  int partA = 0;  ///< child part (index into parts)
  int partB = 0;  ///< parent part (index into parts)
  Vec3 anchor_m = Vec3::Zero();  ///< model frame; converted to each part's local frame
  /// Model frame; hinge axis (Hinge) or twist axis (ConeTwist), pointing from
  /// the parent into the child for cone-twist joints.
  Vec3 axis = Vec3::UnitX();
  Real lowerAngle_rad = 0;        ///< Hinge
  Real upperAngle_rad = 0;        ///< Hinge
  Real swingLimit_rad = kPi / 4;  ///< ConeTwist
  Real twistLower_rad = -kPi / 8; ///< ConeTwist
  Real twistUpper_rad = kPi / 8;  ///< ConeTwist
  Real breakForce_N = 0;          ///< 0: unbreakable
};

struct RagdollDesc {
  std::vector<RagdollPart> parts;
  std::vector<RagdollJoint> joints;
  Real friction = Real(0.6);  ///< every part
  Real restitution = 0;       ///< every part
  /// Every part (BodyDef::rollingResistance). Limbs are not steel balls: a
  /// capsule head or arm pinned by its joint would otherwise roll about the
  /// pin on the ground for seconds (measured: the head of a dropped rag-doll
  /// still creeping at 0.3 rad/s after 5 s, impulse solver).
  Real rollingResistance = Real(0.2);
  /// Pairs of parts whose collisions must be filtered: the adjacent ones
  /// (joined by a joint). Filled by defaultHuman and by validate/finalize;
  /// non-adjacent parts collide.
  std::vector<std::pair<int, int>> noCollide;
};

/// The default human: pelvis, torso, head, upper and lower arms, upper and
/// lower legs (11 parts, 10 joints) for a body of the given height and mass.
RagdollDesc defaultHuman(Real height_m = Real(1.75), Real mass_kg = Real(75));

/// Checks indices, sizes, masses, limits; the message names the part or
/// joint and the field. Fills noCollide from the joints if it is empty.
Status validateRagdoll(RagdollDesc& desc);

/// What the builder created.
struct Ragdoll {
  std::vector<BodyId> bodies;  ///< one per part, in the description's order
  std::vector<JointId> joints;  ///< one per joint
  /// Body pairs whose collisions are filtered (buildRagdoll calls
  /// World::disableCollision on each; destroying a body drops its pairs).
  std::vector<std::pair<BodyId, BodyId>> noCollide;
};

/// Creates the parts as dynamic bodies and the joints, with the model frame
/// at position_m / orientation in the world. On an error nothing is left
/// behind (bodies already created are destroyed).
Result<Ragdoll> buildRagdoll(World& world, JointSystem& joints, RagdollDesc desc, const Vec3& position_m,
                             const Quat& orientation = Quat::Identity());

/// Removes the rag-doll's joints and bodies.
void destroyRagdoll(World& world, JointSystem& joints, const Ragdoll& ragdoll);

}  // namespace tumble::physics
