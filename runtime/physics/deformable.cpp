// Mass-spring deformables (see deformable.h).
//
// The step (Baraff & Witkin 1998, "Large steps in cloth simulation", sec. 3):
// backward Euler for M x'' = f(x, v), linearised once per step:
//
//   M dv = h f(x0 + h (v0 + dv), v0 + dv)
//        ~ h [ f0 + (df/dx) h (v0 + dv) + (df/dv) dv ]
//
// With df/dx = -K and df/dv = -C (K, C assembled from every spring's 3x3
// blocks, physics/integrate.h springForce) this is
//
//   (M + h C + h^2 K) dv = h (f0 - h K v0),    then  v1 = v0 + dv, x1 = x0 + h v1.
//
// K is kept positive semi-definite (the transverse term is clamped at 0 when
// a spring is compressed), C is too, so A = M + h C + h^2 K is symmetric
// positive definite and conjugate gradients apply (Eigen::ConjugateGradient,
// Jacobi preconditioner, warm started from the previous dv, relative
// residual 1e-4). CG iterations grow with h^2 k / m: a free 12 x 12 cloth
// at the default k = 2e4 N/m needs up to 145 per solve (189 at 1e-5), a
// 24 x 24 one 259 (tools/bench/bench_numerics.cpp, BM_ClothStep). Eigen's
// IncompleteCholesky preconditioner cut a 16 x 16 cloth's 79 iterations to
// 25, but refactorising every substep made the whole step 6x slower, so it
// was rejected. Being one
// Newton iteration of backward Euler, the step inherits its L-stability: a
// spring with k/m = 1e6 at h = 1/120 (omega h = 8) is damped, not exploded.
// The price is numerical damping of the slow, visible motion (a swinging
// rope loses amplitude); the substep count trades it against cost.
//
// Pins are hard constraints in the solve: a pinned particle's dv is set so
// it ends the substep at its target; its row and column leave the system
// (the known dv moves to the right-hand side), which keeps A symmetric.
// Rejected: stiff penalty springs to the pin (adds stiffness for no reason)
// and Baraff-Witkin's filtered PCG (needed for sliding constraints, which
// we do not have).
//
// Bending: springs across two segments. Their default stiffness is a
// thousandth of the structural one: a cloth particle weighs m g ~ 0.04 N,
// so a bend spring of k / 20 (100 N/m at k = 2000) held a sheet of 16 x 8
// particles arched 11 cm over a box instead of lying on it (measured: 5 cm
// at k / 1000, what remains is the coarse grid, see the deformable tests).
//
// Forces: gravity, springs (stretch and damping along the spring), air drag
// per particle c (wind - v) (its -c I enters C, so it is implicit too) and,
// for cloth, pressure drag per triangle F = 1/2 rho C_d A (n.u)|n.u| n with
// u = wind - (mean velocity), shared by the three corners, explicit (it is
// soft: a flag in 10 m/s wind is far from stiff).
//
// Collisions after each substep: a particle (a sphere of the material's
// radius) inside the ground, a static / kinematic shape (hulls: the face
// plane it is farthest in front of; compounds: the deepest child) or below
// the height field is moved out along the contact normal; its approaching normal
// velocity is removed (no bounce) and its sliding velocity reduced by mu
// times the normal velocity removed (Coulomb, at most to rest).
#include "physics/deformable.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/integrate.h"
#include "physics/internal/convex_collision.h"
#include "physics/internal/mesh_collision.h"
#include "physics/world.h"

