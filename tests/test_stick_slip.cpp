// Stick-slip dynamics of set-valued Coulomb friction (model.md §14.5-§14.8): cases with a
// hand-checkable answer, the end point inside the stick set, convergence as rtol shrinks.
// The independent reference of one run is tests/reference/stick_slip_reference.py.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <numbers>

#include "abu/core/errors.hpp"
#include "abu/dynamics/stick_slip.hpp"
#include "abu/equilibria/stick_set.hpp"

using namespace abu;

namespace {

// The scene of tests/scenes/stickslip/runup.toml (not in data/): at 800 rad/s and mu = 1e-4
// its stick set is 9.5 % of the torus.
template <int N>
ParamsT<double, N> runup_rotor(double mu, int n = 2) {
  ParamsT<double, N> p;
  p.rotor = {0.15, 9000.0, 3.0, 8e-7};
  p.omega = 800.0;
  p.law = FrictionLaw::coulomb_set;
  if constexpr (N == any_balls) p.balls.resize(std::size_t(n));
  for (std::size_t i = 0; i < p.balls.size(); ++i)
    p.balls[i] = {i == 1 ? 3.5e-5 : 4.0e-5, i == 1 ? 0.021 : 0.02, 1.5e-3, 1.4, mu, 0.0, 0.0, 0.0, 0.0};
  return p;
}

// q of (5.4), (K + iC) q = omega^2 W(beta), written out here (not the library's stick_point).
std::complex<double> static_q(const Params& p, double b1, double b2) {
  const double M = p.total_mass(), w = p.omega;
  std::complex<double> W = p.rotor.unbalance;
  W += p.balls[0].mass * p.balls[0].race_radius * std::polar(1.0, b1);
  W += p.balls[1].mass * p.balls[1].race_radius * std::polar(1.0, b2);
  return w * w * W / std::complex<double>(p.rotor.stiffness - w * w * M, p.rotor.damping * w);
}

}  // namespace

TEST_CASE("stick-slip: with a large mu both balls stick from the start and never move", "[stick_slip]") {
  const Params p = runup_rotor<2>(0.5);
  SimulationOptions o;
  o.t_end = 3.0;
  o.rtol = 1e-10;
  const auto r = simulate_stick_slip(p, SpeedProfile::constant(800.0), start_at_rest(p, {1.0, 2.5}), o);
  REQUIRE(r.run.status == SimulationStatus::completed);
  // Stuck balls have beta' = 0 and beta'' = 0 exactly (14.5.1): the angles are the start's, bit for bit.
  CHECK(r.run.x_end(2) == 1.0);
  CHECK(r.run.x_end(3) == 2.5);
  CHECK(r.sticks + r.slips + r.reversals == 0);
  for (auto m : r.stuck_mask) CHECK(m == 3u);
  // The rotor alone with the balls frozen: a damped oscillator that decays at c / (2 M) = 10 1/s,
  // to e^-30 of its start by t = 3 s: q is (5.4) to 1e-9 relative.
  const std::complex<double> q = static_q(p, 1.0, 2.5);
  CHECK(std::abs(std::complex<double>(r.run.x_end(0), r.run.x_end(1)) - q) < 1e-9 * std::abs(q));
  CHECK(r.end.all_stuck);
  CHECK(r.end.in_set);
  CHECK(r.end.q_abs_static == Approx(std::abs(q)).epsilon(1e-12));
  CHECK(r.run.summary.outcome == SimulationOutcome::rest);
}

TEST_CASE("stick-slip: a ball outside the small stick set must slip, and ends inside it", "[stick_slip]") {
  const Params p = runup_rotor<2>(1e-4);
  ParamsN pn = runup_rotor<any_balls>(1e-4);
  // Precondition: the start (1, 2.5) lies outside E (14.3) at 800 rad/s.
  REQUIRE(std::max(std::abs(stick_point(pn, {1.0, 2.5}).s[0]), std::abs(stick_point(pn, {1.0, 2.5}).s[1])) > 1.0);
  SimulationOptions o;
  o.t_end = 3.0;
  o.rtol = 1e-9;
  const auto r = simulate_stick_slip(p, SpeedProfile::constant(800.0), start_at_rest(p, {1.0, 2.5}), o);
  REQUIRE(r.run.status == SimulationStatus::completed);
  CHECK(r.slips > 0);
  // A slipping ball that comes to rest where stick is not admissible reverses (model.md §14.6):
  // this run does so twice.
  CHECK(r.reversals > 0);
  CHECK(r.end.all_stuck);
  CHECK(r.end.in_set);
  CHECK(r.end.max_abs_s <= 1.0);
  CHECK(std::abs(r.run.x_end(3) - 2.5) > 0.1);  // ball 2 moved
  // The end check agrees with the library's stick set membership at the end angles.
  const StickPoint sp = stick_point(pn, r.end.beta);
  CHECK(sp.s[0] == Approx(r.end.s[0]).margin(1e-14));
}

TEST_CASE("stick-slip: the end point converges as rtol shrinks", "[stick_slip]") {
  // The smooth phases carry a global error proportional to rtol (rk8pd with tolerance-
  // proportional control); the switches are located to rounding of t, so the end angles
  // converge like rtol: each factor 100 in rtol should gain about 100 in the end angles.
  const Params p = runup_rotor<2>(1e-4);
  auto end_of = [&](double rtol) {
    SimulationOptions o;
    o.t_end = 1.0;
    o.rtol = rtol;
    o.record = false;
    const auto r = simulate_stick_slip(p, SpeedProfile::constant(800.0), start_at_rest(p, {1.0, 2.5}), o);
    REQUIRE(r.run.status == SimulationStatus::completed);
    return std::array<double, 2>{r.run.x_end(2), r.run.x_end(3)};
  };
  const auto fine = end_of(1e-12);
  double d[3];
  const double rtols[3] = {1e-6, 1e-8, 1e-10};
  for (int k = 0; k < 3; ++k) {
    const auto e = end_of(rtols[k]);
    d[k] = std::max(std::abs(e[0] - fine[0]), std::abs(e[1] - fine[1]));
    INFO("rtol " << rtols[k] << ": end angle difference " << d[k]);
    CHECK(d[k] < 1e3 * rtols[k]);
  }
  CHECK(d[1] < 0.1 * d[0]);
  CHECK((d[2] < 0.1 * d[1] || d[2] < 1e-9));
}

TEST_CASE("stick-slip: a three-ball run-up ends in the stick set", "[stick_slip]") {
  const ParamsN p = runup_rotor<any_balls>(1e-3, 3);
  SimulationOptions o;
  o.t_end = 4.0;
  o.rtol = 1e-8;
  const auto r = simulate_stick_slip(p, SpeedProfile::ramp(50.0, 800.0, 400.0), start_at_rest(p, {0.5, 2.0, 4.0}), o);
  REQUIRE(r.run.status == SimulationStatus::completed);
  CHECK(r.end.all_stuck);
  CHECK(r.end.in_set);
}

TEST_CASE("stick-slip: refuses implicit methods and mu = 0", "[stick_slip]") {
  Params p = runup_rotor<2>(1e-4);
  SimulationOptions o;
  o.method = IntegrationMethod::bsimp;
  CHECK_THROWS_AS(simulate_stick_slip(p, SpeedProfile::constant(800.0), start_at_rest(p, {1.0, 2.5}), o), InputError);
  o.method = IntegrationMethod::automatic;
  p.balls[1].mu = 0.0;
  CHECK_THROWS_AS(simulate_stick_slip(p, SpeedProfile::constant(800.0), start_at_rest(p, {1.0, 2.5}), o),
                  NotSupportedError);
}
