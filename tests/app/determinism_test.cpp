// Determinism against stored constants, as Box2D's determinism test does:
// each case runs a base scenario through the real `tumble run` and compares
// the state hash it prints (every body's position, orientation and
// velocities, every rope and cloth particle, every effect particle; see
// run_report.cpp) with the value recorded below. The scenarios' own tests
// (tests/scenarios) check that the physics is right; this one checks that it
// did not change: a refactoring, a compiler flag or an "unrelated" edit that
// moves a single bit of the end state fails here.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <ostream>
#include <regex>
#include <string>

#include "tumble_process.h"

namespace tumble::test {
namespace {

struct HashCase {
  const char* name;  ///< the test's name
  const char* args;  ///< after `tumble run`
  const char* hash;  ///< state_hash at the scenario's default duration
};

// The recorded end states. CHANGING ONE IS A REVIEWED COMMIT OF ITS OWN: a
// new value means every run of that scenario now ends somewhere else. That
// can be right (a deliberate change to the solver, a scenario edited), but
// the commit that changes a constant says which change moved it and why the
// new result is right (the scenario's expectations still hold, and what was
// measured), and it never changes a constant just to make this test pass.
//
// Recorded with the release build of main at commit ae2633f, before the
// offline tools moved out of the runtime; for the default float state
// (TUMBLE_DOUBLE=OFF). A debug build (-O0) gives the same values: see the
// README, "Tests".
// Drop, Pyramid, both RagdollPile, Hills, Showroom and Effects changed when
// the contact solver began solving each face manifold's normal rows as one
// block (contact_solver.cpp, "Normal blocks"): every box resting on a face
// is solved differently; each scenario's expectations still hold.
// ChainLagrange changed when the Lagrange solver kept the swing's curvature
// term in its relax sweeps and out of its Baumgarte damping
// (lagrange_substeps.cpp, "Relax target"): the free chain swings on with
// less loss; its expectations still hold (joints 0.26 mm open, no energy
// gain, the bottom link past the vertical).
// Every case but Pyramid, Cloth and Springs changed when bodies began to
// turn torque-free with their angular momentum kept (world_step.cpp,
// "Rotation"): every body whose principal moments differ (boxes that are
// not cubes, capsules, cars, compounds) turns differently; the three left
// move only spheres, cubes, particles or points. Each scenario's
// expectations still hold (tumble run, all 11); base:spin's T-handle keeps
// its energy and |L| closer than before (8e-5 and 8e-6).
// RagdollPileLagrange changed when the Lagrange joints began to project the
// contacts' push-out velocities (lagrange_substeps.cpp, "Push-out"): the
// dolls' parts pushed out of the ground and of each other now move with
// the bodies they hang on. Its expectations still hold (pile at rest, joints
// together) and its largest joint opening went from 11.9 to 2.0 mm; no
// other case has Lagrange joints touching contacts.
constexpr HashCase kCases[] = {
    {"Drop", "base:drop", "a40056f79e507047"},
    {"Pyramid", "base:pyramid", "ecd087b9bc83a7a4"},
    {"RagdollPileLagrange", "base:ragdoll_pile --set physics.joint_solver=lagrange", "20291bb5dcdebd2b"},
    {"RagdollPileImpulse", "base:ragdoll_pile --set physics.joint_solver=impulse", "1241f5e488aa7557"},
    {"Drive", "base:drive --set autopilot=1", "c417c7a7bbd656cf"},
    {"Cloth", "base:cloth", "28da0f5e77239499"},
    {"ChainLagrange", "base:chain --set physics.joint_solver=lagrange", "1a45cae25a3609cd"},
    {"ChainImpulse", "base:chain --set physics.joint_solver=impulse", "4bf415d3a904844a"},
    {"TimeTrial", "base:time_trial --set autopilot=1", "8c9621fc6a3ec554"},
    {"Hills", "base:hills", "23c79783ce3b4b99"},         // terrain contacts
    {"Spin", "base:spin", "6df571d93bbd3840"},           // compounds and a hull
    {"Springs", "base:springs", "7a0abe7d4504b642"},     // the sdirk2 integrator
    {"Showroom", "base:showroom --set autopilot=1", "7ec2a0114f5752ed"},  // static triangle meshes
    {"Effects", "base:effects", "112eb2a99b205a07"},     // effect particles
};

// How ctest and gtest name a case's parameter: its command line.
void PrintTo(const HashCase& c, std::ostream* os) { *os << c.args; }

class Determinism : public testing::TestWithParam<HashCase> {};

TEST_P(Determinism, StateHashIsTheRecordedOne) {
#if defined(TUMBLE_DOUBLE)  // from core, as the binary under test was built
  GTEST_SKIP() << "the constants are for float rigid-body state; this build stores double (TUMBLE_DOUBLE=ON)";
#endif
  const HashCase& c = GetParam();
  // time_trial saves its best lap; `run` keeps saves in a throw-away
  // folder, so no earlier run can change what this one reads back.
  const ProcessResult r = runTumble(std::string("run ") + c.args);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("; state ([0-9a-f]{16})"))) << r.output;
  EXPECT_EQ(m[1].str(), c.hash) << "tumble run " << c.args << " ends in another state than the recorded one; "
                                << "see the comment at kCases before changing the constant\n"
                                << r.output;
}

// WorldSettings::threads: the contact passes shared between two threads
// give the sequential result bit for bit ("Threads" in
// runtime/physics/contact_solver.cpp), so the recorded constants hold with
// --threads 2. The pyramid has enough contacts for the threads (at least
// 128 manifolds in a step; drop and the rag-doll pile have fewer): it must
// have used them (the report's steps_on_threads), or this would test
// nothing but the one-thread path.
TEST_P(Determinism, TwoThreadsGiveTheRecordedHash) {
#if defined(TUMBLE_DOUBLE)
  GTEST_SKIP() << "the constants are for float rigid-body state; this build stores double (TUMBLE_DOUBLE=ON)";
#endif
  const HashCase& c = GetParam();
  const std::string report = outDir(std::string("determinism_threads_") + c.name) + "/report.json";
  const ProcessResult r = runTumble(std::string("run ") + c.args + " --threads 2 --report " + report);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("; state ([0-9a-f]{16})"))) << r.output;
  EXPECT_EQ(m[1].str(), c.hash) << "tumble run " << c.args << " --threads 2 ends elsewhere than with one thread\n"
                                << r.output;
  std::ifstream in(report);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(std::regex_search(text, m, std::regex("\"steps_on_threads\": ?([0-9]+)"))) << text.substr(0, 2000);
  if (std::string(c.name) == "Pyramid") {
    EXPECT_GT(std::stoll(m[1].str()), 0) << "the threads were never used: " << c.args;
  }
}

INSTANTIATE_TEST_SUITE_P(BaseScenarios, Determinism, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<HashCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace tumble::test