namespace tumble::physics {

struct Deformable::Solver {
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd b, dv, f;
  std::vector<Eigen::Vector3d> pinDv;  ///< per pin: the dv that puts it on target
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;  // Jacobi preconditioner
};

namespace {

constexpr int kCgMaxIterations = 400;
constexpr double kCgTolerance = 1e-4;  ///< relative residual (see the measurements at the top)

Status validateMaterial(const DeformableMaterial& m, const char* what) {
  auto bad = [&](const std::string& field, const std::string& expect) {
    return makeError(std::string(what) + " field '" + field + "' must be " + expect);
  };
  if (!std::isfinite(m.stiffness_Npm) || m.stiffness_Npm <= 0) return bad("stiffness", "a finite number > 0 (N/m)");
  if (!std::isfinite(m.shearStiffness_Npm)) return bad("shear", "a finite number (N/m; < 0: stiffness / 4)");
  if (!std::isfinite(m.bendStiffness_Npm)) return bad("bend", "a finite number (N/m; < 0: stiffness / 1000)");
  if (!std::isfinite(m.damping_Nspm) || m.damping_Nspm < 0) return bad("damping", "a finite number >= 0 (N s/m)");
  if (!std::isfinite(m.airDrag_Nspm) || m.airDrag_Nspm < 0) return bad("air_drag", "a finite number >= 0 (N s/m)");
  if (!std::isfinite(m.dragCoefficient) || m.dragCoefficient < 0) return bad("drag", "a finite number >= 0");
  if (!std::isfinite(m.airDensity_kgpm3) || m.airDensity_kgpm3 < 0) return bad("air_density", "a finite number >= 0 (kg/m^3)");
  if (!std::isfinite(m.friction) || m.friction < 0) return bad("friction", "a finite number >= 0");
  if (!std::isfinite(m.radius_m) || m.radius_m <= 0) return bad("radius", "a finite number > 0 (m)");
  if (m.substeps < 1 || m.substeps > 64) return bad("substeps", "an integer in 1..64");
  return Ok{};
}

Eigen::Vector3d d3(const Vec3& v) { return v.cast<double>(); }

/// Pushes a particle out of one shape posed at (p, q): normal and depth (> 0) when inside.
bool shapeContact(const Shape& shape, const Eigen::Vector3d& p, const Eigen::Quaterniond& q, const Eigen::Vector3d& x,
                  double r, Eigen::Vector3d* n, double* depth) {
  switch (shape.type) {
    case ShapeType::Mesh: {
      Vec3 normal;
      Real d;
      if (!sphereMeshContact(x.cast<Real>(), Real(r), p.cast<Real>(), q.cast<Real>(), *shape.mesh, &normal, &d))
        return false;
      *n = d3(normal);
      *depth = double(d);
      return true;
    }
    case ShapeType::Hull: {
      // The face plane the particle is farthest in front of: the separating
      // distance (exact over a face, a little short of the true distance
      // near edges and corners, so contact comes early there, never late).
      const Eigen::Vector3d local = q.conjugate() * (x - p);
      double best = -1e300;
      Eigen::Vector3d bestNormal = Eigen::Vector3d::UnitY();
      for (const HullFace& f : shape.hull->faces) {
        const Eigen::Vector3d fn = f.normal.cast<double>();
        const double dist = fn.dot(local) - double(f.offset_m);
        if (dist > best) best = dist, bestNormal = fn;
      }
      if (best >= r) return false;
      *n = q * bestNormal;
      *depth = r - best;
      return true;
    }
    case ShapeType::Compound: {
      // The deepest child.
      bool any = false;
      for (const CompoundChild& c : shape.compound->children) {
        Eigen::Vector3d cn;
        double cd;
        if (!shapeContact(c.shape, p + q * d3(c.position_m), q * c.orientation.cast<double>(), x, r, &cn, &cd)) continue;
        if (!any || cd > *depth) *n = cn, *depth = cd;
        any = true;
      }
      return any;
    }
    case ShapeType::Plane: {
      *n = q * Eigen::Vector3d::UnitY();
      *depth = r - n->dot(x - p);
      return *depth > 0;
    }
    case ShapeType::Sphere: {
      const Eigen::Vector3d d = x - p;
      const double len = d.norm(), R = shape.radius_m + r;
      if (len >= R) return false;
      *n = len > 1e-12 ? Eigen::Vector3d(d / len) : Eigen::Vector3d::UnitY();
      *depth = R - len;
      return true;
    }
    case ShapeType::Cylinder: {
      Vec3 closest, out;
      const Real dist = pointCylinderDistance(x.cast<Real>(), Pose{p.cast<Real>(), q.cast<Real>().toRotationMatrix()},
                                              shape.radius_m, shape.halfHeight_m, closest, out);
      if (dist >= r) return false;
      *n = d3(out);
      *depth = r - double(dist);
      return true;
    }
    case ShapeType::Capsule: {
      const Eigen::Vector3d axis = q * Eigen::Vector3d::UnitY();
      const double t = std::clamp(axis.dot(x - p), -double(shape.halfHeight_m), double(shape.halfHeight_m));
      const Eigen::Vector3d d = x - (p + t * axis);
      const double len = d.norm(), R = shape.radius_m + r;
      if (len >= R) return false;
      *n = len > 1e-12 ? Eigen::Vector3d(d / len) : Eigen::Vector3d::UnitY();
      *depth = R - len;
      return true;
    }
    case ShapeType::Box: {
      const Eigen::Vector3d e = shape.halfExtents_m.cast<double>();
      const Eigen::Vector3d local = q.conjugate() * (x - p);
      const Eigen::Vector3d clamped = local.cwiseMax(-e).cwiseMin(e);
      const Eigen::Vector3d d = local - clamped;
      const double len = d.norm();
      if (len > 1e-12) {
        if (len >= r) return false;
        *n = q * Eigen::Vector3d(d / len);
        *depth = r - len;
        return true;
      }
      // Centre inside: leave through the nearest face.
      int axis = 0;
      double best = 1e300;
      for (int k = 0; k < 3; ++k) {
        const double gap = e[k] - std::abs(local[k]);
        if (gap < best) best = gap, axis = k;
      }
      Eigen::Vector3d ln = Eigen::Vector3d::Zero();
      ln[axis] = local[axis] >= 0 ? 1 : -1;
      *n = q * ln;
      *depth = best + r;
      return true;
    }
  }
  return false;
}

}  // namespace

Result<std::unique_ptr<Deformable>> Deformable::rope(const RopeDef& def) {
  if (auto s = validateMaterial(def.material, "rope"); !s) return makeError(s.error());
  if (def.segments < 1 || def.segments > 4096) return makeError("rope field 'segments' must be an integer in 1..4096");
  if (!def.start_m.allFinite() || !def.end_m.allFinite()) return makeError("rope fields 'from' and 'to' must be finite points (m)");
  if ((def.end_m - def.start_m).norm() < 1e-6) return makeError("rope fields 'from' and 'to' must be different points");
  if (!std::isfinite(def.mass_kg) || def.mass_kg <= 0) return makeError("rope field 'mass' must be a finite number > 0 (kg)");
  std::unique_ptr<Deformable> d(new Deformable());
  d->m_kind = Kind::Rope;
  d->m_material = def.material;
  const int n = def.segments + 1;
  d->m_columns = n;
  d->m_rows = 1;
  d->m_mass = def.mass_kg / n;
  d->m_x.resize(3 * n);
  d->m_v.setZero(3 * n);
  for (int i = 0; i < n; ++i)
    d->m_x.segment<3>(3 * i) = d3(def.start_m + (def.end_m - def.start_m) * (Real(i) / Real(def.segments)));
  const DeformableMaterial& m = def.material;
  for (int i = 0; i + 1 < n; ++i) d->addSpring(i, i + 1, m.stiffness_Npm, m.damping_Nspm);
  d->m_structuralCount = int(d->m_springs.size());
  const double bend = m.bendStiffness_Npm < 0 ? m.stiffness_Npm / 1000 : m.bendStiffness_Npm;
  if (bend > 0)
    for (int i = 0; i + 2 < n; ++i) d->addSpring(i, i + 2, bend, m.damping_Nspm);
  d->m_pinOf.assign(std::size_t(n), -1);
  d->m_solver = std::make_shared<Solver>();
  if (def.pinStart) d->pinToPoint(0, def.start_m);
  if (def.pinEnd) d->pinToPoint(n - 1, def.end_m);
  return d;
}

Result<std::unique_ptr<Deformable>> Deformable::cloth(const ClothDef& def) {
  if (auto s = validateMaterial(def.material, "cloth"); !s) return makeError(s.error());
  if (def.columns < 2 || def.columns > 256 || def.rows < 2 || def.rows > 256)
    return makeError("cloth fields 'columns' and 'rows' must be integers in 2..256 (particles per side)");
  if (!def.origin_m.allFinite() || !def.edgeU_m.allFinite() || !def.edgeV_m.allFinite())
    return makeError("cloth fields 'origin', 'u' and 'v' must be finite vectors (m)");
  if (def.edgeU_m.cross(def.edgeV_m).norm() < 1e-8)
    return makeError("cloth fields 'u' and 'v' must span an area (non-zero, not parallel)");
  if (!std::isfinite(def.mass_kg) || def.mass_kg <= 0) return makeError("cloth field 'mass' must be a finite number > 0 (kg)");
  std::unique_ptr<Deformable> d(new Deformable());
  d->m_kind = Kind::Cloth;
  d->m_material = def.material;
  const int C = def.columns, R = def.rows, n = C * R;
  d->m_columns = C;
  d->m_rows = R;
  d->m_mass = def.mass_kg / n;
  d->m_x.resize(3 * n);
  d->m_v.setZero(3 * n);
  auto id = [C](int c, int r) { return r * C + c; };
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c)
      d->m_x.segment<3>(3 * id(c, r)) =
          d3(def.origin_m + def.edgeU_m * (Real(c) / Real(C - 1)) + def.edgeV_m * (Real(r) / Real(R - 1)));
  const DeformableMaterial& m = def.material;
  const double k = m.stiffness_Npm, c0 = m.damping_Nspm;
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c) {
      if (c + 1 < C) d->addSpring(id(c, r), id(c + 1, r), k, c0);
      if (r + 1 < R) d->addSpring(id(c, r), id(c, r + 1), k, c0);
    }
  d->m_structuralCount = int(d->m_springs.size());
  const double shear = m.shearStiffness_Npm < 0 ? k / 4 : m.shearStiffness_Npm;
  const double bend = m.bendStiffness_Npm < 0 ? k / 1000 : m.bendStiffness_Npm;
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c) {
      if (shear > 0 && c + 1 < C && r + 1 < R) {
        d->addSpring(id(c, r), id(c + 1, r + 1), shear, c0);
        d->addSpring(id(c + 1, r), id(c, r + 1), shear, c0);
      }
      if (bend > 0 && c + 2 < C) d->addSpring(id(c, r), id(c + 2, r), bend, c0);
      if (bend > 0 && r + 2 < R) d->addSpring(id(c, r), id(c, r + 2), bend, c0);
    }
  d->m_pinOf.assign(std::size_t(n), -1);
  d->m_solver = std::make_shared<Solver>();
  if (def.pins == ClothPins::TopCorners) {
    d->pinToPoint(0, def.origin_m);
    d->pinToPoint(C - 1, def.origin_m + def.edgeU_m);
  } else if (def.pins == ClothPins::TopEdge) {
    for (int c = 0; c < C; ++c) d->pinToPoint(c, d->position(c));
  }
  return d;
}

