#include "physics/mass_properties.h"

#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>

namespace tumble::physics {
namespace {

// Eberly's subexpressions of the polynomial integrals over one triangle for
// one coordinate w (w0, w1, w2 at the three vertices).
struct Sub {
  double f1, f2, f3, g0, g1, g2;
};
Sub subexpressions(double w0, double w1, double w2) {
  Sub s;
  const double t0 = w0 + w1;
  s.f1 = t0 + w2;
  const double t1 = w0 * w0;
  const double t2 = t1 + w1 * t0;
  s.f2 = t2 + w2 * s.f1;
  s.f3 = w0 * t1 + w1 * t2 + w2 * s.f2;
  s.g0 = s.f2 + w0 * (s.f1 + w0);
  s.g1 = s.f2 + w1 * (s.f1 + w1);
  s.g2 = s.f2 + w2 * (s.f1 + w2);
  return s;
}

}  // namespace

static MassProperties finishMassProperties(MassProperties out, const double* in, const Eigen::Vector3d& origin,
                                           Real density);

MassProperties massPropertiesOfMesh(std::span<const Vec3> vertices, std::span<const std::array<std::uint32_t, 3>> triangles,
                                    Real density) {
  MassProperties out;
  // Integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the solid.
  double in[10] = {};
  // Shift to the first vertex: keeps the sums well conditioned for meshes far
  // from the origin (the result is shifted back at the end).
  const Eigen::Vector3d origin = vertices.empty() ? Eigen::Vector3d(Eigen::Vector3d::Zero()) : Eigen::Vector3d(vertices[0].cast<double>());
  for (const auto& t : triangles) {
    if (t[0] >= vertices.size() || t[1] >= vertices.size() || t[2] >= vertices.size()) {
      ++out.skippedTriangles;
      continue;
    }
    const Eigen::Vector3d p0 = vertices[t[0]].cast<double>() - origin;
    const Eigen::Vector3d p1 = vertices[t[1]].cast<double>() - origin;
    const Eigen::Vector3d p2 = vertices[t[2]].cast<double>() - origin;
    const Eigen::Vector3d d = (p1 - p0).cross(p2 - p0);
    const Sub x = subexpressions(p0.x(), p1.x(), p2.x());
    const Sub y = subexpressions(p0.y(), p1.y(), p2.y());
    const Sub z = subexpressions(p0.z(), p1.z(), p2.z());
    in[0] += d.x() * x.f1;
    in[1] += d.x() * x.f2;
    in[2] += d.y() * y.f2;
    in[3] += d.z() * z.f2;
    in[4] += d.x() * x.f3;
    in[5] += d.y() * y.f3;
    in[6] += d.z() * z.f3;
    in[7] += d.x() * (p0.y() * x.g0 + p1.y() * x.g1 + p2.y() * x.g2);
    in[8] += d.y() * (p0.z() * y.g0 + p1.z() * y.g1 + p2.z() * y.g2);
    in[9] += d.z() * (p0.x() * z.g0 + p1.x() * z.g1 + p2.x() * z.g2);
  }
  constexpr double kMult[10] = {1.0 / 6,  1.0 / 24, 1.0 / 24, 1.0 / 24,  1.0 / 60,
                                1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (int i = 0; i < 10; ++i) in[i] *= kMult[i];
  const double volume = in[0];
  out.volume_m3 = Real(volume);
  bool finite = std::isfinite(double(density)) && density > 0;
  for (const Vec3& v : vertices) finite = finite && v.allFinite();
  if (!finite || !(std::abs(volume) >= 1e-12)) return out;
  out.valid = out.skippedTriangles == 0;
  // Inside out (clockwise seen from outside): every integral changes sign;
  // turn them around so mass and inertia are the solid's.
  if (volume < 0)
    for (double& v : in) v = -v;
  return finishMassProperties(out, in, origin, density);
}

static MassProperties finishMassProperties(MassProperties out, const double* in, const Eigen::Vector3d& origin,
                                           Real density) {
  const double volume = in[0];
  const double rho = density;
  const double mass = rho * volume;
  const Eigen::Vector3d c(in[1] / volume, in[2] / volume, in[3] / volume);
  // Second moments about the centre of mass (per unit density).
  const double xx = in[4] - volume * c.x() * c.x();
  const double yy = in[5] - volume * c.y() * c.y();
  const double zz = in[6] - volume * c.z() * c.z();
  const double xy = in[7] - volume * c.x() * c.y();
  const double yz = in[8] - volume * c.y() * c.z();
  const double zx = in[9] - volume * c.z() * c.x();
  Eigen::Matrix3d I;
  I << yy + zz, -xy, -zx,  //
      -xy, xx + zz, -yz,   //
      -zx, -yz, xx + yy;
  out.mass_kg = Real(mass);
  out.centreOfMass_m = (c + origin).cast<Real>();
  out.inertia_kgm2 = (rho * I).cast<Real>();
  return out;
}

PrincipalFrame principalFrame(const Mat3& inertia) {
  PrincipalFrame f;
  const Eigen::Matrix3d I = inertia.cast<double>();
  const double scale = I.diagonal().cwiseAbs().maxCoeff();
  const Eigen::Matrix3d off = I - Eigen::Matrix3d(I.diagonal().asDiagonal());
  if (off.cwiseAbs().maxCoeff() <= 1e-7 * scale) {
    // Already diagonal: keep the given axes (a symmetric shape keeps its
    // frame instead of an arbitrary one inside its degenerate plane).
    f.moments_kgm2 = inertia.diagonal();
    return f;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(I);
  const Eigen::Matrix3d E = solver.eigenvectors();
  // Order and sign the axes so the rotation is as close to the identity as
  // possible: axis i takes the eigenvector with the largest i-component.
  Eigen::Matrix3d R;
  Eigen::Vector3d moments;
  bool used[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    int best = -1;
    for (int c = 0; c < 3; ++c)
      if (!used[c] && (best < 0 || std::abs(E(i, c)) > std::abs(E(i, best)))) best = c;
    used[best] = true;
    R.col(i) = E(i, best) < 0 ? Eigen::Vector3d(-E.col(best)) : Eigen::Vector3d(E.col(best));
    moments[i] = solver.eigenvalues()[best];
  }
  if (R.determinant() < 0) {  // right-handed, so it is a rotation: flip the least aligned axis
    int worst = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(R(i, i)) < std::abs(R(worst, worst))) worst = i;
    R.col(worst) = -R.col(worst);
  }
  f.moments_kgm2 = moments.cast<Real>();
  f.rotation = Quat(R.cast<Real>()).normalized();
  return f;
}

Mat3 shiftedInertia(const Vec3& moments, const Quat& q, Real mass, const Vec3& d) {
  const Mat3 R = q.toRotationMatrix();
  return R * moments.asDiagonal() * R.transpose() + mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

bool isClosedMesh(std::span<const Vec3> vertices_m, std::span<const std::array<std::uint32_t, 3>> triangles) {
  if (triangles.empty()) return false;
  // Weld vertices at identical positions.
  std::map<std::tuple<Real, Real, Real>, std::uint32_t> ids;
  std::vector<std::uint32_t> weld(vertices_m.size());
  for (std::size_t i = 0; i < vertices_m.size(); ++i) {
    const Vec3& p = vertices_m[i];
    weld[i] = ids.emplace(std::make_tuple(p.x(), p.y(), p.z()), std::uint32_t(ids.size())).first->second;
  }
  // Each directed edge once, and its reverse exactly as often.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] >= vertices_m.size() || t[(k + 1) % 3] >= vertices_m.size()) return false;
      const std::uint32_t a = weld[t[k]], b = weld[t[(k + 1) % 3]];
      if (a == b) return false;  // degenerate triangle
      if (++edges[{a, b}] > 1) return false;
    }
  }
  for (const auto& [edge, count] : edges)
    if (edges.find({edge.second, edge.first}) == edges.end()) return false;
  return true;
}

}  // namespace tumble::physics
