// Balls and race as an engineer specifies them (docs/model.md §1.1): diameter and
// density instead of a mass, the rolling-resistance length f instead of mu, the race's
// surface radius instead of the radius to the ball centre. The references are the
// formulas (1.1.1)-(1.1.3) written out here, not the program's output.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/model.hpp"

namespace {

using abu::Quantity;

// Two balls given by diameter (ball 2 with the default density), the race by its
// surface radius, friction by f: data/scenes/engineer.toml's values.
const std::string kEngineer = R"(rolling = true
[rotor]
mass = 6.0
stiffness = 2.0e6
damping = 138.6
unbalance = 1.0e-4
[[ball]]
diameter = 0.008
density = 7800.0
surface_radius = 0.050
[[ball]]
diameter = 0.008
surface_radius = 0.050
[friction]
law = "coulomb"
f = 5.0e-6
kappa = 1.0e3
[speed]
omega = 900.0
)";

// m = rho pi d^3 / 6 in long double, the form (1.1.1) states (the code uses
// rho (4/3) pi r^3): an independent evaluation.
double sphere_mass(double rho, double d) {
  const long double dd = d;
  return double(rho * std::numbers::pi_v<long double> * dd * dd * dd / 6.0L);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// The InputError a scene text raises (its key and line), or fails the test.
abu::InputError error_of(const std::string& text) {
  try {
    abu::parse_scene(text, "spec.toml");
  } catch (const abu::InputError& e) {
    return e;
  }
  FAIL("scene was accepted: " << text);
  return abu::InputError("", 0, "", "");
}

}  // namespace

TEST_CASE("a ball given by diameter, density, f and the race surface radius", "[scene][specification]") {
  const abu::Scene s = abu::parse_scene(kEngineer, "spec.toml");
  REQUIRE(s.balls.size() == 2);
  for (int i = 0; i < 2; ++i) {
    const auto& b = s.balls[std::size_t(i)];
    const double rho = i == 0 ? 7800.0 : 7850.0;  // ball 2: steel by default
    INFO("ball " << i + 1);
    // The code's double product rounds four times: at most ~4 eps = 8.9e-16 relative.
    CHECK(b.mass == Approx(sphere_mass(rho, 0.008)).epsilon(1e-15));
    CHECK(b.radius == 0.004);              // d / 2 is exact
    CHECK(b.mu == 5.0e-6 / 0.004);         // one division, as (1.1.2)
    CHECK(b.race_radius == 0.050 - 0.004); // one subtraction, as (1.1.3)
    CHECK(b.density == rho);
    CHECK(b.specified == (abu::specified::density | abu::specified::rolling_length | abu::specified::surface_radius));
  }
}

TEST_CASE("the engineer's form and the model's form give the same parameters", "[scene][specification]") {
  const abu::Scene eng = abu::parse_scene(kEngineer, "spec.toml");
  std::string direct = kEngineer;
  for (int i = 0; i < 2; ++i) {
    const auto& b = eng.balls[std::size_t(i)];
    direct = replaced(direct, "diameter = 0.008", fmt::format("mass = {}\nradius = 0.004", b.mass));
    direct = replaced(direct, "surface_radius = 0.050", fmt::format("race_radius = {}", b.race_radius));
  }
  direct = replaced(direct, "density = 7800.0\n", "");
  direct = replaced(direct, "f = 5.0e-6", fmt::format("mu = {}", eng.balls[0].mu));
  const abu::Scene old = abu::parse_scene(direct, "direct.toml");
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(old.balls[i].mass == eng.balls[i].mass);
    CHECK(old.balls[i].radius == eng.balls[i].radius);
    CHECK(old.balls[i].race_radius == eng.balls[i].race_radius);
    CHECK(old.balls[i].mu == eng.balls[i].mu);
    CHECK(old.balls[i].specified == 0);
  }
}

TEST_CASE("a --set of r moves mu, m and l of a specified ball, and nothing of a direct one", "[scene][specification]") {
  abu::Scene s = abu::parse_scene(kEngineer, "spec.toml");
  abu::apply_override(s, "r=0.005");
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(s.balls[i].radius == 0.005);
    CHECK(s.balls[i].mu == 5.0e-6 / 0.005);
    CHECK(s.balls[i].race_radius == 0.050 - 0.005);
    CHECK(s.balls[i].mass == Approx(sphere_mass(i == 0 ? 7800.0 : 7850.0, 0.010)).epsilon(1e-15));
  }
  abu::apply_override(s, "f2=1e-5");  // one ball's f
  CHECK(s.balls[1].mu == 1e-5 / 0.005);
  CHECK(s.balls[0].mu == 5.0e-6 / 0.005);
  abu::apply_override(s, "R_s=0.06");
  CHECK(s.balls[0].race_radius == 0.06 - 0.005);
  // Setting the model value itself switches that ball to the direct form (last one wins):
  // r then no longer moves it.
  abu::apply_override(s, "mu1=0.003");
  abu::apply_override(s, "r=0.004");
  CHECK(s.balls[0].mu == 0.003);
  CHECK(s.balls[1].mu == 1e-5 / 0.004);
  // A scene in the direct form: r changes r only (model.md §1: it enters nothing else).
  std::string direct = replaced(kEngineer, "f = 5.0e-6", "mu = 0.002");
  abu::Scene d = abu::parse_scene(direct, "direct.toml");
  abu::apply_override(d, "r=0.003");
  CHECK(d.balls[0].mu == 0.002);
}

