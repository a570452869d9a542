// The [balls] ring shorthand of scene files (scene.hpp, ball_ring.hpp): expansion into its balls,
// overrides, errors at their line and key, set_ball_count, and the bound of 2..12 balls.
#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"
#include "scene_texts.hpp"

using abu::testing::capture;
using abu::testing::kBase;
using abu::testing::kDefaultScene;
using abu::testing::kRing;
using abu::testing::kSourceDir;
using abu::testing::with_line;

namespace {

// kRing (scene_texts.hpp): overrides are appended after line 17 (TOML lets [[balls.override]]
// follow any table), so that the line numbers below stay those of that text.

// kRing with line n (1-based) replaced (possibly by several lines), then `tail` appended.
std::string ring_with(int n, const std::string& replacement, const std::string& tail = "") {
  std::string out, line;
  std::istringstream in(kRing);
  for (int i = 1; std::getline(in, line); ++i) out += (i == n ? replacement : line) + "\n";
  return out + tail;
}
std::string ring_plus(const std::string& tail) { return std::string(kRing) + tail; }

// The kBase rotor/friction/speed with `k` [[ball]] tables (4 lines each, from line 7).
std::string with_ball_tables(int k) {
  std::string text = "rolling = true\n[rotor]\nmass = 0.12\nstiffness = 7500.0\ndamping = 2.0\nunbalance = 6.0e-7\n";
  for (int i = 0; i < k; ++i) text += "[[ball]]\nmass = 3.3e-5\nrace_radius = 0.018\nradius = 1.0e-3\n";
  return text + "[friction]\nlaw = \"coulomb\"\nmu = 0.002\nkappa = 1.0e3\n[speed]\nomega = 900.0\n";
}

const abu::RingOverride* find_override(const abu::BallRing& ring, int ball, abu::BallField field) {
  for (const auto& o : ring.overrides)
    if (o.ball == ball && o.field == field) return &o;
  return nullptr;
}

// `text` with the first `from` replaced by `to`; `from` must be there.
std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}
const std::string kRadius = "radius = 1.0e-3\n";  // line 11 of kRing

}  // namespace

TEST_CASE("scene ring: a [balls] ring expands into its balls", "[scene][ring]") {
  const abu::Scene s = abu::parse_scene(kRing, "ring.toml");
  REQUIRE(s.balls.size() == 3);
  for (const auto& b : s.balls) {
    CHECK(b.mass == 3.3e-5);
    CHECK(b.race_radius == 0.018);
    CHECK(b.radius == 1.0e-3);
    CHECK(b.inertia_factor == Approx(1.4).epsilon(1e-15));
    CHECK(b.mu == 0.002);
    CHECK(b.d == 0.0);
  }
  REQUIRE(s.ring.has_value());
  CHECK(s.ring->count == 3);
  CHECK_FALSE(s.ring->total_mass_held);
  CHECK(s.ring->ball.mass == 3.3e-5);
  CHECK(s.ring->ball.mu == 0.002);
  CHECK(s.ring->overrides.empty());
  // The same scene written as [[ball]] tables has no ring.
  CHECK_FALSE(abu::parse_scene(kBase, "base").ring.has_value());
  const auto p3 = abu::params_of<3>(s);
  CHECK(p3.total_mass() == Approx(0.12 + 3 * 3.3e-5));
}

TEST_CASE("scene ring: a ring's total_mass is shared by its balls", "[scene][ring]") {
  const abu::Scene s = abu::parse_scene(ring_with(9, "total_mass = 1.2e-4"), "ring.toml");
  REQUIRE(s.balls.size() == 3);
  for (const auto& b : s.balls) CHECK(b.mass == 1.2e-4 / 3);
  REQUIRE(s.ring.has_value());
  CHECK(s.ring->total_mass_held);
  CHECK(s.ring->total_mass == 1.2e-4);
  CHECK(s.ring->ball.mass == 1.2e-4 / 3);
  // An override's mass replaces that ball's share only.
  const abu::Scene o = abu::parse_scene(ring_with(9, "total_mass = 1.2e-4", "[[balls.override]]\nball = 2\nmass = 1.0e-5\n"),
                                        "ring.toml");
  CHECK(o.balls[0].mass == 1.2e-4 / 3);
  CHECK(o.balls[1].mass == 1.0e-5);
  CHECK(o.balls[2].mass == 1.2e-4 / 3);
}

