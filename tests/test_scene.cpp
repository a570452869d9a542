// Scene loading: every invalid scene in tests/scenes/invalid fails with the error its
// first line announces; valid scenes load with the right values; command-line overrides; the
// simulate table. The [balls] ring: test_scene_ring.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"
#include "scene_texts.hpp"

namespace fs = std::filesystem;

using abu::testing::capture;
using abu::testing::kBase;
using abu::testing::kDefaultScene;
using abu::testing::kSourceDir;
using abu::testing::with_line;

namespace {

// `# expect: line=7 key=rotor.mass rule=must be > 0` (key may be empty; rule is the rest).
struct Expectation {
  int line = -1;
  std::string key;
  std::string rule;
  bool ok = false;
};

Expectation parse_expectation(const std::string& first_line) {
  Expectation e;
  const std::string prefix = "# expect: line=";
  if (first_line.rfind(prefix, 0) != 0) return e;
  const auto key_at = first_line.find(" key=");
  const auto rule_at = first_line.find(" rule=");
  if (key_at == std::string::npos || rule_at == std::string::npos || rule_at < key_at) return e;
  try {
    e.line = std::stoi(first_line.substr(prefix.size(), key_at - prefix.size()));
  } catch (const std::exception&) {
    return e;
  }
  e.key = first_line.substr(key_at + 5, rule_at - key_at - 5);
  e.rule = first_line.substr(rule_at + 6);
  e.ok = !e.rule.empty();
  return e;
}

std::string first_line_of(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

TEST_CASE("every invalid scene fails with the announced error", "[scene]") {
  const fs::path dir = fs::path(kSourceDir) / "tests" / "scenes" / "invalid";
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 20);

  for (const auto& file : files) {
    DYNAMIC_SECTION(file.filename().string()) {
      const Expectation expect = parse_expectation(first_line_of(file));
      REQUIRE(expect.ok);
      const std::string path = file.string();
      bool thrown = false;
      try {
        abu::load_scene(path);
      } catch (const abu::InputError& e) {
        thrown = true;
        INFO("what(): " << e.what());
        CHECK(e.file() == path);
        CHECK(e.line() == expect.line);
        CHECK(e.key() == expect.key);
        CHECK_THAT(e.rule(), Catch::Contains(expect.rule));
      }
      CHECK(thrown);
    }
  }
}

TEST_CASE("the expectation line parser reads all three fields", "[scene]") {
  const auto e = parse_expectation("# expect: line=7 key=rotor.mass rule=must be > 0 (got 0)");
  CHECK(e.ok);
  CHECK(e.line == 7);
  CHECK(e.key == "rotor.mass");
  CHECK(e.rule == "must be > 0 (got 0)");
  const auto empty_key = parse_expectation("# expect: line=3 key= rule=TOML syntax error");
  CHECK(empty_key.ok);
  CHECK(empty_key.key.empty());
  CHECK_FALSE(parse_expectation("# line=3 key=a rule=b").ok);
}

TEST_CASE("the default scene loads with its values", "[scene]") {
  const abu::Scene s = abu::load_scene(kDefaultScene);
  CHECK(s.file == kDefaultScene);
  CHECK(s.rotor.mass == 0.12);
  CHECK(s.rotor.stiffness == 7500.0);
  CHECK(s.rotor.damping == 2.0);
  CHECK(s.rotor.unbalance == 6.0e-7);
  CHECK(s.omega == 900.0);
  CHECK(s.law == abu::FrictionLaw::coulomb);
  CHECK(s.kappa == 1.0e3);
  REQUIRE(s.balls.size() == 2);
  for (const auto& b : s.balls) {
    CHECK(b.mass == 3.3e-5);
    CHECK(b.race_radius == 0.018);
    CHECK(b.radius == 1.0e-3);
    CHECK(b.inertia_factor == Approx(1.4).epsilon(1e-15));
    CHECK(b.mu == 0.002);
    CHECK(b.d == 0.0);
  }
  const abu::Params p = abu::params_of<2>(s);
  CHECK(p.rotor.mass == 0.12);
  CHECK(p.omega == 900.0);
  CHECK(p.balls[1].race_radius == 0.018);
  CHECK(p.total_mass() == Approx(0.12 + 2 * 3.3e-5));
}

TEST_CASE("the base text of these tests is itself valid", "[scene]") {
  const abu::Scene s = abu::parse_scene(kBase, "base");
  CHECK(s.balls.size() == 2);
  CHECK(s.balls[0].mu == 0.002);
}

TEST_CASE("integers are accepted where reals are expected", "[scene]") {
  const abu::Scene s = abu::parse_scene(with_line(4, "stiffness = 7500") + "", "int.toml");
  CHECK(s.rotor.stiffness == 7500.0);
  const abu::Scene t = abu::parse_scene(with_line(20, "omega = 1200"), "int.toml");
  CHECK(t.omega == 1200.0);
}

TEST_CASE("rolling = false gives j = 1, per ball as well", "[scene]") {
  const abu::Scene sliding = abu::parse_scene(with_line(1, "rolling = false"), "s.toml");
  CHECK(sliding.balls[0].inertia_factor == 1.0);
  CHECK(sliding.balls[1].inertia_factor == 1.0);
  // Ball 2 overrides the global default.
  const abu::Scene mixed = abu::parse_scene(with_line(14, "radius = 1.0e-3\nrolling = false"), "m.toml");
  CHECK(mixed.balls[0].inertia_factor == Approx(1.4));
  CHECK(mixed.balls[1].inertia_factor == 1.0);
}

TEST_CASE("per-ball friction coefficients override [friction]", "[scene]") {
  const abu::Scene s = abu::parse_scene(with_line(10, "radius = 1.0e-3\nmu = 0.005"), "o.toml");
  CHECK(s.balls[0].mu == 0.005);
  CHECK(s.balls[1].mu == 0.002);
  // With every ball giving its own mu, [friction] may omit it.
  const std::string text = [&] {
    std::string t = with_line(17, "");  // drop [friction].mu
    const std::string marker = "radius = 1.0e-3\n";
    auto first = t.find(marker);
    t.insert(first + marker.size(), "mu = 0.004\n");
    auto second = t.find(marker, first + marker.size());
    t.insert(second + marker.size(), "mu = 0.006\n");
    return t;
  }();
  const abu::Scene all = abu::parse_scene(text, "all.toml");
  CHECK(all.balls[0].mu == 0.004);
  CHECK(all.balls[1].mu == 0.006);
}

TEST_CASE("a three-ball scene loads; params_of checks the ball count", "[scene]") {
  const std::string three = with_line(14, "radius = 1.0e-3\n[[ball]]\nmass = 4.0e-5\nrace_radius = 0.02\nradius = 2.0e-3");
  const abu::Scene s = abu::parse_scene(three, "three.toml");
  REQUIRE(s.balls.size() == 3);
  CHECK(s.balls[2].mass == 4.0e-5);
  CHECK(s.balls[2].mu == 0.002);
  const auto p3 = abu::params_of<3>(s);
  CHECK(p3.balls[2].radius == 2.0e-3);
  CHECK_THROWS_AS(abu::params_of<2>(s), abu::NotSupportedError);
  CHECK_THROWS_WITH(abu::params_of<2>(s), Catch::Contains("scene has 3 balls"));

  const abu::Scene two = abu::load_scene(kDefaultScene);
  CHECK_THROWS_AS(abu::params_of<3>(two), abu::NotSupportedError);
}

TEST_CASE("the first violation in file order wins", "[scene]") {
  // Two defects: damping (sorted first by toml++) on line 5, mass on line 3.
  std::string text = with_line(3, "mass = -1.0");
  text = text.replace(text.find("damping = 2.0"), 13, "damping = -2.0");
  const auto e = capture([&] { abu::parse_scene(text, "two.toml"); });
  CHECK(e.line() == 3);
  CHECK(e.key() == "rotor.mass");
  CHECK(std::string(e.what()) == "two.toml:3: key 'rotor.mass': must be > 0 (got -1)");
  // The same defect on ball 2 is reported as ball[2], not ball[1].
  const auto f = capture([&] { abu::parse_scene(with_line(13, "race_radius = -0.018"), "b.toml"); });
  CHECK(f.key() == "ball[2].race_radius");
  CHECK(f.line() == 13);
}

TEST_CASE("unreadable files are InputErrors at line 0", "[scene]") {
  const std::string missing = kSourceDir + "/tests/scenes/no-such-scene.toml";
  const auto e = capture([&] { abu::load_scene(missing); });
  CHECK(e.file() == missing);
  CHECK(e.line() == 0);
  CHECK(e.key().empty());
  CHECK_THAT(e.rule(), Catch::StartsWith("cannot read file: "));
  const auto d = capture([&] { abu::load_scene(kSourceDir + "/tests"); });
  CHECK_THAT(d.rule(), Catch::Contains("directory"));
}

TEST_CASE("apply_override sets parameters", "[scene]") {
  abu::Scene s = abu::load_scene(kDefaultScene);
  abu::apply_override(s, "omega=1200");
  CHECK(s.omega == 1200.0);
  abu::apply_override(s, "m2=4e-5");
  CHECK(s.balls[0].mass == 3.3e-5);
  CHECK(s.balls[1].mass == 4e-5);
  abu::apply_override(s, "mu=0.003");
  CHECK(s.balls[0].mu == 0.003);
  CHECK(s.balls[1].mu == 0.003);
  abu::apply_override(s, "M_r=0.2");
  CHECK(s.rotor.mass == 0.2);
  abu::apply_override(s, "kappa=500");
  CHECK(s.kappa == 500.0);
  abu::apply_override(s, "r1=0.002");
  CHECK(s.balls[0].radius == 0.002);
  CHECK(s.balls[1].radius == 1.0e-3);
}

TEST_CASE("apply_override rejects bad assignments", "[scene]") {
  abu::Scene s = abu::load_scene(kDefaultScene);
  const abu::Scene before = s;
  struct Case {
    const char* assignment;
    const char* key;
    const char* rule;
  };
  const Case cases[] = {
      {"omgea=1200", "omgea", "unknown parameter; did you mean 'omega'? (known: "},
      {"xyz=1", "xyz", "unknown parameter; known: "},
      {"m3=1e-5", "m3", "ball index out of range"},
      {"omega", "omega", "expected NAME=VALUE"},
      {"=1200", "=1200", "expected NAME=VALUE"},
      {"omega=", "omega=", "expected NAME=VALUE"},
      {"omega=fast", "omega", "not a number"},
      {"omega=12x", "omega", "not a number"},
      {"omega=inf", "omega", "must be a finite number"},
      {"omega=nan", "omega", "must be a finite number"},
      {"omega=1e999", "omega", "must be a finite number"},
      {"omega=-5", "omega", "must be > 0"},
      {"c=-1", "c", "must be >= 0"},
      {"d=0.1", "d", "friction law 'coulomb' does not use 'd'"},
      {"v_s=1", "v_s", "friction law 'coulomb' does not use 'v_s'"},
      {"r=0.018", "r", "must be < race_radius"},
      {"l2=0.0005", "l2", "radius < race_radius"},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.assignment) {
      const auto e = capture([&] { abu::apply_override(s, c.assignment); });
      CHECK(e.file() == "--set");
      CHECK(e.line() == 0);
      CHECK(e.key() == c.key);
      CHECK_THAT(e.rule(), Catch::Contains(c.rule));
      // A rejected override leaves the scene as it was.
      CHECK(s.omega == before.omega);
      CHECK(s.rotor.damping == before.rotor.damping);
      CHECK(s.balls[0].radius == before.balls[0].radius);
      CHECK(s.balls[1].race_radius == before.balls[1].race_radius);
      CHECK(s.balls[0].d == before.balls[0].d);
    }
  }
}