void Deformable::addSpring(int i, int j, double k, double c) {
  Spring s;
  s.i = i, s.j = j, s.k_Npm = k, s.c_Nspm = c;
  s.rest_m = (m_x.segment<3>(3 * j) - m_x.segment<3>(3 * i)).norm();
  m_springs.push_back(s);
}

bool Deformable::pinToPoint(int i, const Vec3& point) {
  if (i < 0 || i >= particleCount() || !point.allFinite()) return false;
  unpin(i);
  m_pinOf[std::size_t(i)] = int(m_pins.size());
  m_pins.push_back(Pin{i, BodyId{}, d3(point)});
  return true;
}

bool Deformable::pinToBody(int i, const World& world, BodyId body) {
  if (i < 0 || i >= particleCount() || !world.isValid(body)) return false;
  unpin(i);
  const Body& b = world.body(body);
  const Eigen::Vector3d local =
      b.orientation.cast<double>().conjugate() * (m_x.segment<3>(3 * i) - d3(b.position_m));
  m_pinOf[std::size_t(i)] = int(m_pins.size());
  m_pins.push_back(Pin{i, body, local});
  return true;
}

bool Deformable::unpin(int i) {
  if (i < 0 || i >= particleCount() || m_pinOf[std::size_t(i)] < 0) return false;
  m_pins.erase(m_pins.begin() + m_pinOf[std::size_t(i)]);
  std::fill(m_pinOf.begin(), m_pinOf.end(), -1);
  for (std::size_t p = 0; p < m_pins.size(); ++p) m_pinOf[std::size_t(m_pins[p].particle)] = int(p);
  return true;
}

