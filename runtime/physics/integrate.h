#pragma once
// How the world advances bodies between contact solves: the integrator
// strategies (`--integrator NAME`, scenario field `integrator = "..."`) and
// applied springs, the state-dependent forces that make the choice matter.
//
// Sections
//   BodyIntegrator, bodyIntegrators(), parseBodyIntegrator()   the catalogue
//   SpringDef, SpringId, SpringState                            applied springs
//   springForce()                                               one spring's force and Jacobian
//   BodyIntegration                                             what World calls every substep
//
// The methods are numerics' methods (numerics/integrator.h), applied to the
// translational state of the bodies: the same code steps generic ODE systems
// and the world. integrate.cpp explains how each combines with contacts.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"

namespace tumble {
class ByteWriter;
class ByteReader;
}  // namespace tumble

namespace tumble::physics {

enum class BodyIntegrator {
  SymplecticEuler,  ///< default: v += h a; x += h v (the fast path, no ODE machinery)
  Euler,            ///< explicit Euler: x += h v_old (gains energy; for comparison)
  Heun,             ///< explicit trapezoid, order 2
  Rk4,              ///< classical Runge-Kutta, order 4
  Verlet,           ///< velocity Verlet, order 2, symplectic
  ImplicitEuler,    ///< backward Euler (Newton): stiff springs, damps them
  ImplicitMidpoint, ///< A-stable, symplectic; stiff modes ring
  Sdirk2,           ///< 2-stage L-stable SDIRK: the recommended stiff method
};

struct BodyIntegratorInfo {
  BodyIntegrator method;
  const char* name;  ///< canonical name (command line, scenario field, run report)
  const char* use;   ///< one line: when to choose it
};

/// Every method the world offers, the default first.
std::span<const BodyIntegratorInfo> bodyIntegrators();
const char* bodyIntegratorName(BodyIntegrator method);
/// Canonical names and numerics' aliases ("trapezoid", "leapfrog", "stiff",
/// "backward_euler"). The error names the bad value and lists the valid ones.
Result<BodyIntegrator> parseBodyIntegrator(std::string_view name);

struct SpringTag;
using SpringId = Handle<SpringTag>;

/// A linear spring-damper from the centre of mass of body `a` to the centre
/// of mass of body `b`, or to the fixed point `anchor_m` when b is null.
/// Springs act at centres of mass (no torque), so their stiffness enters
/// only the translational state the integrators advance.
struct SpringDef {
  BodyId a;
  BodyId b;                            ///< null: the spring holds a to anchor_m
  Vec3 anchor_m = Vec3::Zero();        ///< world point, used when b is null
  Real stiffness_Npm = 100;            ///< k > 0 (N/m)
  Real damping_Nspm = 0;               ///< c >= 0 along the spring (N s/m)
  Real restLength_m = 0;               ///< >= 0; < 0 at creation: the current distance
};

/// Checks a SpringDef from user data; the message names the field.
Status validateSpringDef(const SpringDef& def);

/// Force on the first end of a spring from x_a to x_b (N), and its Jacobians
/// for the implicit methods: dF/dx_a = -K, dF/dx_b = K, dF/dv_a = -D,
/// dF/dv_b = D. K uses max(0, 1 - L0/L) for the transverse part so it stays
/// positive semi-definite under compression (Baraff & Witkin 1998, Choi & Ko
/// 2002): the solve stays well posed; the exact force is still used.
struct SpringEval {
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();  ///< N/m
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();  ///< N s/m
  double energy_J = 0;                          ///< k (L - L0)^2 / 2
};
SpringEval springForce(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, const Eigen::Vector3d& va,
                       const Eigen::Vector3d& vb, double k_Npm, double c_Nspm, double restLength_m,
                       bool wantJacobian);

class World;
struct BodyIntegrationScratch;

/// The strategy plus the springs. World owns one and calls advance() and
/// displacement() every substep when engaged(); otherwise its own
/// symplectic-Euler loop runs as before (the default path costs nothing).
class BodyIntegration {
 public:
  BodyIntegration();
  ~BodyIntegration();

  /// Springs. remove returns false for a stale handle. Springs whose body
  /// was destroyed are dropped at the next step.
  SpringId addSpring(const SpringDef& def);
  bool removeSpring(SpringId id);
  bool isValid(SpringId id) const;
  const SpringDef& spring(SpringId id) const;
  int springCount() const { return m_springCount; }
  template <typename F>
  void forEachSpring(F&& f) const {
    for (std::uint32_t i = 0; i < m_springs.size(); ++i)
      if (m_springs[i].alive) f(SpringId{i, m_springs[i].generation}, m_springs[i].def);
  }

  /// True when the world must route translation through advance(): a method
  /// other than symplectic Euler, or at least one spring.
  bool engaged(BodyIntegrator method) const { return method != BodyIntegrator::SymplecticEuler || m_springCount > 0; }

  /// One substep of free motion for every awake dynamic body: from the
  /// current positions and `linear` velocities (m/s, per body slot) under
  /// gravity g, the bodies' accumulated forces and the springs. Writes the
  /// free end velocities into `linear` and remembers each body's free
  /// displacement. Returns the impulse (N s) springs to fixed anchors and
  /// to non-moving bodies applied (external, for momentum bookkeeping).
  Eigen::Vector3d advance(BodyIntegrator method, const World& world, std::span<const Body> bodies,
                          const Vec3& g_mps2, Real h_s, std::span<Vec3> linear);
  /// Where body `index` moves this substep (m): its free displacement plus
  /// h times what contacts changed its velocity by (v_now - v_free).
  /// Bodies advance() did not move (kinematic) get h * v_now.
  Vec3 displacement(std::uint32_t index, const Vec3& vNow_mps, Real h_s) const;

  /// Potential energy stored in the springs (J), for World::totalEnergy.
  double springEnergy(const World& world) const;
  /// Newton iterations that did not converge (implicit methods), summed.
  long newtonFailures() const { return m_newtonFailures; }
  /// The springs as exact bits, for World::saveState / restoreState
  /// (world_state.cpp); restoreSprings refuses damaged bytes or springs on
  /// body slots the world does not have (slotCount).
  void saveSprings(ByteWriter& w) const;
  Status restoreSprings(ByteReader& r, std::uint32_t slotCount);

 private:
  struct Slot {
    SpringDef def;
    std::uint32_t generation = 0;
    bool alive = false;
  };
  std::vector<Slot> m_springs;
  std::vector<std::uint32_t> m_free;
  int m_springCount = 0;
  long m_newtonFailures = 0;
  std::unique_ptr<BodyIntegrationScratch> m_scratch;
};

}  // namespace tumble::physics