TEST_CASE("a --set is refused where it does not fit the race or the law", "[scene][specification]") {
  abu::Scene s = abu::parse_scene(kEngineer, "spec.toml");
  // r = 0.03 gives l = 0.02 < r: the ball would reach past the axis.
  CHECK_THROWS_AS(abu::apply_override(s, "r=0.03"), abu::InputError);
  CHECK_THROWS_AS(abu::apply_override(s, "R_s=0.007"), abu::InputError);
  CHECK_THROWS_AS(abu::apply_override(s, "f=-1e-6"), abu::InputError);
  CHECK(s.balls[0].radius == 0.004);  // unchanged
  abu::Scene v = abu::parse_scene(replaced(replaced(kEngineer, "law = \"coulomb\"", "law = \"viscous\""),
                                           "f = 5.0e-6\nkappa = 1.0e3", "d = 0.1"),
                                  "v.toml");
  CHECK_THROWS_AS(abu::apply_override(v, "f=1e-6"), abu::InputError);
}

TEST_CASE("either form, never both; density only with a diameter", "[scene][specification]") {
  struct Bad {
    std::string from, to, key;
    int line;
  };
  const Bad cases[] = {
      {"diameter = 0.008\ndensity", "diameter = 0.008\nmass = 1e-3\ndensity", "ball[1].mass", 9},
      {"surface_radius = 0.050\n[[ball]]", "surface_radius = 0.050\nrace_radius = 0.04\n[[ball]]", "ball[1].race_radius", 11},
      {"diameter = 0.008\nsurface_radius = 0.050\n[friction]", "radius = 0.004\ndensity = 7850.0\nmass = 2e-3\nsurface_radius = 0.050\n[friction]", "ball[2].density", 13},
      {"f = 5.0e-6", "f = 5.0e-6\nmu = 0.001", "friction.mu", 17},
      {"law = \"coulomb\"", "law = \"stribeck\"\nmu_c = 0.001\nmu_s = 0.002\nv_s = 0.1", "friction.f", 19},
      {"density = 7800.0\nsurface_radius = 0.050", "density = 7800.0\nsurface_radius = 0.0079", "ball[1].diameter", 8},
  };
  for (const Bad& c : cases) {
    INFO(c.to);
    const abu::InputError e = error_of(replaced(kEngineer, c.from, c.to));
    CHECK(e.key() == c.key);
    CHECK(e.line() == c.line);
  }
}

TEST_CASE("a [balls] ring given by diameter and f, with an override", "[scene][specification]") {
  const std::string ring = R"([rotor]
mass = 6.0
stiffness = 2.0e6
damping = 138.6
unbalance = 1.0e-4
[balls]
count = 4
diameter = 0.008
surface_radius = 0.050
f = 5.0e-6
[[balls.override]]
ball = 3
diameter = 0.010
[friction]
law = "coulomb-set"
[speed]
omega = 900.0
)";
  abu::Scene s = abu::parse_scene(ring, "ring.toml");
  REQUIRE(s.balls.size() == 4);
  CHECK(s.balls[2].radius == 0.005);
  CHECK(s.balls[2].mu == 5.0e-6 / 0.005);
  CHECK(s.balls[2].race_radius == 0.050 - 0.005);
  CHECK(s.balls[2].mass == Approx(sphere_mass(7850.0, 0.010)).epsilon(1e-15));
  CHECK(s.balls[0].mu == 5.0e-6 / 0.004);
  abu::set_ball_count(s, 6, "--n");  // the specification follows the ring
  REQUIRE(s.balls.size() == 6);
  CHECK(s.balls[5].mass == Approx(sphere_mass(7850.0, 0.008)).epsilon(1e-15));
  CHECK(s.balls[2].mu == 5.0e-6 / 0.005);
  abu::apply_override(s, "r=0.003");
  abu::set_ball_count(s, 5, "--n");
  CHECK(s.balls[2].mu == 5.0e-6 / 0.003);  // every-ball r replaced the override
  // A template mass and an override diameter are both forms for ball 3.
  const abu::InputError e =
      error_of(replaced(replaced(ring, "diameter = 0.008", "mass = 2e-3\nradius = 0.004"), "f = 5.0e-6", "mu = 1e-3"));
  CHECK(e.key() == "balls.override[1].diameter");
}

TEST_CASE("df/dp for r, rho, f and R_s is the chain rule through m, mu and l", "[model][specification]") {
  const abu::Scene s = abu::parse_scene(kEngineer, "spec.toml");
  const abu::Params p = abu::params_of<2>(s);
  abu::State<double, 2> x;
  x << 1.0e-5, -2.0e-5, 0.3, 2.1, 4.0e-3, -1.0e-3, 0.2, -0.1;  // off equilibrium, both balls slipping
  // Every-ball symbols only where the balls agree (set() makes them equal; the densities differ).
  for (const char* symbol : {"r", "r2", "rho1", "rho2", "f1", "f", "R_s", "R_s2"}) {
    INFO(symbol);
    const abu::ParamRef ref = *abu::parse_param(symbol, 2);
    const abu::State<double, 2> df = abu::parameter_derivative(p, x, ref);
    // Central difference through set() (which re-derives m, mu, l): error O(h^2) + eps/h;
    // h = 1e-5 relative gives ~1e-10 relative, checked at 1e-7 of the field's scale.
    const double v = abu::get(p, ref);
    const double h = 1e-5 * v;
    abu::Params pp = p, pm = p;
    abu::set(pp, ref, v + h);
    abu::set(pm, ref, v - h);
    const abu::State<double, 2> fd = (abu::vector_field(pp, x) - abu::vector_field(pm, x)) / (2 * h);
    CHECK((df - fd).norm() <= 1e-7 * fd.norm());
    CHECK(fd.norm() > 0);  // every one of these moves the field
  }
}