bool Deformable::setVelocity(int i, const Vec3& v_mps) {
  if (i < 0 || i >= particleCount()) return false;
  m_v.segment<3>(3 * i) = v_mps.cast<double>();
  return true;
}

bool Deformable::pinned(int i) const { return i >= 0 && i < particleCount() && m_pinOf[std::size_t(i)] >= 0; }

Eigen::Vector3d Deformable::pinTarget(const Pin& p, const DeformableEnvironment& env) const {
  if (p.body.isNull()) return p.point;
  if (!env.world || !env.world->isValid(p.body)) return m_x.segment<3>(3 * p.particle);  // body gone: held where it is
  const Body& b = env.world->body(p.body);
  return d3(b.position_m) + b.orientation.cast<double>() * p.point;
}

void Deformable::step(Real dt, const DeformableEnvironment& env) {
  if (!(dt > 0) || !std::isfinite(dt)) return;
  const int n = std::max(1, m_material.substeps);
  for (int s = 0; s < n; ++s) substep(double(dt) / n, env);
}

void Deformable::substep(double h, const DeformableEnvironment& env) {
  Solver& S = *m_solver;
  const int np = particleCount(), dim = 3 * np;
  const Eigen::Vector3d g = d3(env.gravity_mps2);
  const double m = m_mass, air = m_material.airDrag_Nspm;
  const Eigen::VectorXd x0 = m_x, v0 = m_v;

  // Pins: the dv that ends each pinned particle on its target.
  S.pinDv.resize(m_pins.size());
  for (std::size_t p = 0; p < m_pins.size(); ++p) {
    const int i = m_pins[p].particle;
    S.pinDv[p] = (pinTarget(m_pins[p], env) - m_x.segment<3>(3 * i)) / h - m_v.segment<3>(3 * i);
  }
  auto pinOf = [&](int i) { return m_pinOf[std::size_t(i)]; };

  S.f.resize(dim);
  S.b.resize(dim);
  S.triplets.clear();
  S.triplets.reserve(std::size_t(9) * (np + 4 * m_springs.size()));
  // Particle terms: mass, air drag (implicit), gravity.
  for (int i = 0; i < np; ++i) {
    S.f.segment<3>(3 * i) = m * g + air * (m_wind - m_v.segment<3>(3 * i));
    const double diag = pinOf(i) >= 0 ? 1.0 : m + h * air;
    for (int k = 0; k < 3; ++k) S.triplets.emplace_back(3 * i + k, 3 * i + k, diag);
  }
  // Cloth: pressure drag per triangle (explicit).
  if (m_kind == Kind::Cloth && m_material.dragCoefficient > 0 && m_material.airDensity_kgpm3 > 0) {
    const double q = 0.5 * m_material.airDensity_kgpm3 * m_material.dragCoefficient;
    auto tri = [&](int a, int b, int c) {
      const Eigen::Vector3d xa = m_x.segment<3>(3 * a), xb = m_x.segment<3>(3 * b), xc = m_x.segment<3>(3 * c);
      const Eigen::Vector3d cr = (xb - xa).cross(xc - xa);
      const double twiceArea = cr.norm();
      if (twiceArea < 1e-12) return;
      const Eigen::Vector3d nrm = cr / twiceArea;
      const Eigen::Vector3d u =
          m_wind - (m_v.segment<3>(3 * a) + m_v.segment<3>(3 * b) + m_v.segment<3>(3 * c)) / 3;
      const double un = nrm.dot(u);
      const Eigen::Vector3d F = q * (0.5 * twiceArea) * un * std::abs(un) * nrm;
      for (int p : {a, b, c}) S.f.segment<3>(3 * p) += F / 3;
    };
    for (int r = 0; r + 1 < m_rows; ++r)
      for (int c = 0; c + 1 < m_columns; ++c) {
        const int i00 = r * m_columns + c, i10 = i00 + 1, i01 = i00 + m_columns, i11 = i01 + 1;
        tri(i00, i01, i10);
        tri(i10, i01, i11);
      }
  }
  // Springs: forces, and the blocks of A = M + h C + h^2 K.
  S.b.setZero();
  for (const Spring& s : m_springs) {
    const SpringEval e = springForce(m_x.segment<3>(3 * s.i), m_x.segment<3>(3 * s.j), m_v.segment<3>(3 * s.i),
                                     m_v.segment<3>(3 * s.j), s.k_Npm, s.c_Nspm, s.rest_m, true);
    S.f.segment<3>(3 * s.i) += e.force_N;
    S.f.segment<3>(3 * s.j) -= e.force_N;
    const Eigen::Matrix3d blk = h * e.D + h * h * e.K;
    // -h^2 K v0 on the right: K (v_i - v_j) on i and its negative on j.
    const Eigen::Vector3d kv = h * h * (e.K * (m_v.segment<3>(3 * s.i) - m_v.segment<3>(3 * s.j)));
    S.b.segment<3>(3 * s.i) -= kv;
    S.b.segment<3>(3 * s.j) += kv;
    const int ends[2] = {s.i, s.j};
    for (int r = 0; r < 2; ++r) {
      if (pinOf(ends[r]) >= 0) continue;  // pinned rows are identity
      for (int c = 0; c < 2; ++c) {
        const Eigen::Matrix3d M3 = r == c ? blk : Eigen::Matrix3d(-blk);
        if (pinOf(ends[c]) >= 0) {
          // Known dv of a pin moves to the right-hand side.
          S.b.segment<3>(3 * ends[r]) -= M3 * S.pinDv[std::size_t(pinOf(ends[c]))];
          continue;
        }
        for (int a = 0; a < 3; ++a)
          for (int bb = 0; bb < 3; ++bb)
            if (M3(a, bb) != 0) S.triplets.emplace_back(3 * ends[r] + a, 3 * ends[c] + bb, M3(a, bb));
      }
    }
  }
  S.b += h * S.f;
  for (std::size_t p = 0; p < m_pins.size(); ++p) S.b.segment<3>(3 * m_pins[p].particle) = S.pinDv[p];

  S.A.resize(dim, dim);
  S.A.setFromTriplets(S.triplets.begin(), S.triplets.end());
  if (S.dv.size() != dim) S.dv.setZero(dim);
  S.cg.setMaxIterations(kCgMaxIterations);
  S.cg.setTolerance(kCgTolerance);
  S.cg.compute(S.A);
  S.dv = S.cg.solveWithGuess(S.b, S.dv);
  m_stats.cgIterationsMax = std::max(m_stats.cgIterationsMax, int(S.cg.iterations()));
  if (S.cg.info() != Eigen::Success) ++m_stats.cgFailures;
  ++m_stats.steps;

  m_v += S.dv;
  m_x += h * m_v;
  collide(env);
  if (!m_x.allFinite() || !m_v.allFinite()) {
    // Never let a fault through: back to the state before, at rest.
    m_x = x0;
    m_v.setZero();
    S.dv.setZero();
    ++m_stats.nanEvents;
  }
}

