#pragma once
// Small fixture after Jolt's tests: make a floor, make a body, simulate T
// seconds, compare with an analytic answer.
#include <gtest/gtest.h>

#include "physics/world.h"

namespace tumble::physics::test {

inline BodyId addGround(World& w, Real friction = Real(0.6), Real restitution = 0) {
  BodyDef d;
  d.type = BodyType::Static;
  d.shape = Shape::plane();
  d.friction = friction;
  d.restitution = restitution;
  return w.createBody(d).value();
}

inline BodyId addBody(World& w, const Shape& s, const Vec3& p, Real mass = 1, Real friction = Real(0.6),
                      Real restitution = 0) {
  BodyDef d;
  d.shape = s;
  d.position_m = p;
  d.mass_kg = mass;
  d.friction = friction;
  d.restitution = restitution;
  return w.createBody(d).value();
}

inline void simulate(World& w, Real seconds, Real dt = Real(1.0 / 60.0)) {
  int steps = int(std::lround(seconds / dt));
  for (int i = 0; i < steps; ++i) w.step(dt);
}

}  // namespace tumble::physics::test
