// Basins of an unround race on an anisotropic support (docs/model.md §20.8): the attractors are
// the race's states as pi/omega-periodic orbits, sampled over the spin angle, and the settle
// test compares a run with the orbit's state at the run's own spin angle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "abu/analysis/basin_targets.hpp"
#include "abu/analysis/composed_sweep.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/basin.hpp"

#include "composed_params.hpp"

using namespace abu;

namespace {

// tests/scenes/composed/oval_anisotropic.toml: its mean support in p, the support and the race.
BasinJob composed_job(double omega) {
  BasinJob job;
  job.any_balls = true;
  job.params_n = test::composed_mean_params();
  job.params_n.omega = omega;
  job.speed = SpeedProfile::constant(omega);
  job.support = AnisotropicSupport{12000.0, 9000.0, -800.0, 4.0, 2.5, 0.6};
  const RaceHarmonics h{{2, 3e-5, 0.4}, {1, 1e-5, 1.1}};
  set_basin_race(job, RaceShape{{h, h}});
  return job;
}

}  // namespace

TEST_CASE("composed basin: an orbit's state between its samples", "[composed_basin]") {
  // Four rows of one ball pair (dim 8) whose values are linear in the row: the interpolation
  // must give them back exactly (to rounding, 1e-12) at any spin angle, wrap at pi (the row
  // after the last is the first) and take ball angles along their short arc across 2 pi.
  BasinOrbit b;
  b.dim = 8;
  b.omega = 100;
  const double angles[4] = {6.0, 6.2, 0.1, 0.3};  // ball 1 crosses 2 pi between rows 1 and 2
  for (int k = 0; k < 4; ++k)
    for (int m = 0; m < 8; ++m) b.states.push_back(m == 2 ? angles[k] : 10.0 * m + k);
  REQUIRE(b.phases() == 4);
  std::vector<double> x(8);
  const double quarter = std::numbers::pi / 4;
  b.at(quarter * 1.5, x.data());  // halfway between rows 1 and 2
  CHECK(x[0] == Approx(1.5).margin(1e-12));
  CHECK(x[5] == Approx(51.5).margin(1e-12));
  CHECK(std::remainder(x[2] - (6.2 + std::remainder(0.1 - 6.2, 2 * std::numbers::pi) / 2), 2 * std::numbers::pi) ==
        Approx(0).margin(1e-12));
  b.at(quarter * 3.5, x.data());  // between the last row and the first: 3 -> 0 halfway
  CHECK(x[0] == Approx(1.5).margin(1e-12));
  b.at(quarter * 3.5 - 7 * std::numbers::pi, x.data());  // any real angle: taken mod pi
  CHECK(x[0] == Approx(1.5).margin(1e-12));
  b.at(2 * std::numbers::pi, x.data());  // row 0
  CHECK(x[7] == Approx(70.0).margin(1e-12));
}

TEST_CASE("composed basin: the attractors are the stable orbits equilibria finds", "[composed_basin]") {
  // At 1100 rad/s (the scene's speed) the targets must be exactly the converged orbits whose
  // multipliers say stable, numbered as composed_orbits_at numbers them. Each target's samples
  // come from one run from x(0) (an orbit that does not close to 1e-7 is no target); their
  // largest |q| is compared with the orbit's q_abs_max, which the shooting computes by another
  // route (trigonometric interpolation of its step points, §10.18): the 128 samples see the
  // maximum to (pi/128)^2 / 8 ~ 7.5e-5 of the orbit's variation, asserted 1e-4 of |q|max, and
  // never above it (1e-9: both are accurate to ~1e-10).
  const double w = 1100.0;
  const BasinJob job = composed_job(w);
  const BasinAttractors a = machine_basin_targets(job);
  ParamsN p = job.params_n;
  const ComposedSweepPoint at = composed_orbits_at(*job.support, {p, job.race}, w);
  std::vector<int> stable;
  for (const auto& row : at.rows)
    if (composed_orbit_usable(row.orbit) && row.orbit.stable()) stable.push_back(row.equilibrium);
  REQUIRE(!stable.empty());
  REQUIRE(a.targets.size() == stable.size());
  CHECK(a.unresolved.empty());
  for (std::size_t k = 0; k < stable.size(); ++k) {
    const BasinTarget& t = a.targets[k];
    CHECK(t.label == "orbit");
    CHECK(t.member == stable[k]);
    REQUIRE(t.orbit);
    CHECK(t.orbit->phases() == 128);
    CHECK(t.orbit->dim == 8);
    const ForcedOrbit& o = at.rows[std::size_t(t.member - 1)].orbit;
    double q_max = 0;
    for (int s = 0; s < t.orbit->phases(); ++s) {
      const double* x = t.orbit->states.data() + std::size_t(s) * 8;
      q_max = std::max(q_max, std::hypot(x[0], x[1]));
    }
    INFO("orbit " << t.member << ": sampled max |q| " << q_max << ", shooting's " << o.q_abs_max);
    CHECK(q_max <= o.q_abs_max * (1 + 1e-9));
    CHECK(q_max >= o.q_abs_max * (1 - 1e-4));
    // The first sample is the orbit's state at theta = 0.
    for (int m = 0; m < 8; ++m) CHECK(t.orbit->states[std::size_t(m)] == o.state0[std::size_t(m)]);
  }
}