void Deformable::collide(const DeformableEnvironment& env) {
  const double r = m_material.radius_m, mu = m_material.friction;
  const int np = particleCount();
  auto respond = [&](int i, const Eigen::Vector3d& n, double depth) {
    m_x.segment<3>(3 * i) += depth * n;
    Eigen::Vector3d v = m_v.segment<3>(3 * i);
    const double vn = v.dot(n);
    if (vn < 0) {
      v -= vn * n;
      Eigen::Vector3d vt = v - v.dot(n) * n;
      const double st = vt.norm();
      if (st > 0) v -= std::min(1.0, mu * -vn / st) * vt;
    }
    m_v.segment<3>(3 * i) = v;
  };
  for (int i = 0; i < np; ++i) {
    if (m_pinOf[std::size_t(i)] >= 0) continue;
    if (env.world) {
      env.world->forEachBody([&](BodyId, const Body& b) {
        if (b.type == BodyType::Dynamic) return;
        Eigen::Vector3d n;
        double depth;
        if (b.shape.type != ShapeType::Plane &&
            (m_x.segment<3>(3 * i) - d3(b.position_m)).norm() > b.shape.boundingRadius() + r)
          return;
        if (shapeContact(b.shape, d3(b.position_m), b.orientation.cast<double>(), m_x.segment<3>(3 * i), r, &n, &depth)) respond(i, n, depth);
      });
    }
    if (env.heightField) {
      Real hgt;
      Vec3 nrm;
      const Eigen::Vector3d x = m_x.segment<3>(3 * i);
      if (env.heightField->surfaceAt(Real(x.x()), Real(x.z()), &hgt, &nrm)) {
        const double gap = x.y() - r - hgt;  // vertical
        if (gap < 0) respond(i, d3(nrm), -gap * nrm.y());
      }
    }
  }
}