TEST_CASE("set_checked uses the given origin", "[scene]") {
  abu::Scene s = abu::load_scene(kDefaultScene);
  const auto ref = abu::parse_param("k", 2);
  REQUIRE(ref.has_value());
  abu::set_checked(s, *ref, 9000.0, "sweep");
  CHECK(s.rotor.stiffness == 9000.0);
  const auto e = capture([&] { abu::set_checked(s, *ref, 0.0, "sweep"); });
  CHECK(e.file() == "sweep");
  CHECK(e.key() == "k");
  CHECK_THAT(e.rule(), Catch::Contains("must be > 0"));
  CHECK(s.rotor.stiffness == 9000.0);
}

TEST_CASE("the simulate table gives the run-up and the integration settings", "[scene][simulate]") {
  const abu::Scene none = abu::parse_scene(kBase, "base");
  CHECK_FALSE(none.simulate.has_value());
  const std::string text = std::string(kBase) +
                           "\n[simulate]\nramp = { omega0 = 100, omega1 = 400, alpha = 200 }\nt_end = 2.5\n"
                           "every = 1e-3\nrtol = 1e-9\nmethod = \"rk8pd\"\nballs = [2, 4.5]\n";
  const abu::Scene s = abu::parse_scene(text, "sim.toml");
  REQUIRE(s.simulate.has_value());
  REQUIRE(s.simulate->speed.has_value());
  // 100 -> 400 rad/s at 200 rad/s^2: the ramp ends at t = 1.5 s, then the speed is held.
  CHECK(s.simulate->speed->omega(0.75) == Approx(250.0).epsilon(1e-15));
  CHECK(s.simulate->speed->end_of_change() == Approx(1.5).epsilon(1e-15));
  CHECK(s.simulate->speed->omega(3.0) == 400.0);
  CHECK(s.simulate->t_end == 2.5);
  CHECK(s.simulate->every == 1e-3);
  CHECK(s.simulate->rtol == 1e-9);
  CHECK(s.simulate->method == "rk8pd");
  CHECK(s.simulate->balls == std::vector<double>{2.0, 4.5});
  CHECK(s.simulate->from_state.empty());
  CHECK(s.omega == 900.0);  // [speed] is unchanged: the run-up is for simulate and basin only
}

TEST_CASE("a speed profile of the simulate table is read relative to the scene file", "[scene][simulate]") {
  const fs::path dir = fs::temp_directory_path() / fs::path("abu_simulate_table_test");
  fs::create_directories(dir);
  {
    std::ofstream(dir / "profile.csv") << "t,omega\n0,120\n0.5,300\n";
    std::ofstream(dir / "scene.toml") << kBase << "\n[simulate]\nspeed_profile = \"profile.csv\"\n";
  }
  const abu::Scene s = abu::load_scene((dir / "scene.toml").string());
  fs::remove_all(dir);
  REQUIRE(s.simulate.has_value());
  REQUIRE(s.simulate->speed.has_value());
  CHECK(s.simulate->speed->points().size() == 2);
  CHECK(s.simulate->speed->omega(0.25) == Approx(210.0).epsilon(1e-15));
}
