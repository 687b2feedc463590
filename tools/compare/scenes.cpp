// The comparison scenes. Sizes, masses and materials are chosen once here and
// read by both engines.
#include <algorithm>
#include <cmath>
#include <random>
#include <time.h>

#include "physics/joints/ragdoll.h"
#include "scenes.h"

namespace tumble::compare {

namespace {

/// Bullet's benchmark ground: a static box 500 x 100 x 500 m, top at y = 0.
void addGroundBox(SceneSpec& s) {
  BodySpec ground;
  ground.shape = BodyShape::Box;
  ground.halfExtents_m = V3(250, 50, 250);
  ground.position_m = V3(0, -50, 0);
  ground.mass_kg = 0;
  s.bodies.push_back(ground);
}

/// An 80 x 1 x 80 m static slab with its top at y = 0 (the pyramids' ground).
void addSlabGround(SceneSpec& s) {
  BodySpec ground;
  ground.shape = BodyShape::Box;
  ground.halfExtents_m = V3(40, 0.5, 40);
  ground.position_m = V3(0, -0.5, 0);
  ground.mass_kg = 0;
  s.bodies.push_back(ground);
}

/// Bullet's own "3000 boxes" benchmark (bullet3 examples/Benchmarks,
/// BenchmarkDemo::createTest1), rebuilt from its description: 47 layers of
/// 8 x 8 cubes of half-extent 1 m and mass 2 kg, 3 m apart (1 m gaps) in x
/// and z; layer k at y = 2 + 3k; every layer shifted by -0.35 m in x and z
/// from the one below, so the columns lean and the pile collapses as it
/// lands: it stresses box-box collision, the broad phase and the solver.
/// The ground is a static box 500 x 100 x 500 m with its top at y = 0.
/// Differences from Bullet's demo: gravity 9.81 (not 10) and friction 0.5 as a
/// pair value (Bullet's default body friction 0.5 gives a pair 0.25).
void boxes3000(SceneSpec& s) {
  s.description = "8x8x47 falling cubes (half 1 m, 2 kg) on a ground box, Bullet's 3000-boxes benchmark layout";
  s.qualityMetric = "penetration_max_m";  // a collapsing pile: drift means nothing, overlap does
  s.friction = 0.5;
  s.restitution = 0;
  s.defaultSteps = 300;
  addGroundBox(s);
  const int size = 8, layers = 47;
  const double half = 1, spacing = 1, pitch = 2 * half + spacing;
  double offset = -size * pitch * 0.5;
  double y = 2 * half;
  for (int k = 0; k < layers; ++k) {
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        BodySpec b;
        b.shape = BodyShape::Box;
        b.halfExtents_m = V3::Constant(half);
        b.position_m = V3(offset + i * pitch, y, offset + j * pitch);
        b.mass_kg = 2;
        s.bodies.push_back(b);
      }
    offset -= 0.05 * spacing * (size - 1);
    y += pitch;
  }
}

/// The same 3008 cubes and ground as boxes_3000, but as 8 x 8 upright columns
/// of 47 (no lean, 1 m between columns, 1 cm vertical gaps): every box rests
/// on another from the first second on, so this times and tests tall-stack
/// solving at scale, and stack_drift_m is meaningful (a column that stands
/// drifts by millimetres, one that falls by metres).
void boxes3000Stacked(SceneSpec& s) {
  s.description = "8x8 upright columns of 47 cubes (half 1 m, 2 kg), 1 cm gaps: tall stacks at scale";
  s.friction = 0.5;
  s.restitution = 0;
  s.defaultSteps = 300;
  addGroundBox(s);
  const int size = 8, layers = 47;
  const double half = 1, pitch = 3, gap = 0.01;
  const double offset = -(size - 1) * pitch * 0.5;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        BodySpec b;
        b.shape = BodyShape::Box;
        b.halfExtents_m = V3::Constant(half);
        b.position_m = V3(offset + i * pitch, half + gap + k * (2 * half + gap), offset + j * pitch);
        b.mass_kg = 2;
        s.bodies.push_back(b);
      }
}

/// A 2-D pyramid in the x-y plane: rows of 20, 19, ..., 1 cubes of half-extent
/// 0.5 m, 1 kg, touching (no gaps), on a static ground box with its top at
/// y = 0. A well-solved pyramid stands still; drift measures how much it
/// creeps or slumps.
void pyramid20(SceneSpec& s) {
  s.description = "2-D pyramid, base 20 (210 cubes, half 0.5 m, 1 kg) on a ground box";
  s.friction = 0.6;
  s.restitution = 0;
  s.defaultSteps = 600;
  addSlabGround(s);
  const int base = 20;
  const double half = 0.5;
  for (int row = 0; row < base; ++row) {
    const int n = base - row;
    for (int i = 0; i < n; ++i) {
      BodySpec b;
      b.shape = BodyShape::Box;
      b.halfExtents_m = V3::Constant(half);
      b.position_m = V3((i - (n - 1) * 0.5) * 2 * half, half + row * 2 * half, 0);
      b.mass_kg = 1;
      s.bodies.push_back(b);
    }
  }
}

