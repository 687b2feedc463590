// terrain_rays: the same batch of rays against the same height field in
// Tumble (terrain::Terrain::rayCast, the implicit quad-tree of AABBs) and in
// Bullet 3 (btHeightfieldTerrainShape in a btCollisionWorld, closest hit),
// the terrain's ray-cast target.
//
// Same triangles: Bullet gets the heights in metres as floats (PHY_FLOAT,
// scale 1), local scaling (spacing, 1, spacing), and flipQuadEdges chosen so
// its quads are cut along the same diagonal as Tumble's (p00-p11; the tool
// checks it: `agreement` counts rays whose hit/miss or distance differ).
// btHeightfieldTerrainShape centres the field on its local origin (X/Z
// midpoint, Y midway between min and max height), so the object sits there.
//
// The batch mixes what games cast: vertical probes (wheels, feet, picking
// from above), steep rays (30-80 degrees down: camera and mouse picks) and
// long grazing rays (2-10 degrees down over 400 m: line of sight, bullets).
// Two Bullet variants are timed: the plain walk of the grid cells along the
// ray (performRaycast) and with buildAccelerator() (16 x 16 chunk min/max).
#include "terrain_rays.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "terrain/generators.h"
#include "terrain/terrain.h"

namespace tumble::compare {

namespace {

struct Ray {
  Vec3 origin, direction;  // direction unit
  Real length_m;
};

struct Hits {
  std::vector<double> distance_m;  // < 0: no hit
  double seconds = 0;
};

std::vector<Ray> makeRays(const terrain::Terrain& t, int count, std::uint64_t seed) {
  const terrain::Aabb b = t.bounds();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Ray> rays;
  rays.reserve(std::size_t(count));
  for (int i = 0; i < count; ++i) {
    Ray r;
    const double x = b.min.x() + u(rng) * (b.max.x() - b.min.x());
    const double z = b.min.z() + u(rng) * (b.max.z() - b.min.z());
    const double top = b.max.y() + 5;
    const double heading = u(rng) * 2 * 3.14159265358979;
    double pitch_deg = 0, length = 0;
    switch (i % 3) {
      case 0: pitch_deg = 90, length = top - b.min.y() + 10; break;         // vertical probe
      case 1: pitch_deg = 30 + 50 * u(rng), length = 200; break;           // steep pick
      default: pitch_deg = 2 + 8 * u(rng), length = 400; break;            // grazing line of sight
    }
    const double p = pitch_deg * 3.14159265358979 / 180;
    r.origin = Vec3(Real(x), Real(i % 3 == 0 ? top : b.min.y() + (top - b.min.y()) * (0.5 + 0.5 * u(rng))), Real(z));
    r.direction = Vec3(Real(std::cos(p) * std::cos(heading)), Real(-std::sin(p)), Real(std::cos(p) * std::sin(heading)));
    r.direction.normalize();
    r.length_m = Real(length);
    rays.push_back(r);
  }
  return rays;
}

Hits castTumble(const terrain::Terrain& t, const std::vector<Ray>& rays) {
  Hits h;
  h.distance_m.resize(rays.size());
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    auto hit = t.rayCast(rays[i].origin, rays[i].direction, rays[i].length_m);
    h.distance_m[i] = hit ? double(hit->distance_m) : -1.0;
  }
  h.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return h;
}

struct BulletField {
  std::vector<float> heights_m;
  std::unique_ptr<btHeightfieldTerrainShape> shape;
  std::unique_ptr<btCollisionObject> object;
  btDefaultCollisionConfiguration config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  btDbvtBroadphase broadphase;
  std::unique_ptr<btCollisionWorld> world;

