#pragma once
// Mass-spring deformables: ropes (a chain of springs) and cloth (a grid with
// structural, shear and bend springs), stepped with one linearised
// backward-Euler step per substep (Baraff & Witkin 1998) solved by Eigen's
// sparse conjugate gradients, so stiff springs stay stable at 60 Hz.
//
// Sections
//   DeformableMaterial            stiffness, damping, drag, collision radius
//   RopeDef, ClothDef             set-up structs with defaults
//   DeformableEnvironment         what a step sees of the world
//   Deformable                    particles, springs, pins, wind; step()
//   DeformableSystem              every deformable of a scene
//
// State is double (the numerics lab's precision; the solve is a sum over
// hundreds of stiff springs). Collisions: the ground and every other static
// or kinematic plane, box, sphere and capsule of the World, and the height
// field; one way (particles are pushed out, bodies feel nothing). Pins hold
// a particle at a fixed point or at a point of a body (carried with it).
// deformable.cpp derives the step and says what was rejected.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/byte_stream.h"
#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"
#include "physics/height_field.h"

namespace tumble::physics {

class World;
class DebugDraw;

struct DeformableMaterial {
  Real stiffness_Npm = 2e4;       ///< each structural spring (N/m); > 0
  Real shearStiffness_Npm = -1;   ///< cloth diagonals (N/m); < 0: stiffness / 4
  Real bendStiffness_Npm = -1;    ///< springs over two segments (N/m); < 0: stiffness / 1000 (drapes; see deformable.cpp)
  Real damping_Nspm = 0.5;        ///< along each spring (N s/m), >= 0
  Real airDrag_Nspm = 0.01;       ///< per particle, against the velocity relative to the wind (N s/m)
  Real dragCoefficient = 1.2;     ///< cloth: per-triangle pressure drag C_d (flat plate ~ 1.2)
  Real airDensity_kgpm3 = Real(1.2);
  Real friction = Real(0.5);      ///< Coulomb coefficient against the ground and static shapes
  Real radius_m = Real(0.02);     ///< particle collision radius (thickness), > 0
  int substeps = 2;               ///< implicit steps per World step, 1..64
};

struct RopeDef {
  Vec3 start_m = Vec3(0, 2, 0);
  Vec3 end_m = Vec3(2, 2, 0);
  int segments = 20;      ///< springs along the rope, 1..4096 (segments + 1 particles)
  Real mass_kg = 1;       ///< total, shared equally by the particles
  DeformableMaterial material;
  bool pinStart = true;   ///< the first particle held where it starts
  bool pinEnd = false;    ///< the last particle held where it starts
};

enum class ClothPins { None, TopCorners, TopEdge };

struct ClothDef {
  Vec3 origin_m = Vec3(0, 2, 0);     ///< the top-left corner (particle 0)
  Vec3 edgeU_m = Vec3(2, 0, 0);      ///< along a row (columns), its full length
  Vec3 edgeV_m = Vec3(0, -1.5, 0);   ///< down the columns (rows), its full length
  int columns = 16;                  ///< particles per row, 2..256
  int rows = 12;                     ///< particles per column, 2..256
  Real mass_kg = Real(0.5);          ///< total
  DeformableMaterial material;
  ClothPins pins = ClothPins::TopEdge;  ///< the top row is the one at origin, along edgeU
};

/// What a step sees: gravity, the World's static / kinematic shapes and
/// bodies pins refer to (null: neither), and the height field (null: none).
struct DeformableEnvironment {
  Vec3 gravity_mps2 = Vec3(0, -kStandardGravity, 0);
  const World* world = nullptr;
  const HeightField* heightField = nullptr;
};

struct DeformableStats {
  int cgIterationsMax = 0;   ///< most CG iterations of one solve
  long cgFailures = 0;       ///< solves that hit the iteration cap (result used anyway)
  long nanEvents = 0;        ///< steps undone because the state became non-finite
  long steps = 0;            ///< substeps taken
};

class Deformable {
 public:
  enum class Kind { Rope, Cloth };

  /// Refuse bad definitions with a message naming the field.
  static Result<std::unique_ptr<Deformable>> rope(const RopeDef& def);
  static Result<std::unique_ptr<Deformable>> cloth(const ClothDef& def);

  Kind kind() const { return m_kind; }
  int particleCount() const { return int(m_x.size() / 3); }
  int columns() const { return m_columns; }  ///< cloth: particles per row; rope: particle count
  Vec3 position(int i) const { return m_x.segment<3>(3 * i).cast<Real>(); }
  Vec3 velocity(int i) const { return m_v.segment<3>(3 * i).cast<Real>(); }
  Real particleMass_kg() const { return Real(m_mass); }
  /// Sets particle i's velocity (m/s), e.g. a kick; false: bad index. A
  /// non-finite velocity is taken as given: the next step then fails, is
  /// undone and counted (DeformableStats::nanEvents).
  bool setVelocity(int i, const Vec3& v_mps);

