// The generated model set (meshgen.h). Geometry is built from a few closed
// primitives (box, cylinder / cone frustum, torus, noisy icosphere); every triangle is given an outward hint and turned to
// face it, so each part is a closed outward-wound surface by construction.
// The hatchback, truck and buggy bodies are each one closed solid of prisms
// (PrismSolid), split into parts by material, so chassis.inertia = "mesh"
// can integrate over them.
// Textures are 64 x 64 procedural images (integer-hash value noise).
#include "tools/meshgen/meshgen.h"

#include <stb_image_write.h>  // libstb provides the implementation

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <tuple>

#include <CLI/CLI.hpp>

#include "core/file_util.h"
#include "core/log.h"
#include "core/math.h"

namespace tumble::tools {

namespace {

using V3 = Eigen::Vector3d;
using V2 = Eigen::Vector2d;
constexpr double kTau = 6.283185307179586;

struct Vertex {
  V3 p, n;
  V2 uv;
};
struct Part {
  std::string name, material;
  std::vector<Vertex> v;
  std::vector<std::array<int, 3>> t;

  int add(const V3& p, const V3& n, const V2& uv) {
    v.push_back({p, n.normalized(), uv});
    return int(v.size()) - 1;
  }
  // Adds a triangle wound so that its normal points along `outward`.
  void tri(int a, int b, int c, const V3& outward) {
    const V3 n = (v[b].p - v[a].p).cross(v[c].p - v[a].p);
    if (n.dot(outward) < 0) std::swap(b, c);
    t.push_back({a, b, c});
  }
  void quad(int a, int b, int c, int d, const V3& outward) {
    tri(a, b, c, outward);
    tri(a, c, d, outward);
  }
};

struct Material {
  std::string name;
  V3 kd;                // sRGB 0..1, as .mtl files store it
  std::string texture;  // file name, empty: colour only
  V3 ke = V3::Zero();   // sRGB 0..1, the light a lamp gives off itself (.mtl Ke)
};

struct ObjModel {
  std::string name;
  std::vector<Part> parts;
  bool oneSurface = false;  // the parts are materials of one closed surface, not closed each
};

// ---- primitives ------------------------------------------------------------

Part box(const std::string& name, const std::string& material, const V3& center, const V3& half,
         double uvPerMetre = 1.0) {
  Part part{name, material, {}, {}};
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      V3 n = V3::Zero();
      n[axis] = sign;
      int idx[4];
      int k = 0;
      for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        V3 p = center;
        p[axis] += sign * half[axis];
        p[u] += a * half[u];
        p[w] += b * half[w];
        const V2 uv((a + 1) * half[u] * uvPerMetre, (b + 1) * half[w] * uvPerMetre);
        idx[k++] = part.add(p, n, uv);
      }
      part.quad(idx[0], idx[1], idx[2], idx[3], n);
    }
  }
  return part;
}

// Basis (axis, u, w) for a cylinder along `axis` (a unit vector).
std::pair<V3, V3> perpendiculars(const V3& axis) {
  const V3 helper = std::abs(axis.y()) < 0.9 ? V3::UnitY() : V3::UnitX();
  const V3 u = axis.cross(helper).normalized();
  return {u, axis.cross(u)};
}

// A cone frustum (a cylinder when r0 == r1) from `base` along `axis` for
// `length`; flat caps. Caps get planar uvs in [0, 1] (capUv), the side wraps.
Part frustum(const std::string& name, const std::string& sideMaterial, const V3& base, const V3& axisDir,
             double length, double r0, double r1, int segments, double sideUvV = 1.0) {
  Part part{name, sideMaterial, {}, {}};
  const V3 axis = axisDir.normalized();
  const auto [u, w] = perpendiculars(axis);
  const V3 top = base + axis * length;
  const double slope = (r0 - r1) / length;  // normal tilt of the side
  std::vector<int> bottomRing, topRing;
  for (int i = 0; i <= segments; ++i) {
    const double a = kTau * i / segments;
    const V3 radial = std::cos(a) * u + std::sin(a) * w;
    const V3 n = radial + slope * axis;
    bottomRing.push_back(part.add(base + r0 * radial, n, V2(double(i) / segments, 0)));
    topRing.push_back(part.add(top + r1 * radial, n, V2(double(i) / segments, sideUvV)));
  }
  for (int i = 0; i < segments; ++i) {
    const double a = kTau * (i + 0.5) / segments;
    const V3 radial = std::cos(a) * u + std::sin(a) * w;
    part.quad(bottomRing[i], bottomRing[i + 1], topRing[i + 1], topRing[i], radial);
  }
  for (auto [centre, r, normal] : {std::tuple{base, r0, V3(-axis)}, std::tuple{top, r1, axis}}) {
    const int c = part.add(centre, normal, V2(0.5, 0.5));
    std::vector<int> ring;
    for (int i = 0; i < segments; ++i) {
      const double a = kTau * i / segments;
      const V3 radial = std::cos(a) * u + std::sin(a) * w;
      ring.push_back(part.add(centre + r * radial, normal, V2(0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a))));
    }
    for (int i = 0; i < segments; ++i) part.tri(c, ring[i], ring[(i + 1) % segments], normal);
  }
  return part;
}

// Splits a part's triangles by a predicate into a second material (same
// vertices, so the two parts together stay one closed surface).
Part splitOff(Part& part, const std::string& name, const std::string& material,
              const std::function<bool(const V3& faceNormal)>& take) {
  Part other{name, material, part.v, {}};
  std::vector<std::array<int, 3>> keep;
  for (const auto& t : part.t) {
    const V3 n = (part.v[t[1]].p - part.v[t[0]].p).cross(part.v[t[2]].p - part.v[t[0]].p);
    (take(n.normalized()) ? other.t : keep).push_back(t);
  }
  part.t = keep;
  return other;
}

Part torus(const std::string& name, const std::string& material, const V3& center, const V3& axisDir, double major,
           double minor, int rings, int sides) {
  Part part{name, material, {}, {}};
  const V3 axis = axisDir.normalized();
  const auto [u, w] = perpendiculars(axis);
  std::vector<std::vector<int>> grid(rings + 1, std::vector<int>(sides + 1));
  for (int i = 0; i <= rings; ++i) {
    const double a = kTau * i / rings;
    const V3 radial = std::cos(a) * u + std::sin(a) * w;
    for (int j = 0; j <= sides; ++j) {
      const double b = kTau * j / sides;
      const V3 n = std::cos(b) * radial + std::sin(b) * axis;
      grid[i][j] = part.add(center + major * radial + minor * n, n, V2(double(i) / rings, double(j) / sides));
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const V3 out = part.v[grid[i][j]].n + part.v[grid[i + 1][j + 1]].n;
      part.quad(grid[i][j], grid[i + 1][j], grid[i + 1][j + 1], grid[i][j + 1], out);
    }
  }
  return part;
}

// ---- prism solids ------------------------------------------------------------

