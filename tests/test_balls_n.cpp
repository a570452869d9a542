// Any number of balls (model.md §13): the bounded-dynamic model against complex-step
// derivatives for n = 3 .. 12, the general equilibrium algorithm against the two-ball
// closed forms, the count of 2^n aligned equilibria, the structural zeros of the balanced
// set, the trace identity and the lambda -> -lambda symmetry of the conservative case.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "abu/core/widen_params.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/scan.hpp"

using namespace abu;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The default scene's rotor with n balls; `spread` makes every ball differ in every
// coefficient (so index mix-ups cannot cancel).
ParamsN ring(int n, FrictionLaw law, double omega = 900.0, bool spread = true) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = omega;
  p.law = law;
  p.kappa = 1e3;
  p.balls.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const double f = spread ? 1 + 0.07 * i : 1;
    p.balls[std::size_t(i)] = {3.3e-5 * f, 0.018 * (spread ? 1 + 0.01 * i : 1), 1e-3, 1.4, 0.002 * f, 1e-4 * f,
                               0.001 * f, 0.003 * f, 0.1 * f};
  }
  return p;
}

}  // namespace

// Complex step: Im f(x + i h e_j) / h is df/dx_j with no cancellation, to rounding
// (h = 1e-20 of the component's natural size). Errors per column, relative to the
// column's norm in natural units (q in the displacement scale, rates times omega): the
// analytic and complex-step columns differ only by the rounding of their terms, ~1e-15;
// 1e-11 leaves room for the conditioning of A^-1 and catches any wrong term (O(1)).
TEST_CASE("n-ball Jacobian agrees with the complex-step derivative, n = 3 .. 12", "[n-balls]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 3; n <= max_balls; ++n) {
    for (auto law : {FrictionLaw::viscous, FrictionLaw::coulomb, FrictionLaw::stribeck}) {
      const ParamsN p = ring(n, law);
      const auto pc = p.cast<std::complex<double>>();
      const double length = displacement_scale(p);
      const int d = n + 2;
      State<double, any_balls> scale(2 * d), x(2 * d);
      for (int i = 0; i < 2 * d; ++i) {
        scale(i) = (i % d < 2 ? length : 1.0) * (i >= d ? p.omega : 1.0);
        x(i) = u(rng) * scale(i);
      }
      const StateMatrix<double, any_balls> J = jacobian(p, x);
      double worst = 0;
      for (int j = 0; j < 2 * d; ++j) {
        const double h = 1e-20 * scale(j);
        State<std::complex<double>, any_balls> xc = x.cast<std::complex<double>>();
        xc(j) += std::complex<double>(0, h);
        const auto f = vector_field(pc, xc);
        double diff = 0, norm = 0;
        for (int i = 0; i < 2 * d; ++i) {
          const double w = scale(i) / scale(j);
          const double ref = f(i).imag() / h;
          diff = std::max(diff, std::abs(J(i, j) - ref) / w);
          norm = std::max(norm, std::abs(ref) / w);
        }
        worst = std::max(worst, norm > 0 ? diff / norm : diff);
      }
      INFO("n = " << n << ", law " << to_string(law));
      CHECK(worst < 1e-11);
    }
  }
}

// The general algorithm (§13.2, §13.4 sampling) reproduces the two-ball closed forms of
// §5 (equilibria.cpp, a separate implementation): states to 1e-12 of the displacement
// scale / in rad (both are long-double computations of the same roots, ~1e-18 apart;
// 1e-12 still fails any branch or sign error), and the same spectra to 1e-10 relative.
TEST_CASE("the n-ball algorithm reproduces the two-ball closed forms", "[n-balls]") {
  for (double omega : {150.0, 240.0, 300.0, 900.0, 3000.0}) {
    Params p;
    p.rotor = {0.12, 7500.0, 2.0, 6e-7};
    p.omega = omega;
    p.law = FrictionLaw::coulomb;
    p.kappa = 1e3;
    p.balls[0] = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 0, 0, 0, 0};
    p.balls[1] = {2.9e-5, 0.018, 1e-3, 1.4, 0.002, 0, 0, 0, 0};
    const Analysis two = analyze(p);
    const AnalysisN general = analyze(widen(p));
    const auto a = two.equilibria.points();
    const auto b = general.equilibria.points();
    INFO("omega = " << omega);
    REQUIRE(a.size() == b.size());
    const double length = double(displacement_scale(p));
    for (std::size_t i = 0; i < a.size(); ++i) {
      // the same (family, pattern, member) somewhere in the general list
      std::size_t k = b.size();
      for (std::size_t j = 0; j < b.size(); ++j)
        if (b[j].family == a[i].family && b[j].member == a[i].member && b[j].pattern == a[i].pattern) k = j;
      INFO("equilibrium " << to_string(a[i].family) << " " << a[i].member);
      REQUIRE(k < b.size());
      CHECK(std::abs(double(a[i].position(0) - b[k].position(0))) < 1e-12 * length);
      CHECK(std::abs(double(a[i].position(1) - b[k].position(1))) < 1e-12 * length);
      for (int j = 2; j < 4; ++j)
        CHECK(std::abs(std::remainder(double(a[i].position(j) - b[k].position(j)), 2 * std::numbers::pi)) < 1e-12);
      for (int e = 0; e < 8; ++e) {
        const auto x = two.spectra[i].eigenvalues[std::size_t(e)];
        const auto y = general.spectra[k].eigenvalues[std::size_t(e)];
        CHECK(std::abs(x - y) <= 1e-10 * std::abs(x) + 1e-300);
      }
    }
  }
}

