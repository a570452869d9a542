// The non-balanced states on an anisotropic support as pi/omega-periodic orbits
// (docs/model.md §10.14): the field's Jacobian against finite differences, the isotropic
// limit delta -> 0 (the orbit is the equilibrium, the multipliers exp(lambda pi/omega)),
// the first-order growth of the orbit with delta, and the periodicity at full anisotropy.
// The orbits' values at full anisotropy are checked against the independent Python
// reference (tests/reference/forced_orbit_reference.py, ctest reference_forced_orbits/*).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "abu/dynamics/forced_orbits.hpp"
#include "abu/equilibria/equilibria_n.hpp"

using namespace abu;

namespace {

// BASE of docs/model.md §10.8 (two viscous balls, omega = 900 rad/s).
ParamsN base() {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = FrictionLaw::viscous;
  p.kappa = 1e6;
  p.balls.resize(2);
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-3, 0.001, 0.003, 0.1};
  return p;
}

// §10.8's anisotropy: dk = 375, k_xy = 150, dc = 0.3, c_xy = 0.1 about the mean of `p`.
AnisotropicSupport support_of(const ParamsN& p) {
  const double k = p.rotor.stiffness, c = p.rotor.damping;
  return {k + 375.0, k - 375.0, 150.0, c + 0.3, c - 0.3, 0.1};
}

std::vector<EquilibriumN> aligned(const ParamsN& p) {
  std::vector<EquilibriumN> out;
  const EquilibriumSetN set = find_equilibria(p);
  for (const auto& e : set.points())
    if (e.family != Family::balanced) out.push_back(e);
  return out;
}

}  // namespace

// (10.14.2) is the analytic Jacobian of (10.14.1); central differences of the field with
// steps 1e-6 of each coordinate's scale have a truncation error ~1e-12 relative and a
// rounding error ~1e-10 of the largest entry: 1e-7 of the row's largest entry is safe.
// delta_end = 0: the mean system, whose aligned equilibrium is a constant orbit. Its
// shooting multipliers (the transition matrices integrated to rtol 1e-13 and multiplied
// by periodic orthogonal iteration) must equal exp(lambda pi/omega) of the equilibrium's
// eigenvalues (Eigen's, of the analytic Jacobian) to 1e-9 relative: the integration's
// error over 8 intervals, far above rounding, far below any modelling question.
TEST_CASE("forced orbits: delta -> 0 gives the equilibrium and exp(lambda pi/omega)", "[forced]") {
  const ParamsN p = base();
  const AnisotropicSupport s = support_of(p);
  const std::vector<EquilibriumN> eqs = aligned(p);
  REQUIRE(eqs.size() == 4);
  ForcedOrbitOptions o;
  o.delta_end = 0;
  for (const EquilibriumN& e : eqs) {
    const ForcedOrbit orbit = forced_orbit(p, s, e, o);
    INFO(orbit.kind << ": " << orbit.reason);
    REQUIRE(orbit.status.ok());
    const double q = std::hypot(double(e.position(0)), double(e.position(1)));
    CHECK(std::abs(orbit.q_abs_max - q) <= 1e-10 * q);
    CHECK(std::abs(orbit.q_abs_mean - q) <= 1e-10 * q);
    CHECK(orbit.periodicity <= 1e-10);
    const Eigen::MatrixXd J = jacobian(p, at_rest<double, any_balls>(e.position_si()));
    Eigen::EigenSolver<Eigen::MatrixXd> es(J, false);
    std::vector<std::complex<double>> want;
    for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k)
      want.push_back(std::exp(es.eigenvalues()(k) * std::numbers::pi / p.omega));
    REQUIRE(orbit.multipliers.size() == want.size());
    for (const auto& rho : orbit.multipliers) {
      double best = 1e300;
      for (const auto& w : want) best = std::min(best, std::abs(rho - w) / std::abs(w));
      INFO("rho = " << rho);
      CHECK(best <= 1e-9);
    }
  }
}