// A solid built from prisms along X, for vehicle bodies that must be one
// closed surface (chassis.inertia = "mesh" integrates over it). The side
// view (z, y) is cut into convex cells that meet along whole edges (two
// cells that touch share both end points of the edge they touch along; no
// T-junctions); stations cut X into slabs, and each cell says in which
// slabs it is solid. The surface is the boundary of that union of prisms: a
// cap where a cell's solidity changes from one slab to the next (or at the
// first and last station), a wall where a cell is solid in a slab and its
// neighbour across an edge is not (or has none). Every wall is cut at every
// station, so all faces meet edge to edge and the surface is closed and
// consistently outward-wound by construction, whatever the cells; the
// prisms never overlap, so no volume counts twice. Pockets (a truck bed),
// holes (a window in a roll cage) and parts across the width (cross tubes)
// are cells solid in some slabs only. Materials: each cell has one, and a
// paint rule may override it per face (windscreen, headlights).
struct ProfileCell {
  std::vector<int> loop;    // indices into PrismSolid::points, convex, either winding
  std::vector<bool> solid;  // per slab
  std::string material;
};

struct PrismSolid {
  std::vector<V2> points;         // (z, y), m
  std::vector<double> stations;   // x, m, ascending
  std::vector<ProfileCell> cells;
  // Material for a face (its centre and outward normal) of a cell with `material`.
  std::function<std::string(const V3& centre, const V3& normal, const std::string& material)> paint;

  int point(double z, double y) {
    points.emplace_back(z, y);
    return int(points.size()) - 1;
  }
  void cell(std::vector<int> loop, const std::string& material, const std::function<bool(double x)>& solidAt) {
    ProfileCell c{std::move(loop), {}, material};
    for (std::size_t k = 0; k + 1 < stations.size(); ++k) c.solid.push_back(solidAt(0.5 * (stations[k] + stations[k + 1])));
    cells.push_back(std::move(c));
  }
};

V3 at(double x, const V2& zy) { return V3(x, zy.y(), zy.x()); }

std::vector<Part> buildPrismSolid(const PrismSolid& solid) {
  std::vector<Part> parts;
  std::map<std::string, std::size_t> partOf;
  auto partFor = [&](const std::string& material) -> Part& {
    auto [it, fresh] = partOf.try_emplace(material, parts.size());
    if (fresh) parts.push_back(Part{material, material, {}, {}});
    return parts[it->second];
  };
  auto materialOf = [&](const ProfileCell& c, const V3& centre, const V3& normal) {
    return solid.paint ? solid.paint(centre, normal, c.material) : c.material;
  };
  // The cells along each edge (at most two: the cells tile the side view).
  std::map<std::pair<int, int>, std::vector<std::size_t>> along;
  for (std::size_t c = 0; c < solid.cells.size(); ++c) {
    const auto& loop = solid.cells[c].loop;
    for (std::size_t i = 0; i < loop.size(); ++i) along[std::minmax(loop[i], loop[(i + 1) % loop.size()])].push_back(c);
  }
  const std::size_t slabs = solid.stations.size() - 1;
  for (std::size_t ci = 0; ci < solid.cells.size(); ++ci) {
    const ProfileCell& c = solid.cells[ci];
    V2 centroid = V2::Zero();
    for (int i : c.loop) centroid += solid.points[std::size_t(i)];
    centroid /= double(c.loop.size());
    const std::size_t n = c.loop.size();
    // Caps, fanned from the centroid (the cell is convex).
    for (std::size_t k = 0; k <= slabs; ++k) {
      const bool below = k > 0 && c.solid[k - 1], above = k < slabs && c.solid[k];
      if (below == above) continue;
      const double x = solid.stations[k];
      const V3 normal(below ? 1 : -1, 0, 0);
      Part& part = partFor(materialOf(c, at(x, centroid), normal));
      const int mid = part.add(at(x, centroid), normal, 0.5 * centroid);
      std::vector<int> ring;
      for (int i : c.loop) ring.push_back(part.add(at(x, solid.points[std::size_t(i)]), normal, 0.5 * solid.points[std::size_t(i)]));
      for (std::size_t i = 0; i < n; ++i) part.tri(mid, ring[i], ring[(i + 1) % n], normal);
    }
    // Walls, one quad per edge and slab.
    for (std::size_t i = 0; i < n; ++i) {
      const int ia = c.loop[i], ib = c.loop[(i + 1) % n];
      const V2 a = solid.points[std::size_t(ia)], b = solid.points[std::size_t(ib)];
      V2 out(b.y() - a.y(), a.x() - b.x());
      if (out.dot(0.5 * (a + b) - centroid) < 0) out = -out;
      const V3 normal(0, out.y(), out.x());
      const ProfileCell* other = nullptr;
      for (std::size_t o : along[std::minmax(ia, ib)])
        if (o != ci) other = &solid.cells[o];
      const double length = (b - a).norm();
      for (std::size_t k = 0; k < slabs; ++k) {
        if (!c.solid[k] || (other && other->solid[k])) continue;
        const double x0 = solid.stations[k], x1 = solid.stations[k + 1];
        const V3 centre = 0.5 * (at(x0, a) + at(x1, b));
        Part& part = partFor(materialOf(c, centre, normal.normalized()));
        const int q0 = part.add(at(x0, a), normal, V2(0, x0 * 0.5)), q1 = part.add(at(x0, b), normal, V2(length * 0.5, x0 * 0.5));
        const int q2 = part.add(at(x1, b), normal, V2(length * 0.5, x1 * 0.5)), q3 = part.add(at(x1, a), normal, V2(0, x1 * 0.5));
        part.quad(q0, q1, q2, q3, normal);
      }
    }
  }
  return parts;
}

// ---- deterministic noise ---------------------------------------------------

std::uint32_t hash3(std::int32_t x, std::int32_t y, std::uint32_t seed) {
  std::uint32_t h = std::uint32_t(x) * 0x8da6b343u ^ std::uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return h;
}
double hash01(std::int32_t x, std::int32_t y, std::uint32_t seed) { return (hash3(x, y, seed) >> 8) / 16777216.0; }

// Value noise that tiles with period `period` cells (textures repeat).
double tiledNoise(double x, double y, int period, std::uint32_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const int ix = int(fx), iy = int(fy);
  const double tx = x - fx, ty = y - fy;
  const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  auto at = [&](int i, int j) { return hash01(((i % period) + period) % period, ((j % period) + period) % period, seed); };
  const double a = at(ix, iy), b = at(ix + 1, iy), c = at(ix, iy + 1), d = at(ix + 1, iy + 1);
  return a + (b - a) * sx + (c - a) * sy + (a - b - c + d) * sx * sy;
}

// Fractal sum of three octaves, 0..1, tiling over a 64-pixel texture.
double fractal(int px, int py, int baseCells, std::uint32_t seed) {
  double sum = 0, amp = 0.5, norm = 0;
  for (int o = 0, cells = baseCells; o < 3; ++o, cells *= 2, amp *= 0.5) {
    sum += amp * tiledNoise(px * cells / 64.0, py * cells / 64.0, cells, seed + o);
    norm += amp;
  }
  return sum / norm;
}