TEST_CASE("scene ring: ring overrides change one ball each and are kept with their origin", "[scene][ring]") {
  const std::string text = ring_with(1, "rolling = false",
                                     "[[balls.override]]\n"    // 18
                                     "ball = 3\n"              // 19
                                     "mass = 4.0e-5\n"         // 20
                                     "race_radius = 0.02\n"    // 21
                                     "[[balls.override]]\n"    // 22
                                     "ball = 1\n"              // 23
                                     "rolling = true\n"        // 24
                                     "mu = 0.005\n");          // 25
  const abu::Scene s = abu::parse_scene(text, "ring.toml");
  REQUIRE(s.balls.size() == 3);
  // Ball 1: rolling and its own mu; ball 2: the template (sliding, [friction]'s mu).
  CHECK(s.balls[0].inertia_factor == Approx(1.4).epsilon(1e-15));
  CHECK(s.balls[0].mu == 0.005);
  CHECK(s.balls[0].mass == 3.3e-5);
  CHECK(s.balls[1].inertia_factor == 1.0);
  CHECK(s.balls[1].mu == 0.002);
  CHECK(s.balls[1].mass == 3.3e-5);
  CHECK(s.balls[1].race_radius == 0.018);
  CHECK(s.balls[2].mass == 4.0e-5);
  CHECK(s.balls[2].race_radius == 0.02);
  CHECK(s.balls[2].radius == 1.0e-3);
  CHECK(s.balls[2].inertia_factor == 1.0);

  REQUIRE(s.ring.has_value());
  CHECK(s.ring->ball.inertia_factor == 1.0);
  REQUIRE(s.ring->overrides.size() == 4);
  const auto* m3 = find_override(*s.ring, 2, abu::BallField::mass);
  REQUIRE(m3 != nullptr);
  CHECK(m3->value == 4.0e-5);
  CHECK(m3->line == 20);
  CHECK(m3->origin == "ring.toml");
  CHECK(m3->key == "balls.override[1].mass");
  const auto* j1 = find_override(*s.ring, 0, abu::BallField::inertia_factor);
  REQUIRE(j1 != nullptr);
  CHECK(j1->value == Approx(1.4).epsilon(1e-15));
  CHECK(j1->line == 24);
  CHECK(j1->key == "balls.override[2].rolling");
  const auto* mu1 = find_override(*s.ring, 0, abu::BallField::mu);
  REQUIRE(mu1 != nullptr);
  CHECK(mu1->line == 25);

  // ring_balls reproduces the expansion exactly.
  const auto again = abu::ring_balls(*s.ring);
  REQUIRE(again.size() == s.balls.size());
  for (std::size_t i = 0; i < again.size(); ++i) {
    CHECK(again[i].mass == s.balls[i].mass);
    CHECK(again[i].race_radius == s.balls[i].race_radius);
    CHECK(again[i].inertia_factor == s.balls[i].inertia_factor);
    CHECK(again[i].mu == s.balls[i].mu);
  }
}

TEST_CASE("scene ring: [balls] rolling and coefficients override the top level and [friction]", "[scene][ring]") {
  const abu::Scene sliding = abu::parse_scene(ring_with(1, "rolling = false"), "ring.toml");
  for (const auto& b : sliding.balls) CHECK(b.inertia_factor == 1.0);
  // rolling in [balls] beats the top-level one, for the whole ring.
  const abu::Scene back = abu::parse_scene(edit(ring_with(1, "rolling = false"), kRadius, "radius = 1.0e-3\nrolling = true\n"),
                                           "ring.toml");
  for (const auto& b : back.balls) CHECK(b.inertia_factor == Approx(1.4).epsilon(1e-15));
  CHECK(back.ring->ball.inertia_factor == Approx(1.4).epsilon(1e-15));
  // [balls].mu beats [friction].mu.
  const abu::Scene own = abu::parse_scene(edit(kRing, kRadius, "radius = 1.0e-3\nmu = 0.003\n"), "ring.toml");
  for (const auto& b : own.balls) CHECK(b.mu == 0.003);
  CHECK(own.ring->ball.mu == 0.003);
  // With [balls].mu, [friction] may omit mu.
  const abu::Scene only = abu::parse_scene(edit(edit(kRing, kRadius, "radius = 1.0e-3\nmu = 0.004\n"), "mu = 0.002\n", ""),
                                           "ring.toml");
  for (const auto& b : only.balls) CHECK(b.mu == 0.004);
}

