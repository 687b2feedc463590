// Overlap query (World::overlapShape): the bodies a shape placed somewhere
// touches. It reuses the narrow phase, so every shape pair that can collide
// can be queried, compounds included.
#include "physics/internal/narrow_phase.h"
#include "physics/internal/query_probe.h"
#include "physics/world.h"

namespace tumble::physics {

std::vector<BodyId> World::overlapShape(const Shape& shape, const Vec3& position, const Quat& orientation) const {
  std::vector<BodyId> out;
  if (!queryShapeValid(shape, position, orientation)) return out;
  const Body probe = probeBody(shape, position, orientation);
  Vec3 lo, hi;
  shape.bounds(probe.position_m, probe.orientation, &lo, &hi);
  std::vector<Manifold> found;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive) continue;
    Vec3 blo, bhi;
    b.shape.bounds(b.position_m, b.orientation, &blo, &bhi);
    if ((lo.array() > bhi.array() + kQueryTolerance_m).any() || (hi.array() < blo.array() - kQueryTolerance_m).any())
      continue;
    collidePair(probe, b, kQueryTolerance_m, found);
    bool touches = false;
    for (const Manifold& m : found)
      for (int k = 0; k < m.count; ++k) touches |= m.points[k].separation_m <= kQueryTolerance_m;
    if (touches) out.push_back(idOf(i));
  }
  return out;
}

}  // namespace tumble::physics