Part icosphere(const std::string& name, const std::string& material, const V3& center, const V3& radii,
               int subdivisions, double roughness, std::uint32_t seed) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<V3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                           {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (V3& q : p) q.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto [it, fresh] = mid.try_emplace({key.first, key.second}, int(p.size()));
      if (fresh) p.push_back((p[a] + p[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : faces) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.insert(next.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    faces = next;
  }
  // Displace each (shared) vertex by noise on its direction, then flat-shade.
  std::vector<V3> displaced;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double bump = 1 + roughness * (2 * hash01(int(i), int(i * 7 + 3), seed) - 1);
    displaced.push_back(center + (p[i] * bump).cwiseProduct(radii));
  }
  Part part{name, material, {}, {}};
  for (const auto& f : faces) {
    const V3 a = displaced[f[0]], b = displaced[f[1]], c = displaced[f[2]];
    const V3 n = (b - a).cross(c - a).normalized();
    const V3 out = (a + b + c) / 3 - center;
    auto uv = [&](const V3& q) { return V2(0.7 * (q.x() + q.z()), 0.7 * q.y()); };
    const int ia = part.add(a, n, uv(a)), ib = part.add(b, n, uv(b)), ic = part.add(c, n, uv(c));
    part.tri(ia, ib, ic, out);
  }
  for (const auto& tri : part.t) {
    const V3 n = (part.v[tri[1]].p - part.v[tri[0]].p).cross(part.v[tri[2]].p - part.v[tri[0]].p).normalized();
    for (int k : tri) part.v[k].n = n;
  }
  return part;
}

// ---- textures --------------------------------------------------------------

constexpr int kTex = 64;
using Pixel = std::array<std::uint8_t, 3>;

std::uint8_t clampByte(double v) { return std::uint8_t(std::clamp(std::lround(v), 0L, 255L)); }
Pixel rgb(double r, double g, double b) { return {clampByte(r), clampByte(g), clampByte(b)}; }

std::string encodePng(const std::function<Pixel(int x, int y)>& shade) {
  std::vector<std::uint8_t> pixels;
  pixels.reserve(kTex * kTex * 3);
  for (int y = 0; y < kTex; ++y) {
    for (int x = 0; x < kTex; ++x) {
      const Pixel p = shade(x, y);
      pixels.insert(pixels.end(), p.begin(), p.end());
    }
  }
  std::string out;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
      },
      &out, kTex, kTex, 3, pixels.data(), kTex * 3);
  return out;
}

std::vector<GeneratedFile> textures() {
  std::vector<GeneratedFile> out;
  // Tyre tread: dark rubber, grooves across the tread every 8 pixels.
  out.push_back({"tyre.png", encodePng([](int x, int y) {
                   const double n = fractal(x, y, 8, 11);
                   const bool groove = (y % 8) < 2 || ((x / 16 + y / 8) % 2 == 0 && (x % 16) < 2);
                   const double v = (groove ? 12 : 38) + 14 * n;
                   return rgb(v, v, v * 1.05);
                 })});
  // Wheel side (planar on the caps): black sidewall ring, silver rim, five
  // dark holes between the spokes, dark hub.
  out.push_back({"rim.png", encodePng([](int x, int y) {
                   const double dx = (x + 0.5) / 32.0 - 1, dy = (y + 0.5) / 32.0 - 1;
                   const double r = std::sqrt(dx * dx + dy * dy);
                   const double a = std::atan2(dy, dx);
                   if (r > 0.68) return rgb(28, 28, 30);
                   if (r < 0.12) return rgb(60, 60, 64);
                   const double spoke = std::cos(5 * a);
                   if (r > 0.25 && r < 0.58 && spoke < -0.3) return rgb(20, 20, 22);
                   const double v = 175 + 40 * (1 - r) + 10 * fractal(x, y, 8, 12);
                   return rgb(v, v, v + 6);
                 })});
  out.push_back({"rock.png", encodePng([](int x, int y) {
                   const double n = fractal(x, y, 4, 21), m = fractal(x, y, 16, 22);
                   const double v = 85 + 80 * n + 25 * (m - 0.5);
                   return rgb(v * 1.04, v, v * 0.9);
                 })});
  out.push_back({"bark.png", encodePng([](int x, int y) {
                   const double n = tiledNoise(x / 4.0, y / 32.0, 16, 31) * 0.7 + 0.3 * fractal(x, y, 16, 32);
                   return rgb(70 + 60 * n, 45 + 40 * n, 25 + 20 * n);
                 })});
  out.push_back({"leaves.png", encodePng([](int x, int y) {
                   const double n = fractal(x, y, 8, 41), m = fractal(x, y, 32, 42);
                   return rgb(30 + 40 * m, 80 + 90 * n, 25 + 30 * m);
                 })});
  // Building wall: plaster with a 2 x 2 grid of windows per repeat (3 m).
  out.push_back({"building.png", encodePng([](int x, int y) {
                   const int cx = x % 32, cy = y % 32;
                   const bool window = cx >= 8 && cx < 24 && cy >= 6 && cy < 22;
                   const double n = fractal(x, y, 16, 51);
                   if (window) {
                     const bool frame = cx == 8 || cx == 23 || cy == 6 || cy == 21 || cx == 16;
                     return frame ? rgb(220, 220, 215) : rgb(40 + 30 * n, 60 + 30 * n, 90 + 40 * n);
                   }
                   return rgb(190 + 25 * n, 170 + 25 * n, 140 + 20 * n);
                 })});
  out.push_back({"stripes.png", encodePng([](int x, int y) {
                   const bool red = ((x + y) / 16) % 2 == 0;
                   const double n = 12 * fractal(x, y, 16, 61);
                   return red ? rgb(200 + n, 30 + n, 25 + n) : rgb(230 + n, 230 + n, 225 + n);
                 })});
  out.push_back({"checker.png", encodePng([](int x, int y) {
                   const bool dark = ((x / 16) + (y / 16)) % 2 == 0;
                   return dark ? rgb(20, 20, 20) : rgb(240, 240, 240);
                 })});
  return out;
}

// ---- models ----------------------------------------------------------------

const std::vector<Material>& materials() {
  static const std::vector<Material> list = {
      {"paint_red", {0.75, 0.08, 0.06}, ""},   {"paint_green", {0.22, 0.32, 0.16}, ""},
      {"paint_yellow", {0.95, 0.75, 0.10}, ""}, {"glass", {0.10, 0.13, 0.16}, ""},
      {"plastic_black", {0.06, 0.06, 0.06}, ""}, {"chrome", {0.75, 0.75, 0.78}, ""},
      {"headlight", {1.0, 0.95, 0.75}, "", {0.9, 0.88, 0.75}},
      {"taillight", {0.9, 0.08, 0.06}, "", {0.95, 0.10, 0.05}},
      {"plate", {0.92, 0.92, 0.88}, ""},
      {"tyre", {1, 1, 1}, "tyre.png"},         {"rim", {1, 1, 1}, "rim.png"},
      {"dashboard", {0.12, 0.12, 0.13}, ""},   {"seat", {0.25, 0.22, 0.20}, ""},
      {"trim", {0.35, 0.35, 0.36}, ""},        {"rock", {1, 1, 1}, "rock.png"},
      {"bark", {1, 1, 1}, "bark.png"},         {"leaves", {1, 1, 1}, "leaves.png"},
      {"building", {1, 1, 1}, "building.png"}, {"roof", {0.30, 0.28, 0.27}, ""},
      {"stripes", {1, 1, 1}, "stripes.png"},   {"checker", {1, 1, 1}, "checker.png"},
      {"post", {0.85, 0.85, 0.85}, ""},        {"ramp_deck", {0.52, 0.52, 0.55}, ""},
  };
  return list;
}