TEST_CASE("scene ring: data/scenes/ring11.toml is the default scene with an 11-ball ring", "[scene][ring]") {
  const abu::Scene s = abu::load_scene(kSourceDir + "/data/scenes/ring11.toml");
  const abu::Scene d = abu::load_scene(kDefaultScene);
  REQUIRE(s.balls.size() == 11);
  REQUIRE(s.ring.has_value());
  CHECK(s.ring->count == 11);
  CHECK(s.rotor.mass == d.rotor.mass);
  CHECK(s.rotor.stiffness == d.rotor.stiffness);
  CHECK(s.rotor.damping == d.rotor.damping);
  CHECK(s.rotor.unbalance == d.rotor.unbalance);
  CHECK(s.omega == d.omega);
  CHECK(s.law == d.law);
  CHECK(s.kappa == d.kappa);
  for (const auto& b : s.balls) {
    CHECK(b.mass == d.balls[0].mass);
    CHECK(b.race_radius == d.balls[0].race_radius);
    CHECK(b.radius == d.balls[0].radius);
    CHECK(b.inertia_factor == d.balls[0].inertia_factor);
    CHECK(b.mu == d.balls[0].mu);
  }
}

TEST_CASE("scene ring: ring errors name their line and key", "[scene][ring]") {
  struct Case {
    const char* name;
    std::string text;
    int line;
    const char* key;
    const char* rule;
  };
  const std::string ovr = "[[balls.override]]\nball = 2\n";  // lines 18, 19
  const std::string ball_table = "[[ball]]\nmass = 3.3e-5\nrace_radius = 0.018\nradius = 1.0e-3\n";
  const Case cases[] = {
      {"[[ball]] after [balls]", ring_plus(ball_table), 18, "ball", "exclude each other"},
      {"[balls] after [[ball]]",
       std::string(kBase) + "[balls]\ncount = 3\nmass = 3.3e-5\nrace_radius = 0.018\nradius = 1.0e-3\n", 21, "balls",
       "exclude each other"},
      {"missing count", ring_with(8, ""), 7, "balls.count", "missing required key"},
      {"count 1", ring_with(8, "count = 1"), 8, "balls.count", "at least 2 balls are required, got 1"},
      {"count 0", ring_with(8, "count = 0"), 8, "balls.count", "at least 2 balls are required, got 0"},
      {"count 13", ring_with(8, "count = 13"), 8, "balls.count", "at most 12 balls (the analyzer's bound; model.md §13), got 13"},
      {"count 11.0", ring_with(8, "count = 11.0"), 8, "balls.count", "must be an integer (2..12), got the floating-point number 11.0"},
      {"count 11.5", ring_with(8, "count = 11.5"), 8, "balls.count", "must be an integer (2..12), got the floating-point number 11.5"},
      {"count string", ring_with(8, "count = \"3\""), 8, "balls.count", "must be an integer (2..12), got the string \"3\""},
      {"mass and total_mass", ring_with(9, "mass = 3.3e-5\ntotal_mass = 1e-4"), 10, "balls.total_mass",
       "give either mass (per ball) or total_mass (of the ring), not both (mass is at line 9)"},
      {"total_mass and mass", ring_with(9, "total_mass = 1e-4\nmass = 3.3e-5"), 10, "balls.mass", "not both (total_mass is at line 9)"},
      {"neither mass", ring_with(9, ""), 7, "balls.mass", "mass (per ball) or total_mass (of the ring)"},
      {"missing race_radius", ring_with(10, ""), 7, "balls.race_radius", "missing required key"},
      {"unknown key", ring_with(9, "mass = 3.3e-5\nkappa = 5.0"), 10, "balls.kappa",
       "unknown key; allowed here: count, mass, total_mass, race_radius, radius, diameter, density, surface_radius, "
       "rolling, mu, f, d, mu_c, mu_s, v_s, sigma0, sigma1, sigma2, override"},
      {"total_mass 0", ring_with(9, "total_mass = 0"), 9, "balls.total_mass", "must be > 0 (got 0)"},
      {"negative mass", ring_with(9, "mass = -1e-5"), 9, "balls.mass", "must be > 0 (got -1e-05)"},
      {"rolling not bool", ring_with(9, "mass = 3.3e-5\nrolling = 1"), 10, "balls.rolling", "must be true or false"},
      {"template radius", ring_with(11, "radius = 0.018"), 11, "balls.radius",
       "must be < race_radius (got radius 0.018 >= race_radius 0.018)"},
      {"template d", ring_with(11, "radius = 1.0e-3\nd = 0.1"), 12, "balls.d", "friction law 'coulomb' does not use 'd'"},
      {"[[balls]]", ring_with(7, "[[balls]]"), 7, "balls", "must be a table ([balls]), got an array"},
      {"[balls.override] single", ring_plus("[balls.override]\nball = 2\n"), 18, "balls.override",
       "must be an array of tables ([[balls.override]], one per ball that differs), got a single table"},
      {"override unknown key", ring_plus(ovr + "count = 4\n"), 20, "balls.override[1].count",
       "unknown key; allowed here: ball, mass, race_radius, radius, diameter, density, surface_radius, rolling, mu, "
       "f, d, mu_c, mu_s, v_s, sigma0, sigma1, sigma2"},
      {"override kappa", ring_plus(ovr + "kappa = 4\n"), 20, "balls.override[1].kappa", "unknown key"},
      {"override missing ball", ring_plus("[[balls.override]]\nmass = 4e-5\n"), 18, "balls.override[1].ball",
       "missing required key"},
      {"override ball 0", ring_plus("[[balls.override]]\nball = 0\n"), 19, "balls.override[1].ball",
       "must be 1..3 (a ball of the ring, 1-based), got 0"},
      {"override ball 4", ring_plus("[[balls.override]]\nball = 4\n"), 19, "balls.override[1].ball",
       "must be 1..3 (a ball of the ring, 1-based), got 4"},
      {"override ball 2.0", ring_plus("[[balls.override]]\nball = 2.0\n"), 19, "balls.override[1].ball",
       "must be an integer (a 1-based ball index), got the floating-point number 2.0"},
      {"override repeated", ring_plus(ovr + "mass = 4e-5\n" + ovr + "mass = 5e-5\n"), 22, "balls.override[2].ball",
       "ball 2 is already overridden at line 19: at most one [[balls.override]] per ball"},
      {"override negative mass", ring_plus(ovr + "mass = -4e-5\n"), 20, "balls.override[1].mass", "must be > 0"},
      {"override radius", ring_plus(ovr + "radius = 0.02\n"), 20, "balls.override[1].radius",
       "must be < race_radius (got radius 0.02 >= race_radius 0.018) for ball 2 of the ring"},
      {"override race_radius", ring_plus(ovr + "race_radius = 5e-4\n"), 20, "balls.override[1].race_radius",
       "must be > radius, as radius < race_radius (got race_radius 0.0005 <= radius 0.001) for ball 2 of the ring"},
      {"override both radii", ring_plus(ovr + "race_radius = 0.002\nradius = 0.003\n"), 21, "balls.override[1].radius",
       "must be < race_radius (got radius 0.003 >= race_radius 0.002) for ball 2 of the ring"},
      {"override d", ring_plus(ovr + "d = 0.1\n"), 20, "balls.override[1].d", "friction law 'coulomb' does not use 'd'"},
      {"override rolling", ring_plus(ovr + "rolling = \"yes\"\n"), 20, "balls.override[1].rolling", "must be true or false"},
      {"mu on one ball only", ring_with(14, "", ovr + "mu = 0.004\n"), 12, "friction.mu",
       "per-ball values replace it only if every ball has one, and ball 1 of the [balls] ring has none"},
      {"no balls at all",
       "[rotor]\nmass = 0.12\nstiffness = 7500.0\ndamping = 2.0\nunbalance = 6.0e-7\n"
       "[friction]\nlaw = \"none\"\n[speed]\nomega = 900.0\n",
       9, "ball", "at least 2 balls are required ([[ball]] tables or a [balls] ring), got 0"},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.name) {
      const auto e = capture([&] { abu::parse_scene(c.text, "ring.toml"); });
      INFO("what(): " << e.what());
      CHECK(e.file() == "ring.toml");
      CHECK(e.line() == c.line);
      CHECK(e.key() == c.key);
      CHECK_THAT(e.rule(), Catch::Contains(c.rule));
    }
  }
}

