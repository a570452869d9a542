// Periodic orbits from Hopf points (dynamics/periodic_orbits.hpp, docs/model.md §17) on
// the viscous two-ball scene (model.md §7's default rotor, viscous friction d = 1e-4):
// its balanced state loses stability at a Hopf point omega_H = 281.31 rad/s with
// l1 = +5.5e-6 (subcritical, small: a generalized Hopf point is near, so the unstable
// cycles turn at a fold of cycles, LPC, a few 1e-5 rad/s above omega_H and come back
// stable).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <utility>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/dynamics/periodic_orbits.hpp"
#include "../src/dynamics/shooting_flow.hpp"  // cyclic_max (internal to the dynamics layer)

namespace {

abu::Params viscous_params() {
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = abu::FrictionLaw::viscous;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-4, 0.0, 0.0, 0.0};
  return p;
}

abu::SpecialPoint viscous_hopf() {
  abu::StartSelection sel;
  sel.family = abu::Family::balanced;
  const abu::ContinuationRun run = abu::continue_branches(viscous_params(), *abu::parse_param("omega", 2), 50.0, {}, sel);
  for (const auto& b : run.branches)
    for (const auto& s : b.specials)
      if (s.label == abu::Label::HB && s.converged) return s;
  FAIL("no Hopf point on the balanced branch");
  return {};
}

}  // namespace

TEST_CASE("periodic orbits: viscous cycles from the Hopf point, trivial multiplier 1, a fold of cycles") {
  const abu::SpecialPoint hb = viscous_hopf();
  REQUIRE(hb.lyapunov > 0);
  abu::CycleOptions o;
  o.first_amplitude = 2e-2;
  // 14 steps of the default length (the orbit's L2 norm, model.md §17.7) reach T = 1.011 T_H.
  o.continuation.max_steps = 14;
  const abu::CycleBranch c = abu::continue_cycles(viscous_params(), *abu::parse_param("omega", 2), hb, 50.0, 900.0, o);
  REQUIRE(c.orbits.size() >= 12);
  const double pH = c.hopf_parameter;
  for (const abu::CycleOrbit& orbit : c.orbits) {
    INFO("omega " << orbit.parameter << " period " << orbit.period);
    // The flow direction's multiplier is 1 exactly; numerically to the orbit's accuracy
    // (integrator rtol 1e-13, Newton residual 1e-10 scaled): 1e-7 leaves room for the
    // orbits next to the LPC, where a second multiplier approaches 1 too.
    CHECK(orbit.trivial_distance < 1e-7);
    CHECK(orbit.multipliers.size() == 8);
    CHECK(orbit.floquet_status.ok());
    // Near the Hopf point the period is 2 pi / omega_H.
    CHECK(std::abs(orbit.period * hb.frequency / (2 * M_PI) - 1) < 0.02);
  }
  // Subcritical: born on the stable side (omega > omega_H) and unstable there.
  CHECK(c.orbits.front().parameter > pH);
  CHECK(c.orbits.front().unstable == 1);
  // One LPC, past which the cycles are stable and the parameter goes back down.
  REQUIRE(c.specials.size() == 1);
  CHECK(c.specials[0].label == "LPC");
  CHECK(c.specials[0].parameter > pH);
  CHECK(c.specials[0].parameter < pH + 1e-4);
  CHECK(c.orbits.back().unstable == 0);
  CHECK(c.orbits.back().parameter < c.specials[0].parameter);
}