// The hatchback's wheel arches, seen from the side: an opening 0.84 m
// long around each wheel (base:hatchback's axles at z = 1.25 and -1.30,
// tyres of radius 0.30 whose top is 0.60 m up at rest), 0.72 m high, as a
// half octagon standing on the body's underside (y = 0.28).
constexpr double kArchHalfLength = 0.42, kArchTop = 0.72;
std::vector<V2> archOutline(double centreZ) {
  const double l = kArchHalfLength;
  return {{centreZ - l, 0.28}, {centreZ - 0.38, 0.50}, {centreZ - 0.24, 0.66}, {centreZ, kArchTop},
          {centreZ + 0.24, 0.66}, {centreZ + 0.38, 0.50}, {centreZ + l, 0.28}};
}

// A car's lower body with wheel arches cut in, seen from the side: below
// the sill line (y = sill) a strip behind the first arch, one between each
// pair and one in front of the last, each arch (an outline from the
// underside up and back down, solid only where wellSolid holds: the wheel
// well's inner wall) and one quad over each arch edge up to the sill.
// rearFace and frontFace are the points on the body's ends from the sill
// down (rear) and from the underside up (front), both ends of the sill
// included. Returns the sill line's points, rear to front: the lower edge
// of the cell above must carry every one (cells meet edge to edge).
std::vector<int> archedLowerBody(PrismSolid& s, double sill, const std::vector<int>& rearFace,
                                 const std::vector<int>& frontFace, const std::vector<std::vector<V2>>& arches,
                                 const std::string& material, const std::function<bool(double)>& rearSolid,
                                 const std::function<bool(double)>& wellSolid) {
  const int rearBottom = rearFace.back();
  std::vector<std::pair<double, int>> sillPoints{{s.points[std::size_t(rearFace.front())].x(), rearFace.front()},
                                                 {s.points[std::size_t(frontFace.back())].x(), frontFace.back()}};
  auto sillAt = [&](double z) {
    for (const auto& [zz, i] : sillPoints)
      if (std::abs(zz - z) < 1e-9) return i;
    const int i = s.point(z, sill);
    sillPoints.emplace_back(z, i);
    return i;
  };
  auto all = [](double) { return true; };
  int last = rearBottom;  // the underside point the next strip starts from
  double lastZ = sillPoints.front().first;
  for (const std::vector<V2>& outline : arches) {
    std::vector<int> arch;
    for (const V2& q : outline) arch.push_back(s.point(q.x(), q.y()));
    if (last == rearBottom) {
      std::vector<int> strip{rearBottom, arch.front(), sillAt(outline.front().x())};
      strip.insert(strip.end(), rearFace.begin(), rearFace.end() - 1);
      s.cell(strip, material, rearSolid);
    } else {
      s.cell({last, arch.front(), sillAt(outline.front().x()), sillAt(lastZ)}, material, all);
    }
    s.cell(arch, "plastic_black", wellSolid);
    for (std::size_t i = 1; i < arch.size(); ++i)
      s.cell({arch[i - 1], arch[i], sillAt(outline[i].x()), sillAt(outline[i - 1].x())}, material, all);
    last = arch.back();
    lastZ = outline.back().x();
  }
  std::vector<int> front{last};
  front.insert(front.end(), frontFace.begin(), frontFace.end());
  front.push_back(sillAt(lastZ));
  s.cell(front, material, all);
  std::sort(sillPoints.begin(), sillPoints.end());
  std::vector<int> line;
  for (const auto& [z, i] : sillPoints) line.push_back(i);
  return line;
}

// Hatchback, 4.14 m long with its bumpers, 1.56 m wide body (wheels outside
// it at x = +-0.8, z = +-1.3, radius 0.32). One closed solid (a
// PrismSolid), so chassis.inertia = "mesh" counts no volume twice: the
// lower body up to the belt line, the greenhouse above it cut into a side
// window, a B pillar and a rear side window framed by pillars, and the
// bumpers as cells in front and behind. Windscreen, rear window and lights
// are painted faces of the body.
//
// wheelArches: the drawn body (hatchback_shaped.obj, chassis.display_mesh)
// with wheel arches open from the sides down to x = +-0.40 (the wells lined
// black) and the rear below the sill and the rear bumper tucked in to x =
// +-0.60, so the tyres show from the side and from behind; the plain one
// (hatchback.obj) stays the solid the chassis inertia is taken from.
ObjModel hatchback(bool wheelArches) {
  PrismSolid h;
  // The lights' edges across the width (0.40 .. 0.70 m from the middle),
  // the rear window's (0.6 m) and the number plate's (0.26 m).
  h.stations = {-0.78, -0.70, -0.60, -0.40, -0.26, 0.26, 0.40, 0.60, 0.70, 0.78};
  auto all = [](double) { return true; };
  auto tucked = [](double x) { return std::abs(x) < 0.60; };
  // Lower body, front to back; the front and rear faces are cut where the
  // bumpers and the lights end.
  const int b0 = h.point(-2.0, 0.28), b1 = h.point(2.0, 0.28), f045 = h.point(2.0, 0.45), f062 = h.point(2.0, 0.62);
  const int f074 = h.point(2.0, 0.74), f078 = h.point(2.0, 0.78), belt0 = h.point(1.25, 0.92), belt1 = h.point(-2.0, 0.95);
  const int r088 = h.point(-2.0, 0.88), r074 = h.point(-2.0, 0.74), r045 = h.point(-2.0, 0.45);
  const int r064 = h.point(-2.0, 0.64), r052 = h.point(-2.0, 0.52);  // the number plate's top and bottom
  if (!wheelArches) {
    h.cell({b0, b1, f045, f062, f074, f078, belt0, belt1, r088, r074, r064, r052, r045}, "paint_red", all);
  } else {
    // Below y = 0.74 the arches (wells lined black, solid only inside
    // |x| < 0.40); behind the rear arch the body below the sill is tucked
    // in to |x| < 0.60 (as the bumper), so the rear tyres show from behind.
    // Above the sill one cell to the belt line.
    std::vector<int> upper = archedLowerBody(h, 0.74, {r074, r064, r052, r045, b0}, {b1, f045, f062, f074},
                                             {archOutline(-1.30), archOutline(1.25)}, "paint_red", tucked,
                                             [](double x) { return std::abs(x) < 0.40; });
    for (int q : {f078, belt0, belt1, r088}) upper.push_back(q);
    h.cell(upper, "paint_red", all);
  }
  const int fb0 = h.point(2.07, 0.28), fb1 = h.point(2.07, 0.45), rb0 = h.point(-2.07, 0.28), rb1 = h.point(-2.07, 0.45);
  h.cell({b1, fb0, fb1, f045}, "plastic_black", all);
  h.cell({rb0, b0, r045, rb1}, "plastic_black", wheelArches ? std::function<bool(double)>(tucked) : all);
  // Greenhouse: the windscreen line from (1.25, 0.92) to (0.45, 1.42), the
  // roof to (-1.55, 1.45), the hatch line down to (-2.0, 0.95). The side
  // glass runs from y = lo to hi, inset from both lines, split by a B pillar.
  auto screen = [](double y) { return 1.25 - 0.8 * (y - 0.92) / 0.5; };
  auto hatch = [](double y) { return -2.0 + 0.45 * (y - 0.95) / 0.5; };
  const double lo = 1.05, hi = 1.33;
  const int wlo = h.point(screen(lo), lo), whi = h.point(screen(hi), hi), hlo = h.point(hatch(lo), lo),
            hhi = h.point(hatch(hi), hi);
  const int flo = h.point(screen(lo) - 0.14, lo), fhi = h.point(screen(hi) - 0.14, hi);   // A pillar's back
  const int blo0 = h.point(-0.25, lo), bhi0 = h.point(-0.25, hi);                          // B pillar
  const int blo1 = h.point(-0.37, lo), bhi1 = h.point(-0.37, hi);
  const int clo = h.point(hatch(lo) + 0.2, lo), chi = h.point(hatch(hi) + 0.2, hi);        // C pillar's front
  const int roof0 = h.point(0.45, 1.42), roof1 = h.point(-1.55, 1.45);
  h.cell({belt1, belt0, wlo, flo, blo0, blo1, clo, hlo}, "paint_red", all);
  h.cell({flo, wlo, whi, fhi}, "paint_red", all);
  h.cell({blo0, flo, fhi, bhi0}, "glass", all);
  h.cell({blo1, blo0, bhi0, bhi1}, "paint_red", all);
  h.cell({clo, blo1, bhi1, chi}, "glass", all);
  h.cell({hlo, clo, chi, hhi}, "paint_red", all);
  h.cell({hhi, chi, bhi1, bhi0, fhi, whi, roof0, roof1}, "paint_red", all);
  h.paint = [lo, hi, wheelArches](const V3& c, const V3& n, const std::string& material) -> std::string {
    const double ax = std::abs(c.x());
    if (n.z() > 0.4 && n.y() > 0.5 && c.y() > 0.95 && ax < 0.7) return "glass";      // windscreen
    if (n.z() < -0.5 && n.y() > 0.3 && c.y() > lo && c.y() < hi && ax < 0.6) return "glass";  // rear window
    if (ax > 0.4 && ax < 0.7 && n.z() > 0.9 && c.z() > 1.99 && c.y() > 0.62 && c.y() < 0.74) return "headlight";
    if (ax > 0.4 && ax < 0.7 && n.z() < -0.9 && c.z() < -1.99 && c.y() > 0.74 && c.y() < 0.88) return "taillight";
    if (ax < 0.26 && n.z() < -0.9 && c.z() < -1.99 && c.y() > 0.52 && c.y() < 0.64) return "plate";
    if (wheelArches && n.y() < -0.2 && c.y() > 0.3 && c.y() < 0.75) return "plastic_black";  // the arches' ceilings
    return material;
  };
  return {wheelArches ? "hatchback_shaped" : "hatchback", buildPrismSolid(h), true};
}