TEST_CASE("a scene has at most 12 [[ball]] tables", "[scene][ring]") {
  const abu::Scene twelve = abu::parse_scene(with_ball_tables(12), "twelve.toml");
  CHECK(twelve.balls.size() == 12);
  CHECK_FALSE(twelve.ring.has_value());
  for (int k : {13, 14}) {
    const auto e = capture([&] { abu::parse_scene(with_ball_tables(k), "many.toml"); });
    // Table i (1-based) starts at line 7 + 4 (i - 1): the 13th at line 55.
    CHECK(e.line() == 55);
    CHECK(e.key() == "ball");
    CHECK(e.rule() == "at most 12 balls (the analyzer's bound; model.md §13), got " + std::to_string(k));
  }
  const auto one = capture([&] { abu::parse_scene(with_ball_tables(1), "one.toml"); });
  CHECK(one.line() == 7);
  CHECK(one.rule() == "at least 2 balls are required, got 1");
}

TEST_CASE("scene ring: set_ball_count rebuilds a ring", "[scene][ring]") {
  SECTION("mass held: every ball keeps its mass") {
    abu::Scene s = abu::parse_scene(kRing, "ring.toml");
    abu::set_ball_count(s, 5, "--n");
    REQUIRE(s.balls.size() == 5);
    CHECK(s.ring->count == 5);
    for (const auto& b : s.balls) {
      CHECK(b.mass == 3.3e-5);
      CHECK(b.mu == 0.002);
      CHECK(b.radius == 1.0e-3);
    }
    abu::set_ball_count(s, 2, "--n");
    CHECK(s.balls.size() == 2);
    CHECK(s.balls[1].mass == 3.3e-5);
    abu::set_ball_count(s, 12, "--n");
    CHECK(s.balls.size() == 12);
  }
  SECTION("total mass held: the balls share it") {
    abu::Scene s = abu::parse_scene(ring_with(9, "total_mass = 1.2e-4"), "ring.toml");
    abu::set_ball_count(s, 6, "--n");
    REQUIRE(s.balls.size() == 6);
    for (const auto& b : s.balls) CHECK(b.mass == 1.2e-4 / 6);
    CHECK(s.ring->ball.mass == 1.2e-4 / 6);
    CHECK(s.ring->total_mass == 1.2e-4);
    CHECK(s.ring->total_mass_held);
    abu::set_ball_count(s, 4, "--n");
    for (const auto& b : s.balls) CHECK(b.mass == 1.2e-4 / 4);
  }
  SECTION("overrides beyond the count are inactive and return") {
    abu::Scene s = abu::parse_scene(ring_plus("[[balls.override]]\nball = 3\nmass = 4.0e-5\n"), "ring.toml");
    CHECK(s.balls[2].mass == 4.0e-5);
    abu::set_ball_count(s, 2, "--n");
    REQUIRE(s.balls.size() == 2);
    CHECK(s.balls[0].mass == 3.3e-5);
    CHECK(s.balls[1].mass == 3.3e-5);
    REQUIRE(s.ring->overrides.size() == 1);  // kept, inactive
    CHECK(s.ring->overrides[0].ball == 2);
    abu::set_ball_count(s, 4, "--n");
    REQUIRE(s.balls.size() == 4);
    CHECK(s.balls[1].mass == 3.3e-5);
    CHECK(s.balls[2].mass == 4.0e-5);
    CHECK(s.balls[3].mass == 3.3e-5);
  }
}