TEST_CASE("periodic orbits: the amplitude near the Hopf point follows the first Lyapunov coefficient") {
  // max |q| = C sqrt(|omega - omega_H|) + O(|omega - omega_H|), C from l1, d Re(lambda)/d omega and
  // the critical eigenvector (model.md (17.3)). Two first orbits (the normal form's start,
  // corrected at a fixed amplitude, the parameter free) at omega - omega_H = 8e-8 and
  // 2e-8 rad/s: max|q| / sqrt(omega - omega_H) must equal C to 2e-3 at both (the
  // corrections are of relative order |z| ~ 1e-3 here: the mean shift and the second
  // harmonic of the orbit). A factor 2 or sqrt 2 in the normalization of q or l1 fails it.
  const abu::SpecialPoint hb = viscous_hopf();
  const abu::ParamRef omega = *abu::parse_param("omega", 2);
  const abu::HopfPrediction pred = abu::predict_from_hopf(viscous_params(), omega, hb);
  REQUIRE(pred.ok);
  CHECK(pred.slope < 0);  // the balanced state is stable above omega_H
  double error[2];
  double distance[2];
  const double amplitudes[2] = {4e-3, 2e-3};
  for (int k = 0; k < 2; ++k) {
    abu::CycleOptions o;
    o.first_amplitude = amplitudes[k];
    o.continuation.max_steps = 1;
    const abu::CycleBranch c = abu::continue_cycles(viscous_params(), omega, hb, 50.0, 900.0, o);
    INFO(c.reason);
    REQUIRE(!c.orbits.empty());
    const abu::CycleOrbit& first = c.orbits.front();
    distance[k] = first.parameter - c.hopf_parameter;
    const double ratio = first.amplitude / std::sqrt(std::abs(distance[k]));
    error[k] = ratio / pred.amplitude_coefficient - 1;
  }
  INFO("relative errors " << error[0] << " at " << distance[0] << ", " << error[1] << " at " << distance[1]);
  CHECK(std::abs(error[0]) < 2e-3);
  CHECK(std::abs(error[1]) < 2e-3);
  CHECK(distance[0] > 0);  // subcritical: on the stable side
  CHECK(distance[1] < distance[0]);
}

TEST_CASE("periodic orbits: the peak of cyclic samples from values and rates (quintic) against the parabola") {
  // v(t) = 1 + 0.3 cos(t - 0.123) + 0.05 cos(2 t + 0.4) + 0.01 sin(3 t): its true maximum by
  // Newton on v' from a fine grid; 80 uniform samples over [0, 2 pi) with their exact rates.
  const auto v = [](double t) { return 1 + 0.3 * std::cos(t - 0.123) + 0.05 * std::cos(2 * t + 0.4) + 0.01 * std::sin(3 * t); };
  const auto dv = [](double t) { return -0.3 * std::sin(t - 0.123) - 0.1 * std::sin(2 * t + 0.4) + 0.03 * std::cos(3 * t); };
  const auto d2v = [](double t) { return -0.3 * std::cos(t - 0.123) - 0.2 * std::cos(2 * t + 0.4) - 0.09 * std::sin(3 * t); };
  double best = 0;
  for (int i = 0; i < 100000; ++i)
    if (v(2 * M_PI * i / 100000) > v(best)) best = 2 * M_PI * i / 100000;
  for (int it = 0; it < 50; ++it) best -= dv(best) / d2v(best);
  const double truth = v(best);
  // Measured errors (quintic / parabola): n = 40: 7.1e-9 / 2.7e-5, n = 80: 9.5e-11 / 1.4e-6,
  // n = 160: 2.7e-12 / 3.8e-7. The bounds are about 3 times the quintic's (its order ~6
  // would move them by 64 per halving); the parabola at least 100 times worse at each n.
  const std::pair<int, double> cases[] = {{40, 2e-8}, {80, 3e-10}, {160, 1e-11}};
  for (const auto& [n, bound] : cases) {
    const double dt = 2 * M_PI / n;
    std::vector<double> values, rates;
    for (int i = 0; i < n; ++i) values.push_back(v(i * dt)), rates.push_back(dv(i * dt));
    const double quintic = abu::detail::cyclic_max(values, rates, dt);
    const double parabola = abu::detail::cyclic_max(values);
    INFO("n " << n << " quintic " << std::abs(quintic - truth) << " parabola " << std::abs(parabola - truth));
    CHECK(std::abs(quintic - truth) < bound);
    CHECK(std::abs(parabola - truth) > 100 * std::abs(quintic - truth));
  }
  // Without rates (or a spacing) the parabola's value.
  std::vector<double> values;
  for (int i = 0; i < 80; ++i) values.push_back(v(i * 2 * M_PI / 80));
  CHECK(abu::detail::cyclic_max(values, {}, 0.1) == std::max(*std::max_element(values.begin(), values.end()),
                                                              abu::detail::cyclic_max(values)));
}