// Off-road truck: a cab with side windows and a flatbed, 4.9 m long, high
// ground clearance (base:truck's wheels at x = +-0.82, z = +-1.55, radius
// 0.42, so their hubs are 0.42 m up at rest and the tyres' tops 0.84). One
// closed solid (a PrismSolid): the bed is a pocket between its side walls,
// the bull bar a cell solid between x = +-0.8 only; glass, lights and the
// number plate are painted faces of the body; the upright tail lights sit
// at the bed's rear corners.
//
// wheelArches: the drawn body (truck_shaped.obj, chassis.display_mesh) with
// the lower body cut away around each wheel up to 0.92 m (the wells lined
// black, solid only inside |x| < 0.55, where the bed's humps over the rear
// wheels already stand), so the tyres show from the side; the plain one
// (truck.obj) stays the solid the chassis inertia is taken from.
constexpr double kTruckArchHalfLength = 0.58, kTruckArchTop = 0.92, kTruckSill = 0.94;
ObjModel truck(bool wheelArches) {
  PrismSolid t;
  t.stations = {-0.9, -0.82, -0.8, -0.75, -0.7, -0.55, -0.45, -0.26, 0.26, 0.45, 0.55, 0.7, 0.75, 0.8, 0.82, 0.9};
  auto all = [](double) { return true; };
  // Body below the bed floor, front to back; its rear face carries the
  // number plate (0.80 .. 0.94 m up), and with arches the sill line (0.94).
  const int b0 = t.point(-2.4, 0.62), b1 = t.point(2.4, 0.62), f065 = t.point(2.4, 0.65), f098 = t.point(2.4, 0.98);
  const int m098 = t.point(0.2, 0.98), a098 = t.point(-1.1, 0.98), c098 = t.point(-2.0, 0.98);
  const int g098 = t.point(-2.32, 0.98), r098 = t.point(-2.4, 0.98), r078 = t.point(-2.4, 0.78);
  const int r094 = t.point(-2.4, kTruckSill), r080 = t.point(-2.4, 0.80);
  const int f094 = t.point(2.4, kTruckSill);
  if (!wheelArches) {
    t.cell({b0, b1, f065, f098, m098, a098, c098, g098, r098, r094, r080, r078}, "paint_green", all);
  } else {
    // Below the sill the arches (wells lined black, solid only inside
    // |x| < 0.55); above it one band to the bed floor.
    auto truckArch = [](double centre) {
      const double l = kTruckArchHalfLength, h = kTruckArchTop - 0.62;
      return std::vector<V2>{{centre - l, 0.62},           {centre - 0.92 * l, 0.62 + 0.55 * h},
                             {centre - 0.6 * l, 0.62 + 0.9 * h}, {centre, kTruckArchTop},
                             {centre + 0.6 * l, 0.62 + 0.9 * h}, {centre + 0.92 * l, 0.62 + 0.55 * h},
                             {centre + l, 0.62}};
    };
    std::vector<int> band = archedLowerBody(t, kTruckSill, {r094, r080, r078, b0}, {b1, f065, f094},
                                            {truckArch(-1.55), truckArch(1.55)}, "paint_green", all,
                                            [](double x) { return std::abs(x) < 0.55; });
    for (int q : {f098, m098, a098, c098, g098, r098}) band.push_back(q);
    t.cell(band, "paint_green", all);
  }
  // Rear bumper and bull bar (the bar's back edge carries the sill point
  // when the body below it is cut there).
  const int rb0 = t.point(-2.5, 0.62), rb1 = t.point(-2.5, 0.78);
  t.cell({rb0, b0, r078, rb1}, "plastic_black", all);
  const int bb0 = t.point(2.5, 0.65), bb1 = t.point(2.5, 1.15), f115 = t.point(2.4, 1.15);
  std::vector<int> bar{f065, bb0, bb1, f115, f098};
  if (wheelArches) bar.push_back(f094);
  t.cell(bar, "chrome", [](double x) { return std::abs(x) < 0.8; });
  // Tailgate, and the bed: solid only in its side walls (|x| > 0.82) but
  // for the humps over the rear wheels (|x| > 0.55, up to y = 1.28, above
  // the tyres at full bump). The tailgate's back carries the tail lights
  // (1.08 .. 1.36 m up).
  const int g128 = t.point(-2.32, 1.28), g146 = t.point(-2.32, 1.46), r146 = t.point(-2.4, 1.46);
  const int r136 = t.point(-2.4, 1.36), r108 = t.point(-2.4, 1.08);
  const int c128 = t.point(-2.0, 1.28), a128 = t.point(-1.1, 1.28), m128 = t.point(0.2, 1.28), m146 = t.point(0.2, 1.46);
  auto walls = [](double x) { return std::abs(x) > 0.82; };
  t.cell({r098, g098, g128, g146, r146, r136, r108}, "paint_green", all);
  t.cell({g098, c098, c128, g128}, "paint_green", walls);
  t.cell({c098, a098, a128, c128}, "paint_green", [](double x) { return std::abs(x) > 0.55; });
  t.cell({a098, m098, m128, a128}, "paint_green", walls);
  t.cell({g128, c128, a128, m128, m146, g146}, "paint_green", walls);
  // Bonnet up to the waist line (y = 1.5); the front carries the headlights.
  const int f118 = t.point(2.4, 1.18), f130 = t.point(2.4, 1.30), f135 = t.point(2.4, 1.35);
  const int w0 = t.point(1.6, 1.5), m150 = t.point(0.2, 1.5);
  t.cell({m098, f098, f115, f118, f130, f135, w0, m150, m146, m128}, "paint_green", all);
  // Cabin: the windscreen line from (1.6, 1.5) to (1.2, 2.25), a side window
  // (glass cell) framed by four strips.
  auto screen = [](double y) { return 1.6 - 0.4 * (y - 1.5) / 0.75; };
  const double lo = 1.62, hi = 2.11, inset = 0.17;
  const int s0 = t.point(screen(lo), lo), s1 = t.point(screen(hi), hi), top = t.point(1.2, 2.25), back = t.point(0.2, 2.25);
  const int wlo0 = t.point(0.2, lo), wlo1 = t.point(0.35, lo), wlo2 = t.point(screen(lo) - inset, lo);
  const int whi0 = t.point(0.2, hi), whi1 = t.point(0.35, hi), whi2 = t.point(screen(hi) - inset, hi);
  t.cell({m150, w0, s0, wlo2, wlo1, wlo0}, "paint_green", all);
  t.cell({wlo0, wlo1, whi1, whi0}, "paint_green", all);
  t.cell({wlo1, wlo2, whi2, whi1}, "glass", all);
  t.cell({wlo2, s0, s1, whi2}, "paint_green", all);
  t.cell({whi0, whi1, whi2, s1, top, back}, "paint_green", all);
  t.paint = [=](const V3& c, const V3& n, const std::string& material) -> std::string {
    const double ax = std::abs(c.x());
    if (n.z() > 0.5 && n.y() > 0.3 && c.y() > 1.5 && ax < 0.8) return "glass";                      // windscreen
    if (n.z() < -0.9 && c.z() < 0.21 && c.y() > lo && c.y() < hi && ax < 0.7) return "glass";       // rear window
    if (n.z() > 0.9 && c.z() > 2.39 && c.y() > 1.18 && c.y() < 1.30 && ax > 0.45 && ax < 0.75) return "headlight";
    if (n.z() < -0.9 && c.z() < -2.39 && c.y() > 1.08 && c.y() < 1.36 && ax > 0.75) return "taillight";
    if (n.z() < -0.9 && c.z() < -2.39 && c.y() > 0.80 && c.y() < 0.94 && ax < 0.26) return "plate";
    if (wheelArches && n.y() < -0.2 && c.y() > 0.63 && c.y() < kTruckSill) return "plastic_black";  // the arches' ceilings
    return material;
  };
  return {wheelArches ? "truck_shaped" : "truck", buildPrismSolid(t), true};
}

