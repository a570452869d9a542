// Rotordynamics views (docs/model.md §16, docs/views.md) against values derived by hand:
// the rotor alone (balls of vanishing mass) has the fixed-frame eigenvalues of
// M z'' + c z' + k z = 0 at every speed, forward at +omega_d and backward at -omega_d, and
// its forward mode crosses 1X at omega_d; the reference amplitude (16.5.1); the stated
// answer of a point; the stable ranges of the default scene against the special points of
// the independent mpmath reference (README "Continuation"); rpm in a scene.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>

#include "abu/continuation/continuation.hpp"
#include "abu/core/errors.hpp"
#include "abu/output/report_views.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/modes.hpp"
#include "abu/scan/scan.hpp"

namespace {

using cd = std::complex<double>;

abu::Params default_params(double omega) {
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = omega;
  p.law = abu::FrictionLaw::coulomb;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 0.0, 0.0, 0.0, 0.0};
  return p;
}

// The default rotor with balls of 1e-10 kg: the massless-ball limit of model.md §7, whose
// small parameter is 2 m l / U = 6e-6 (rotor eigenvalues move by that relative order).
abu::Params bare_rotor(double omega) {
  abu::Params p = default_params(omega);
  for (auto& b : p.balls) b.mass = 1e-10;
  return p;
}

struct Bare {
  double M, omega_n, zeta, omega_d;
};
Bare bare_values(const abu::Params& p) {
  const double M = p.total_mass();
  const double omega_n = std::sqrt(p.rotor.stiffness / M);
  const double zeta = p.rotor.damping / (2 * M * omega_n);
  return {M, omega_n, zeta, omega_n * std::sqrt(1 - zeta * zeta)};
}

}  // namespace

TEST_CASE("views: the bare rotor whirls at +-omega_d in the fixed frame at every speed", "[views]") {
  // Tolerance: 10 x the limit's small parameter 2 m l / U (model.md §7) on the rotor
  // eigenvalues' modulus ~ omega_n.
  const double tol = 10 * 2 * 1e-10 * 0.018 / 6e-7;
  for (double omega : {60.0, 200.0, 249.0, 251.0, 400.0, 1500.0}) {
    const abu::Params p = bare_rotor(omega);
    const Bare h = bare_values(p);
    const cd forward(-h.zeta * h.omega_n, h.omega_d), backward(-h.zeta * h.omega_n, -h.omega_d);
    const abu::Analysis a = abu::analyze(p);
    const auto points = a.equilibria.points();
    REQUIRE(!points.empty());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto modes = abu::mode_views(p, points[i].position, a.spectra[i]);
      int n_forward = 0, n_backward = 0;
      for (const auto& m : modes) {
        INFO("omega " << omega << " mode " << m.index << " " << abu::to_string(m.kind) << " fixed " << m.fixed);
        // (16.1.2): the fixed-frame eigenvalue is lambda + i omega or conj(lambda) + i omega;
        // adding and removing i omega in double rounds by at most eps omega each way.
        const cd shifted = m.fixed - cd(0, omega);
        const double rounding = 4 * std::numeric_limits<double>::epsilon() * omega;
        CHECK(std::min(std::abs(shifted - m.rotating), std::abs(shifted - std::conj(m.rotating))) <= rounding);
        if (m.kind == abu::ModeKind::rotor_forward) {
          ++n_forward;
          CHECK(std::abs(m.fixed - forward) <= tol * h.omega_n);
          CHECK(m.whirl_frequency > 0);
          CHECK(m.rotor_share > 0.999);
          // zeta and delta (16.4.1) of M z'' + c z' + k z = 0: c / (2 M omega_n), 2 pi zeta / sqrt(1 - zeta^2).
          CHECK(m.damping_ratio == Approx(h.zeta).epsilon(tol));
          CHECK(m.log_decrement == Approx(2 * std::numbers::pi * h.zeta / std::sqrt(1 - h.zeta * h.zeta)).epsilon(tol));
        } else if (m.kind == abu::ModeKind::rotor_backward) {
          ++n_backward;
          CHECK(std::abs(m.fixed - backward) <= tol * h.omega_n);
          CHECK(m.whirl_frequency < 0);
        } else {
          CHECK(m.rotor_share < 0.5);
        }
      }
      CHECK(n_forward == 1);
      CHECK(n_backward == 1);
    }
  }
}

