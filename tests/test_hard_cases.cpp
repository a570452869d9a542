// The hard cases of model.md §5 and §8: stiff friction, near and exact merging of
// equilibria, U = 0 circles, the undamped resonance, tiny balls, high speed. Expected
// counts come from the closed-form existence conditions written here; every eigenvalue
// is checked against det(lambda^2 A + lambda C + K) evaluated independently.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "abu/equilibria/equilibria.hpp"
#include "abu/model/model.hpp"
#include "abu/core/params.hpp"
#include "abu/scan/scan.hpp"
#include "abu/linear/spectrum.hpp"

namespace {

using ld = long double;
using cld = std::complex<ld>;
using cd = std::complex<double>;
using abu::Family;
constexpr double kEps = std::numeric_limits<double>::epsilon();  // 2^-52
constexpr ld kPi = std::numbers::pi_v<ld>;

abu::Params base_params() {
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = abu::FrictionLaw::coulomb;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 0.0, 0.0, 0.0, 0.0};
  return p;
}

ld total_mass(const abu::Params& p) { return ld(p.rotor.mass) + ld(p.balls[0].mass) + ld(p.balls[1].mass); }
ld capacity(const abu::Params& p, int ball) { return ld(p.balls[std::size_t(ball)].mass) * ld(p.balls[std::size_t(ball)].race_radius); }
ld stiffness_K(const abu::Params& p) { return ld(p.rotor.stiffness) - ld(p.omega) * ld(p.omega) * total_mass(p); }

struct Counts {
  int balanced, together, opposite;
};

// Existence conditions (model.md §5) for a generic (non-degenerate) scene: balanced iff
// |a1 - a2| <= U <= a1 + a2 (two mirror points); K U sin b + C U cos b + C a = 0 has two
// roots iff |C a| <= U sqrt(K^2 + C^2), a = a1 + a2 (together) or a1 - a2 (opposite).
Counts expected_counts(const abu::Params& p) {
  const ld U = p.rotor.unbalance, a1 = capacity(p, 0), a2 = capacity(p, 1);
  const ld K = stiffness_K(p), C = ld(p.rotor.damping) * ld(p.omega), R = std::hypot(K, C);
  const auto roots = [&](ld a) { return R > 0 && std::abs(C * a) <= U * R ? 2 : 0; };
  return {std::abs(a1 - a2) <= U && U <= a1 + a2 ? 2 : 0, roots(a1 + a2), roots(a1 - a2)};
}

int count(const abu::EquilibriumSet& set, Family f) {
  const auto pts = set.points();
  return int(std::count_if(pts.begin(), pts.end(), [f](const abu::Equilibrium& e) { return e.family == f; }));
}

// det of a 4x4 by the Leibniz sum, with perm(|.|) of the magnitudes as its natural size.
struct DetAndScale {
  cld det;
  ld scale;
};
DetAndScale leibniz(const std::array<std::array<cld, 4>, 4>& t, const std::array<std::array<ld, 4>, 4>& s) {
  std::array<int, 4> perm{0, 1, 2, 3};
  DetAndScale r{0, 0};
  do {
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) inversions += perm[std::size_t(i)] > perm[std::size_t(j)];
    cld term = inversions % 2 ? -1 : 1;
    ld mag = 1;
    for (std::size_t i = 0; i < 4; ++i) term *= t[i][std::size_t(perm[i])], mag *= s[i][std::size_t(perm[i])];
    r.det += term;
    r.scale += mag;
  } while (std::next_permutation(perm.begin(), perm.end()));
  return r;
}