/// Where the lines p0 + s d0 and p1 + t d1 cross (they must not be parallel).
V2 crossing(const V2& p0, const V2& d0, const V2& p1, const V2& d1) {
  const double det = d0.x() * d1.y() - d0.y() * d1.x();
  const double s = ((p1 - p0).x() * d1.y() - (p1 - p0).y() * d1.x()) / det;
  return p0 + s * d0;
}

// Buggy: a floor pan, a seat and a square-tube roll cage (wheels at x =
// +-0.85, z = +-1.2, radius 0.38), one closed solid (a PrismSolid). Seen
// from the side, each half of the cage is a frame (main hoop leg, roof
// rail, front leg on a lower rail) solid only at |x| 0.52..0.59; the tube
// corners are mitred; cross tubes (top of the main hoop, top of the front
// legs, the front of the rails) are cells solid across the whole width.
// Lights are painted faces: a light bar on the front of the upper front
// cross tube (two lamps, 0.10 .. 0.40 m either side of the middle) and tail
// lights on the floor pan's back at its corners (0.40 .. 0.52 m).
ObjModel buggy() {
  PrismSolid b;
  b.stations = {-0.59, -0.52, -0.40, -0.25, -0.10, 0.10, 0.25, 0.40, 0.52, 0.59};
  auto all = [](double) { return true; };
  auto sides = [](double x) { return std::abs(x) > 0.52; };
  auto seatSlab = [](double x) { return std::abs(x) < 0.25; };
  const double w = 0.035;  // half the tube width, m
  const double railLo = 0.48, railHi = 0.55;
  // Frame centre line A (main hoop foot), B (main hoop top), C (front hoop top), D (front leg foot).
  const V2 A(-0.9, 0.515), B(-0.6, 1.55), C(0.1, 1.45), D(0.6, 0.515);
  const V2 dAB = (B - A).normalized(), dBC = (C - B).normalized(), dCD = (D - C).normalized();
  auto normalOf = [](const V2& d) { return V2(-d.y(), d.x()); };  // the outside of the frame loop A B C D
  const V2 nAB = normalOf(dAB), nBC = normalOf(dBC), nCD = normalOf(dCD);
  // Mitred corners: where the offset lines cross.
  const V2 oA = crossing(V2(0, railLo), V2(1, 0), A + w * nAB, dAB), iA = crossing(V2(0, railHi), V2(1, 0), A - w * nAB, dAB);
  const V2 oB = crossing(A + w * nAB, dAB, B + w * nBC, dBC), iB = crossing(A - w * nAB, dAB, B - w * nBC, dBC);
  const V2 oC = crossing(B + w * nBC, dBC, C + w * nCD, dCD), iC = crossing(B - w * nBC, dBC, C - w * nCD, dCD);
  const V2 oD = crossing(V2(0, railLo), V2(1, 0), D + w * nCD, dCD), iD = crossing(V2(0, railHi), V2(1, 0), D - w * nCD, dCD);
  // Where the legs' outer faces meet the top of the rail, and the cuts that
  // end the cross tubes 0.1 m below the top corners.
  const V2 pA = crossing(V2(0, railHi), V2(1, 0), A + w * nAB, dAB), pD = crossing(V2(0, railHi), V2(1, 0), D + w * nCD, dCD);
  const V2 cutB = B - 0.1 * dAB, cutC = C + 0.1 * dCD;
  auto P = [&](const V2& p) { return b.point(p.x(), p.y()); };
  const int poA = P(oA), piA = P(iA), poB = P(oB), piB = P(iB), poC = P(oC), piC = P(iC), poD = P(oD), piD = P(iD);
  const int ppA = P(pA), ppD = P(pD), qBo = P(cutB + w * nAB), qBi = P(cutB - w * nAB), qCo = P(cutC + w * nCD),
            qCi = P(cutC - w * nCD);
  // Floor pan under everything (its top carries every point the rails put on it).
  const int pan0 = b.point(-1.5, 0.40), pan1 = b.point(1.5, 0.40), pan2 = b.point(1.5, railLo), pan3 = b.point(-1.5, railLo);
  const int r0 = b.point(-1.45, railLo), r1 = b.point(-1.45, railHi), s0 = b.point(-0.55, railLo), s1 = b.point(-0.05, railLo);
  const int s2 = b.point(-0.05, railHi), s3 = b.point(-0.55, railHi);
  const int f0 = b.point(1.38, railLo), f1 = b.point(1.38, railHi), f2 = b.point(1.45, railLo), f3 = b.point(1.45, railHi);
  b.cell({pan0, pan1, pan2, f2, f0, poD, s1, s0, poA, r0, pan3}, "plastic_black", all);
  // Lower rails and the front cross tube.
  b.cell({r0, poA, ppA, r1}, "paint_yellow", sides);
  b.cell({poA, s0, s3, piA}, "paint_yellow", sides);
  b.cell({s0, s1, s2, s3}, "paint_yellow", [](double x) { return std::abs(x) > 0.52 || std::abs(x) < 0.25; });
  b.cell({s1, poD, piD, s2}, "paint_yellow", sides);
  b.cell({poD, f0, f1, ppD}, "paint_yellow", sides);
  b.cell({f0, f2, f3, f1}, "paint_yellow", all);
  // Legs, roof rail and the two upper cross tubes.
  b.cell({poA, ppA, qBo, qBi, piA}, "paint_yellow", sides);
  b.cell({qBo, poB, piB, qBi}, "paint_yellow", all);
  b.cell({poB, poC, piC, piB}, "paint_yellow", sides);
  b.cell({poC, qCo, qCi, piC}, "paint_yellow", all);
  b.cell({qCo, ppD, poD, piD, qCi}, "paint_yellow", sides);
  // Seat on the middle of the rail cell, and its back.
  const int t0 = b.point(-0.05, 0.9), t1 = b.point(-0.47, 0.9), t2 = b.point(-0.55, 0.9), t3 = b.point(-0.57, 0.9);
  const int u0 = b.point(-0.47, 1.3), u1 = b.point(-0.57, 1.3);
  b.cell({s3, s2, t0, t1, t2}, "seat", seatSlab);
  b.cell({t3, t2, t1, u0, u1}, "seat", seatSlab);
  b.paint = [=](const V3& c, const V3& n, const std::string& material) -> std::string {
    const double ax = std::abs(c.x());
    if (c.z() > 0 && c.y() > 1.2 && n.z() > 0.6 && ax > 0.10 && ax < 0.40) return "headlight";
    if (c.z() < -1.49 && n.z() < -0.9 && ax > 0.40 && ax < 0.52) return "taillight";
    // The rail cell under the seat is the seat's base between x = +-0.25.
    const bool underSeat = c.z() > -0.56 && c.z() < -0.04 && c.y() > railLo && c.y() < 0.56;
    return underSeat && ax < 0.251 ? "seat" : material;
  };
  return {"buggy", buildPrismSolid(b), true};
}