// Tiny damping (C -> 0) gives every pattern two real roots (C^2 S^2 < U^2 (K^2 + C^2)),
// so exactly 2^n aligned equilibria (§13.3); each solves the static equations to
// rounding (residual ~1e-16; 1e-13 allows a few hundred roundings).
TEST_CASE("2^n aligned equilibria where every pattern has two roots", "[n-balls]") {
  for (int n = 3; n <= 6; ++n) {
    ParamsN p = ring(n, FrictionLaw::viscous, 500.0);
    p.rotor.damping = 1e-3;
    const auto set = find_equilibria(p);
    int aligned = 0;
    for (const auto& e : set.points()) {
      if (e.family == Family::balanced) continue;
      ++aligned;
      CHECK(e.converged);
      CHECK(e.residual < 1e-13);
    }
    INFO("n = " << n);
    CHECK(aligned == (1 << n));
  }
}

// On the balanced set the tangent directions are zero modes (§13.4): n - 2 of them with
// friction slope, 2 (n - 2) (Jordan pairs) without. The reported spectrum lists them as
// exact zeros, and each sample lies on the set (|W| to rounding, q = 0 exactly).
TEST_CASE("balanced samples carry exactly the structural zeros of the set", "[n-balls]") {
  for (int n : {3, 4, 5}) {
    for (auto law : {FrictionLaw::viscous, FrictionLaw::coulomb, FrictionLaw::none}) {
      const ParamsN p = ring(n, law, 900.0, false);
      const AnalysisN a = analyze(p, BalancedSampling{16});
      int samples = 0;
      for (std::size_t i = 0; i < a.equilibria.list.size(); ++i) {
        const auto& e = a.equilibria.list[i];
        if (!e.on_balanced_set) continue;
        ++samples;
        std::complex<long double> W = p.rotor.unbalance;
        for (int b = 0; b < n; ++b)
          W += (long double)p.balls[std::size_t(b)].mass * (long double)p.balls[std::size_t(b)].race_radius *
               std::polar(1.0L, e.position(2 + b));
        const int expected = law == FrictionLaw::none ? 2 * (n - 2) : n - 2;
        INFO("n = " << n << ", law " << to_string(law) << ", sample " << e.member);
        CHECK(e.position(0) == 0);
        CHECK(e.position(1) == 0);
        CHECK(double(std::abs(W)) < 1e-17 * (p.rotor.unbalance + n * 3.3e-5 * 0.018));
        CHECK(a.spectra[i].n_structural == expected);
        int zeros = 0;
        for (int k = 0; k < a.spectra[i].count; ++k) zeros += a.spectra[i].eigenvalues[std::size_t(k)] == 0.0;
        CHECK(zeros >= expected);
      }
      CHECK(samples > 0);
    }
  }
}

// trace J = sum of the eigenvalues (§7) at an aligned equilibrium of n = 4 unequal balls,
// relative to the sum of moduli: each eigenvalue to ~1e-15 of its modulus, so 1e-12.
// Conservative (c = 0, friction none): the spectrum is symmetric under lambda -> -lambda;
// each eigenvalue's mirror is in the spectrum to 1e-9 of its modulus (the refined
// eigenvalues are good to ~1e-12 here).
TEST_CASE("trace identity and conservative symmetry for n balls", "[n-balls]") {
  {
    const ParamsN p = ring(4, FrictionLaw::coulomb);
    const AnalysisN a = analyze(p);
    int checked = 0;
    for (std::size_t i = 0; i < a.equilibria.list.size(); ++i) {
      const auto& e = a.equilibria.list[i];
      if (e.family == Family::balanced) continue;
      const auto J = jacobian(linearize(p.cast<long double>(), e.state()));
      std::complex<double> sum = 0;
      double moduli = 0;
      for (int k = 0; k < a.spectra[i].count; ++k) {
        sum += a.spectra[i].eigenvalues[std::size_t(k)];
        moduli += std::abs(a.spectra[i].eigenvalues[std::size_t(k)]);
      }
      CHECK(std::abs(sum.real() - double(J.trace())) <= 1e-12 * moduli);
      CHECK(std::abs(sum.imag()) <= 1e-12 * moduli);
      ++checked;
    }
    CHECK(checked > 0);
  }
  {
    ParamsN p = ring(3, FrictionLaw::none);
    p.rotor.damping = 0;
    const AnalysisN a = analyze(p);
    int checked = 0;
    for (std::size_t i = 0; i < a.equilibria.list.size(); ++i) {
      if (a.equilibria.list[i].family == Family::balanced) continue;
      const auto& sp = a.spectra[i];
      for (int k = 0; k < sp.count; ++k) {
        const auto l = sp.eigenvalues[std::size_t(k)];
        double nearest = std::numeric_limits<double>::infinity();
        for (int j = 0; j < sp.count; ++j) nearest = std::min(nearest, std::abs(sp.eigenvalues[std::size_t(j)] + l));
        CHECK(nearest <= 1e-9 * std::abs(l) + 1e3 * kEps);
      }
      ++checked;
    }
    CHECK(checked > 0);
  }
}

// Existence of the balanced set is the polygon inequality (§13.4): three equal balls
// balance U up to 3 m l and no more.
TEST_CASE("the balanced set exists exactly up to the capacity", "[n-balls]") {
  ParamsN p = ring(3, FrictionLaw::viscous, 900.0, false);
  const double capacity = 3 * 3.3e-5 * 0.018;
  p.rotor.unbalance = capacity * (1 - 1e-9);
  CHECK(balanced_set_exists(p));
  CHECK(find_equilibria(p).balanced_set.samples > 0);
  p.rotor.unbalance = capacity * (1 + 1e-9);
  CHECK_FALSE(balanced_set_exists(p));
  const auto set = find_equilibria(p);
  CHECK(set.balanced_set.samples == 0);
  CHECK((set.degeneracy & balanced_absent) != 0);
}