TEST_CASE("composed basin: the sampled orbit at any spin angle is the orbit's state there", "[composed_basin]") {
  // The settle test reads the orbit at the run's spin angle theta(t) (model.md (20.8)). Here the
  // orbit is integrated afresh from x(0) at constant speed to times tau between the samples
  // (theta = omega tau, the field's own angle) and compared with BasinOrbit::at(omega tau): the
  // linear interpolation over 128 samples is accurate to (pi/128)^2 / 8 ~ 7.5e-5 of the orbit's
  // variation over a period (here ~5e-3 scaled, largest in q'), so 1e-5 scaled is asserted;
  // the same comparison a quarter turn off (the wrong phase) must differ by more (measured 4e-3 .. 8e-3).
  const double w = 1100.0;
  const BasinJob job = composed_job(w);
  const BasinAttractors a = machine_basin_targets(job);
  REQUIRE(!a.targets.empty());
  ParamsN p = job.params_n;
  const double L = displacement_scale(p), period = std::numbers::pi / w;
  const auto scaled = [&](const double* x, const double* y) {
    double d = 0;
    for (int k = 0; k < 2; ++k) d = std::max({d, std::abs(x[k] - y[k]) / L, std::abs(x[4 + k] - y[4 + k]) / (L * w)});
    for (int k = 2; k < 4; ++k)
      d = std::max({d, std::abs(std::remainder(x[k] - y[k], 2 * std::numbers::pi)), std::abs(x[4 + k] - y[4 + k]) / w});
    return d;
  };
  for (const BasinTarget& t : a.targets) {
    State<double, any_balls> x0(8);
    for (int m = 0; m < 8; ++m) x0(m) = t.orbit->states[std::size_t(m)];
    for (double fraction : {0.137, 0.5, 0.861}) {
      const double tau = fraction * period;
      SimulationOptions o;
      o.t_end = tau;
      o.rtol = 1e-11;
      o.record = false;
      o.race = &job.race;
      o.support = &*job.support;
      const SimulationResult<any_balls> r = simulate(p, SpeedProfile::constant(w), x0, o);
      REQUIRE(r.status == SimulationStatus::completed);
      std::vector<double> right(8), wrong(8);
      t.orbit->at(w * tau, right.data());
      t.orbit->at(w * tau + std::numbers::pi / 2, wrong.data());
      INFO("orbit " << t.member << " at tau = " << fraction << " period: " << scaled(r.x_end.data(), right.data())
                    << " at its angle, " << scaled(r.x_end.data(), wrong.data()) << " a quarter turn off");
      CHECK(scaled(r.x_end.data(), right.data()) <= 1e-5);
      CHECK(scaled(r.x_end.data(), wrong.data()) >= 1e-4);
    }
  }
}

TEST_CASE("composed basin: a simulate run's end named by its orbit at the end's spin angle", "[composed_basin]") {
  // classify_composed_end (model.md §20.8): an end state on orbit k at spin angle theta is `orbit`
  // k, at distance ~0 (the interpolation between samples is exact at a sample's own angle, so the
  // state is taken between samples: 7.5e-5 of the variation, far below the tolerance 1e-3); the
  // same state at an angle a quarter turn off is 4e-3 .. 8e-3 away (the previous test) and stays
  // `periodic`; an unstable orbit is named with its verdict in the note.
  const double w = 1100.0;
  const BasinJob job = composed_job(w);
  ParamsN p = job.params_n;
  const ComposedStates states = composed_states(p, job.race, *job.support);
  REQUIRE(states.orbits.size() == 8);  // `equilibria` finds 8 orbits there, every one converged
  bool unstable_seen = false;
  for (const SampledOrbit& o : states.orbits) {
    const double theta = 1.2345;
    std::vector<double> x(8);
    o.orbit->at(theta, x.data());
    SimulationSummary s;
    s.outcome = SimulationOutcome::periodic;
    s.state_end = x;
    classify_composed_end(s, p, states, theta + 7 * std::numbers::pi, 1e-3);  // any turn of the angle
    INFO("orbit " << o.member << ": " << s.note);
    CHECK(s.outcome == SimulationOutcome::orbit);
    CHECK(s.orbit_member == o.member);
    CHECK(s.orbit_distance <= 1e-9);
    CHECK(s.orbit_q_abs_max == o.q_abs_max);
    CHECK(s.note.find(std::string(to_string(o.verdict))) != std::string::npos);
    unstable_seen = unstable_seen || o.verdict == Stability::unstable;
    SimulationSummary off;
    off.outcome = SimulationOutcome::periodic;
    off.state_end = x;
    classify_composed_end(off, p, states, theta + std::numbers::pi / 2, 1e-3);
    CHECK(off.outcome == SimulationOutcome::periodic);
    CHECK(off.orbit_member == 0);
  }
  CHECK(unstable_seen);
}
