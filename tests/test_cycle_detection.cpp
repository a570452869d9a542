// The cycle bifurcation tests of linear/floquet.hpp (docs/model.md §17.5) on synthetic
// multiplier families with known crossings: the detection layer is generic (any multiplier
// set with one trivial multiplier), so it is checked here apart from any orbit, on the
// form product_eigenvalues returns (sorted by modulus, log moduli alongside).
//
// Tolerances: a family whose test function is linear in s is located by the linear
// interpolation of §17.5 to rounding (asserted 1e-12); a curved one to the interpolation
// error ds^2 |g''| / (8 |g'|) (asserted 1e-2 for ds = 0.1; a few 1e-4 here).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <iomanip>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/dynamics/periodic_orbits.hpp"
#include "abu/linear/floquet.hpp"

namespace {

using Set = std::vector<std::complex<double>>;

// A multiplier set as product_eigenvalues returns it: by modulus, descending.
abu::CycleTestValues tests_of(Set mu) {
  std::stable_sort(mu.begin(), mu.end(), [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  std::vector<double> logs;
  for (auto m : mu) logs.push_back(std::log(std::abs(m)));
  return abu::cycle_test_values(mu, logs);
}

// Steps s = 0.05, 0.15, ... through [0, 1]: the zero of the chosen test function by linear
// interpolation between the two members where it changes sign; -1 if none, -2 if more than one.
template <class Family, class Pick>
double located(Family family, Pick pick, bool* complex_pair = nullptr) {
  double found = -1;
  double s0 = 0.05, g0 = pick(tests_of(family(s0)));
  for (int k = 1; k < 10; ++k) {
    const double s1 = 0.05 + 0.1 * k;
    const abu::CycleTestValues t1 = tests_of(family(s1));
    const double g1 = pick(t1);
    if ((g0 > 0) != (g1 > 0)) {
      if (found >= 0) return -2;
      found = s0 + g0 / (g0 - g1) * (s1 - s0);
      if (complex_pair) *complex_pair = t1.complex_pair_near_circle;
    }
    s0 = s1;
    g0 = g1;
  }
  return found;
}

const std::complex<double> kI(0, 1);

}  // namespace

TEST_CASE("period doubling: a real multiplier through -1 is found once and located", "[cycles][detection]") {
  // mu = -(0.6 + 0.8 s) crosses -1 at s = 0.5; the others stay away from -1 and the circle.
  const auto family = [](double s) {
    return Set{1.0, -(0.6 + 0.8 * s), 0.3, 0.1 * std::exp(0.5 * kI), 0.1 * std::exp(-0.5 * kI), 1e-5, 1e-200, -1e-9};
  };
  CHECK(std::abs(located(family, [](const auto& t) { return t.period_doubling; }) - 0.5) < 1e-12);
  CHECK(located(family, [](const auto& t) { return t.neimark_sacker; }) == -1);
  CHECK(tests_of(family(0.45)).unstable == 0);
  CHECK(tests_of(family(0.55)).unstable == 1);
  CHECK(tests_of(family(0.3)).trivial_distance == 0);
}

TEST_CASE("Neimark-Sacker: a complex pair through the unit circle, flagged as a pair", "[cycles][detection]") {
  // |mu| = r(s) = 0.7 + 0.6 s reaches 1 at s = 0.5; test ~ r^2 - 1 (quadratic in s).
  const auto family = [](double s) {
    const double r = 0.7 + 0.6 * s;
    return Set{1.0, r * std::exp(1.1 * kI), r * std::exp(-1.1 * kI), 0.4, -0.2, 1e-3, 1e-12, 1e-300};
  };
  bool pair = false;
  CHECK(std::abs(located(family, [](const auto& t) { return t.neimark_sacker; }, &pair) - 0.5) < 1e-2);
  CHECK(pair);
  CHECK(located(family, [](const auto& t) { return t.period_doubling; }) == -1);
  CHECK(tests_of(family(0.55)).unstable == 2);
}

TEST_CASE("a neutral saddle (real mu_i mu_j = 1) changes the NS test but is not a pair", "[cycles][detection]") {
  // 3 (0.2 + 0.2 s) = 1 at s = 2/3 (the other factors sigma mu_k - 1 vary with s too: the
  // product is not linear, interpolation error ~ ds^2 as for the pair, asserted 1e-2).
  const auto family = [](double s) { return Set{3.0, 1.0, 0.2 + 0.2 * s, 0.5, 0.1, 1e-2, 1e-4, 1e-8}; };
  bool pair = true;
  CHECK(std::abs(located(family, [](const auto& t) { return t.neimark_sacker; }, &pair) - 2.0 / 3.0) < 1e-2);
  CHECK_FALSE(pair);
  // The trivial multiplier is the one closest to 1, not the largest.
  CHECK(tests_of(family(0.1)).unstable == 1);
}

TEST_CASE("multiplier_jump: how far the set moved, matched, escaping moduli clamped", "[cycles][detection]") {
  const Set a{1.0, 0.5 * std::exp(kI), 0.5 * std::exp(-kI), -0.3, 1e-6};
  Set b = a;
  CHECK(abu::multiplier_jump(a, b) == 0);
  std::reverse(b.begin(), b.end());  // order does not matter
  CHECK(abu::multiplier_jump(a, b) == 0);
  b = a;
  b[3] = -0.6;  // one real multiplier moved by 0.3
  CHECK(std::abs(abu::multiplier_jump(a, b) - 0.3) < 1e-15);
  Set c{5.0, 0.1}, d{10.0, 0.1};  // both beyond 2 in one direction: no jump
  CHECK(abu::multiplier_jump(c, d) == 0);
  // A crossing of -1 and back within one step leaves the endpoints' signs unchanged; the
  // step control sees the move instead: a step that carries mu from -0.9 to -1.3 moves 0.4.
  CHECK(abu::multiplier_jump(Set{1.0, -0.9}, Set{1.0, -1.3}) > 0.25);
}

// ---------------------------------------------------------------------------------------
// On real scenes (model.md §17.10): the default two-ball rotor (M_r = 0.12 kg, k = 7500 N/m,
// U = 6e-7 kg m; balls 3.3e-5 kg at l = 18 mm, viscous d = 1e-4 N s/m) on a lightly damped
// support. With c = 0.05 N s/m (instead of 2) the balanced state loses stability at a
// supercritical Hopf point at omega_H = 278.0985 rad/s and its stable cycles, followed down in
// omega, lose stability at a period doubling near 277.78 rad/s (the real multiplier of the
// rotor's lightly damped mode passes -1). With c = 0.3 N s/m the Hopf point is at
// 272.994 rad/s and the cycles lose stability at a Neimark-Sacker point near 272.43 rad/s (a
// complex pair leaves the unit circle). Each branch is followed down to a bound past the point
// with the default maximum step (0.1) and with 10 and 100 times it.

namespace {

abu::Params light_support(double c) {
  abu::Params p;
  p.rotor = {0.12, 7500.0, c, 6e-7};
  p.omega = 2000.0;
  p.law = abu::FrictionLaw::viscous;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-4, 0.0, 0.0, 0.0};
  return p;
}

// PD: the real multiplier closest to -1, its distance from -1 signed (> 0 inside).
// NS: the complex multiplier closest to the unit circle, 1 - |mu| (> 0 inside).
double crossing_margin(const abu::CycleOrbit& o, bool pd) {
  double best = 1e300, margin = 0;
  for (auto m : o.multipliers) {
    const bool complex = std::abs(m.imag()) > 1e-9;
    if (pd && !complex && std::abs(m.real() + 1) < best) best = std::abs(m.real() + 1), margin = m.real() + 1;
    if (!pd && complex && std::abs(std::abs(m) - 1) < best) best = std::abs(std::abs(m) - 1), margin = 1 - std::abs(m);
  }
  return margin;
}

// Follows the cycles of the balanced state's Hopf point down to `bound` at three maximum
// steps: the point `label` found exactly once and no other, and its location checked on
// orbits corrected at fixed omega.
void crossing_at_any_step(double c, double hopf, double bound, const char* label, double near_value) {
  const abu::Params p = light_support(c);
  const abu::ParamRef omega = *abu::parse_param("omega", 2);
  abu::StartSelection sel;
  sel.family = abu::Family::balanced;
  const abu::ContinuationRun run = abu::continue_branches(p, omega, 20.0, {}, sel);
  const abu::SpecialPoint* hb = nullptr;
  for (const auto& b : run.branches)
    for (const auto& s : b.specials)
      if (s.label == abu::Label::HB && s.converged && !hb) hb = &s;
  REQUIRE(hb);
  CHECK(std::abs(double(hb->parameter) - hopf) < 1e-3);
  CHECK(hb->lyapunov < 0);  // supercritical: stable cycles below omega_H
  const bool pd = std::string(label) == "PD";
  std::vector<double> located;
  for (const double ds_max : {0.1, 1.0, 10.0}) {
    INFO(label << ", ds_max " << ds_max);
    abu::CycleOptions o;
    o.continuation.ds_max = ds_max;
    o.continuation.max_steps = 1000;
    const abu::CycleBranch br = abu::continue_cycles(p, omega, *hb, bound, 2000.0, o);
    INFO(br.reason);
    REQUIRE(br.end == abu::arclength::End::end_of_interval);
    int found = 0;
    double where = 0;
    for (const auto& s : br.specials) {
      CHECK(s.label == label);  // nothing else on this stretch
      CHECK(s.located);         // on the branch, not interpolated
      if (s.label == label) ++found, where = s.parameter;
    }
    REQUIRE(found == 1);
    located.push_back(where);
    CHECK(std::abs(where - near_value) < 0.05);
    // Independent of the location's own test function: the orbit corrected at the located
    // omega has its multiplier on the circle (PD: at -1) to the location's error times the
    // multiplier's rate (~0.8 per rad/s for the PD, ~2.3 for the NS pair's modulus). Brent's
    // method stops within ~1e-8 of the step (scaled unknowns, < 1e-7 rad/s here) and the
    // multipliers are integrated to floquet_rtol 1e-11 (~1e-10 relative): margin < 1e-6, where
    // the interpolation between orbits it replaced (multipliers moving up to
    // max_multiplier_jump = 0.25 per step) was off by ~1e-3. And 0.02 rad/s above it the
    // multiplier is inside, 0.02 below outside: the crossing is there.
    const abu::CycleOrbit* nearest = &br.orbits.front();
    for (const auto& orbit : br.orbits)
      if (std::abs(orbit.parameter - where) < std::abs(nearest->parameter - where)) nearest = &orbit;
    abu::CycleOrbit guess = *nearest;
    double margin[3];
    const double at[3] = {where, where + 0.02, where - 0.02};
    for (int k = 0; k < 3; ++k) {
      guess.parameter = at[k];
      const abu::CycleCorrection fixed = abu::correct_cycle(p, omega, *hb, guess, bound - 1.0, 2000.0, o);
      INFO(fixed.reason);
      REQUIRE(fixed.status.ok());
      margin[k] = crossing_margin(fixed.orbit, pd);
    }
    INFO(std::setprecision(12) << "at " << where << ": margin " << margin[0] << ", " << margin[1] << " above, " << margin[2] << " below");
    CHECK(std::abs(margin[0]) < 1e-6);
    CHECK(margin[1] > 0);
    CHECK(margin[2] < 0);
  }
  // The same point whatever the step: the three locations agree to 1e-7 rad/s (the orbits'
  // own accuracy, rtol 1e-13, over a test function of slope ~1 per rad/s, with room for the
  // chord's 1e-9).
  REQUIRE(located.size() == 3);
  INFO(std::setprecision(15) << "located at " << located[0] << ", " << located[1] << ", " << located[2]);
  CHECK(std::abs(located[1] - located[0]) < 1e-7);
  CHECK(std::abs(located[2] - located[0]) < 1e-7);
}

}  // namespace

TEST_CASE("period doubling on a real scene: detected once and located at any maximum step", "[cycles][detection]") {
  crossing_at_any_step(0.05, 278.0985, 277.5, "PD", 277.78);
}

TEST_CASE("Neimark-Sacker on a real scene: detected once and located at any maximum step", "[cycles][detection]") {
  crossing_at_any_step(0.3, 272.994, 272.2, "NS", 272.43);
}
