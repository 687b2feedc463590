// Stacks whose boxes differ in mass by 1:10 to 1:1000, in both orders, as
// columns and as pyramids, at default settings. The exact answer for every
// one of them is static equilibrium: nothing moves. So the tests bound what
// does move: the largest sideways drift of any box, the largest sink of any
// box below its resting height, and the tilt; and they require that nothing
// fell (a box more than half its size off its start).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "physics_fixture.h"

namespace tumble::physics::test {
namespace {

struct StackMotion {
  Real drift_m = 0;  ///< largest horizontal distance of any box from its start
  Real sink_m = 0;   ///< largest drop of any box below its start height
  Real minUp = 1;    ///< smallest y component of any box's up axis
  Real penetration_m = 0;  ///< the run's deepest contact (World::errorStats)
  int nanEvents = 0;
};

/// A box stack: positions and masses, bottom first.
struct Stack {
  std::vector<Vec3> positions_m;
  std::vector<Real> masses_kg;
  int levels = 0;  ///< contact layers from the ground to the top box
};

/// A column of `count` 1 m cubes; boxes [oddFrom, oddTo) (from the bottom)
/// weigh `odd_kg`, the others 1 kg.
Stack column(int count, int oddFrom, int oddTo, Real odd_kg) {
  Stack s;
  for (int i = 0; i < count; ++i) {
    s.positions_m.push_back(Vec3(0, Real(0.5) + Real(i), 0));
    s.masses_kg.push_back(i >= oddFrom && i < oddTo ? odd_kg : Real(1));
  }
  s.levels = count;
  return s;
}

/// A pyramid of 1 m cubes with `rows` boxes in the bottom row, 5 cm gaps
/// between the boxes of a row; rows [oddFrom, oddTo) weigh `odd_kg` each box,
/// the others 1 kg.
Stack pyramid(int rows, int oddFrom, int oddTo, Real odd_kg) {
  Stack s;
  const Real pitch = Real(1.05);
  for (int r = 0; r < rows; ++r) {
    const int n = rows - r;
    for (int i = 0; i < n; ++i) {
      s.positions_m.push_back(Vec3((Real(i) - Real(n - 1) / 2) * pitch, Real(0.5) + Real(r), 0));
      s.masses_kg.push_back(r >= oddFrom && r < oddTo ? odd_kg : Real(1));
    }
  }
  s.levels = rows;
  return s;
}

StackMotion simulateStack(const Stack& s, Real seconds, bool sleep) {
  WorldSettings settings;
  settings.enableSleep = sleep;
  World w(settings);
  addGround(w);
  std::vector<BodyId> ids;
  for (std::size_t i = 0; i < s.positions_m.size(); ++i)
    ids.push_back(addBody(w, Shape::box(Vec3::Constant(Real(0.5))), s.positions_m[i], s.masses_kg[i]));
  StackMotion m;
  const Real dt = Real(1.0 / 60.0);
  const int steps = int(std::lround(seconds / dt));
  for (int k = 0; k < steps; ++k) {
    w.step(dt);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const Body& b = w.body(ids[i]);
      const Vec3 d = b.position_m - s.positions_m[i];
      m.drift_m = std::max(m.drift_m, Vec2(d.x(), d.z()).norm());
      m.sink_m = std::max(m.sink_m, -d.y());
      m.minUp = std::min(m.minUp, (b.orientation * Vec3::UnitY()).y());
    }
  }
  m.penetration_m = w.errorStats().penetrationMax_m;
  m.nanEvents = int(w.errorStats().nanEvents);
  return m;
}

void report(const char* what, Real ratio, bool sleep, const StackMotion& m) {
  std::printf("%-32s 1:%-5g sleep %-3s drift %9.2f mm  sink %8.2f mm  penetration %6.2f mm  min up %.5f\n", what,
              double(ratio), sleep ? "on" : "off", double(m.drift_m * 1000), double(m.sink_m * 1000),
              double(m.penetration_m * 1000), double(m.minUp));
}

// The bounds are the engine's claims elsewhere, not fitted to these stacks:
// a 20-box stack holds 1 cm sideways (Contact.TwentyBoxStackStandsForTenSeconds);
// a contact is left overlapping by up to WorldSettings::linearSlop_m (split
// impulses push out only beyond it), so a box sinks at most one slop per
// contact layer beneath it; the deepest contact stays under the 2 cm
// penetration bound; upright is a tilt under 2.6 degrees.
constexpr Real kDrift_m = Real(0.01), kPenetration_m = Real(0.02), kMinUp = Real(0.999);

/// Runs the stack for a minute with sleep on (the default) and off (so that
/// falling asleep cannot hide motion) and checks it stood.
void expectStands(const char* what, Real ratio, const Stack& s) {
  const Real sink_m = Real(s.levels) * WorldSettings{}.linearSlop_m;
  for (bool sleep : {true, false}) {
    const StackMotion m = simulateStack(s, 60, sleep);
    report(what, ratio, sleep, m);
    const char* mode = sleep ? " (sleep on)" : " (sleep off)";
    EXPECT_LT(m.drift_m, kDrift_m) << what << " 1:" << ratio << mode;
    EXPECT_LT(m.sink_m, sink_m) << what << " 1:" << ratio << mode;
    EXPECT_LT(m.penetration_m, kPenetration_m) << what << " 1:" << ratio << mode;
    EXPECT_GT(m.minUp, kMinUp) << what << " 1:" << ratio << mode;
    EXPECT_EQ(m.nanEvents, 0) << what << " 1:" << ratio << mode;
  }
}

/// Every other box of a column of 8 weighs `odd_kg`: each light box is
/// squeezed between heavy ones.
Stack alternating(Real odd_kg) {
  Stack s = column(8, 0, 0, 1);
  for (std::size_t i = 1; i < s.masses_kg.size(); i += 2) s.masses_kg[i] = odd_kg;
  return s;
}

TEST(MassRatio, HeavyBoxOnAColumnOfTenLightBoxesStandsAMinute) {
  for (Real ratio : {Real(10), Real(100)}) expectStands("heavy on 10 light (column)", ratio, column(11, 10, 11, ratio));
}

TEST(MassRatio, LightBoxOnAColumnOfTenHeavyBoxesStandsAMinute) {
  for (Real ratio : {Real(10), Real(100)}) expectStands("light on 10 heavy (column)", ratio, column(11, 0, 10, ratio));
}

TEST(MassRatio, HeavyTopRowsOnALightPyramidStandAMinute) {
  for (Real ratio : {Real(10), Real(100)}) expectStands("heavy top 2 rows, pyramid of 5", ratio, pyramid(5, 3, 5, ratio));
}

TEST(MassRatio, LightTopRowsOnAHeavyPyramidStandAMinute) {
  for (Real ratio : {Real(10), Real(100)}) expectStands("light top 3 rows, pyramid of 5", ratio, pyramid(5, 0, 2, ratio));
}

TEST(MassRatio, AlternatingHeavyAndLightColumnStandsAMinute) {
  for (Real ratio : {Real(10), Real(100)}) expectStands("alternating column of 8", ratio, alternating(ratio));
}

// 1:1000: light boxes on heavy ones must stand like the others. Light
// boxes under a 1000 kg box are beyond what the contact solver holds (its
// known limit, measured in contact_solver.cpp "Normal blocks" and in the
// accuracy suite, docs/physics-accuracy.md): a single pair keeps its place
// but sinks by more than one slop per layer, tall stacks fall. Those are
// run and printed, and must only stay finite.
TEST(MassRatio, ThousandToOneLightOnHeavyStandsAMinute) {
  const Real r = 1000;
  expectStands("light on 10 heavy (column)", r, column(11, 0, 10, r));
  expectStands("light top 3 rows, pyramid of 5", r, pyramid(5, 0, 2, r));
}

TEST(MassRatio, ThousandToOneTallHeavyOnLightIsMeasured) {
  const Real r = 1000;
  const std::pair<const char*, Stack> cases[] = {{"heavy on 10 light (column)", column(11, 10, 11, r)},
                                                 {"heavy top 2 rows, pyramid of 5", pyramid(5, 3, 5, r)},
                                                 {"alternating column of 8", alternating(r)},
                                                 {"heavy on 1 light (column)", column(2, 1, 2, r)}};
  for (const auto& [what, stack] : cases) {
    const StackMotion m = simulateStack(stack, 60, false);
    report(what, r, false, m);
    EXPECT_EQ(m.nanEvents, 0) << what;
  }
}

}  // namespace
}  // namespace tumble::physics::test
