// Continuous collision: what stops fast bodies from passing through things
// between two steps. Speculative contacts (collision_pipeline.cpp) do most
// of it; this file has the two cases they miss.
//
// 1. A fast sphere against a shape that does not move (sweptSphereContact).
// Speculative contacts take their normal from the positions at the start of
// the step. A fast sphere that will hit a wall's face squarely can be, at
// the start of the step, closest to the wall's end edge: that contact's
// normal is tilted towards the sphere, and the solver stops the sphere's
// motion along it, deflecting a ball that was about to hit the face (a
// "ghost" contact; bullets.lua with 4 m walls measured 3 of 15 balls turned
// away). So, as collideSpheresSwept does for two spheres, a sphere that can
// move more than 2 * spec this step against a shape that does not move or
// turn gets its contact from the time of impact: its centre's path against
// the shape grown by the radius (rayShape; the grown box and cylinder have
// sharp corners and rims, so a path grazing one counts as a hit:
// conservative). Boxes, hulls and cylinders (a post: before, 32 of 244
// shots at 200 m/s that pass a 0.15 m post were turned away by it). The normal is
// the face normal there, the separation the distance to that face plane
// along it (so the solver lets it approach exactly until impact), and a path
// that misses gives no contact. A sphere already within spec of the shape
// gets the ordinary contact.
//
// 2. After the step, against static geometry (World::clampToStatic; see
// WorldSettings::continuousStatic). Speculative contacts stop a body that heads for a
// wall, but their margins use the velocities at the start of the step: a
// fast body that another body deflects this step can be sent at a wall it
// has no contact with and pass through it (measured: 89 of 1000 spheres
// left highspeed_1000's box). So every body that moved more than half its
// inner radius r is swept as a sphere of radius r (a ray against each
// static shape grown by r) from its start to its end position. If it ends
// more than r/2 inside a grown shape it is put back at the time of impact;
// its velocity is kept, so the next step's speculative contact bounces it
// with its restitution (no energy lost). The r/2 depth test keeps bodies
// that slide along a floor and dip by millimetres from being held back.
// Rejected: growing the speculative margins by a bound on the velocity
// change (any body could be hit by any other: margins, pairs and solver
// work grow for the whole scene to guard a few bodies).
// The height field: the centre's path as a ray; a hit means the centre
// ends below the surface, and the body goes back to where a sphere of
// radius r touches the hit triangle's plane (t - r / cos).
#include <algorithm>
#include <cmath>

#include "physics/internal/ccd.h"
#include "physics/internal/narrow_phase.h"
#include "physics/internal/ray_shape.h"
#include "physics/internal/step_scratch.h"
#include "physics/world.h"

namespace tumble::physics {

bool sweptSphereContact(const Body& sphere, const Body& other, const Vec3& motion, Real spec, bool sphereIsA,
                        Manifold& m) {
  m.count = 0;
  if (collideBodies(sphereIsA ? sphere : other, sphereIsA ? other : sphere, spec, m) > 0) return true;
  m.count = 0;
  const Real len = motion.norm();
  if (!(len > 0)) return false;
  const Vec3 dir = motion / len;
  const Real r = sphere.shape.radius_m;
  Real t;
  Vec3 n;
  if (!rayShape(other, sphere.position_m, dir, len + spec, t, n, r)) return false;
  const Real approach = -n.dot(dir);
  if (!(approach > 0)) return false;
  const Real sep = std::max<Real>(t * approach, 0);
  m.normal = sphereIsA ? Vec3(-n) : n;
  ContactPoint& c = m.points[0];
  c.point_m = sphere.position_m - n * (r + sep / 2);
  c.separation_m = sep;
  c.id = 0;
  m.count = 1;
  return true;
}

void World::clampToStatic() {
  // See the top of the file (2).
  StepScratch& st = *m_scratch;
  if (st.statics.empty() && st.planes.empty() && !m_heightField) return;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.isDynamic() || !b.awake) continue;
    const Real r = b.shape.innerRadius();
    if (!(r > 0)) continue;  // no sphere about the centre inside the shape (a compound whose centre is in no child)
    const Vec3 p0 = m_stepStartPosition[i];
    const Vec3 d = b.position_m - p0;
    const Real len2 = d.squaredNorm();
    if (!(len2 > Real(0.25) * r * r)) continue;
    const Real len = std::sqrt(len2);
    const Vec3 dir = d / len;
    Aabb swept;
    swept.lo = p0.cwiseMin(b.position_m) - Vec3::Constant(r);
    swept.hi = p0.cwiseMax(b.position_m) + Vec3::Constant(r);
    Real toi = len;
    auto test = [&](std::uint32_t j) {
      Real t;
      Vec3 nrm;
      if (!rayShape(m_bodies[j], p0, dir, toi, t, nrm, r) || !(t > 0)) return;
      const Real depth = (len - t) * -dir.dot(nrm);  // end position below the grown surface
      if (depth > Real(0.5) * r) toi = t;
    };
    for (std::uint32_t j : st.statics)
      if (swept.overlaps(st.boxes[j])) test(j);
    for (std::uint32_t j : st.planes) test(j);
    if (m_heightField) {
      HeightFieldHit hit;
      Real h;
      Vec3 n;
      const bool startAbove = !m_heightField->surfaceAt(p0.x(), p0.z(), &h, &n) || p0.y() >= h;
      if (startAbove && m_heightField->rayCast(p0, dir, len, &hit)) {
        const Real cosine = -dir.dot(hit.normal);
        if (cosine > 0) toi = std::min(toi, std::max<Real>(hit.distance_m - r / cosine, 0));
      }
    }
    if (toi < len) b.position_m = p0 + dir * toi;
  }
}

}  // namespace tumble::physics
