// The stick set of set-valued Coulomb friction (model.md §14) against results known by
// hand: the whole torus when mu is large (area (2 pi)^n, V = omega^2 (U + sum m l)/|K + iC|
// at beta = 0), the small-mu limit of V (the farthest vertex of the parallelogram
// |q . n_i| <= mu_i l_i around a balanced point, model.md §14.3), and the refusals.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <utility>

#include "abu/core/errors.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/input/scene.hpp"

#include <string>
#include <vector>

namespace {

constexpr double two_pi = 2 * std::numbers::pi;

abu::ParamsN rotor(int n, double mu) {
  abu::ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = abu::FrictionLaw::coulomb_set;
  p.balls.resize(std::size_t(n));
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, mu, 0.0, 0.0, 0.0, 0.0};
  return p;
}

double together_at_unbalance(const abu::ParamsN& p) {
  double M = p.rotor.mass, capacity = 0.0;
  for (const auto& b : p.balls) M += b.mass, capacity += b.mass * b.race_radius;
  const std::complex<double> dyn(p.rotor.stiffness - p.omega * p.omega * M, p.rotor.damping * p.omega);
  return p.omega * p.omega * (p.rotor.unbalance + capacity) / std::abs(dyn);
}

}  // namespace

TEST_CASE("stick set: large mu sticks everywhere, V is the balls together at the unbalance", "[stick_set]") {
  // max |s| over the torus is 0.302 at mu = 0.002 (model.md §14.4): E = T^2.
  const abu::ParamsN p = rotor(2, 0.002);
  const abu::StickSet s = abu::stick_set(p);
  CHECK(s.whole_torus);
  CHECK(s.components.size() == 1);
  // area: the column lengths are exactly 2 pi; Simpson sums them to rounding
  CHECK(s.area == Approx(two_pi * two_pi).epsilon(1e-12));
  // |W| <= U + sum m l with equality only at beta = 0: exact on the column beta_1 = 0
  CHECK(s.worst_q_abs == Approx(together_at_unbalance(p)).epsilon(1e-12));
  CHECK(s.worst_q_abs_any == Approx(s.worst_q_abs).epsilon(1e-15));
  CHECK(std::fabs(std::remainder(s.worst_beta[0], two_pi)) < 1e-6);
  CHECK(std::fabs(std::remainder(s.worst_beta[1], two_pi)) < 1e-6);
  CHECK(s.spread[0] == Approx(two_pi));
  CHECK(s.max_abs_s < 1.0);
}

TEST_CASE("stick set: small mu, V approaches the parallelogram vertex", "[stick_set]") {
  // First order in mu (model.md §14.3): V = mu l / min(x, sqrt(1 - x^2)), x = U/(2 m l).
  // Its relative error is linear in mu, about 1.5e-4 at mu = 1e-6; tolerance 1e-3.
  const double mu = 1e-6;
  const abu::ParamsN p = rotor(2, mu);
  const abu::StickSet s = abu::stick_set(p);
  const double x = 6e-7 / (2 * 3.3e-5 * 0.018);
  const double first_order = mu * 0.018 / std::min(x, std::sqrt(1 - x * x));
  CHECK(s.worst_q_abs == Approx(first_order).epsilon(1e-3));
  CHECK(s.balanced_exists);
  CHECK_FALSE(s.whole_torus);
  // both balanced points sit in their own small island
  int balanced_components = 0;
  for (const auto& c : s.components) balanced_components += !c.balanced_points.empty();
  CHECK(balanced_components == 2);
}

