// Mod dependencies: semver constraints, optional dependencies, load order by
// dependency then name, and clear problems for missing, mismatched and
// circular dependencies (ModRegistry and `tumble check`).
#include "script_fixture.h"

namespace tumble::test {

using script::compareVersions;
using script::parseDependency;
using script::satisfies;

namespace {

bool sat(const std::string& version, const std::string& dependency) {
  auto dep = parseDependency("x " + dependency);
  EXPECT_TRUE(dep) << dependency << ": " << (dep ? "" : dep.error());
  return dep && satisfies(version, dep->constraints);
}

std::string allProblems(const std::vector<script::ModProblem>& problems) {
  std::string s;
  for (const auto& p : problems) s += p.text() + "\n";
  return s;
}

std::vector<std::string> names(const script::ModRegistry& reg) {
  std::vector<std::string> out;
  for (const auto& m : reg.mods()) out.push_back(m.name);
  return out;
}

}  // namespace

TEST(ModDependencies, ParseNamesOperatorsAndOptional) {
  auto d = parseDependency("base >= 1.0");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->name, "base");
  EXPECT_FALSE(d->optional);
  ASSERT_EQ(d->constraints.size(), 1u);
  EXPECT_EQ(d->constraints[0].op, ">=");
  EXPECT_EQ(d->constraints[0].version, "1.0");

  d = parseDependency("physics_extras?");
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->optional);
  EXPECT_TRUE(d->constraints.empty());

  d = parseDependency("extras? ^2.1, < 2.5");
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->optional);
  EXPECT_EQ(d->constraints.size(), 2u);
  EXPECT_TRUE(parseDependency("extras >= 2?")->optional);

  for (const char* bad : {"base 1.0", "base >=", "base >= one", "", "base >= 1.0,", "two words"}) {
    auto r = parseDependency(bad);
    EXPECT_FALSE(r) << bad;
    if (!r) {
      EXPECT_NE(r.error().find("is not"), std::string::npos) << r.error();
    }
  }
}

TEST(ModDependencies, SemverOrderFollowsTheSpec) {
  // semver.org 11: 1.0.0-alpha < 1.0.0-alpha.1 < 1.0.0-alpha.beta < 1.0.0-beta
  // < 1.0.0-beta.2 < 1.0.0-beta.11 < 1.0.0-rc.1 < 1.0.0.
  const char* order[] = {"1.0.0-alpha", "1.0.0-alpha.1", "1.0.0-alpha.beta", "1.0.0-beta", "1.0.0-beta.2",
                         "1.0.0-beta.11", "1.0.0-rc.1", "1.0.0", "1.0.1", "1.1.0", "2.0.0", "10.0.0"};
  for (std::size_t i = 0; i + 1 < std::size(order); ++i) {
    EXPECT_LT(compareVersions(order[i], order[i + 1]), 0) << order[i] << " < " << order[i + 1];
    EXPECT_GT(compareVersions(order[i + 1], order[i]), 0);
  }
  EXPECT_EQ(compareVersions("1.2", "1.2.0"), 0);
  EXPECT_EQ(compareVersions("1.2.0+build.5", "1.2.0"), 0);
}

TEST(ModDependencies, ConstraintOperators) {
  EXPECT_TRUE(sat("1.0.0", ">= 1.0"));
  EXPECT_FALSE(sat("0.9.9", ">= 1.0"));
  EXPECT_FALSE(sat("1.0.0-beta", ">= 1.0"));
  EXPECT_TRUE(sat("1.0.1", "> 1.0"));
  EXPECT_FALSE(sat("1.0.0", "> 1.0"));
  EXPECT_TRUE(sat("2.0.0", "<= 2"));
  EXPECT_FALSE(sat("2.0.0", "< 2"));
  EXPECT_TRUE(sat("1.2.3", "= 1.2.3"));
  EXPECT_TRUE(sat("1.2.3", "== 1.2.3"));
  EXPECT_FALSE(sat("1.2.4", "= 1.2.3"));
  // ^: the left-most non-zero part stays.
  EXPECT_TRUE(sat("1.9.9", "^1.2.3"));
  EXPECT_FALSE(sat("1.2.2", "^1.2.3"));
  EXPECT_FALSE(sat("2.0.0", "^1.2.3"));
  EXPECT_FALSE(sat("2.0.0-rc.1", "^1.2.3"));
  EXPECT_TRUE(sat("0.2.9", "^0.2.3"));
  EXPECT_FALSE(sat("0.3.0", "^0.2.3"));
  EXPECT_TRUE(sat("0.0.3", "^0.0.3"));
  EXPECT_FALSE(sat("0.0.4", "^0.0.3"));
  EXPECT_TRUE(sat("1.5.0", "^1"));
  // ~: the minor stays (the major, when only it is given).
  EXPECT_TRUE(sat("1.2.9", "~1.2"));
  EXPECT_FALSE(sat("1.3.0", "~1.2.3"));
  EXPECT_TRUE(sat("1.9.0", "~1"));
  EXPECT_FALSE(sat("2.0.0", "~1"));
  // Several constraints: all must hold.
  EXPECT_TRUE(sat("1.4.0", ">= 1.2, < 2"));
  EXPECT_FALSE(sat("2.1.0", ">= 1.2, < 2"));
}

class ModRegistryTest : public ScriptTest {};