// |det T(lambda)| / perm(|lambda|^2 |A| + |lambda| |C| + |K|) in long double, from the
// linearization at the equilibrium. Every monomial c lambda^k of det T (k <= 8) is bounded
// by the permanent, so |lambda d det/d lambda| <= 8 perm: an eigenvalue with relative
// error r leaves a scaled determinant below 8 r (plus long-double evaluation noise).
ld scaled_det(const abu::Params& p, const abu::Equilibrium& e, cd lambda_d) {
  const auto lin = abu::linearize(p.cast<ld>(), e.state());
  const cld l(lambda_d.real(), lambda_d.imag());
  const ld a = std::abs(l);
  std::array<std::array<cld, 4>, 4> t{};
  std::array<std::array<ld, 4>, 4> s{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const auto ui = std::size_t(i), uj = std::size_t(j);
      t[ui][uj] = l * l * lin.mass(i, j) + l * lin.damping(i, j) + lin.stiffness(i, j);
      s[ui][uj] = a * a * std::abs(lin.mass(i, j)) + a * std::abs(lin.damping(i, j)) + std::abs(lin.stiffness(i, j));
    }
  }
  const DetAndScale d = leibniz(t, s);
  return std::abs(d.det) / d.scale;
}

// What every case must satisfy: counts, residuals at rounding, converged polish and
// refinement, finite eigenvalues each solving the quadratic eigenproblem.
abu::Analysis check_common(const abu::Params& p, Counts expected) {
  const abu::Analysis a = abu::analyze(p);
  CHECK(count(a.equilibria, Family::balanced) == expected.balanced);
  CHECK(count(a.equilibria, Family::together) == expected.together);
  CHECK(count(a.equilibria, Family::opposite) == expected.opposite);
  for (std::size_t i = 0; i < a.equilibria.points().size(); ++i) {
    const auto& e = a.equilibria.points()[i];
    const auto& sp = a.spectra[i];
    INFO(to_string(e.family) << " member " << e.member);
    // Residual at the double-rounded state over each equation's natural size: rounding q
    // (eps/2 relative) and the angles (<= 2 pi eps/2) moves it by <= (1/2 + pi) eps ~ 8e-16.
    CHECK(e.residual < 1e-14);
    CHECK(e.converged);
    CHECK(sp.converged);
    for (std::size_t k = 0; k < 8; ++k) {
      const cd z = sp.eigenvalues[k];
      INFO("lambda " << z << " error " << sp.error[k]);
      REQUIRE(std::isfinite(z.real()));
      REQUIRE(std::isfinite(z.imag()));
      REQUIRE(std::isfinite(sp.error[k]));
      // 8 |d lambda| / |lambda| from the error estimate and the double rounding of lambda,
      // doubled for safety (see scaled_det).
      const ld rel = ld(sp.error[k]) / ld(std::abs(z)) + ld(kEps);
      CHECK(scaled_det(p, e, z) <= 16 * rel);
    }
  }
  return a;
}

// The ball modes of largest |lambda|: -(2/pi) mu w^2 kappa / j, the friction slope over the
// ball inertia. Corrections: the rotor carries O(m/(jM)) ~ 2e-4 of the ball inertia, the
// restoring term changes the root by O(w^2 |q| j l / gamma^2) ~ 1e-9: 1% is conservative.
void check_fast_modes(const abu::Params& p, const abu::Spectrum& sp) {
  const double fast = 2 / std::numbers::pi * p.balls[0].mu * p.omega * p.omega * p.kappa / p.balls[0].inertia_factor;
  std::array<double, 8> modulus{};
  for (std::size_t k = 0; k < 8; ++k) modulus[k] = std::abs(sp.eigenvalues[k]);
  std::sort(modulus.begin(), modulus.end());
  for (const std::size_t k : {std::size_t(6), std::size_t(7)}) {
    INFO("fast " << modulus[k] << " formula " << fast);
    CHECK(std::abs(modulus[k] - fast) <= 0.01 * fast);
  }
  CHECK(sp.eigenvalues[7].real() < 0);  // sorted by Re: the fast modes decay
  CHECK(sp.eigenvalues[6].real() < 0);
}

}  // namespace