TEST_CASE("stick set: the mirror islands of equal balls have equal areas", "[stick_set]") {
  // Equal balls: E is symmetric under beta_1 <-> beta_2, so the "opposite" island at
  // (0.020, 3.162) and its mirror at (3.162, 0.020) have one area (and one mean |q|). The
  // scan crosses the first in columns of beta_1 and the second within them, each area an
  // adaptive Simpson over beta_1 (model.md §14.3). The components' areas were the columns'
  // trapezoid rescaled to the total: the first island, wider in beta_1 than the dense columns
  // at its seed, had its last arcs weighted by half a uniform gap, and came out 5.30e-5 rad^2
  // against 4.24e-5 at mu = 1e-6, 4.433e-3 against 4.426e-3 at mu = 1e-5.
  // mu = 1e-6: each area within the Simpson tolerance, 1e-10 rad^2 per rad of beta_1, so the
  // two within 2 pi 1e-10 (they agree to 8e-12). mu = 1e-5: 1e-4 relative, the area's accuracy
  // (tests/reference/stick_set_reference.py): the island's thin tip along beta_1 (1e-4 rad
  // across, beyond the dense samples) is partly shorter than the beta_2 sample step, and the
  // scan misses 4e-8 rad^2 of it (9e-6 relative; the mirror's tip lies across the columns).
  abu::StickSetOptions o;
  o.trace = false;
  for (const auto& [mu, tolerance] : {std::pair{1e-6, two_pi * o.area_tolerance}, std::pair{1e-5, 1e-4 * 4.43e-3}}) {
    CAPTURE(mu);
    const abu::StickSet s = abu::stick_set(rotor(2, mu), o);
    REQUIRE(s.components.size() == 6);
    std::vector<const abu::StickSeed*> opposite;
    for (const auto& sd : s.seeds)
      if (sd.family == "opposite") opposite.push_back(&sd);
    REQUIRE(opposite.size() == 2);
    REQUIRE(opposite[0]->component >= 0);
    REQUIRE(opposite[1]->component >= 0);
    REQUIRE(opposite[0]->component != opposite[1]->component);
    const abu::StickComponent& x = s.components[std::size_t(opposite[0]->component)];
    const abu::StickComponent& y = s.components[std::size_t(opposite[1]->component)];
    CHECK(std::fabs(x.area - y.area) <= tolerance);
    // the island is O(mu) wide, |q| on it within O(mu) of the seed's (its max 1.1e-4 above
    // at mu = 1e-6, 7e-4 at 1e-5): the mean |q| too (the rescaled trapezoid gave 5.30e-6 m
    // at mu = 1e-6, the seed's |q| being 5.414e-6 m)
    for (const abu::StickComponent* c : {&x, &y}) {
      CHECK(c->q_abs_integral / c->area <= c->q_abs_max);
      CHECK(c->q_abs_integral / c->area >= opposite[0]->q_abs * (1 - 1e-3));
    }
    // every arc is attributed to a component: their areas sum to the total
    double sum = 0.0;
    for (const auto& c : s.components) sum += c.area;
    CHECK(sum == Approx(s.area).epsilon(1e-12));
  }
}

TEST_CASE("stick set: n = 3 on a grid, large mu", "[stick_set]") {
  const abu::ParamsN p = rotor(3, 0.01);
  abu::StickSetOptions o;
  o.grid_budget = 1L << 15;  // 32 per angle: enough for a set that is the whole torus
  const abu::StickSet s = abu::stick_set(p, o);
  CHECK(s.sampled);
  CHECK(s.whole_torus);
  CHECK(s.area == Approx(two_pi * two_pi * two_pi).epsilon(1e-12));
  // the grid holds beta = 0, the maximiser of |W|
  CHECK(s.worst_q_abs == Approx(together_at_unbalance(p)).epsilon(1e-12));
}

TEST_CASE("stick set: mu = 0 has no area and is refused", "[stick_set]") {
  CHECK_THROWS_AS(abu::stick_set(rotor(2, 0.0)), abu::NotSupportedError);
}

// The dry-friction verdict (StickSetOptions::verdict_only, model.md §14.10) against the full
// stick-set scan: where the bound |G| (U + sum m l) <= min mu l decides E = T^n, by the
// closed form; elsewhere by the same column scan without the |q| integrals and spreads.
namespace {
abu::StickSet verdict(const abu::ParamsN& p, abu::StickSetOptions o = {}) {
  o.trace = false;
  o.verdict_only = true;
  return abu::stick_set(p, o);
}
void check_same_verdict(const abu::StickSet& v, const abu::StickSet& full, double tolerance) {
  CHECK(v.whole_torus == full.whole_torus);
  CHECK(v.components.size() == full.components.size());
  CHECK(v.balanced_exists == full.balanced_exists);
  CHECK(v.area == Approx(full.area).epsilon(tolerance));
  CHECK(v.area_fraction == Approx(full.area_fraction).epsilon(tolerance));
  CHECK(v.worst_q_abs == Approx(full.worst_q_abs).epsilon(tolerance));
  CHECK(v.worst_q_abs_any == Approx(full.worst_q_abs_any).epsilon(tolerance));
  CHECK(v.bare_rotor_q_abs == full.bare_rotor_q_abs);
}
}  // namespace