TEST_CASE("scene ring: set_ball_count refuses and leaves the scene unchanged", "[scene][ring]") {
  SECTION("a scene of [[ball]] tables") {
    abu::Scene s = abu::load_scene(kDefaultScene);
    const auto e = capture([&] { abu::set_ball_count(s, 3, "study"); });
    CHECK(e.file() == "study");
    CHECK(e.line() == 0);
    CHECK(e.key() == "n");
    CHECK_THAT(e.rule(), Catch::StartsWith("the ball count is a study parameter only for a [balls] ring scene"));
    CHECK(s.balls.size() == 2);
    CHECK_FALSE(s.ring.has_value());
  }
  SECTION("a count outside 2..12") {
    abu::Scene s = abu::parse_scene(ring_plus("[[balls.override]]\nball = 3\nmass = 4.0e-5\n"), "ring.toml");
    const struct {
      int n;
      const char* rule;
    } cases[] = {{1, "at least 2 balls are required, got 1"},
                 {0, "at least 2 balls are required, got 0"},
                 {-3, "at least 2 balls are required, got -3"},
                 {13, "at most 12 balls (the analyzer's bound; model.md §13), got 13"}};
    for (const auto& c : cases) {
      const auto e = capture([&] { abu::set_ball_count(s, c.n, "--n"); });
      CHECK(e.file() == "--n");
      CHECK(e.line() == 0);
      CHECK(e.key() == "n");
      CHECK(e.rule() == c.rule);
      REQUIRE(s.balls.size() == 3);
      CHECK(s.ring->count == 3);
      CHECK(s.balls[2].mass == 4.0e-5);
    }
  }
  SECTION("a ball of the new ring that breaks a rule") {
    // Ball 3's race radius (line 20) is inactive at n = 2 while r grows past it.
    abu::Scene s = abu::parse_scene(ring_plus("[[balls.override]]\nball = 3\nrace_radius = 0.01\n"), "ring.toml");
    abu::set_ball_count(s, 2, "--n");
    abu::apply_override(s, "r=0.015");
    CHECK(s.balls[1].radius == 0.015);
    const auto e = capture([&] { abu::set_ball_count(s, 3, "--n"); });
    CHECK(e.key() == "n");
    CHECK(e.rule() ==
          "with n = 3, ball 3: radius must be < race_radius (got radius 0.015 >= race_radius 0.01) (race_radius set by "
          "balls.override[1].race_radius (ring.toml:20))");
    CHECK(s.balls.size() == 2);
    CHECK(s.ring->count == 2);
    CHECK(s.balls[0].radius == 0.015);
  }
  SECTION("a coefficient that only overrides gave") {
    // No mu in [friction] or [balls]: both balls have their own, a third would have none.
    const std::string text =
        ring_with(14, "", "[[balls.override]]\nball = 1\nmu = 0.003\n[[balls.override]]\nball = 2\nmu = 0.004\n");
    abu::Scene s = abu::parse_scene(edit(text, "count = 3", "count = 2"), "ring.toml");
    CHECK(s.balls[0].mu == 0.003);
    CHECK(s.balls[1].mu == 0.004);
    CHECK(std::isnan(s.ring->ball.mu));
    const auto e = capture([&] { abu::set_ball_count(s, 3, "--n"); });
    CHECK_THAT(e.rule(), Catch::StartsWith("with n = 3, ball 3 has no mu: neither [friction] nor [balls] gives one"));
    CHECK(s.balls.size() == 2);
    // Once every ball is given mu, the count may grow.
    abu::apply_override(s, "mu=0.005");
    abu::set_ball_count(s, 3, "--n");
    CHECK(s.balls[2].mu == 0.005);
  }
}

