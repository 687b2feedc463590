#include "physics/mass_properties.h"

#include <cmath>
#include <map>
#include <tuple>
#include <vector>

namespace tumble::physics {

namespace {

// Eberly's subexpressions for one coordinate w of a triangle's corners.
struct Sub {
  double f1, f2, f3, g0, g1, g2;
};
Sub subexpressions(double w0, double w1, double w2) {
  Sub s{};
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

MassProperties massPropertiesOfMesh(std::span<const Vec3> vertices_m,
                                    std::span<const std::array<std::uint32_t, 3>> triangles,
                                    Real density_kg_m3) {
  MassProperties out;
  if (!(density_kg_m3 > 0) || !std::isfinite(double(density_kg_m3))) return out;
  // Integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the volume.
  double in[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (const auto& t : triangles) {
    if (t[0] >= vertices_m.size() || t[1] >= vertices_m.size() || t[2] >= vertices_m.size()) return out;
    const Eigen::Vector3d p0 = vertices_m[t[0]].cast<double>();
    const Eigen::Vector3d p1 = vertices_m[t[1]].cast<double>();
    const Eigen::Vector3d p2 = vertices_m[t[2]].cast<double>();
    if (!p0.allFinite() || !p1.allFinite() || !p2.allFinite()) return out;
    // d = (p1 - p0) x (p2 - p0): twice the area times the outward normal.
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
  constexpr double kScale[10] = {1.0 / 6,  1.0 / 24, 1.0 / 24, 1.0 / 24,  1.0 / 60,
                                 1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (int i = 0; i < 10; ++i) in[i] *= kScale[i];
  // Wound inwards, every integral changes sign: turn the mesh around.
  if (in[0] < 0) {
    for (double& v : in) v = -v;
  }
  const double volume = in[0];
  if (!(volume >= 1e-12)) return out;
  const double rho = double(density_kg_m3);
  const double mass = rho * volume;
  const Eigen::Vector3d c(in[1] / volume, in[2] / volume, in[3] / volume);
  // Second moments about the origin, then shifted to the centre of mass
  // (parallel axis theorem).
  Eigen::Matrix3d inertia;
  inertia(0, 0) = rho * (in[5] + in[6]) - mass * (c.y() * c.y() + c.z() * c.z());
  inertia(1, 1) = rho * (in[4] + in[6]) - mass * (c.z() * c.z() + c.x() * c.x());
  inertia(2, 2) = rho * (in[4] + in[5]) - mass * (c.x() * c.x() + c.y() * c.y());
  inertia(0, 1) = inertia(1, 0) = -(rho * in[7] - mass * c.x() * c.y());
  inertia(1, 2) = inertia(2, 1) = -(rho * in[8] - mass * c.y() * c.z());
  inertia(0, 2) = inertia(2, 0) = -(rho * in[9] - mass * c.z() * c.x());
  out.mass_kg = Real(mass);
  out.volume_m3 = Real(volume);
  out.centerOfMass_m = c.cast<Real>();
  out.inertia_kgm2 = inertia.cast<Real>();
  out.valid = true;
  return out;
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
  for (const auto& [edge, count] : edges) {
    if (edges.find({edge.second, edge.first}) == edges.end()) return false;
  }
  return true;
}

}  // namespace tumble::physics