/// A large pile: a square 3-D pyramid of 14 x 14, 13 x 13, ..., 1 cubes
/// (1015 cubes of half-extent 0.5 m, 1 kg), touching, on a static ground box
/// with its top at y = 0; friction 0.6, no sleeping. Every box rests on four
/// (or the ground), so the contact graph is one large island, the case a
/// sleeping, island-splitting engine cannot dodge. A well-solved pile stands
/// still: stack_drift_m measures how much it creeps or slumps.
void pile1015(SceneSpec& s) {
  s.description = "3-D pyramid, base 14 x 14 (1015 cubes, half 0.5 m, 1 kg) on a ground box";
  s.friction = 0.6;
  s.restitution = 0;
  s.defaultSteps = 300;
  addSlabGround(s);
  const int base = 14;
  const double half = 0.5;
  for (int layer = 0; layer < base; ++layer) {
    const int n = base - layer;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        BodySpec b;
        b.shape = BodyShape::Box;
        b.halfExtents_m = V3::Constant(half);
        b.position_m = V3((i - (n - 1) * 0.5) * 2 * half, half + layer * 2 * half, (j - (n - 1) * 0.5) * 2 * half);
        b.mass_kg = 1;
        s.bodies.push_back(b);
      }
  }
}

/// 1000 spheres (radius 0.1 m, 1 kg) at 250 m/s in random directions inside
/// a closed box: 6 static walls 1 m thick around a 20 m cube cavity centred
/// on the origin. Restitution 1, friction 0, no gravity. At 1/60 s a sphere
/// moves 4.2 m per step, 42 diameters and 4 wall thicknesses: without
/// continuous collision everything escapes. Spheres start on a jittered
/// 10 x 10 x 10 grid (pitch 1.8 m), so none overlap at the start. Fixed seed.
void highspeed1000(SceneSpec& s) {
  s.description = "1000 spheres (r 0.1 m) at 250 m/s in a closed 20 m box, e = 1, no friction, no gravity";
  s.gravity_mps2 = V3::Zero();
  s.friction = 0;
  s.restitution = 1;
  s.fastBodies = true;
  s.defaultSteps = 600;
  s.qualityMetric = "energy_rel_change";  // elastic and frictionless: kinetic energy is conserved
  const double inner = 10, wallHalf = 0.5;
  s.containHalf_m = inner;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1}) {
      BodySpec w;
      w.shape = BodyShape::Box;
      w.halfExtents_m = V3::Constant(inner + 2 * wallHalf);
      w.halfExtents_m[axis] = wallHalf;
      w.position_m = V3::Zero();
      w.position_m[axis] = side * (inner + wallHalf);
      w.mass_kg = 0;
      s.bodies.push_back(w);
    }
  std::mt19937 rng(20240613u);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::uniform_real_distribution<double> unit(-1, 1);
  const int n = 10;
  const double pitch = 1.8;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        BodySpec b;
        b.shape = BodyShape::Sphere;
        b.radius_m = 0.1;
        b.position_m = V3((i - (n - 1) * 0.5) * pitch + jitter(rng), (j - (n - 1) * 0.5) * pitch + jitter(rng),
                          (k - (n - 1) * 0.5) * pitch + jitter(rng));
        V3 d;
        do d = V3(unit(rng), unit(rng), unit(rng));  // rejection: uniform on the sphere
        while (d.squaredNorm() > 1 || d.squaredNorm() < 1e-6);
        b.velocity_mps = 250 * d.normalized();
        b.mass_kg = 1;
        s.bodies.push_back(b);
      }
}

