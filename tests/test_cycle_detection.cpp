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
#include <vector>

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
