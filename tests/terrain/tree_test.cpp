// The quad-tree: index arithmetic, tight bounds, refit, memory budget, and
// static objects at the tightest node.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "terrain/generators.h"
#include "terrain/height_tree.h"
#include "terrain/terrain.h"
#include "test_util.h"

using namespace tumble;
using namespace tumble::terrain;
using namespace tumble::terrain::test;

namespace {

// Min and max of the samples under a node, the slow way.
std::pair<std::uint16_t, std::uint16_t> bruteBounds(const HeightMap& m, const BlockRange& b) {
  std::uint16_t lo = 0xffff, hi = 0;
  for (int j = b.bj0; j <= b.bj1; ++j)
    for (int i = b.bi0; i <= b.bi1; ++i) lo = std::min(lo, m.at(i, j)), hi = std::max(hi, m.at(i, j));
  return {lo, hi};
}

void expectTightBounds(const HeightTree& tree, const HeightMap& m) {
  for (std::uint32_t idx = 0; idx < tree.nodeCount(); ++idx) {
    const NodeRef r = tree.ref(idx);
    const BlockRange b = tree.blocks(r);
    ASSERT_LT(b.bi0, b.bi1);
    ASSERT_LT(b.bj0, b.bj1);
    const auto [lo, hi] = bruteBounds(m, b);
    ASSERT_EQ(tree.node(idx).minHeight, lo) << "node " << idx << " level " << r.level;
    ASSERT_EQ(tree.node(idx).maxHeight, hi) << "node " << idx << " level " << r.level;
  }
}

}  // namespace

TEST(HeightTree, EveryNodeBoundsAllHeightsBelowItTightly) {
  for (int leaf : {1, 2, 8, 32}) {
    const HeightMap m = generatePlasma(133, 77, {21, 0.6});
    HeightTree tree;
    tree.build(m, leaf);
    SCOPED_TRACE(leaf);
    expectTightBounds(tree, m);
    EXPECT_EQ(tree.levelWidth(0), 1);
    EXPECT_EQ(tree.levelHeight(0), 1);
  }
}

TEST(HeightTree, IndexArithmeticParentsAndChildrenAgree) {
  const HeightMap m(301, 45);  // non-square: 300 x 44 blocks
  HeightTree tree;
  tree.build(m, 2);
  std::vector<int> visits(tree.nodeCount(), 0);
  std::array<NodeRef, 4> kids;
  for (std::uint32_t idx = 0; idx < tree.nodeCount(); ++idx) {
    const NodeRef r = tree.ref(idx);
    ASSERT_EQ(tree.index(r), idx);
    const int n = tree.children(r, kids);
    if (r.level == tree.leafLevel()) {
      EXPECT_EQ(n, 0);
      continue;
    }
    ASSERT_GT(n, 0);
    // Children tile the parent's blocks exactly.
    const BlockRange pb = tree.blocks(r);
    long area = 0;
    for (int k = 0; k < n; ++k) {
      const NodeRef c = kids[std::size_t(k)];
      EXPECT_EQ(HeightTree::parent(c).x, r.x);
      EXPECT_EQ(HeightTree::parent(c).z, r.z);
      EXPECT_EQ(HeightTree::parent(c).level, r.level);
      const BlockRange cb = tree.blocks(c);
      EXPECT_GE(cb.bi0, pb.bi0);
      EXPECT_LE(cb.bi1, pb.bi1);
      EXPECT_GE(cb.bj0, pb.bj0);
      EXPECT_LE(cb.bj1, pb.bj1);
      area += long(cb.bi1 - cb.bi0) * (cb.bj1 - cb.bj0);
      ++visits[tree.index(c)];
    }
    EXPECT_EQ(area, long(pb.bi1 - pb.bi0) * (pb.bj1 - pb.bj0));
  }
  for (std::uint32_t idx = 1; idx < tree.nodeCount(); ++idx) EXPECT_EQ(visits[idx], 1) << idx;
  // No padding to a square: 150 x 22 leaves.
  EXPECT_EQ(tree.levelWidth(tree.leafLevel()), 150);
  EXPECT_EQ(tree.levelHeight(tree.leafLevel()), 22);
}

TEST(HeightTree, RefitAfterAnEditKeepsBoundsTight) {
  auto t = Terrain::create(generatePlasma(97, 65, {8, 0.5}), {});
  ASSERT_TRUE(t.ok());
  t->editHeights(40, 10, 47, 12, [](HeightMap& m) {
    for (int j = 10; j <= 12; ++j)
      for (int i = 40; i <= 47; ++i) m.set(i, j, std::uint16_t(i == 44 ? 65535 : 0));
  });
  expectTightBounds(t->tree(), t->heights());
}

TEST(HeightTree, MemoryOfA4097MapIsUnder2Point1BytesPerSample) {
  // Measured from the containers' capacities, as `terrain info` reports it.
  auto t = Terrain::create(HeightMap(4097, 4097, 100), {});
  ASSERT_TRUE(t.ok());
  const TerrainMemory mem = t->memory();
  const double samples = 4097.0 * 4097.0;
  EXPECT_EQ(mem.heights, std::size_t(4097) * 4097 * 2);
  EXPECT_LE(double(mem.heights + mem.tree) / samples, 2.1);
  EXPECT_EQ(mem.materials, 0u);  // not created until asked for
  // Even 2 x 2-block leaves stay inside the 8 bytes-per-block budget.
  HeightTree fine;
  fine.build(t->heights(), 2);
  EXPECT_LE(double(fine.bytes()) / (4096.0 * 4096.0), 8.0);
}