TEST_CASE("scene ring: overrides keep the ring consistent", "[scene][ring]") {
  SECTION("a one-ball symbol becomes a ring override") {
    abu::Scene s = abu::parse_scene(kRing, "ring.toml");
    abu::apply_override(s, "m3=4e-5");
    CHECK(s.balls[0].mass == 3.3e-5);
    CHECK(s.balls[2].mass == 4e-5);
    const auto* o = find_override(*s.ring, 2, abu::BallField::mass);
    REQUIRE(o != nullptr);
    CHECK(o->value == 4e-5);
    CHECK(o->origin == "--set");
    CHECK(o->line == 0);
    CHECK(o->key == "m3");
    abu::set_ball_count(s, 2, "--n");
    abu::set_ball_count(s, 3, "--n");
    CHECK(s.balls[2].mass == 4e-5);
    // Setting it again replaces the override.
    abu::apply_override(s, "m3=5e-5");
    CHECK(s.ring->overrides.size() == 1);
    CHECK(s.ring->overrides[0].value == 5e-5);
  }
  SECTION("a one-ball symbol replaces the file's override of that ball and field") {
    abu::Scene s = abu::parse_scene(ring_plus("[[balls.override]]\nball = 2\nmu = 0.004\nmass = 4e-5\n"), "ring.toml");
    abu::set_checked(s, *abu::parse_param("mu2", 3), 0.006, "sweep");
    REQUIRE(s.ring->overrides.size() == 2);
    const auto* o = find_override(*s.ring, 1, abu::BallField::mu);
    REQUIRE(o != nullptr);
    CHECK(o->value == 0.006);
    CHECK(o->origin == "sweep");
    CHECK(o->key == "mu2");
    CHECK(s.balls[1].mu == 0.006);
    CHECK(s.balls[1].mass == 4e-5);
  }
  SECTION("an every-ball symbol sets the template and drops that field's overrides") {
    abu::Scene s = abu::parse_scene(ring_plus("[[balls.override]]\nball = 3\nradius = 2e-3\nmass = 4e-5\n"), "ring.toml");
    abu::set_ball_count(s, 2, "--n");  // the override is inactive: dropped all the same
    abu::apply_override(s, "r=1.5e-3");
    CHECK(s.ring->ball.radius == 1.5e-3);
    REQUIRE(s.ring->overrides.size() == 1);
    CHECK(s.ring->overrides[0].field == abu::BallField::mass);
    abu::set_ball_count(s, 4, "--n");
    for (const auto& b : s.balls) CHECK(b.radius == 1.5e-3);
    CHECK(s.balls[2].mass == 4e-5);
  }
  SECTION("m on a total-mass ring holds the per-ball mass from then on") {
    abu::Scene s = abu::parse_scene(ring_with(9, "total_mass = 1.2e-4"), "ring.toml");
    abu::apply_override(s, "m=5e-5");
    for (const auto& b : s.balls) CHECK(b.mass == 5e-5);
    CHECK_FALSE(s.ring->total_mass_held);
    abu::set_ball_count(s, 6, "--n");
    for (const auto& b : s.balls) CHECK(b.mass == 5e-5);
  }
  SECTION("global symbols leave the ring alone") {
    abu::Scene s = abu::parse_scene(ring_with(9, "total_mass = 1.2e-4"), "ring.toml");
    abu::apply_override(s, "omega=1000");
    abu::apply_override(s, "M_r=0.2");
    CHECK(s.omega == 1000.0);
    CHECK(s.ring->total_mass_held);
    CHECK(s.ring->overrides.empty());
  }
}

