// The order in which the Lagrange solver eliminates the joints, and in which
// the impulse solver sweeps them (JointSystem::solveOrder).
//
// ---- Linear time --------------------------------------------------------------
// (J W J^T)_{rs} = sum over bodies b shared by rows r and s of J_rb W_b J_sb^T.
// It is non-zero only where two joints share a dynamic body: for a chain it
// is block tridiagonal, for a tree of bodies it is the "line graph" of the
// tree, a chordal graph whose perfect elimination order is: joints in a
// post-order walk of the body tree (a body's child joints before the joint
// to its parent). Eliminating in that order creates no fill-in, so LDL^T with
// that (natural) ordering costs O(sum of squared body degrees) = O(links) for
// bounded degree. We order the joints that way whenever the joint set changes
// (joints closing a loop go last; loops cause some fill, as they must) and
// factorize with Eigen::SimplicialLDLT under NaturalOrdering. lastSolve()
// reports the fill-in measured from the factor (0 for chains and trees).
// Baraff factorizes the larger but always tree-structured system
// [M -J^T; -J 0] instead; J W J^T is smaller and for the trees we build (no
// body with more than 5 joints) equally sparse, so we kept the textbook form.
// Rejected: a dense LLT (cubic: 1000 links = 3000 rows, ~1 s per step) and
// Eigen's AMD ordering (finds a zero-fill order too, but costs a symbolic
// analysis that our post-order gives for free).
#include <algorithm>
#include <vector>

#include "physics/internal/lagrange_solver.h"
#include "physics/world.h"

namespace tumble::physics::lagrange {

// Post-order walk of the body tree (see the top of the file): on finishing a
// body, emit its world/static joints, then the joint to its parent. Joints
// that close loops go last.
std::vector<std::uint32_t> eliminationOrder(const World& world, const std::vector<JointDef>& defs,
                                            const std::vector<std::uint32_t>& slotIds) {
  const std::size_t nj = defs.size();
  std::uint32_t maxBody = 0;
  for (const JointDef& d : defs) {
    maxBody = std::max(maxBody, d.bodyA.index);
    if (!d.bodyB.isNull()) maxBody = std::max(maxBody, d.bodyB.index);
  }
  auto dyn = [&](BodyId id) { return !id.isNull() && world.isValid(id) && world.body(id).isDynamic(); };
  std::vector<std::vector<int>> incident(maxBody + 1);  // joints at each body (dynamic ends only)
  std::vector<char> isTwoBody(nj, 0);
  for (std::size_t j = 0; j < nj; ++j) {
    const bool da = dyn(defs[j].bodyA), db = dyn(defs[j].bodyB);
    if (da) incident[defs[j].bodyA.index].push_back(int(j));
    if (db) incident[defs[j].bodyB.index].push_back(int(j));
    isTwoBody[j] = da && db;
  }
  std::vector<char> visited(maxBody + 1, 0), emitted(nj, 0);
  std::vector<std::uint32_t> out;
  out.reserve(nj);
  auto other = [&](int j, std::uint32_t body) {
    return defs[j].bodyA.index == body ? defs[j].bodyB.index : defs[j].bodyA.index;
  };
  auto emitAnchors = [&](std::uint32_t body) {
    for (int j : incident[body])
      if (!isTwoBody[j] && !emitted[j]) emitted[j] = 1, out.push_back(slotIds[j]);
  };
  // Roots: bodies with a world/static joint first (a hanging chain is then
  // rooted at its anchor), then any other.
  std::vector<std::uint32_t> roots;
  for (std::uint32_t b = 0; b <= maxBody; ++b)
    for (int j : incident[b])
      if (!isTwoBody[j]) {
        roots.push_back(b);
        break;
      }
  for (std::uint32_t b = 0; b <= maxBody; ++b)
    if (!incident[b].empty()) roots.push_back(b);
  struct Frame {
    std::uint32_t body;
    int viaJoint;     ///< joint to the parent (-1 at the root)
    std::size_t next;  ///< next incident joint to look at
  };
  std::vector<Frame> stack;
  std::vector<char> treeJoint(nj, 0);
  for (std::uint32_t root : roots) {
    if (visited[root]) continue;
    visited[root] = 1;
    stack.push_back({root, -1, 0});
    while (!stack.empty()) {
      Frame& f = stack.back();
      if (f.next < incident[f.body].size()) {
        const int j = incident[f.body][f.next++];
        if (!isTwoBody[j] || treeJoint[j]) continue;
        const std::uint32_t o = other(j, f.body);
        if (visited[o]) continue;  // closes a loop: emitted at the end
        visited[o] = 1;
        treeJoint[j] = 1;
        stack.push_back({o, j, 0});
        continue;
      }
      emitAnchors(f.body);
      if (f.viaJoint >= 0) emitted[f.viaJoint] = 1, out.push_back(slotIds[f.viaJoint]);
      stack.pop_back();
    }
  }
  for (std::size_t j = 0; j < nj; ++j)
    if (!emitted[j]) out.push_back(slotIds[j]);  // loops (and joints without dynamic bodies)
  return out;
}

}  // namespace tumble::physics::lagrange
