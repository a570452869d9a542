// The eigenvalues' sensitivity to the arctan sharpness kappa (model.md (6.11)) against
// finite differences of the refined spectra in log kappa, and the creep flag (|s + 1| <=
// 0.1) against the modes that the differences show scaling like 1/kappa.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

#include "abu/linear/kappa_sensitivity.hpp"
#include "abu/scan/scan.hpp"

namespace {

abu::Params scene(abu::FrictionLaw law, double kappa, double omega) {
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = omega;
  p.law = law;
  p.kappa = kappa;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 0.0, 0.002, 0.003, 0.05};
  return p;
}

// log|lambda| of eigenvalue k of equilibrium e at kappa * f, matched to lambda by the
// nearest eigenvalue (the step is small enough that every mode moves by far less than the
// distance to its neighbours at the scenes below).
double log_modulus_at(abu::Params p, double factor, std::size_t e, std::complex<double> lambda) {
  p.kappa *= factor;
  const abu::Analysis a = abu::analyze(p);
  const auto& sp = a.spectra[e];
  double best = INFINITY, value = 0;
  for (int k = 0; k < sp.count; ++k) {
    const std::complex<double> z = sp.eigenvalues[std::size_t(k)];
    // distance in log modulus and angle: the modes span 16 decades
    const double dist = std::abs(std::log(z / lambda));
    if (dist < best) best = dist, value = std::log(std::abs(z));
  }
  return value;
}

void check_scene(const abu::Params& p, int expected_min_creep) {
  const abu::Analysis a = abu::analyze(p);
  const auto pl = p.cast<long double>();
  int creep_total = 0;
  for (std::size_t e = 0; e < a.equilibria.points().size(); ++e) {
    const auto& eq = a.equilibria.points()[e];
    const auto lin = abu::linearize(pl, abu::at_rest<long double, 2>(eq.position));
    const auto& sp = a.spectra[e];
    const abu::KappaSensitivity<2> ks = abu::kappa_sensitivity(p, lin, sp);
    REQUIRE(ks.defined);
    for (int k = 0; k < sp.count; ++k) {
      const auto kk = std::size_t(k);
      if (!ks.computed[kk]) continue;
      // Central difference in log kappa with h = 1e-6: each mode moves by ~1e-6 of its
      // modulus, far less than the closest pair's gap (the two fast ball modes, 2e-4
      // apart), so matching by nearest eigenvalue is safe; truncation ~h^2 = 1e-12,
      // rounding of the refined eigenvalues (~1e-12 of their modulus typically, 7e-11 at
      // worst, README) / h = 1e-6 .. 7e-5. Tolerance 1e-3 absolute on s, whose meaningful
      // values are O(1) (-1 creep, +1 fast, 0 unaffected) and whose flag threshold is 0.1.
      const double h = 1e-6;
      const double fd = (log_modulus_at(p, std::exp(h), e, sp.eigenvalues[kk]) -
                         log_modulus_at(p, std::exp(-h), e, sp.eigenvalues[kk])) /
                        (2 * h);
      INFO("equilibrium " << e << " eigenvalue " << sp.eigenvalues[kk] << ": s = " << ks.log_slope[kk]
                          << ", finite differences " << fd);
      CHECK(std::abs(ks.log_slope[kk] - fd) <= 1e-3);
      // Flagged exactly when the differences say the mode scales like 1/kappa.
      CHECK(ks.creep[kk] == (std::abs(fd + 1) <= abu::creep_tolerance));
      creep_total += ks.creep[kk] ? 1 : 0;
    }
  }
  CHECK(creep_total >= expected_min_creep);
}

}  // namespace

TEST_CASE("kappa sensitivity of every eigenvalue matches finite differences in log kappa", "[kappa]") {
  // The balanced state at 750 rad/s: its slow pair is the creep pair (abscissa exactly
  // proportional to 1/kappa over kappa = 1e1 .. 1e6); the aligned states' ball modes too.
  SECTION("coulomb, kappa = 1e3, 750 rad/s") { check_scene(scene(abu::FrictionLaw::coulomb, 1e3, 750), 2); }
  SECTION("coulomb, kappa = 1e6, 900 rad/s") { check_scene(scene(abu::FrictionLaw::coulomb, 1e6, 900), 2); }
  SECTION("stribeck, kappa = 1e4, 400 rad/s") { check_scene(scene(abu::FrictionLaw::stribeck, 1e4, 400), 2); }
  SECTION("viscous: kappa does not enter") {
    abu::Params p = scene(abu::FrictionLaw::viscous, 1e3, 750);
    for (auto& b : p.balls) b.d = 1e-4;
    const abu::Analysis a = abu::analyze(p);
    const auto& eq = a.equilibria.points()[0];
    const auto lin = abu::linearize(p.cast<long double>(), abu::at_rest<long double, 2>(eq.position));
    CHECK_FALSE(abu::kappa_sensitivity(p, lin, a.spectra[0]).defined);
  }
}