// Wheel: 0.35 m radius, 0.25 m wide, axle along X, centred at the origin.
ObjModel wheel() {
  ObjModel m{"wheel", {}, true};
  Part tyre = frustum("tyre", "tyre", {-0.125, 0, 0}, V3::UnitX(), 0.25, 0.35, 0.35, 32, 3.0);
  Part sides = splitOff(tyre, "rim", "rim", [](const V3& n) { return std::abs(n.x()) > 0.9; });
  m.parts.push_back(tyre);
  m.parts.push_back(sides);
  return m;
}

// Cockpit interior around the driver's eye (the origin), looking along +Z:
// dashboard, steering wheel and column, seats, pillars, roof and doors.
ObjModel cockpit() {
  ObjModel m{"cockpit", {}};
  m.parts.push_back(box("dashboard", "dashboard", {-0.35, -0.33, 0.72}, {0.8, 0.12, 0.14}));
  m.parts.push_back(box("instrument_hood", "dashboard", {0, -0.18, 0.62}, {0.2, 0.04, 0.08}));
  const V3 wheelCentre(0, -0.32, 0.42);
  const V3 wheelAxis = V3(0, 0.45, -1).normalized();
  m.parts.push_back(torus("steering_wheel", "plastic_black", wheelCentre, wheelAxis, 0.18, 0.018, 32, 8));
  m.parts.push_back(frustum("steering_column", "plastic_black", wheelCentre, -wheelAxis, 0.3, 0.025, 0.03, 10));
  m.parts.push_back(frustum("steering_hub", "trim", wheelCentre, -wheelAxis, 0.04, 0.05, 0.05, 16));
  m.parts.push_back(box("seat_driver", "seat", {0, -0.65, -0.15}, {0.26, 0.08, 0.26}));
  m.parts.push_back(box("seat_driver_back", "seat", {0, -0.25, -0.45}, {0.26, 0.35, 0.06}));
  m.parts.push_back(box("seat_passenger", "seat", {-0.7, -0.65, -0.15}, {0.26, 0.08, 0.26}));
  m.parts.push_back(box("seat_passenger_back", "seat", {-0.7, -0.25, -0.45}, {0.26, 0.35, 0.06}));
  auto pillar = [&](const std::string& name, const V3& a, const V3& b) {
    m.parts.push_back(frustum(name, "trim", a, b - a, (b - a).norm(), 0.04, 0.04, 8));
  };
  pillar("a_pillar_left", {0.45, -0.22, 0.82}, {0.42, 0.36, 0.22});
  pillar("a_pillar_right", {-1.15, -0.22, 0.82}, {-1.12, 0.36, 0.22});
  m.parts.push_back(box("roof_liner", "trim", {-0.35, 0.4, -0.3}, {0.82, 0.03, 0.55}));
  m.parts.push_back(box("door_left", "trim", {0.5, -0.42, 0.1}, {0.03, 0.24, 0.7}));
  m.parts.push_back(box("door_right", "trim", {-1.2, -0.42, 0.1}, {0.03, 0.24, 0.7}));
  return m;
}

ObjModel rock() {
  ObjModel m{"rock", {}};
  // About 1.6 x 1.0 x 1.3 m, sunk 0.15 m into the ground.
  m.parts.push_back(icosphere("rock", "rock", {0, 0.35, 0}, {0.8, 0.5, 0.65}, 2, 0.18, 7));
  return m;
}

ObjModel tree() {
  ObjModel m{"tree", {}};
  m.parts.push_back(frustum("trunk", "bark", {0, 0, 0}, V3::UnitY(), 1.6, 0.18, 0.12, 12, 2.0));
  m.parts.push_back(frustum("crown_low", "leaves", {0, 1.2, 0}, V3::UnitY(), 2.0, 1.3, 0.15, 16, 2.0));
  m.parts.push_back(frustum("crown_high", "leaves", {0, 2.5, 0}, V3::UnitY(), 1.8, 0.9, 0.05, 16, 2.0));
  return m;
}