TEST_F(ModRegistryTest, LoadOrderIsByDependencyThenName) {
  makeMod(m_root, "zed");
  makeMod(m_root, "alpha", "  depends = {\"middle >= 1.0\"},\n");
  makeMod(m_root, "middle", "  depends = {\"base ^1.2\", \"extras?\"},\n");
  makeMod(m_root, "base", "", {}, "1.2.5");
  makeMod(m_root, "extras", "  depends = {\"base\"},\n", {}, "0.1.0");
  auto reg = script::ModRegistry::discover({m_root.string()});
  EXPECT_TRUE(reg.problems().empty()) << allProblems(reg.problems());
  // base first; extras before middle (optional but present), then by name.
  EXPECT_EQ(names(reg), (std::vector<std::string>{"base", "extras", "middle", "alpha", "zed"}));
}

TEST_F(ModRegistryTest, AbsentOptionalDependencyIsFine) {
  makeMod(m_root, "base");
  makeMod(m_root, "user", "  depends = {\"base\", \"physics_extras?\", \"more? >= 2\"},\n");
  auto reg = script::ModRegistry::discover({m_root.string()});
  EXPECT_TRUE(reg.problems().empty()) << allProblems(reg.problems());
  EXPECT_EQ(names(reg), (std::vector<std::string>{"base", "user"}));
}

TEST_F(ModRegistryTest, MissingDependencyIsAProblemWithFileAndLine) {
  makeMod(m_root, "user", "  depends = {\n    \"nothere >= 1.0\",\n  },\n");
  auto reg = script::ModRegistry::discover({m_root.string()});
  EXPECT_TRUE(reg.mods().empty());
  ASSERT_EQ(reg.problems().size(), 1u) << allProblems(reg.problems());
  const auto& p = reg.problems()[0];
  EXPECT_NE(p.message.find("missing dependency"), std::string::npos) << p.text();
  EXPECT_NE(p.message.find("nothere"), std::string::npos) << p.text();
  EXPECT_NE(p.text().find("user/mod.lua:6:"), std::string::npos) << p.text();
}

TEST_F(ModRegistryTest, VersionMismatchNamesBothVersions) {
  makeMod(m_root, "base", "", {}, "1.2.0");
  makeMod(m_root, "user", "  depends = {\"base >= 2.0\"},\n");
  makeMod(m_root, "picky", "  depends = {\"base? ~1.1\"},\n");  // optional, present, wrong version
  auto reg = script::ModRegistry::discover({m_root.string()});
  EXPECT_EQ(names(reg), (std::vector<std::string>{"base"}));
  std::string all = allProblems(reg.problems());
  EXPECT_NE(all.find("version mismatch: mod \"user\" needs base >= 2.0 but base is 1.2.0"), std::string::npos) << all;
  EXPECT_NE(all.find("version mismatch: mod \"picky\" needs base ~ 1.1 but base is 1.2.0"), std::string::npos) << all;
}

TEST_F(ModRegistryTest, CyclesAreReportedAndTheirDependentsToo) {
  makeMod(m_root, "x", "  depends = {\"y\"},\n");
  makeMod(m_root, "y", "  depends = {\"x >= 1\"},\n");
  makeMod(m_root, "w", "  depends = {\"x\"},\n");
  makeMod(m_root, "ok");
  auto reg = script::ModRegistry::discover({m_root.string()});
  EXPECT_EQ(names(reg), (std::vector<std::string>{"ok"}));
  std::string all = allProblems(reg.problems());
  EXPECT_NE(all.find("dependency cycle: x -> y -> x"), std::string::npos) << all;
  EXPECT_NE(all.find("x/mod.lua"), std::string::npos) << all;
  EXPECT_NE(all.find("y/mod.lua"), std::string::npos) << all;
  EXPECT_NE(all.find("mod \"w\" needs \"x\", which cannot be loaded"), std::string::npos) << all;
}

TEST_F(ModRegistryTest, ApiVersionIsChecked) {
  fs::path dir = m_root / "future";
  writeFile(dir / "mod.lua", "return {name = \"future\", version = \"1.0.0\",\n  api = 99}\n");
  auto reg = script::ModRegistry::discover({m_root.string()});
  EXPECT_TRUE(reg.mods().empty());
  std::string all = allProblems(reg.problems());
  EXPECT_NE(all.find("mod.lua:2: field 'api' is 99 but this Tumble provides API 1"), std::string::npos) << all;
}

TEST_F(ModRegistryTest, CheckReportsDependencyProblemsAgainstSiblings) {
  makeMod(m_root, "base", "", {}, "1.0.0");
  fs::path user = makeMod(m_root, "user", "  depends = {\"base >= 1.5\", \"gone\", \"self_ok?\"},\n",
                          {{"scenarios/bad.lua", "return {\n on_start = function( end }"}});
  auto problems = script::checkMod(user.string());
  std::string all = allProblems(problems);
  EXPECT_EQ(problems.size(), 3u) << all;
  EXPECT_NE(all.find("version mismatch"), std::string::npos) << all;
  EXPECT_NE(all.find("missing dependency: mod \"user\" needs \"gone\""), std::string::npos) << all;
  EXPECT_NE(all.find("bad.lua:2"), std::string::npos) << all;
  // With explicit search folders that hold a newer base, only "gone" is left.
  fs::path other = m_root.parent_path() / (m_root.filename().string() + "_other");
  fs::remove_all(other);
  makeMod(other, "base", "", {}, "1.6.0");
  makeMod(other, "gone");
  problems = script::checkMod(user.string(), {m_root.string(), other.string()});
  EXPECT_EQ(problems.size(), 1u) << allProblems(problems);
}

}  // namespace tumble::test