// kappa = 1e6: spectrum spans 16 orders (fast 7e8 1/s, slow ~1e-7 1/s, model.md §8); the
// balanced state above omega_n must still come out stable, slow modes included.
TEST_CASE("stiff coulomb friction, kappa = 1e6", "[hard]") {
  abu::Params p = base_params();
  p.kappa = 1e6;
  const auto a = check_common(p, expected_counts(p));
  for (std::size_t i = 0; i < a.equilibria.points().size(); ++i) {
    check_fast_modes(p, a.spectra[i]);
    if (a.equilibria.points()[i].family != Family::balanced) continue;
    CHECK(a.spectra[i].stability == abu::Stability::stable);
    for (const cd z : a.spectra[i].eigenvalues) CHECK(z.real() < 0);
  }
}

// 1e-9 from merging: the two balanced points sit at pi -+ theta with cos theta = U / 2ml,
// theta = 2 asin(sqrt(delta / 2)), delta = 1 - U / 2ml ~ 1e-9 (the exact triangle).
TEST_CASE("balanced points 1e-9 from merging are resolved", "[hard]") {
  abu::Params p = base_params();
  p.rotor.unbalance = 2 * 3.3e-5 * 0.018 * (1 - 1e-9);
  const auto a = check_common(p, expected_counts(p));
  CHECK(a.equilibria.degeneracy == abu::degeneracy_none);
  const ld two_ml = 2 * capacity(p, 0), delta = (two_ml - ld(p.rotor.unbalance)) / two_ml;
  const ld theta = 2 * std::asin(std::sqrt(delta / 2));
  REQUIRE(count(a.equilibria, Family::balanced) == 2);
  const auto& e1 = a.equilibria.points()[0];
  const auto& e2 = a.equilibria.points()[1];
  REQUIRE(e1.family == Family::balanced);
  REQUIRE(e2.family == Family::balanced);
  CHECK(e1.position(2) != e1.position(3));
  // delta from exact doubles in long double is good to eps_ld / 1e-9 ~ 5e-11; an arccos of
  // U / 2ml formed in double would be off by eps / 1e-9 ~ 1e-7 in delta: 1e-9 tells them apart.
  for (const auto* e : {&e1, &e2}) {
    for (int i = 2; i < 4; ++i) CHECK(std::abs(std::abs(e->position(i) - kPi) - theta) <= 1e-9L * theta);
    CHECK((e->position(2) - kPi) * (e->position(3) - kPi) < 0);  // one ball each side of pi
  }
  // The two points are one configuration with the (equal) balls relabelled: same spectrum,
  // within the two error estimates plus the double rounding of the values.
  const auto& s1 = a.spectra[0];
  const auto& s2 = a.spectra[1];
  for (std::size_t k = 0; k < 8; ++k)
    CHECK(std::abs(s1.eigenvalues[k] - s2.eigenvalues[k]) <=
          4 * (s1.error[k] + s2.error[k]) + 4 * kEps * std::abs(s1.eigenvalues[k]));
  // The merging mode: its eigenvalue is O(delta) times the slow rates, resolved from zero
  // (above 8 error estimates) yet below 1e-6 of every other eigenvalue; same sign twice.
  for (const auto* sp : {&s1, &s2}) {
    std::array<std::size_t, 8> order{0, 1, 2, 3, 4, 5, 6, 7};
    std::sort(order.begin(), order.end(), [sp](std::size_t x, std::size_t y) {
      return std::abs(sp->eigenvalues[x]) < std::abs(sp->eigenvalues[y]);
    });
    const cd tiny = sp->eigenvalues[order[0]];
    INFO("tiny " << tiny << " next " << sp->eigenvalues[order[1]]);
    CHECK(std::abs(tiny) > 8 * sp->error[order[0]]);
    CHECK(std::abs(tiny) < 1e-6 * std::abs(sp->eigenvalues[order[1]]));
    CHECK(tiny.imag() == 0);
    CHECK(std::signbit(tiny.real()) == std::signbit(s1.eigenvalues[order[0]].real()));
  }
}