  BulletField(const terrain::Terrain& t, bool flipQuadEdges, bool accelerate) {
    const auto& map = t.heights();
    const int w = map.width(), l = map.height();
    heights_m.resize(std::size_t(w) * std::size_t(l));
    float lo = 1e30f, hi = -1e30f;
    for (int j = 0; j < l; ++j)
      for (int i = 0; i < w; ++i) {
        const float y = float(t.toHeight_m(map.at(i, j)));
        heights_m[std::size_t(j) * std::size_t(w) + std::size_t(i)] = y;
        lo = std::min(lo, y), hi = std::max(hi, y);
      }
    shape = std::make_unique<btHeightfieldTerrainShape>(w, l, heights_m.data(), btScalar(1), btScalar(lo), btScalar(hi),
                                                        1, PHY_FLOAT, flipQuadEdges);
    const double spacing = t.desc().spacing_m;
    shape->setLocalScaling(btVector3(btScalar(spacing), 1, btScalar(spacing)));
    if (accelerate) shape->buildAccelerator();
    object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(shape.get());
    const terrain::Aabb b = t.bounds();
    btTransform tr;
    tr.setIdentity();
    tr.setOrigin(btVector3(btScalar((b.min.x() + b.max.x()) / 2), btScalar((lo + hi) / 2.0f),
                           btScalar((b.min.z() + b.max.z()) / 2)));
    object->setWorldTransform(tr);
    dispatcher = std::make_unique<btCollisionDispatcher>(&config);
    world = std::make_unique<btCollisionWorld>(dispatcher.get(), &broadphase, &config);
    world->addCollisionObject(object.get());
    world->updateAabbs();
  }

  Hits cast(const std::vector<Ray>& rays) const {
    Hits h;
    h.distance_m.resize(rays.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Ray& r = rays[i];
      const btVector3 from(btScalar(r.origin.x()), btScalar(r.origin.y()), btScalar(r.origin.z()));
      const Vec3 end = r.origin + r.direction * r.length_m;
      const btVector3 to(btScalar(end.x()), btScalar(end.y()), btScalar(end.z()));
      btCollisionWorld::ClosestRayResultCallback cb(from, to);
      world->rayTest(from, to, cb);
      h.distance_m[i] = cb.hasHit() ? double(cb.m_closestHitFraction) * double(r.length_m) : -1.0;
    }
    h.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return h;
  }
};

struct Agreement {
  int hitMissDiffer = 0;
  int distanceDiffer = 0;  // both hit, |d| > tolerance
  double maxDistanceDiff_m = 0;
  int hits = 0;
};

Agreement compare(const Hits& a, const Hits& b, double tolerance_m) {
  Agreement g;
  for (std::size_t i = 0; i < a.distance_m.size(); ++i) {
    const bool ha = a.distance_m[i] >= 0, hb = b.distance_m[i] >= 0;
    if (ha != hb) {
      ++g.hitMissDiffer;
      continue;
    }
    if (!ha) continue;
    ++g.hits;
    const double d = std::abs(a.distance_m[i] - b.distance_m[i]);
    g.maxDistanceDiff_m = std::max(g.maxDistanceDiff_m, d);
    if (d > tolerance_m) ++g.distanceDiffer;
  }
  return g;
}

nlohmann::json timing(const Hits& h, std::size_t rays) {
  int hits = 0;
  for (double d : h.distance_m) hits += d >= 0;
  return {{"seconds", h.seconds},
          {"rays_per_s", h.seconds > 0 ? double(rays) / h.seconds : 0.0},
          {"ns_per_ray", 1e9 * h.seconds / double(rays)},
          {"hits", hits}};
}

nlohmann::json agreementJson(const Agreement& g, double tolerance_m) {
  return {{"rays_hit_in_one_only", g.hitMissDiffer},
          {"rays_distance_differs", g.distanceDiffer},
          {"tolerance_m", tolerance_m},
          {"max_distance_difference_m", g.maxDistanceDiff_m}};
}

}  // namespace