TEST_CASE("views: the bare rotor's critical speed is omega_d", "[views]") {
  // g = whirl - omega = omega_d - omega is linear in omega, so the interpolated crossing is
  // exact up to the massless-ball limit's 2 m l / U = 6e-6 (times 10) and rounding.
  const abu::Params base = bare_rotor(100.0);
  const Bare h = bare_values(base);
  const auto values = abu::grid_values(100.0, 400.0, 37, false);
  const abu::SweepResult s = abu::sweep(base, *abu::parse_param("omega", 2), values);
  const auto samples = abu::campbell_samples(s, base);
  REQUIRE(!samples.empty());
  const auto critical = abu::critical_speeds(samples);
  REQUIRE(!critical.empty());
  for (const auto& c : critical) {
    INFO(c.series);
    CHECK(c.omega == Approx(h.omega_d).epsilon(6e-5));
    CHECK(c.bracket_from <= h.omega_d);
    CHECK(c.bracket_to >= h.omega_d);
    CHECK(c.damping_ratio == Approx(h.zeta).epsilon(6e-5));
  }
}

TEST_CASE("views: the default balancer's rotor modes and 1X crossing", "[views]") {
  // With 2 x 33 g balls the rotor modes are no longer those of the bare rotor exactly; the
  // forward rotor mode still crosses 1X within 1 % of omega_n (the balls' share of M is
  // 5.5e-4; the rest is the ball coupling) and the backward mode stays backward.
  const abu::Params base = default_params(100.0);
  const double omega_n = std::sqrt(base.rotor.stiffness / base.total_mass());
  const auto values = abu::grid_values(100.0, 600.0, 100, false);
  const abu::SweepResult s = abu::sweep(base, *abu::parse_param("omega", 2), values);
  const auto samples = abu::campbell_samples(s, base);
  bool balanced_crossing = false;
  for (const auto& c : abu::critical_speeds(samples))
    if (c.family == "balanced") {
      balanced_crossing = true;
      CHECK(c.omega == Approx(omega_n).epsilon(0.01));
    }
  CHECK(balanced_crossing);
  for (const auto& smp : samples)
    for (const auto& m : smp.modes)
      if (m.kind == abu::ModeKind::rotor_backward) CHECK(m.whirl_frequency == Approx(-omega_n).epsilon(0.05));
}