// U = 2ml as doubles: the balanced pair has merged with a together point at beta = pi.
// The inputs fix U / 2ml only to the rounding the program calls equal (8 eps), where the
// exact triangle gives theta <= sqrt(16 eps) ~ 6e-8.
TEST_CASE("balanced points merged at U = 2ml", "[hard]") {
  abu::Params p = base_params();
  p.rotor.unbalance = 2 * p.balls[0].mass * p.balls[0].race_radius;
  // One merged balanced point; the together roots (D = U^2 K^2 > 0) are two, one at pi.
  const auto a = check_common(p, {1, 2, 2});
  CHECK((a.equilibria.degeneracy & abu::balanced_merges_together) != 0);
  CHECK((a.equilibria.degeneracy & ~unsigned(abu::balanced_merges_together)) == 0);
  REQUIRE(a.equilibria.points()[0].family == Family::balanced);
  for (int i = 2; i < 4; ++i) CHECK(std::abs(a.equilibria.points()[0].position(i) - kPi) <= std::sqrt(16 * kEps));
  // The merge is a pitchfork: a zero eigenvalue up to input rounding (O(8 eps) of the slow rates).
  std::array<double, 8> modulus{};
  for (std::size_t k = 0; k < 8; ++k) modulus[k] = std::abs(a.spectra[0].eigenvalues[k]);
  std::sort(modulus.begin(), modulus.end());
  CHECK(modulus[0] <= 64 * kEps * modulus[1]);
}

// Tiny balls (2ml = 3.6e-11 << U): no balanced point, two together, two opposite.
TEST_CASE("tiny balls cannot balance", "[hard]") {
  abu::Params p = base_params();
  for (auto& b : p.balls) b.mass = 1e-9;
  const Counts c = expected_counts(p);
  CHECK(c.balanced == 0);
  check_common(p, c);
}

// U = 0: rotational symmetry, the balanced set is the circle beta2 = beta1 + pi, listed once
// (is_set); no together/opposite points (C a != 0). Along the circle the spectrum has an
// exact zero eigenvalue, so the circle cannot be asymptotically stable.
TEST_CASE("zero unbalance: one circle with a zero eigenvalue", "[hard]") {
  abu::Params p = base_params();
  p.rotor.unbalance = 0;
  const auto a = check_common(p, {1, 0, 0});
  CHECK(a.equilibria.degeneracy == abu::unbalance_zero);
  REQUIRE(a.equilibria.points().size() == 1);
  const auto& e = a.equilibria.points()[0];
  CHECK(e.is_set);
  CHECK(std::abs(std::remainder(e.position(3) - e.position(2) - kPi, 2 * kPi)) <= 8 * kEps);
  const auto& sp = a.spectra[0];
  std::array<std::size_t, 8> order{0, 1, 2, 3, 4, 5, 6, 7};
  std::sort(order.begin(), order.end(),
            [&sp](std::size_t x, std::size_t y) { return std::abs(sp.eigenvalues[x]) < std::abs(sp.eigenvalues[y]); });
  const std::size_t zero = order[0];
  INFO("zero eigenvalue " << sp.eigenvalues[zero] << " error " << sp.error[zero]);
  // Zero to rounding: below eps times the slowest genuine rate.
  CHECK(std::abs(sp.eigenvalues[zero]) <= kEps * std::abs(sp.eigenvalues[order[1]]));
  // ... and reported as such: inside the marginal band, so the verdict is not `stable`.
  // (A band proportional to |lambda| itself, as in spectrum.cpp, can never contain a computed
  // zero eigenvalue of -2e-44: it needs an absolute floor or the is_set information.)
  CHECK(sp.on_axis[zero]);
  CHECK(sp.stability != abu::Stability::stable);
  // Every other eigenvalue is resolved well away from the axis (decays: above omega_n).
  for (std::size_t k = 1; k < 8; ++k) {
    INFO("lambda " << sp.eigenvalues[order[k]]);
    CHECK(-sp.eigenvalues[order[k]].real() > 1e6 * sp.error[order[k]]);
    CHECK_FALSE(sp.on_axis[order[k]]);
  }
}