nlohmann::json runTerrainRays(const TerrainRaysOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  terrain::HeightMap map = terrain::generatePlasma(o.size, o.size, {o.seed, 0.5});
  terrain::TerrainDesc desc;
  desc.spacing_m = 1;
  desc.heightScale_m = 80.0 / 65535;  // 80 m of relief
  desc.originX_m = -(o.size - 1) / 2.0;
  desc.originZ_m = -(o.size - 1) / 2.0;
  auto created = terrain::Terrain::create(std::move(map), desc);
  if (!created) return {{"error", created.error()}};
  const terrain::Terrain& t = created.value();
  const double buildTumble = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<Ray> rays = makeRays(t, o.rays, o.seed);
  std::fprintf(stderr, "tumble_compare: terrain_rays, %d x %d samples, %d rays\n", o.size, o.size, o.rays);

  // Which diagonal matches Tumble's is checked on a small batch, not assumed.
  const double tolerance_m = 1e-3;
  std::vector<Ray> probe(rays.begin(), rays.begin() + std::min<std::ptrdiff_t>(std::ptrdiff_t(rays.size()), 3000));
  const Hits tumbleProbe = castTumble(t, probe);
  bool flip = false;
  {
    const Agreement a = compare(tumbleProbe, BulletField(t, false, false).cast(probe), tolerance_m);
    const Agreement b = compare(tumbleProbe, BulletField(t, true, false).cast(probe), tolerance_m);
    flip = b.hitMissDiffer + b.distanceDiffer < a.hitMissDiffer + a.distanceDiffer;
  }

  std::fprintf(stderr, "  tumble ...\n");
  const Hits tumbleHits = castTumble(t, rays);
  std::fprintf(stderr, "  bullet (grid walk) ...\n");
  const auto b0 = std::chrono::steady_clock::now();
  BulletField plain(t, flip, false);
  const double buildPlain = std::chrono::duration<double>(std::chrono::steady_clock::now() - b0).count();
  const Hits bulletHits = plain.cast(rays);
  std::fprintf(stderr, "  bullet (with buildAccelerator) ...\n");
  const auto b1 = std::chrono::steady_clock::now();
  BulletField accelerated(t, flip, true);
  const double buildAccel = std::chrono::duration<double>(std::chrono::steady_clock::now() - b1).count();
  const Hits bulletAccelHits = accelerated.cast(rays);

  nlohmann::json j;
  j["scene"] = "terrain_rays";
  j["description"] = "one batch of rays (1/3 vertical, 1/3 steep 30-80 deg over 200 m, 1/3 grazing 2-10 deg over "
                     "400 m) against a plasma height field with 80 m of relief, 1 m spacing";
  j["samples"] = {o.size, o.size};
  j["rays"] = o.rays;
  j["seed"] = o.seed;
  j["threads"] = 1;
  j["tumble"] = timing(tumbleHits, rays.size());
  j["tumble"]["structure"] = "terrain::Terrain::rayCast: implicit quad-tree of AABBs in one array (8x8-block leaves)";
  j["tumble"]["build_s"] = buildTumble;
  j["tumble"]["bytes"] = t.memory().heights + t.memory().tree;
  j["bullet"] = timing(bulletHits, rays.size());
  j["bullet"]["structure"] = "btHeightfieldTerrainShape (PHY_FLOAT) in a btCollisionWorld, rayTest closest hit";
  j["bullet"]["build_s"] = buildPlain;
  j["bullet"]["bytes"] = plain.heights_m.size() * sizeof(float);
  j["bullet"]["flip_quad_edges"] = flip;
  j["bullet_accelerated"] = timing(bulletAccelHits, rays.size());
  j["bullet_accelerated"]["structure"] = "same, after btHeightfieldTerrainShape::buildAccelerator() (16x16 chunks)";
  j["bullet_accelerated"]["build_s"] = buildAccel;
  auto ratio = [](const Hits& a, const Hits& b) { return b.seconds > 0 ? a.seconds / b.seconds : 0.0; };
  j["ratio_time"] = ratio(tumbleHits, bulletHits);
  j["ratio_time_accelerated"] = ratio(tumbleHits, bulletAccelHits);
  j["agreement"] = agreementJson(compare(tumbleHits, bulletHits, tolerance_m), tolerance_m);
  j["agreement_accelerated"] = agreementJson(compare(tumbleHits, bulletAccelHits, tolerance_m), tolerance_m);
  j["measures"] = "ratio_time: Tumble's time for the whole batch / Bullet's (below 1: Tumble is faster); "
                  "agreement: rays where one engine hits and the other misses, or both hit at distances more than "
                  "tolerance_m apart (float heights in Bullet vs 16-bit samples times the scale in Tumble agree to "
                  "float rounding)";
  return j;
}

}  // namespace tumble::compare