// A small anisotropy moves the orbit off the equilibrium at first order in delta (the
// residual e^{-2i omega t}(kappa - i omega gamma) conj(q) of §10.3 is linear in delta):
// the spread max|q| - min... measured as max|q| - mean|q| doubles with delta to 2 %
// (the second-order term is delta^2 against delta), and the multipliers stay within
// O(delta) of the equilibrium's. At full anisotropy the orbit closes to its tolerance.
TEST_CASE("forced orbits: first order in delta, periodic at full anisotropy", "[forced]") {
  const ParamsN p = base();
  const AnisotropicSupport s = support_of(p);
  const std::vector<EquilibriumN> eqs = aligned(p);
  REQUIRE(!eqs.empty());
  const EquilibriumN& e = eqs.front();
  ForcedOrbitOptions o;
  o.delta_end = 0.01;
  const ForcedOrbit a = forced_orbit(p, s, e, o);
  o.delta_end = 0.02;
  const ForcedOrbit b = forced_orbit(p, s, e, o);
  REQUIRE(a.status.ok());
  REQUIRE(b.status.ok());
  const double sa = a.q_abs_max - a.q_abs_mean, sb = b.q_abs_max - b.q_abs_mean;
  CHECK(sa > 0);
  CHECK(std::abs(sb / sa - 2.0) <= 0.04);
  const ForcedOrbit full = forced_orbit(p, s, e, {});
  INFO(full.reason);
  REQUIRE(full.status.ok());
  CHECK(full.delta == 1.0);
  CHECK(full.periodicity <= 1e-9);
  CHECK(full.multipliers.size() == 8);
}

namespace {

// Stiff coulomb balls on an anisotropic support, not a scene of data/ or tests/scenes: two
// unequal balls (one rolling, one sliding), kappa = 1e6 s/rad (ball rates ~1e9 1/s, the stuck
// balls' slow exponents ~1e-7 1/s), omega = 1300 rad/s (supercritical).
ParamsN stiff_coulomb() {
  ParamsN p;
  p.rotor = {0.2, 10500.0, 3.25, 8e-7};
  p.omega = 1300.0;
  p.law = FrictionLaw::coulomb;
  p.kappa = 1e6;
  p.balls.resize(2);
  p.balls[0] = {4e-5, 0.02, 1e-3, 1.4, 0.003, 0, 0, 0, 0};
  p.balls[1] = {3e-5, 0.021, 1.2e-3, 1.0, 0.003, 0, 0, 0, 0};
  return p;
}

AnisotropicSupport stiff_support() { return {12000.0, 9000.0, -800.0, 4.0, 2.5, 0.6}; }

}  // namespace

// The gap this closes (model.md §10.18): with stiff coulomb balls every aligned equilibrium
// continues to its orbit. Each closes (the uninterrupted run's periodicity to 1e-12 scaled:
// the increments are summed apart from the state, so rounding, not a tolerance, limits it),
// its multipliers' estimated discretization error is below the 1e-10 target, and the stiff
// ball multipliers are flagged (2 per orbit: one fast rate per ball) with ln|rho| below -1e4
// (rates ~1e8-1e9 1/s over pi/omega = 2.4 ms).
TEST_CASE("forced orbits: every orbit of stiff coulomb balls is found", "[forced]") {
  const ParamsN p = stiff_coulomb();
  const AnisotropicSupport s = stiff_support();
  const std::vector<EquilibriumN> eqs = aligned(p);
  REQUIRE(eqs.size() == 4);
  for (const EquilibriumN& e : eqs) {
    const ForcedOrbit o = forced_orbit(p, s, e, {});
    INFO(o.kind << ": " << o.reason);
    REQUIRE(o.status.ok());
    CHECK(o.delta == 1.0);
    CHECK(o.periodicity <= 1e-12);
    CHECK(o.discretization_error <= 1e-10);
    CHECK(o.unresolved_multipliers == 2);
    REQUIRE(o.log_moduli.size() == 8);
    CHECK(o.log_moduli[6] < -1e4);
    CHECK(o.log_moduli[7] < -1e4);
    // |q| moves off the equilibrium's at first order: by a fraction of |kappa|/k_bar ~ 0.16 at most
    const double q = std::hypot(double(e.position(0)), double(e.position(1)));
    CHECK(o.q_abs_max > o.q_abs_mean);
    CHECK(std::abs(o.q_abs_mean - q) <= 0.5 * q);
  }
}