ObjModel building() {
  ObjModel m{"building", {}};
  m.parts.push_back(box("walls", "building", {0, 3.0, 0}, {4.0, 3.0, 5.0}, 1.0 / 3.0));
  m.parts.push_back(box("roof", "roof", {0, 6.15, 0}, {4.2, 0.15, 5.2}));
  return m;
}

ObjModel barrier() {
  ObjModel m{"barrier", {}};
  m.parts.push_back(box("barrier", "stripes", {0, 0.4, 0}, {1.0, 0.4, 0.2}, 1.0));
  return m;
}

// Jump ramp for designed courses: 4 m wide, rising over 6 m along +Z from
// the ground to a 0.9 m lip (8.5 degrees), where it drops straight down. A
// car driven along +Z climbs it and leaves the lip in the air.
constexpr double kRampHalfWidth = 2.0, kRampHalfLength = 3.0, kRampLip = 0.9;
ObjModel ramp() {
  PrismSolid r;
  r.stations = {-kRampHalfWidth, kRampHalfWidth};
  const int back = r.point(-kRampHalfLength, 0), front = r.point(kRampHalfLength, 0);
  const int lip = r.point(kRampHalfLength, kRampLip);
  r.cell({back, front, lip}, "ramp_deck", [](double) { return true; });
  // The deck grey, the sides and the lip's face striped so the edge shows.
  r.paint = [](const V3&, const V3& n, const std::string& material) -> std::string {
    return n.y() > 0.5 ? material : "stripes";
  };
  return {"ramp", buildPrismSolid(r), true};
}

// Checkpoint arch: two posts 8 m apart (x = +-4), a chequered banner on top.
ObjModel arch() {
  ObjModel m{"checkpoint_arch", {}};
  m.parts.push_back(box("post_left", "post", {4.0, 2.2, 0}, {0.2, 2.2, 0.2}));
  m.parts.push_back(box("post_right", "post", {-4.0, 2.2, 0}, {0.2, 2.2, 0.2}));
  m.parts.push_back(box("banner", "checker", {0, 4.8, 0}, {4.4, 0.4, 0.1}, 1.25));
  return m;
}

// ---- writers ---------------------------------------------------------------

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.5f", v == 0 ? 0.0 : v);  // no "-0.00000"
  std::string s = buf;
  if (s == "-0.00000") s = "0.00000";
  return s;
}

GeneratedFile writeObj(const ObjModel& model) {
  std::string out = "# " + model.name + ": generated by `tumble meshgen` (tools/meshgen/meshgen.cpp); do not edit\n";
  out += model.oneSurface ? "# Y up, metres, front +Z. The objects together are one closed outward-wound surface.\n"
                          : "# Y up, metres, front +Z. Every object is a closed outward-wound surface.\n";
  out += "mtllib " + model.name + ".mtl\n";
  std::size_t base = 1;
  for (const Part& part : model.parts) {
    out += "o " + part.name + "\n";
    for (const Vertex& v : part.v) out += "v " + fmt(v.p.x()) + " " + fmt(v.p.y()) + " " + fmt(v.p.z()) + "\n";
    for (const Vertex& v : part.v) out += "vt " + fmt(v.uv.x()) + " " + fmt(v.uv.y()) + "\n";
    for (const Vertex& v : part.v) out += "vn " + fmt(v.n.x()) + " " + fmt(v.n.y()) + " " + fmt(v.n.z()) + "\n";
    out += "usemtl " + part.material + "\n";
    for (const auto& t : part.t) {
      out += "f";
      for (int k : t) {
        const std::string i = std::to_string(base + std::size_t(k));
        out += " " + i + "/" + i + "/" + i;
      }
      out += "\n";
    }
    base += part.v.size();
  }
  return {model.name + ".obj", out};
}

GeneratedFile writeMtl(const ObjModel& model) {
  std::string out = "# " + model.name + ": generated by `tumble meshgen`; do not edit\n";
  std::vector<std::string> used;
  for (const Part& part : model.parts) {
    if (std::find(used.begin(), used.end(), part.material) == used.end()) used.push_back(part.material);
  }
  for (const std::string& name : used) {
    const auto& list = materials();
    auto it = std::find_if(list.begin(), list.end(), [&](const Material& m) { return m.name == name; });
    out += "\nnewmtl " + name + "\n";
    out += "Kd " + fmt(it->kd.x()) + " " + fmt(it->kd.y()) + " " + fmt(it->kd.z()) + "\n";
    out += "Ka 0.00000 0.00000 0.00000\nKs 0.10000 0.10000 0.10000\nNs 20\nd 1\nillum 2\n";
    if (!it->texture.empty()) out += "map_Kd " + it->texture + "\n";
    if (!it->ke.isZero()) out += "Ke " + fmt(it->ke.x()) + " " + fmt(it->ke.y()) + " " + fmt(it->ke.z()) + "\n";
  }
  return {model.name + ".mtl", out};
}

// A folder's files: each model's .obj and .mtl, then the textures its
// materials name, in textures()' order.
GeneratedFolder folderOf(const std::string& path, const std::vector<ObjModel>& models) {
  GeneratedFolder folder{path, {}};
  std::vector<std::string> used;
  for (const ObjModel& model : models) {
    folder.files.push_back(writeObj(model));
    folder.files.push_back(writeMtl(model));
    for (const Part& part : model.parts) {
      const auto& list = materials();
      auto it = std::find_if(list.begin(), list.end(), [&](const Material& m) { return m.name == part.material; });
      if (!it->texture.empty()) used.push_back(it->texture);
    }
  }
  for (GeneratedFile& png : textures())
    if (std::find(used.begin(), used.end(), png.name) != used.end()) folder.files.push_back(std::move(png));
  return folder;
}

}  // namespace

std::vector<GeneratedFolder> generateModelFolders() {
  return {folderOf("assets/models", {wheel()}),
          folderOf("mods/base/assets/models",
                   {hatchback(false), hatchback(true), truck(false), truck(true), buggy(), cockpit(), rock(), tree(), building(), barrier(), arch(),
                    ramp()})};
}

Result<std::vector<std::string>> writeModelFolders(const std::string& root) {
  std::vector<std::string> lines;
  for (const GeneratedFolder& folder : generateModelFolders()) {
    const std::filesystem::path dir = std::filesystem::path(root) / folder.path;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) return makeError(dir.string() + ": cannot create the folder (" + ec.message() + ")");
    for (const GeneratedFile& file : folder.files)
      if (Status s = writeFileAtomic((dir / file.name).string(), file.bytes); !s) return makeError(s.error());
    lines.push_back(std::to_string(folder.files.size()) + " files to " + dir.string());
  }
  return lines;
}

void addMeshgenOptions(CLI::App& cli, int& exitCode) {
  auto root = std::make_shared<std::string>(TUMBLE_SOURCE_TREE);
  cli.add_option("--out", *root,
                 "top folder to write under: ROOT/assets/models and ROOT/mods/base/assets/models (default: the "
                 "source tree, " TUMBLE_SOURCE_TREE ")");
  cli.callback([root, &exitCode] {
    auto written = writeModelFolders(*root);
    if (!written) {
      log::error("meshgen: " + written.error());
      exitCode = 1;
      return;
    }
    for (const std::string& line : *written) std::printf("meshgen: wrote %s\n", line.c_str());
    exitCode = 0;
  });
}

}  // namespace tumble::tools