TEST_CASE("stick set verdict: the bound decides the whole torus as the full scan finds it", "[stick_set]") {
  // mu = 0.002: |G| (U + 2 m l) / (mu l) = 0.45 <= 1. The scan's area sums columns of
  // exactly 2 pi (rounding) and its V is the refined maximum at beta = 0, the closed
  // form's value (the first test: 1e-12): tolerance 1e-12.
  for (int n : {2, 3}) {
    const abu::ParamsN p = rotor(n, 0.002);
    abu::StickSetOptions o;
    o.trace = false;
    o.grid_budget = 1L << 15;
    const abu::StickSet full = abu::stick_set(p, o), v = verdict(p);
    CHECK(v.whole_torus);
    CHECK(v.resolution == 0.0);  // no scan ran
    check_same_verdict(v, full, 1e-12);
  }
}

TEST_CASE("stick set verdict: where the bound does not decide, the full scan's figures", "[stick_set]") {
  // mu = 0.0008: the bound is 1.12 > 1, yet max |s| = 0.76 (the scan finds E = T^2); the
  // scene of tests/scenes/stick with two merged components (`several`: the doc, §14.10).
  // The verdict runs the same column scan and maxima: equal to the last bit, whatever the
  // resolution (a coarse one here: the test's time).
  std::vector<abu::ParamsN> cases{rotor(2, 0.0008)};
  for (const char* name : {"merged"}) {
    const abu::Scene scene =
        abu::load_scene(std::string(ABU_SOURCE_DIR) + "/tests/scenes/stick/" + name + ".toml");
    cases.push_back(abu::params_of<abu::any_balls>(scene));
  }
  abu::StickSetOptions o;
  o.trace = false;
  o.columns = 128;
  o.samples = 256;
  for (const abu::ParamsN& p : cases) {
    const abu::StickSet full = abu::stick_set(p, o), v = verdict(p, o);
    check_same_verdict(v, full, 0.0);
    CHECK(v.resolution > 0.0);   // the scan ran
    CHECK(v.mean_q_abs == 0.0);  // not computed
  }
  CHECK(verdict(cases[0], o).whole_torus);
}

TEST_CASE("stick set: as mu -> 0 it shrinks onto the smooth equilibria, never empty", "[stick_set]") {
  // Every smooth equilibrium is in E (tau = 0, model.md §14.2); its part of E has a width
  // proportional to mu. At mu = 1e-20 that is ~1e-20 rad, below any column: the scan found
  // nothing and reported "no balanced state", V_E = 0. Each equilibrium is now a point
  // component: V within rounding of the balanced points' |q| = 0 (the first-order V is
  // 3.6e-22 m; 1e-20 m allows the seeds' own rounding), V_E the largest |q| of an equilibrium,
  // as at mu = 1e-8 (where the set is resolved) to 1e-4 (V_E moves by O(mu) relative).
  const abu::StickSet resolved = abu::stick_set(rotor(2, 1e-8));
  REQUIRE(resolved.balanced_exists);
  CHECK(resolved.point_components == 0);
  for (const double mu : {1e-20, 1e-300}) {
    const abu::StickSet s = abu::stick_set(rotor(2, mu));
    CHECK(s.balanced_exists);
    CHECK(s.status.ok());
    CHECK(s.point_components == int(s.seeds.size()));
    CHECK(s.components.size() == s.seeds.size());
    CHECK(s.seeds.size() == 6);
    CHECK(s.area == 0.0);
    CHECK(s.worst_q_abs < 1e-20);
    double largest = 0;
    for (const auto& sd : s.seeds) largest = std::max(largest, sd.q_abs);
    CHECK(s.worst_q_abs_any == largest);
    CHECK(s.worst_q_abs_any == Approx(resolved.worst_q_abs_any).epsilon(1e-4));
  }
}