// delta_end = 0 with stiff coulomb balls: the constant orbit, and rho = exp(lambda pi/omega)
// for every eigenvalue of §6's J. The resolved multipliers to 1e-9 relative (the
// discretization error target is 1e-10; near-double ones see below); the two stiff ones (|rho| = e^{-1e5}) are compared
// through their logarithms, to 1e-9 relative: on a constant orbit the period average of the
// fast eigenvalue that replaces them is that eigenvalue exactly.
TEST_CASE("forced orbits: delta -> 0 with stiff coulomb balls gives exp(lambda pi/omega)", "[forced]") {
  const ParamsN p = stiff_coulomb();
  const AnisotropicSupport s = stiff_support();
  ForcedOrbitOptions o;
  o.delta_end = 0;
  for (const EquilibriumN& e : aligned(p)) {
    const ForcedOrbit orbit = forced_orbit(p, s, e, o);
    INFO(orbit.kind << ": " << orbit.reason);
    REQUIRE(orbit.status.ok());
    const double q = std::hypot(double(e.position(0)), double(e.position(1)));
    CHECK(std::abs(orbit.q_abs_max - q) <= 1e-10 * q);
    CHECK(std::abs(orbit.q_abs_mean - q) <= 1e-10 * q);
    // J on the scaled state (q / L, beta, q' / (L omega), beta' / omega): the SI J spans 1e-6 m
    // against 1 rad and its stiff rows 1e9 1/s, and an unbalanced eigensolver would lose digits.
    Eigen::MatrixXd J = jacobian(p, at_rest<double, any_balls>(e.position_si()));
    const double L = displacement_scale(p);
    const Eigen::VectorXd D = (Eigen::VectorXd(8) << L, L, 1, 1, L * p.omega, L * p.omega, p.omega, p.omega).finished();
    J = D.cwiseInverse().asDiagonal() * J * D.asDiagonal();
    Eigen::EigenSolver<Eigen::MatrixXd> es(J, false);
    std::vector<std::complex<double>> want;
    for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k) want.push_back(es.eigenvalues()(k) * std::numbers::pi / p.omega);
    std::sort(want.begin(), want.end(), [](auto a, auto b) { return a.real() > b.real(); });
    REQUIRE(orbit.multipliers.size() == want.size());
    REQUIRE(orbit.unresolved_multipliers == 2);
    // The isotropic rotor's forward and backward exponents differ by 2i omega (§10.7): at
    // delta = 0 their multipliers nearly coincide (here within ~1e-9, split only by the balls),
    // and the members of a near-double multiplier move by the square root of the monodromy's
    // error (1e-10 -> 1e-5). So: the members of such a cluster (pairwise within 1e-5) to 1e-5
    // each, and the cluster's mean to 1e-9 like every isolated multiplier.
    for (std::size_t k = 0; k < 6; ++k) {
      const std::complex<double> wk = std::exp(want[k]);
      std::complex<double> got_sum = 0, want_sum = 0;
      int members = 0;
      for (std::size_t i = 0; i < 6; ++i)
        if (std::abs(std::exp(want[i]) - wk) <= 1e-5 * std::abs(wk)) {
          want_sum += std::exp(want[i]);
          ++members;
        }
      double best = 1e300;
      std::vector<std::pair<double, std::size_t>> near;
      for (std::size_t i = 0; i < 6; ++i) near.emplace_back(std::abs(orbit.multipliers[i] - wk), i);
      std::sort(near.begin(), near.end());
      for (int m = 0; m < members; ++m) got_sum += orbit.multipliers[near[std::size_t(m)].second];
      best = near.front().first / std::abs(wk);
      INFO("exp(lambda pi/omega) = " << wk << ", cluster of " << members);
      CHECK(best <= (members > 1 ? 1e-5 : 1e-9));
      CHECK(std::abs(got_sum - want_sum) <= 1e-9 * std::abs(want_sum));
    }
    for (std::size_t k = 6; k < 8; ++k) {
      INFO("ln|rho| = " << orbit.log_moduli[k] << ", lambda pi/omega = " << want[k].real());
      CHECK(std::abs(orbit.log_moduli[k] - want[k].real()) <= 1e-9 * std::abs(want[k].real()));
    }
  }
}