// c = 0 at omega = omega_n: K = C = 0, no bounded rotor response; only the balanced points.
TEST_CASE("undamped resonance has only the balanced equilibria", "[hard]") {
  abu::Params p = base_params();
  p.rotor.damping = 0;
  p.omega = std::sqrt(p.rotor.stiffness / double(total_mass(p)));
  const auto a = check_common(p, {2, 0, 0});
  CHECK((a.equilibria.degeneracy & abu::no_rotor_equilibrium) != 0);
}

// Unequal balls (a1 = 5.94e-7, a2 = 5e-7): balanced iff |a1 - a2| <= U <= a1 + a2.
TEST_CASE("unequal balls: existence window of the balanced state", "[hard]") {
  for (const double U : {5e-8, 3e-7, 6e-7, 1e-6, 1.2e-6}) {
    abu::Params p = base_params();
    p.balls[1].mass = 2.5e-5;
    p.balls[1].race_radius = 0.02;
    p.rotor.unbalance = U;
    INFO("U " << U);
    const Counts c = expected_counts(p);
    CHECK(c.balanced == (U > 9.4e-8 && U < 1.094e-6 ? 2 : 0));  // the window by hand
    const auto a = check_common(p, c);
    CHECK(a.equilibria.degeneracy == abu::degeneracy_none);
  }
}

// omega = 1e4 rad/s (40 omega_n): fast modes ~ 9e7 1/s, the slow ones ~ 1e-4 1/s.
TEST_CASE("high spin speed", "[hard]") {
  abu::Params p = base_params();
  p.omega = 1e4;
  const auto a = check_common(p, expected_counts(p));
  for (std::size_t i = 0; i < a.equilibria.points().size(); ++i) check_fast_modes(p, a.spectra[i]);
}

// c = 0 just off resonance: K = -2e-6 k, so |q| = w^2 |U + sum a e^{ib}| / |K| is metres,
// yet the static equations still hold to rounding. K carries the cancellation of k - w^2 M:
// its long-double relative error is ~ eps_ld (k + w^2 M) / |K| ~ 5e-14.
TEST_CASE("undamped, just off resonance: huge but exact rotor response", "[hard]") {
  abu::Params p = base_params();
  p.rotor.damping = 0;
  p.omega = std::sqrt(p.rotor.stiffness / double(total_mass(p))) * (1 + 1e-6);
  const auto a = check_common(p, expected_counts(p));
  const ld K = stiffness_K(p), w2 = ld(p.omega) * ld(p.omega);
  const ld tol = 64 * std::numeric_limits<ld>::epsilon() * (ld(p.rotor.stiffness) + w2 * total_mass(p)) / std::abs(K);
  for (const auto& e : a.equilibria.points()) {
    if (e.family == Family::balanced) continue;
    const cld load = ld(p.rotor.unbalance) + capacity(p, 0) * std::polar(ld(1), e.position(2)) +
                     capacity(p, 1) * std::polar(ld(1), e.position(3));
    const ld q = std::hypot(e.position(0), e.position(1)), expected = w2 * std::abs(load) / std::abs(K);
    INFO(to_string(e.family) << " |q| " << double(q) << " expected " << double(expected));
    CHECK(expected > 1e5 * (ld(p.rotor.unbalance) + 2 * capacity(p, 0)) / total_mass(p));
    CHECK(std::abs(q - expected) <= tol * expected);
  }
}

// Regression: equal balls 1e-6 from merging, undamped, coulomb: the decoupled antisymmetric
// ball mode once made the eigenvalue refinement diverge.
TEST_CASE("near-merge equal balls without damping refine cleanly", "[hard]") {
  abu::Params p = base_params();
  p.rotor.damping = 0;
  p.rotor.unbalance = 0.999999 * 2 * 3.3e-5 * 0.018;
  check_common(p, expected_counts(p));
}