TEST(StaticObjects, LandInTheTightestNodeAndAreFoundByBoxQueries) {
  TerrainDesc desc;
  desc.spacing_m = 2;
  desc.originX_m = -100;
  desc.originZ_m = 50;
  auto t = Terrain::create(generatePlasma(129, 129, {1, 0.5}), desc, 2);
  ASSERT_TRUE(t.ok());
  const HeightTree& tree = t->tree();
  auto rectOf = [&](std::uint32_t node) { return t->nodeBounds(node); };
  auto covers = [&](const Aabb& n, const Aabb& b) {
    return b.min.x() >= n.min.x() && b.max.x() <= n.max.x() && b.min.z() >= n.min.z() && b.max.z() <= n.max.z();
  };
  // A pebble inside one leaf (a leaf is 2 x 2 blocks = 4 m).
  const Aabb pebble{Vec3(-100 + 41, 0, 50 + 81), Vec3(-100 + 42.5f, 700, 50 + 82)};
  // A rock straddling the middle of the terrain (x = 28 m): only the root covers it.
  const Aabb rock{Vec3(27, 0, 100), Vec3(29, 700, 102)};
  // A boulder within one quadrant but across a leaf boundary.
  const Aabb boulder{Vec3(-100 + 30, 0, 50 + 30), Vec3(-100 + 34.5f, 700, 50 + 31)};
  // A house off the terrain's edge.
  const Aabb house{Vec3(-120, 0, 0), Vec3(-110, 10, 10)};
  ASSERT_TRUE(t->addStaticObject(1, pebble).ok());
  ASSERT_TRUE(t->addStaticObject(2, rock).ok());
  ASSERT_TRUE(t->addStaticObject(3, boulder).ok());
  ASSERT_TRUE(t->addStaticObject(4, house).ok());
  EXPECT_FALSE(t->addStaticObject(4, house).ok());  // duplicate id

  EXPECT_EQ(tree.ref(t->staticObjects().nodeOf(1)).level, tree.leafLevel());
  EXPECT_EQ(t->staticObjects().nodeOf(2), 0u);
  EXPECT_EQ(t->staticObjects().nodeOf(4), 0u);
  for (std::uint32_t id : {1u, 3u}) {
    const std::uint32_t node = t->staticObjects().nodeOf(id);
    const Aabb box = t->staticObjects().boxOf(id);
    EXPECT_TRUE(covers(rectOf(node), box)) << id;
    // Tightest: no child covers it.
    std::array<NodeRef, 4> kids;
    const int n = tree.children(tree.ref(node), kids);
    for (int k = 0; k < n; ++k) EXPECT_FALSE(covers(rectOf(tree.index(kids[std::size_t(k)])), box)) << id;
  }
  EXPECT_GT(tree.ref(t->staticObjects().nodeOf(3)).level, 0);
  EXPECT_LT(tree.ref(t->staticObjects().nodeOf(3)).level, tree.leafLevel());

  auto query = [&](const Aabb& box) {
    std::vector<std::uint32_t> ids;
    t->staticObjectsInBox(box, ids);
    return std::set<std::uint32_t>(ids.begin(), ids.end());
  };
  EXPECT_EQ(query({Vec3(-60, -10, 130), Vec3(-58, 1000, 132)}), (std::set<std::uint32_t>{1}));
  EXPECT_EQ(query({Vec3(-200, -10, -100), Vec3(400, 1000, 400)}), (std::set<std::uint32_t>{1, 2, 3, 4}));
  EXPECT_EQ(query({Vec3(-115, 5, 5), Vec3(-114, 6, 6)}), (std::set<std::uint32_t>{4}));
  EXPECT_EQ(query({Vec3(-60, 800, 130), Vec3(-58, 1000, 132)}), (std::set<std::uint32_t>{}));  // above the pebble
  EXPECT_EQ(query({Vec3(0, 0, 180), Vec3(10, 1000, 190)}), (std::set<std::uint32_t>{}));

  // The box query returns terrain triangles and objects together.
  std::vector<TerrainTriangle> tris;
  std::vector<std::uint32_t> objects;
  t->overlapBox({Vec3(-59, -10, 130.5f), Vec3(-58.5f, 1000, 131)}, tris, &objects);
  EXPECT_EQ(objects, (std::vector<std::uint32_t>{1}));
  EXPECT_FALSE(tris.empty());

  EXPECT_TRUE(t->removeStaticObject(1));
  EXPECT_FALSE(t->removeStaticObject(1));
  EXPECT_EQ(query({Vec3(-60, -10, 130), Vec3(-58, 1000, 132)}), (std::set<std::uint32_t>{}));
  EXPECT_FALSE(t->addStaticObject(9, {Vec3(1, 1, 1), Vec3(0, 0, 0)}).ok());  // inverted box
}