TEST_CASE("views: the stated answer of a point", "[views]") {
  SECTION("above omega_n: balanced and stable, reduction 0") {
    const abu::Params p = default_params(900.0);
    const auto ans = abu::point_answer(abu::analyze(p), p);
    CHECK(ans.omega_n == Approx(std::sqrt(7500.0 / (0.12 + 6.6e-5))).epsilon(1e-15));
    CHECK(ans.capacity == Approx(2 * 3.3e-5 * 0.018).epsilon(1e-15));
    CHECK_FALSE(ans.capacity_exceeded);
    CHECK(ans.balanced_stable);
    REQUIRE(ans.best);
    CHECK(ans.best->rfind("balanced", 0) == 0);
    CHECK(ans.best_q_abs == 0.0);
    CHECK(ans.reduction == 0.0);
    // (16.5.1) by hand: U w^2 / |k - M w^2 + i c w|.
    const double M = 0.12 + 6.6e-5, w = 900;
    CHECK(ans.q0_balls_neutral == Approx(6e-7 * w * w / std::hypot(7500 - M * w * w, 2 * w)).epsilon(1e-14));
    CHECK(ans.q0_without_balls == Approx(6e-7 * w * w / std::hypot(7500 - 0.12 * w * w, 2 * w)).epsilon(1e-14));
  }
  SECTION("in the band 236.1 .. 249.93 rad/s nothing is stable") {
    const abu::Params p = default_params(245.0);
    const auto ans = abu::point_answer(abu::analyze(p), p);
    CHECK_FALSE(ans.best);
    CHECK(ans.stable_states.empty());
    CHECK(abu::answer_lines(ans, abu::SpeedUnit::rpm, "").find("no stable state at this speed") != std::string::npos);
  }
  SECTION("below the band the balls together are the best stable state, with a reduction < 1") {
    const abu::Params p = default_params(150.0);
    const auto ans = abu::point_answer(abu::analyze(p), p);
    REQUIRE(ans.best);
    CHECK(ans.best->rfind("together", 0) == 0);
    CHECK(ans.reduction > 0);
    CHECK(ans.reduction == Approx(ans.best_q_abs / ans.q0_balls_neutral).epsilon(1e-15));
  }
  SECTION("capacity exceeded") {
    abu::Params p = default_params(900.0);
    p.rotor.unbalance = 2e-6;  // > 2 m l = 1.188e-6
    const auto ans = abu::point_answer(abu::analyze(p), p);
    CHECK(ans.capacity_exceeded);
    CHECK_FALSE(ans.balanced_exists);
    CHECK(abu::answer_lines(ans, abu::SpeedUnit::rad_per_s, "# ").find("# capacity exceeded: no balanced state") !=
          std::string::npos);
  }
}

TEST_CASE("views: stable ranges of the default continuation are bounded by the located LP and HB", "[views]") {
  // The reference values are the mpmath special points of the default scene (README,
  // "Continuation": LP 236.1030736838683, HB 249.93374034470625, agreeing to 1e-16); the
  // continuation locates them to 1e-8 relative (the `special` tests), hence the tolerance.
  const abu::Params p = default_params(50.0);
  const abu::ContinuationRun run =
      abu::continue_branches(p, *abu::parse_param("omega", 2), 2000.0, abu::ContinuationOptions{}, {});
  const auto r = abu::stability_ranges(run);
  REQUIRE(r.nothing_stable.size() == 1);
  CHECK(r.nothing_stable[0].from == Approx(236.1030736838683).epsilon(1e-8));
  CHECK(r.nothing_stable[0].to == Approx(249.93374034470625).epsilon(1e-8));
  CHECK(r.nothing_stable[0].from_kind == "located");
  CHECK(r.nothing_stable[0].to_kind == "located");
  REQUIRE(r.balanced_stable.size() == 1);
  CHECK(r.balanced_stable[0].from == Approx(249.93374034470625).epsilon(1e-8));
  CHECK(r.balanced_stable[0].to == 2000.0);
}

TEST_CASE("views: a scene gives the speed as omega or rpm, exactly one", "[views][scene]") {
  const std::string head = R"(
[rotor]
mass = 0.12
stiffness = 7500.0
damping = 2.0
unbalance = 6.0e-7
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[friction]
law = "none"
[speed]
)";
  const abu::Scene s = abu::parse_scene(head + "rpm = 3000\n", "rpm.toml");
  CHECK(s.omega == Approx(3000 * 2 * std::numbers::pi / 60).epsilon(1e-15));
  try {
    abu::parse_scene(head + "omega = 100\nrpm = 3000\n", "both.toml");
    FAIL("both omega and rpm accepted");
  } catch (const abu::InputError& e) {
    const std::string what = e.what();
    CHECK(what.find("both.toml") != std::string::npos);
    CHECK(what.find("rpm") != std::string::npos);
    CHECK(what.find(":19") != std::string::npos);  // the line of rpm
  }
  CHECK_THROWS_AS(abu::parse_scene(head, "none.toml"), abu::InputError);
  CHECK_THROWS_AS(abu::parse_scene(head + "rpm = -5\n", "neg.toml"), abu::InputError);
}
