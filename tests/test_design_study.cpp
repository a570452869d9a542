// The design study's pieces (docs/model.md §22): the variables' grids, a design's machine, and
// the `stable` constraint's value against the located Hopf point.
#include <catch2/catch.hpp>

#include "abu/analysis/design_study.hpp"
#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"
#include "scene_texts.hpp"

using namespace abu;

namespace {

// The default balls as a ring of two that holds its total mass (scene_texts.hpp's kRing).
const std::string kRing = abu::testing::line_replaced(
    abu::testing::line_replaced(abu::testing::kRing.c_str(), 8, "count = 2").c_str(), 9, "total_mass = 6.6e-5");

}  // namespace

TEST_CASE("design variables: grids, the ball count, the ramp's acceleration and the hold", "[design]") {
  const DesignVariable n = parse_design_variable("n=2:4");
  CHECK(n.grid() == std::vector<double>{2, 3, 4});
  const DesignVariable k = parse_design_variable("k=1000:16000:5:log");
  REQUIRE(k.grid().size() == 5);
  CHECK(k.grid()[2] == Approx(4000).epsilon(1e-12));  // the geometric middle
  CHECK_THROWS_AS(parse_design_variable("k=5:1"), InputError);
  CHECK_THROWS_AS(parse_design_variable("n=2:3.5"), InputError);
  CHECK_THROWS_AS(parse_design_variable("k=1:2:0"), InputError);

  const Scene s = parse_scene(kRing, "ring.toml");
  DesignOptions o;
  o.variables = {n, parse_design_variable("alpha=100:1000"), parse_design_variable("hold=0:5")};
  o.outcomes.sim.t_end = 3;
  const DesignedMachine m = designed_machine(s, SpeedProfile::ramp(50, 900, 400), o, {3, 250, 1.5});
  REQUIRE(m.scene.balls.size() == 3);
  CHECK(m.scene.balls[0].mass == Approx(2.2e-5).epsilon(1e-14));  // the ring's total mass held
  CHECK(m.speed.omega_dot(0.1) == Approx(250));
  CHECK(m.t_end == Approx(850.0 / 250 + 1.5).epsilon(1e-14));
}

TEST_CASE("the stable constraint's value changes sign at the balanced state's Hopf point", "[design]") {
  // The Hopf point of the default rotor in k at omega = 300 rad/s, as `continue --param k`
  // locates it: 10805.727120519181 N/m (tests/cli/check_design.py checks the two against each
  // other on every run). A relative step of 1e-6 either side moves the abscissa by about 1e-3 1/s.
  Scene s = parse_scene(kRing, "ring.toml");
  const double k_hopf = 10805.727120519181;
  s.rotor.stiffness = k_hopf * (1 - 1e-6);
  CHECK(balanced_abscissa_over(s, 300, 2000, {6e-7}, 41) < 0);
  s.rotor.stiffness = k_hopf * (1 + 1e-6);
  CHECK(balanced_abscissa_over(s, 300, 2000, {6e-7}, 41) > 0);
  // No balanced state (U above the capacity 1.188e-6 kg m): the constraint fails.
  CHECK(balanced_abscissa_over(s, 300, 2000, {2e-6}, 41) >= 1e3);
}
