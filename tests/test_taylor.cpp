// Truncated Taylor series (include/abu/core/taylor.hpp): every recurrence against the
// closed-form derivatives of the function it implements, and the model's second and
// third directional derivatives against finite differences of the long-double model.
#include <catch2/catch.hpp>

#include <cmath>

#include "abu/core/taylor.hpp"
#include "abu/model/model.hpp"

namespace {

using ld = long double;
using Jet = abu::Taylor<ld, 3>;

// Relative error against a nonzero reference.
ld rel(ld got, ld want) { return std::abs(got - want) / std::abs(want); }

// The coefficients are sums of at most a few products of O(1) numbers rounded in long
// double (eps = 1.1e-19); the closed forms below are evaluated in long double too. 1e-17
// leaves a factor ~100 for the accumulation, and is 10^8 below any finite-difference
// derivative's accuracy, so a wrong recurrence (a missing factor k, a sign) cannot pass.
constexpr ld tol = 1e-17L;

}  // namespace

TEST_CASE("Taylor series of the elementary functions match their derivatives", "[taylor]") {
  const ld x0 = 0.7L;
  const Jet x = Jet::variable(x0);
  SECTION("sin and cos: c_k = f^(k)(x0) / k!") {
    const Jet s = sin(2 * x), c = cos(2 * x);
    CHECK(rel(s.c[0], std::sin(2 * x0)) <= tol);
    CHECK(rel(s.c[1], 2 * std::cos(2 * x0)) <= tol);
    CHECK(rel(s.c[2], -4 * std::sin(2 * x0) / 2) <= tol);
    CHECK(rel(s.c[3], -8 * std::cos(2 * x0) / 6) <= tol);
    CHECK(rel(c.c[3], 8 * std::sin(2 * x0) / 6) <= tol);
  }
  SECTION("exp of a polynomial argument") {
    // g = exp(x^2): g' = 2x g, g'' = (2 + 4x^2) g, g''' = (12x + 8x^3) g.
    const Jet g = exp(x * x);
    const ld e = std::exp(x0 * x0);
    CHECK(rel(g.c[1], 2 * x0 * e) <= tol);
    CHECK(rel(g.c[2], (2 + 4 * x0 * x0) * e / 2) <= tol);
    CHECK(rel(g.c[3], (12 * x0 + 8 * x0 * x0 * x0) * e / 6) <= tol);
  }
  SECTION("atan: the smoothed sign of the friction laws") {
    // d/dx atan x = 1/(1+x^2), d2 = -2x/(1+x^2)^2, d3 = (6x^2 - 2)/(1+x^2)^3.
    const Jet a = atan(x);
    const ld u = 1 + x0 * x0;
    CHECK(rel(a.c[0], std::atan(x0)) <= tol);
    CHECK(rel(a.c[1], 1 / u) <= tol);
    CHECK(rel(a.c[2], -2 * x0 / (u * u) / 2) <= tol);
    CHECK(rel(a.c[3], (6 * x0 * x0 - 2) / (u * u * u) / 6) <= tol);
  }
  SECTION("quotient") {
    // 1 / (1 + x): (-1)^k / (1 + x0)^(k+1).
    const Jet q = Jet(1) / (1 + x);
    for (int k = 0; k <= 3; ++k) CHECK(rel(q.c[std::size_t(k)], std::pow(-1.0L, k) / std::pow(1 + x0, k + 1)) <= tol);
  }
}

TEST_CASE("the model's directional derivatives in Taylor series match finite differences", "[taylor]") {
  // Default-like two-ball scene with coulomb friction at an arbitrary (non-equilibrium)
  // state and direction: the Taylor coefficients of f(x0 + t u) against central
  // differences of the long-double model. The differences have truncation error O(h^2)
  // (O(h^4) for the extrapolated third) and rounding eps / h^k: with h = 1e-4 (second) and
  // 1e-3 (third) both are ~1e-8 relative, so 1e-6 is a check the recurrences must pass and
  // that a wrong one (off by a factor, a sign, a missing term) fails by O(1).
  abu::ParamsT<ld, 2> p;
  p.rotor = {0.1L, 7500.0L, 0.5L, 2e-5L};
  p.omega = 400.0L;
  p.law = abu::FrictionLaw::coulomb;
  p.kappa = 1e2L;  // moderate, so that the differences resolve the third derivative
  for (auto& b : p.balls) {
    b.mass = 0.01L;
    b.race_radius = 0.02L;
    b.radius = 0.004L;
    b.inertia_factor = 1.4L;
    b.mu = 0.002L;
  }
  abu::State<ld, 2> x0;
  x0 << 3e-6L, -2e-6L, 1.1L, 2.9L, 1e-3L, 2e-3L, 0.01L, -0.02L;
  abu::State<ld, 2> u;
  u << 1e-6L, 2e-6L, 0.3L, -0.5L, 1e-3L, -1e-3L, 0.02L, 0.01L;
  const abu::ParamsT<Jet, 2> pj = p.cast<Jet>();
  abu::State<Jet, 2> xj;
  for (int k = 0; k < 8; ++k) {
    xj(k) = Jet(x0(k));
    xj(k).c[1] = u(k);
  }
  const abu::State<Jet, 2> fj = abu::vector_field(pj, xj);
  const auto f = [&](ld t) { return abu::vector_field(p, abu::State<ld, 2>(x0 + t * u)); };
  const ld h2 = 1e-4L, h3 = 1e-3L;
  const abu::State<ld, 2> second = (f(h2) - 2 * f(0) + f(-h2)) / (h2 * h2);
  // Central third difference, O(h^2), Richardson-extrapolated from h and h/2 to O(h^4)
  // (the plain O(h^2) stencil was 2e-5 off at h = 1e-3: the atan of the friction law has
  // large fifth derivatives).
  const auto third_at = [&](ld h) -> abu::State<ld, 2> {
    return (f(2 * h) - 2 * f(h) + 2 * f(-h) - f(-2 * h)) / (2 * h * h * h);
  };
  const abu::State<ld, 2> third = (4 * third_at(h3 / 2) - third_at(h3)) / 3;
  const abu::State<ld, 2> f0 = f(0);
  // Rows 0..3 are the velocities, linear in t: their higher coefficients are exactly 0.
  for (int k = 0; k < 4; ++k) {
    CHECK(fj(k).c[1] == u(4 + k));
    CHECK(fj(k).c[2] == 0);
    CHECK(fj(k).c[3] == 0);
  }
  for (int k = 4; k < 8; ++k) {
    // The value part is the model itself; it differs from the long-double path only in
    // how sin and cos are reduced (Cody-Waite there, libm here): last-bit differences.
    CHECK(std::abs(fj(k).c[0] - f0(k)) <= 1e-15L * std::abs(f0(k)));
    CHECK(std::abs(2 * fj(k).c[2] - second(k)) <= 1e-6L * std::abs(second(k)));
    CHECK(std::abs(6 * fj(k).c[3] - third(k)) <= 1e-6L * std::abs(third(k)));
  }
}