TEST_CASE("periodic orbits: the extrapolated Newton matrix gives the integrated one's orbits") {
  // The chord corrector's Newton matrix at a predicted orbit, extrapolated from the last
  // three accepted orbits (model.md §17.7), changes only the corrector's contraction, not
  // the orbits it converges to: the same branch (the fast configuration of model.md §17.9,
  // M = 5, state 1e-10, Newton matrix 1e-4, Floquet 1e-8) with and without it. Each orbit is
  // converged to Newton steps of 10 rtol = 1e-9 (scaled unknowns), so parameter and period
  // agree to 1e-8 relative. The multipliers are integrated to 1e-8 relative to each factor
  // (|Phi_j| ~ 1 here), so each carries ~1e-8 absolute error; the two runs stop their Newton
  // iterations at different iterates (the extrapolated matrix contracts faster), so those errors
  // are independent: 1e-5 relative to max(|mu|, 1e-3) (1e-8 / 1e-3). A wrong matrix (a sign, a stale phase row) would make the chord fail or
  // stall, and the iterations per orbit are held to 1.5 times the integrated matrix's.
  const abu::SpecialPoint hb = viscous_hopf();
  const abu::ParamRef omega = *abu::parse_param("omega", 2);
  abu::CycleOptions o;
  o.intervals = 5;
  o.rtol = 1e-10;
  o.newton_rtol = 1e-4;
  o.floquet_rtol = 1e-8;
  o.first_amplitude = 2e-2;
  o.continuation.max_steps = 20;
  o.extrapolate_newton_matrix = false;
  const abu::CycleBranch integrated = abu::continue_cycles(viscous_params(), omega, hb, 50.0, 900.0, o);
  o.extrapolate_newton_matrix = true;
  const abu::CycleBranch extrapolated = abu::continue_cycles(viscous_params(), omega, hb, 50.0, 900.0, o);
  INFO(integrated.reason << " / " << extrapolated.reason);
  REQUIRE(integrated.orbits.size() >= 15);
  REQUIRE(extrapolated.orbits.size() == integrated.orbits.size());
  CHECK(integrated.extrapolated_matrices == 0);
  CHECK(extrapolated.extrapolated_matrices >= long(extrapolated.orbits.size()) - 3);
  CHECK(extrapolated.newton_steps * 5 < integrated.newton_steps);
  CHECK(double(extrapolated.newton_iterations) < 1.5 * double(integrated.newton_iterations));
  double worst_period = 0, worst_parameter = 0, worst_multiplier = 0;
  for (std::size_t k = 0; k < integrated.orbits.size(); ++k) {
    const abu::CycleOrbit &a = integrated.orbits[k], &b = extrapolated.orbits[k];
    worst_parameter = std::max(worst_parameter, std::abs(b.parameter / a.parameter - 1));
    worst_period = std::max(worst_period, std::abs(b.period / a.period - 1));
    REQUIRE(a.multipliers.size() == b.multipliers.size());
    for (std::size_t i = 0; i < a.multipliers.size(); ++i)
      worst_multiplier = std::max(worst_multiplier, std::abs(b.multipliers[i] - a.multipliers[i]) /
                                                        std::max(std::abs(a.multipliers[i]), 1e-3));
  }
  INFO("parameter " << worst_parameter << ", period " << worst_period << ", multipliers " << worst_multiplier);
  CHECK(worst_parameter < 1e-8);
  CHECK(worst_period < 1e-8);
  CHECK(worst_multiplier < 1e-5);
  CHECK(extrapolated.specials.size() == integrated.specials.size());
  // Make the figures visible in the test log.
  WARN("extrapolated against integrated: parameter " << worst_parameter << ", period " << worst_period
                                                      << ", multipliers " << worst_multiplier << "; iterations "
                                                      << extrapolated.newton_iterations << " / " << integrated.newton_iterations);
}