TEST_CASE("scene ring: one-ball symbols address balls 1..n of a three-ball scene", "[scene][ring]") {
  const std::string listed =
      with_line(14, "radius = 1.0e-3\n[[ball]]\nmass = 3.3e-5\nrace_radius = 0.018\nradius = 1.0e-3");
  for (const std::string& text : {listed, std::string(kRing)}) {
    abu::Scene s = abu::parse_scene(text, "three.toml");
    REQUIRE(s.balls.size() == 3);
    abu::apply_override(s, "m3=4e-5");
    CHECK(s.balls[2].mass == 4e-5);
    abu::apply_override(s, "l3=0.02");
    CHECK(s.balls[2].race_radius == 0.02);
    const auto e = capture([&] { abu::apply_override(s, "m4=4e-5"); });
    CHECK(e.file() == "--set");
    CHECK(e.key() == "m4");
    CHECK(e.rule() == "ball index out of range: the scene has 3 balls (m1..m3)");
    const auto f = capture([&] { abu::apply_override(s, "mu_c12=0.1"); });
    CHECK(f.rule() == "ball index out of range: the scene has 3 balls (mu_c1..mu_c3)");
    CHECK(s.balls[2].mass == 4e-5);
    // set_checked with a reference beyond the scene says the same.
    const auto g = capture([&] { abu::set_checked(s, abu::ParamRef{abu::Quantity::ball_mass, 3}, 1e-5, "sweep"); });
    CHECK(g.key() == "m4");
    CHECK(g.rule() == "ball index out of range: the scene has 3 balls (m1..m3)");
  }
}