double Deformable::springEnergy() const {
  double e = 0;
  for (const Spring& s : m_springs) {
    const double stretch = (m_x.segment<3>(3 * s.j) - m_x.segment<3>(3 * s.i)).norm() - s.rest_m;
    e += 0.5 * s.k_Npm * stretch * stretch;
  }
  return e;
}

double Deformable::energy(const Vec3& gravity) const {
  double e = springEnergy();
  const Eigen::Vector3d g = d3(gravity);
  for (int i = 0; i < particleCount(); ++i)
    e += 0.5 * m_mass * m_v.segment<3>(3 * i).squaredNorm() - m_mass * g.dot(m_x.segment<3>(3 * i));
  return e;
}

double Deformable::structuralLength() const {
  double L = 0;
  for (int s = 0; s < m_structuralCount; ++s)
    L += (m_x.segment<3>(3 * m_springs[std::size_t(s)].j) - m_x.segment<3>(3 * m_springs[std::size_t(s)].i)).norm();
  return L;
}

double Deformable::structuralRestLength() const {
  double L = 0;
  for (int s = 0; s < m_structuralCount; ++s) L += m_springs[std::size_t(s)].rest_m;
  return L;
}

double Deformable::lowestPoint() const {
  double y = 1e300;
  for (int i = 0; i < particleCount(); ++i) y = std::min(y, m_x[3 * i + 1] - m_material.radius_m);
  return y;
}