/// 100 rag-dolls of 11 parts and 10 joints (Tumble's default human, 1.75 m,
/// 75 kg: capsules and boxes; 8 cone-twist joints at waist, neck, shoulders
/// and hips, 2 hinges at the knees... as physics::defaultHuman lays them
/// out), lying face down in a 10 x 10 grid 2.5 m apart, dropped from 0.5 to
/// 1.4 m (rows at alternating heights) onto the ground box. Bullet's own
/// RagdollDemo builds its doll the same way (capsules, btConeTwistConstraint
/// and btHingeConstraint).
void ragdolls100(SceneSpec& s) {
  s.description = "100 rag-dolls (11 parts, 10 joints each) dropped on a ground box";
  s.qualityMetric = "joint_error_max_m";
  s.friction = 0.6;
  s.restitution = 0;
  s.defaultSteps = 300;
  addGroundBox(s);
  physics::RagdollDesc desc = physics::defaultHuman(Real(1.75), Real(75));
  const Eigen::Quaterniond lying(Eigen::AngleAxisd(M_PI / 2, V3::UnitX()));
  for (int k = 0; k < 100; ++k) {
    const V3 origin((k % 10 - 4.5) * 2.5, 0.5 + 0.3 * (k % 4), (k / 10 - 4.5) * 2.5 - 0.9);
    const int first = int(s.bodies.size());
    for (const physics::RagdollPart& p : desc.parts) {
      BodySpec b;
      b.shape = p.shape == physics::RagdollShape::Box ? BodyShape::Box : BodyShape::Capsule;
      b.halfExtents_m = p.halfExtents_m.cast<double>();
      b.radius_m = p.radius_m;
      b.halfHeight_m = p.halfHeight_m;
      b.mass_kg = p.mass_kg;
      b.position_m = origin + lying * p.position_m.cast<double>();
      b.orientation = lying * p.orientation.cast<double>();
      s.bodies.push_back(b);
    }
    for (const physics::RagdollJoint& j : desc.joints) {
      JointSpec js;
      js.type = j.type == physics::JointType::Hinge ? JointSpec::Type::Hinge : JointSpec::Type::ConeTwist;
      js.a = first + j.partA;
      js.b = first + j.partB;
      js.anchor_m = origin + lying * j.anchor_m.cast<double>();
      js.axis = (lying * j.axis.cast<double>()).normalized();
      js.swingLimit_rad = j.swingLimit_rad;
      js.twistLower_rad = j.twistLower_rad;
      js.twistUpper_rad = j.twistUpper_rad;
      js.lower_rad = j.lowerAngle_rad;
      js.upper_rad = j.upperAngle_rad;
      s.joints.push_back(js);
    }
  }
}

/// Cylinders standing on their caps: 10 x 10 columns of 4 (radius 0.4 m,
/// height 0.8 m, 1 kg), 1.2 m apart, 1 cm vertical gaps, on the slab
/// ground. Cap-on-cap and cap-on-ground face contacts at scale; a column
/// that stands drifts by millimetres, one that rocks or falls by more, so
/// stack_drift_m is the quality. Tumble's cylinder is exact (its own
/// support and face clipping), Bullet's btCylinderShape is GJK/EPA with
/// its persistent manifold.
void cylinders400(SceneSpec& s) {
  s.description = "10x10 upright columns of 4 cylinders (radius 0.4 m, height 0.8 m, 1 kg), 1 cm gaps, on a slab";
  s.friction = 0.6;
  s.restitution = 0;
  s.defaultSteps = 600;
  addSlabGround(s);
  const int size = 10, layers = 4;
  const double radius = 0.4, half = 0.4, pitch = 1.2, gap = 0.01;
  const double offset = -(size - 1) * pitch * 0.5;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        BodySpec b;
        b.shape = BodyShape::Cylinder;
        b.radius_m = radius;
        b.halfHeight_m = half;
        b.position_m = V3(offset + i * pitch, half + gap + k * (2 * half + gap), offset + j * pitch);
        b.mass_kg = 1;
        s.bodies.push_back(b);
      }
}

struct Entry {
  const char* name;
  void (*build)(SceneSpec&);
};
constexpr Entry kScenes[] = {
    {"boxes_3000", boxes3000},
    {"boxes_3000_stacked", boxes3000Stacked},
    {"pyramid_20", pyramid20},
    {"pile_1015", pile1015},
    {"highspeed_1000", highspeed1000},
    {"ragdolls_100", ragdolls100},
    {"cylinders_400", cylinders400},
};

}  // namespace

std::vector<std::string> sceneNames() {
  std::vector<std::string> names;
  for (const Entry& e : kScenes) names.emplace_back(e.name);
  return names;
}

bool buildScene(const std::string& name, SceneSpec* out) {
  for (const Entry& e : kScenes)
    if (name == e.name) {
      *out = SceneSpec{};
      out->name = name;
      e.build(*out);
      return true;
    }
  return false;
}

std::string sceneDescription(const std::string& name) {
  SceneSpec s;
  return buildScene(name, &s) ? s.description : std::string();
}

double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

void measureEnd(const SceneSpec& scene, const std::vector<V3>& end, RunResult* r) {
  r->escaped = 0;
  r->stackDrift_m = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    if (b.isStatic()) continue;
    const V3 d = end[i] - b.position_m;
    r->stackDrift_m = std::max(r->stackDrift_m, std::hypot(d.x(), d.z()));
    if (scene.containHalf_m > 0 && !(end[i].cwiseAbs().maxCoeff() <= scene.containHalf_m)) ++r->escaped;
  }
}

}  // namespace tumble::compare
