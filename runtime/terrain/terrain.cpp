#include "terrain/terrain.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::terrain {

namespace {

using Vec3d = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Ray {
  Vec3d origin;
  Vec3d dir;  // unit
};

// Slab test against [lo, hi]; narrows [t0, t1]. Axis-parallel rays are
// handled explicitly so 0 * inf never produces NaN.
bool clipToBox(const Ray& r, const Vec3d& lo, const Vec3d& hi, double& t0, double& t1) {
  for (int k = 0; k < 3; ++k) {
    if (r.dir[k] == 0) {
      if (r.origin[k] < lo[k] || r.origin[k] > hi[k]) return false;
      continue;
    }
    const double inv = 1.0 / r.dir[k];
    double a = (lo[k] - r.origin[k]) * inv, b = (hi[k] - r.origin[k]) * inv;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

// Moller-Trumbore, two-sided. Returns the ray parameter in t.
bool intersectTriangle(const Ray& r, const Vec3d& p0, const Vec3d& p1, const Vec3d& p2, double& t) {
  const Vec3d e1 = p1 - p0, e2 = p2 - p0;
  const Vec3d pv = r.dir.cross(e2);
  const double det = e1.dot(pv);
  if (det == 0) return false;
  const double inv = 1.0 / det;
  const Vec3d tv = r.origin - p0;
  const double u = tv.dot(pv) * inv;
  if (u < 0 || u > 1) return false;
  const Vec3d qv = tv.cross(e1);
  const double v = r.dir.dot(qv) * inv;
  if (v < 0 || u + v > 1) return false;
  t = e2.dot(qv) * inv;
  return true;
}

// Unit normal of a block half from its corner heights in metres: the plane
// y = y00 + a*dx + b*dz has normal (-a, 1, -b).
Vec3 faceNormal(double y00, double y10, double y01, double y11, int half, double spacing) {
  const double a = half == 0 ? (y10 - y00) / spacing : (y11 - y01) / spacing;  // dy/dx
  const double b = half == 0 ? (y11 - y10) / spacing : (y01 - y00) / spacing;  // dy/dz
  return Vec3d(-a, 1.0, -b).normalized().cast<Real>();
}

}  // namespace

Frustum Frustum::fromViewProjection(const Eigen::Matrix<Real, 4, 4>& m) {
  Frustum f;
  const Vec4 r0 = m.row(0).transpose(), r1 = m.row(1).transpose(), r2 = m.row(2).transpose(),
             r3 = m.row(3).transpose();
  f.planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
  for (Vec4& p : f.planes) {
    const Real n = p.head<3>().norm();
    if (n > 0) p /= n;
  }
  return f;
}

// --- creation ----------------------------------------------------------------

Result<Terrain> Terrain::create(HeightMap heights, const TerrainDesc& desc, int leafBlocks) {
  if (auto ok = checkHeightMapSize(heights.width(), heights.height(), "terrain"); !ok) return makeError(ok.error());
  if (!(desc.spacing_m > 0) || !std::isfinite(desc.spacing_m))
    return makeError("terrain: spacing_m must be a finite number > 0 (metres between samples)");
  if (!(desc.heightScale_m > 0) || !std::isfinite(desc.heightScale_m))
    return makeError("terrain: height_scale_m must be a finite number > 0 (metres per 16-bit unit)");
  if (!std::isfinite(desc.baseHeight_m) || !std::isfinite(desc.originX_m) || !std::isfinite(desc.originZ_m))
    return makeError("terrain: base_height_m, origin_x_m and origin_z_m must be finite");
  Terrain t;
  t.m_heights = std::move(heights);
  t.m_desc = desc;
  t.m_tree.build(t.m_heights, leafBlocks);
  return t;
}

Result<Terrain> Terrain::loadPng(const std::string& path, const TerrainDesc& defaults, int leafBlocks) {
  auto map = loadHeightMapPng(path);
  if (!map) return makeError(map.error());
  auto desc = loadSidecar(path, defaults);
  if (!desc) return makeError(desc.error());
  auto t = create(std::move(*map), *desc, leafBlocks);
  if (!t) return makeError(path + ": " + t.error());
  return t;
}

// --- world mapping -------------------------------------------------------------

Vec3 Terrain::samplePosition(int i, int j) const {
  return Vec3(Real(m_desc.originX_m + i * m_desc.spacing_m), Real(toHeight_m(m_heights.at(i, j))),
              Real(m_desc.originZ_m + j * m_desc.spacing_m));
}

bool Terrain::contains(Real x_m, Real z_m) const {
  const double gx = (x_m - m_desc.originX_m) / m_desc.spacing_m, gz = (z_m - m_desc.originZ_m) / m_desc.spacing_m;
  return gx >= 0 && gz >= 0 && gx <= blocksX() && gz <= blocksZ();
}

void Terrain::blockAt(Real x_m, Real z_m, int& bi, int& bj) const {
  double gx = (x_m - m_desc.originX_m) / m_desc.spacing_m, gz = (z_m - m_desc.originZ_m) / m_desc.spacing_m;
  // A NaN position (a body that blew up) must not become an out-of-range index.
  if (std::isnan(gx)) gx = 0;
  if (std::isnan(gz)) gz = 0;
  bi = int(std::clamp(std::floor(gx), 0.0, double(blocksX() - 1)));
  bj = int(std::clamp(std::floor(gz), 0.0, double(blocksZ() - 1)));
}

// --- point queries -------------------------------------------------------------

Real Terrain::heightAt(Real x_m, Real z_m) const {
  int bi, bj;
  blockAt(x_m, z_m, bi, bj);
  const double u = std::clamp((x_m - m_desc.originX_m) / m_desc.spacing_m - bi, 0.0, 1.0);
  const double v = std::clamp((z_m - m_desc.originZ_m) / m_desc.spacing_m - bj, 0.0, 1.0);
  const double h00 = m_heights.at(bi, bj), h10 = m_heights.at(bi + 1, bj);
  const double h01 = m_heights.at(bi, bj + 1), h11 = m_heights.at(bi + 1, bj + 1);
  const double h = u >= v ? h00 + u * (h10 - h00) + v * (h11 - h10) : h00 + v * (h01 - h00) + u * (h11 - h01);
  return Real(toHeight_m(h));
}

Vec3 Terrain::normalAt(Real x_m, Real z_m) const {
  int bi, bj;
  blockAt(x_m, z_m, bi, bj);
  const double u = std::clamp((x_m - m_desc.originX_m) / m_desc.spacing_m - bi, 0.0, 1.0);
  const double v = std::clamp((z_m - m_desc.originZ_m) / m_desc.spacing_m - bj, 0.0, 1.0);
  return faceNormal(toHeight_m(m_heights.at(bi, bj)), toHeight_m(m_heights.at(bi + 1, bj)),
                    toHeight_m(m_heights.at(bi, bj + 1)), toHeight_m(m_heights.at(bi + 1, bj + 1)), u >= v ? 0 : 1,
                    m_desc.spacing_m);
}

TerrainTriangle Terrain::triangle(std::uint32_t block, int half) const {
  const int bi = int(block % std::uint32_t(blocksX())), bj = int(block / std::uint32_t(blocksX()));
  const Vec3 p00 = samplePosition(bi, bj), p10 = samplePosition(bi + 1, bj);
  const Vec3 p01 = samplePosition(bi, bj + 1), p11 = samplePosition(bi + 1, bj + 1);
  TerrainTriangle t;
  t.vertices = half == 0 ? std::array<Vec3, 3>{p00, p11, p10} : std::array<Vec3, 3>{p00, p01, p11};
  t.normal = faceNormal(p00.y(), p10.y(), p01.y(), p11.y(), half, m_desc.spacing_m);
  t.block = block;
  t.half = std::uint8_t(half);
  return t;
}

// --- ray cast ------------------------------------------------------------------

std::optional<RayHit> Terrain::rayCast(const Vec3& origin, const Vec3& direction, Real maxDistance_m) const {
  Ray ray{origin.cast<double>(), direction.cast<double>()};
  const double len = ray.dir.norm();
  if (!(len > 0) || !ray.origin.allFinite() || !ray.dir.allFinite() || !(maxDistance_m >= 0)) return std::nullopt;
  ray.dir /= len;
  const TerrainDesc& d = m_desc;
  const double s = d.spacing_m;
  // Boxes are padded by a hair so rounding can only make them bigger: the
  // tree may then test a few extra blocks, but never skips a hit.
  const double padXZ = 1e-7 * s;
  auto nodeBox = [&](const NodeRef& r, Vec3d& lo, Vec3d& hi) {
    const BlockRange b = m_tree.blocks(r);
    const TreeNode& n = m_tree.node(r);
    lo = {d.originX_m + b.bi0 * s - padXZ, toHeight_m(n.minHeight), d.originZ_m + b.bj0 * s - padXZ};
    hi = {d.originX_m + b.bi1 * s + padXZ, toHeight_m(n.maxHeight), d.originZ_m + b.bj1 * s + padXZ};
    const double padY = 1e-9 * (1 + std::abs(lo.y()) + std::abs(hi.y()));
    lo.y() -= padY;
    hi.y() += padY;
  };

  double best = maxDistance_m;
  std::optional<RayHit> hit;
  const int stepX = ray.dir.x() > 0 ? 1 : (ray.dir.x() < 0 ? -1 : 0);
  const int stepZ = ray.dir.z() > 0 ? 1 : (ray.dir.z() < 0 ? -1 : 0);
  const double deltaX = stepX ? s / std::abs(ray.dir.x()) : kInf;
  const double deltaZ = stepZ ? s / std::abs(ray.dir.z()) : kInf;

  // Tests both halves of a block; updates best/hit. True if either was hit.
  auto testBlock = [&](int bi, int bj, double tA, double tB) {
    const double y00 = toHeight_m(m_heights.at(bi, bj)), y10 = toHeight_m(m_heights.at(bi + 1, bj));
    const double y01 = toHeight_m(m_heights.at(bi, bj + 1)), y11 = toHeight_m(m_heights.at(bi + 1, bj + 1));
    const double lo = std::min(std::min(y00, y10), std::min(y01, y11));
    const double hi = std::max(std::max(y00, y10), std::max(y01, y11));
    const double yA = ray.origin.y() + tA * ray.dir.y(), yB = ray.origin.y() + tB * ray.dir.y();
    const double pad = 1e-6 * (1 + std::abs(lo) + std::abs(hi));
    if (std::max(yA, yB) < lo - pad || std::min(yA, yB) > hi + pad) return false;
    const double x0 = d.originX_m + bi * s, z0 = d.originZ_m + bj * s;
    const Vec3d p00(x0, y00, z0), p10(x0 + s, y10, z0), p01(x0, y01, z0 + s), p11(x0 + s, y11, z0 + s);
    bool any = false;
    for (int half = 0; half < 2; ++half) {
      double t;
      const bool ok = half == 0 ? intersectTriangle(ray, p00, p11, p10, t) : intersectTriangle(ray, p00, p01, p11, t);
      if (ok && t >= 0 && t <= best) {
        best = t;
        any = true;
        RayHit h;
        h.distance_m = Real(t);
        h.point = (ray.origin + t * ray.dir).cast<Real>();
        h.normal = faceNormal(y00, y10, y01, y11, half, s);
        h.block = std::uint32_t(bj) * std::uint32_t(blocksX()) + std::uint32_t(bi);
        h.half = std::uint8_t(half);
        hit = h;
      }
    }
    return any;
  };

  // Inside a leaf: 2D DDA (Amanatides & Woo) over its blocks in ray order,
  // so the first block with a hit holds the closest hit of the leaf.
  auto walkLeaf = [&](const NodeRef& r, double t0, double t1) {
    const BlockRange b = m_tree.blocks(r);
    const Vec3d p = ray.origin + t0 * ray.dir;
    int bi = int(std::clamp(std::floor((p.x() - d.originX_m) / s), double(b.bi0), double(b.bi1 - 1)));
    int bj = int(std::clamp(std::floor((p.z() - d.originZ_m) / s), double(b.bj0), double(b.bj1 - 1)));
    double tMaxX = stepX ? (d.originX_m + (bi + (stepX > 0)) * s - ray.origin.x()) / ray.dir.x() : kInf;
    double tMaxZ = stepZ ? (d.originZ_m + (bj + (stepZ > 0)) * s - ray.origin.z()) / ray.dir.z() : kInf;
    double tCell = t0;
    for (;;) {
      const double tNext = std::min(tMaxX, tMaxZ);
      if (testBlock(bi, bj, tCell, std::min(tNext, t1))) return;
      if (tNext > std::min(t1, best)) return;
      tCell = tNext;
      if (tMaxX < tMaxZ) {
        bi += stepX;
        tMaxX += deltaX;
      } else {
        bj += stepZ;
        tMaxZ += deltaZ;
      }
      if (bi < b.bi0 || bi >= b.bi1 || bj < b.bj0 || bj >= b.bj1) return;
    }
  };

  struct Item {
    NodeRef ref;
    double tEnter, tExit;
  };
  std::array<Item, 4 * HeightTree::kMaxLevels> stack;
  int top = 0;
  {
    Vec3d lo, hi;
    nodeBox({0, 0, 0}, lo, hi);
    double t0 = 0, t1 = best;
    if (!clipToBox(ray, lo, hi, t0, t1)) return std::nullopt;
    stack[std::size_t(top++)] = {{0, 0, 0}, t0, t1};
  }
  std::array<NodeRef, 4> kids;
  const int leaf = m_tree.leafLevel();
  while (top > 0) {
    const Item item = stack[std::size_t(--top)];
    if (item.tEnter > best) continue;
    if (item.ref.level == leaf) {
      walkLeaf(item.ref, item.tEnter, std::min(item.tExit, best));
      continue;
    }
    // Push children far-to-near so the nearest is popped first; once a hit
    // is found, farther boxes are skipped by the tEnter > best test.
    std::array<Item, 4> near;
    int n = 0;
    const int count = m_tree.children(item.ref, kids);
    for (int k = 0; k < count; ++k) {
      Vec3d lo, hi;
      nodeBox(kids[std::size_t(k)], lo, hi);
      double t0 = 0, t1 = best;
      if (!clipToBox(ray, lo, hi, t0, t1)) continue;
      Item it{kids[std::size_t(k)], t0, t1};
      int pos = n++;
      while (pos > 0 && near[std::size_t(pos - 1)].tEnter < t0) {
        near[std::size_t(pos)] = near[std::size_t(pos - 1)];
        --pos;
      }
      near[std::size_t(pos)] = it;
    }
    for (int k = 0; k < n; ++k) stack[std::size_t(top++)] = near[std::size_t(k)];
  }
  return hit;
}

// --- box overlap -----------------------------------------------------------------

void Terrain::visitTrianglesInBox(const Aabb& box, TriangleVisitor visit, void* ctx) const {
  const TerrainDesc& d = m_desc;
  const double s = d.spacing_m;
  const double bx0 = (box.min.x() - d.originX_m) / s, bx1 = (box.max.x() - d.originX_m) / s;
  const double bz0 = (box.min.z() - d.originZ_m) / s, bz1 = (box.max.z() - d.originZ_m) / s;
  if (bx1 < 0 || bz1 < 0 || bx0 > blocksX() || bz0 > blocksZ()) return;
  // Blocks whose closed X/Z extent touches the box.
  const int qi0 = std::max(0, int(std::ceil(bx0)) - 1), qi1 = std::min(blocksX() - 1, int(std::floor(bx1)));
  const int qj0 = std::max(0, int(std::ceil(bz0)) - 1), qj1 = std::min(blocksZ() - 1, int(std::floor(bz1)));
  auto yOverlaps = [&](double lo, double hi) { return lo <= box.max.y() && hi >= box.min.y(); };

  std::array<NodeRef, 4 * HeightTree::kMaxLevels> stack;
  int top = 0;
  stack[std::size_t(top++)] = {0, 0, 0};
  std::array<NodeRef, 4> kids;
  while (top > 0) {
    const NodeRef r = stack[std::size_t(--top)];
    const BlockRange b = m_tree.blocks(r);
    if (b.bi1 - 1 < qi0 || b.bi0 > qi1 || b.bj1 - 1 < qj0 || b.bj0 > qj1) continue;
    const TreeNode& n = m_tree.node(r);
    if (!yOverlaps(toHeight_m(n.minHeight), toHeight_m(n.maxHeight))) continue;
    const int count = m_tree.children(r, kids);
    if (count > 0) {
      for (int k = 0; k < count; ++k) stack[std::size_t(top++)] = kids[std::size_t(k)];
      continue;
    }
    for (int bj = std::max(b.bj0, qj0); bj <= std::min(b.bj1 - 1, qj1); ++bj)
      for (int bi = std::max(b.bi0, qi0); bi <= std::min(b.bi1 - 1, qi1); ++bi) {
        const double y00 = toHeight_m(m_heights.at(bi, bj)), y10 = toHeight_m(m_heights.at(bi + 1, bj));
        const double y01 = toHeight_m(m_heights.at(bi, bj + 1)), y11 = toHeight_m(m_heights.at(bi + 1, bj + 1));
        const double x0 = d.originX_m + bi * s, z0 = d.originZ_m + bj * s;
        const Vec3 p00 = Vec3d(x0, y00, z0).cast<Real>(), p10 = Vec3d(x0 + s, y10, z0).cast<Real>();
        const Vec3 p01 = Vec3d(x0, y01, z0 + s).cast<Real>(), p11 = Vec3d(x0 + s, y11, z0 + s).cast<Real>();
        const std::uint32_t block = std::uint32_t(bj) * std::uint32_t(blocksX()) + std::uint32_t(bi);
        if (yOverlaps(std::min({y00, y11, y10}), std::max({y00, y11, y10}))) {
          TerrainTriangle t{{p00, p11, p10}, faceNormal(y00, y10, y01, y11, 0, s), block, 0};
          visit(ctx, t);
        }
        if (yOverlaps(std::min({y00, y01, y11}), std::max({y00, y01, y11}))) {
          TerrainTriangle t{{p00, p01, p11}, faceNormal(y00, y10, y01, y11, 1, s), block, 1};
          visit(ctx, t);
        }
      }
  }
}

void Terrain::overlapBox(const Aabb& box, std::vector<TerrainTriangle>& out, std::vector<std::uint32_t>* objects) const {
  out.clear();
  forEachTriangleInBox(box, [&out](const TerrainTriangle& t) { out.push_back(t); });
  if (objects) {
    objects->clear();
    m_objects.query(m_tree, m_desc, box, *objects);
  }
}

// --- frustum culling --------------------------------------------------------------

Aabb Terrain::nodeBounds(std::uint32_t nodeIndex) const {
  const NodeRef r = m_tree.ref(nodeIndex);
  const BlockRange b = m_tree.blocks(r);
  const TreeNode& n = m_tree.node(nodeIndex);
  const double s = m_desc.spacing_m;
  return {Vec3(Real(m_desc.originX_m + b.bi0 * s), Real(toHeight_m(n.minHeight)), Real(m_desc.originZ_m + b.bj0 * s)),
          Vec3(Real(m_desc.originX_m + b.bi1 * s), Real(toHeight_m(n.maxHeight)), Real(m_desc.originZ_m + b.bj1 * s))};
}

void Terrain::frustumCull(const Frustum& frustum, int level, std::vector<std::uint32_t>& out) const {
  out.clear();
  const int target = std::clamp(level, 0, m_tree.leafLevel());
  enum class Side { Outside, Partial, Inside };
  auto classify = [&](const NodeRef& r) {
    const Aabb box = nodeBounds(m_tree.index(r));
    bool inside = true;
    for (const Vec4& p : frustum.planes) {
      // The corner farthest along the plane normal decides "outside"; the
      // nearest decides "inside".
      const Vec3 far(p.x() >= 0 ? box.max.x() : box.min.x(), p.y() >= 0 ? box.max.y() : box.min.y(),
                     p.z() >= 0 ? box.max.z() : box.min.z());
      const Vec3 nearest(p.x() >= 0 ? box.min.x() : box.max.x(), p.y() >= 0 ? box.min.y() : box.max.y(),
                         p.z() >= 0 ? box.min.z() : box.max.z());
      if (p.head<3>().dot(far) + p.w() < 0) return Side::Outside;
      if (p.head<3>().dot(nearest) + p.w() < 0) inside = false;
    }
    return inside ? Side::Inside : Side::Partial;
  };
  std::array<NodeRef, 4 * HeightTree::kMaxLevels> stack;
  int top = 0;
  stack[std::size_t(top++)] = {0, 0, 0};
  std::array<NodeRef, 4> kids;
  while (top > 0) {
    const NodeRef r = stack[std::size_t(--top)];
    const Side side = classify(r);
    if (side == Side::Outside) continue;
    if (r.level == target) {
      out.push_back(m_tree.index(r));
      continue;
    }
    if (side == Side::Inside) {
      // Every descendant at the target level is visible: list them without tests.
      const int shift = target - r.level;
      const int x1 = std::min((r.x + 1) << shift, m_tree.levelWidth(target));
      const int z1 = std::min((r.z + 1) << shift, m_tree.levelHeight(target));
      for (int z = r.z << shift; z < z1; ++z)
        for (int x = r.x << shift; x < x1; ++x) out.push_back(m_tree.index(target, x, z));
      continue;
    }
    const int n = m_tree.children(r, kids);
    for (int k = 0; k < n; ++k) stack[std::size_t(top++)] = kids[std::size_t(k)];
  }
}

// --- materials ---------------------------------------------------------------------

MaterialMaps& Terrain::createMaterials(const MaterialDefaults& defaults) {
  if (!m_materials) m_materials.emplace(blocksX(), blocksZ(), defaults);
  return *m_materials;
}

Real Terrain::frictionAt(Real x_m, Real z_m) const {
  if (!m_materials) return Real(MaterialDefaults{}.friction * kFrictionPerUnit);
  int bi, bj;
  blockAt(x_m, z_m, bi, bj);
  return Real(m_materials->frictionCoefficient(bi, bj));
}

Real Terrain::softnessAt(Real x_m, Real z_m) const {
  if (!m_materials) return Real(MaterialDefaults{}.softness * kSoftnessPerUnit);
  int bi, bj;
  blockAt(x_m, z_m, bi, bj);
  return Real(m_materials->softness(bi, bj));
}

// --- memory ------------------------------------------------------------------------

TerrainMemory Terrain::memory() const {
  TerrainMemory m;
  m.heights = m_heights.bytes();
  m.tree = m_tree.bytes();
  m.materials = m_materials ? m_materials->bytes() : 0;
  m.staticObjects = m_objects.approximateBytes();
  return m;
}

}  // namespace tumble::terrain