void Deformable::debugDraw(DebugDraw& draw, const Vec3& color) const {
  forEachStructuralSegment([&](const Vec3& a, const Vec3& b) { draw.line(a, b, color); });
}

const Eigen::VectorXd& Deformable::lastSolve() const { return m_solver->dv; }
void Deformable::setLastSolve(Eigen::VectorXd dv) { m_solver->dv = std::move(dv); }
void Deformable::useOwnSolver() { m_solver = std::make_shared<Solver>(); }

int DeformableSystem::add(std::unique_ptr<Deformable> d) {
  const int id = m_nextId++;
  m_items.emplace_back(id, std::move(d));
  return id;
}

bool DeformableSystem::remove(int id) {
  for (auto& [i, d] : m_items)
    if (i == id && d) {
      d.reset();
      return true;
    }
  return false;
}

Deformable* DeformableSystem::get(int id) {
  for (auto& [i, d] : m_items)
    if (i == id) return d.get();
  return nullptr;
}

const Deformable* DeformableSystem::get(int id) const {
  for (const auto& [i, d] : m_items)
    if (i == id) return d.get();
  return nullptr;
}

int DeformableSystem::count() const {
  int c = 0;
  for (const auto& [i, d] : m_items) c += d != nullptr;
  return c;
}

void DeformableSystem::step(Real dt, const DeformableEnvironment& env) {
  for (auto& [i, d] : m_items)
    if (d) d->step(dt, env);
}

}  // namespace tumble::physics