  /// Pins: particle i held at a world point, or at the body point where it
  /// is now (carried with the body). false: bad index or stale body.
  bool pinToPoint(int i, const Vec3& point_m);
  bool pinToBody(int i, const World& world, BodyId body);
  bool unpin(int i);
  bool pinned(int i) const;

  void setWind(const Vec3& wind_mps) { m_wind = wind_mps.cast<double>(); }
  Vec3 wind() const { return m_wind.cast<Real>(); }
  const DeformableMaterial& material() const { return m_material; }

  /// Advances dt (s) in material().substeps implicit steps.
  void step(Real dt_s, const DeformableEnvironment& env);

  /// Kinetic, gravitational (relative to y = 0) and spring energy (J).
  double energy(const Vec3& gravity_mps2) const;
  double springEnergy() const;
  /// Sum of the structural springs' lengths now (m): a rope's length.
  double structuralLength() const;
  double structuralRestLength() const;
  /// Lowest particle surface: min over particles of y - radius (m).
  double lowestPoint() const;
  const DeformableStats& stats() const { return m_stats; }

  /// The state a later step reads, as exact bits (deformable_state.cpp):
  /// particles, velocities, pins, wind, material, counters and the last
  /// solve's result (the next one starts from it). restoreState refuses a
  /// deformable of another kind or size, and pins on body slots at or past
  /// bodySlots (the World's).
  void saveState(ByteWriter& w) const;
  Status restoreState(ByteReader& r, std::size_t bodySlots);

  /// Structural springs as lines (cloth: the grid; rope: the chain).
  void debugDraw(DebugDraw& draw, const Vec3& color) const;
  template <typename F>
  void forEachStructuralSegment(F&& f) const {
    for (int s = 0; s < m_structuralCount; ++s) f(position(m_springs[s].i), position(m_springs[s].j));
  }

 private:
  struct Spring {
    int i = 0, j = 0;
    double rest_m = 0, k_Npm = 0, c_Nspm = 0;
  };
  struct Pin {
    int particle = -1;
    BodyId body;                                        ///< null: fixed point
    Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< world point, or body-local offset
  };

  friend class DeformableSystem;  ///< restoreState works on a copy
  Deformable() = default;
  void addSpring(int i, int j, double k, double c);
  void substep(double h, const DeformableEnvironment& env);
  Eigen::Vector3d pinTarget(const Pin& p, const DeformableEnvironment& env) const;
  void collide(const DeformableEnvironment& env);

  Kind m_kind = Kind::Rope;
  int m_columns = 0, m_rows = 0;
  double m_mass = 0;  ///< per particle, kg
  DeformableMaterial m_material;
  Eigen::VectorXd m_x, m_v;  ///< 3 per particle, m and m/s
  std::vector<Spring> m_springs;  ///< structural first
  int m_structuralCount = 0;
  std::vector<Pin> m_pins;
  std::vector<int> m_pinOf;  ///< per particle: index into m_pins, -1 none
  Eigen::Vector3d m_wind = Eigen::Vector3d::Zero();
  DeformableStats m_stats;
  struct Solver;
  std::shared_ptr<Solver> m_solver;
  // The last solve's velocity change (the next solve's first guess), for
  // deformable_state.cpp, which does not see Solver; a fresh solver.
  const Eigen::VectorXd& lastSolve() const;
  void setLastSolve(Eigen::VectorXd dv);
  void useOwnSolver();  ///< sparse matrix, CG and scratch (deformable.cpp)
};

/// Every deformable of a scene; the app steps it after World::step.
class DeformableSystem {
 public:
  int add(std::unique_ptr<Deformable> d);  ///< returns its id (> 0)
  bool remove(int id);
  Deformable* get(int id);
  const Deformable* get(int id) const;
  int count() const;
  void step(Real dt_s, const DeformableEnvironment& env);
  template <typename F>
  void forEach(F&& f) const {
    for (const auto& [id, d] : m_items)
      if (d) f(id, *d);
  }
  /// Every deformable's state (Deformable::saveState) for snapshots of a
  /// running scene. Shapes are not stored: restoreState goes back into a
  /// system with the same ropes and cloth (made by the same scenario) and
  /// refuses, naming the first that differs, when it does not.
  std::string saveState() const;
  Status restoreState(const std::string& bytes, std::size_t bodySlots);

 private:
  std::vector<std::pair<int, std::unique_ptr<Deformable>>> m_items;
  int m_nextId = 1;
};

}  // namespace tumble::physics
