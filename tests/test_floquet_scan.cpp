// Anisotropic support across parameters (docs/model.md §10.10-10.12): the magnus route of the
// Floquet verdict against the hill route (the cross-check retained), the sweep's values
// against `equilibria`'s analysis at the same parameter, its isotropic limit against the
// isotropic sweep's verdicts, and a map cell against the balanced state's verdict.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <vector>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/analysis/floquet_sweep.hpp"
#include "abu/linear/balanced_floquet.hpp"
#include "abu/scan/map.hpp"
#include "abu/scan/scan.hpp"
#include "anisotropic_base.hpp"

using namespace abu;

namespace {

ParamsN base(FrictionLaw law) { return testing::anisotropic_base(law); }
AnisotropicSupport support_of(const ParamsN& p, double scale) { return testing::anisotropic_base_support(p, scale); }

FloquetOptions magnus_route() {
  FloquetOptions o;
  o.route = FloquetRoute::magnus;
  return o;
}

// max_i |a_i - b_i| / |b_i| over multipliers of modulus >= 1e-6 (both in floquet_order).
double relative_difference(const std::vector<std::complex<double>>& a, const std::vector<std::complex<double>>& b) {
  REQUIRE(a.size() == b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(b[i]) >= 1e-6) worst = std::max(worst, std::abs(a[i] - b[i]) / std::abs(b[i]));
  return worst;
}

}  // namespace

// The cheap route keeps Hill's answer: Magnus-4 with 256 steps is 2e-11 relative on the
// viscous case (§10.6) and ~1e-11 on stiff coulomb (kappa = 1e5), so 1e-9 leaves a factor
// 50; the verdicts must be the same. This is the retained Hill/Magnus cross-check.
TEST_CASE("floquet: the magnus route agrees with the hill route (viscous, stiff coulomb, 3 speeds)", "[floquet_scan]") {
  for (FrictionLaw law : {FrictionLaw::viscous, FrictionLaw::coulomb})
    for (double omega : {300.0, 900.0, 2000.0}) {
      ParamsN p = base(law);
      p.omega = omega;
      const AnisotropicSupport s = support_of(p, 1.0);
      const EquilibriumSetN set = find_equilibria(p);
      for (const EquilibriumN& e : set.points()) {
        if (e.family != Family::balanced) continue;
        const BalancedFloquet hill = balanced_floquet(p, s, e);
        const BalancedFloquet fast = balanced_floquet(p, s, e, magnus_route());
        INFO(to_string(law) << " omega " << omega << " by_hill " << fast.by_hill);
        CHECK(relative_difference(fast.multipliers, hill.multipliers) < 1e-9);
        CHECK(fast.verdict == hill.verdict);
        CHECK(std::abs(fast.abscissa - hill.abscissa) < 1e-9 * omega);
      }
    }
}

// The sweep's rows are analyze_floquet at the value (what `equilibria` reports) up to the
// route: the same states, multipliers to 1e-9 relative, the same verdicts.
TEST_CASE("floquet sweep: values equal equilibria's analysis at the same parameter", "[floquet_scan]") {
  const ParamsN p = base(FrictionLaw::viscous);
  const AnisotropicSupport s = support_of(p, 1.0);
  const std::vector<double> values{250.0, 600.0, 1400.0};
  const FloquetSweep sweep = floquet_sweep(p, s, ParamRef{Quantity::omega, -1}, values, {});
  REQUIRE(sweep.points.size() == values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    ParamsN q = p;
    q.omega = values[i];
    const FloquetAnalysis a = analyze_floquet(q, s, {});
    REQUIRE(a.balanced.size() == sweep.points[i].balanced.size());
    for (std::size_t k = 0; k < a.balanced.size(); ++k) {
      CHECK(a.balanced[k].member == sweep.points[i].balanced[k].member);
      CHECK(relative_difference(sweep.points[i].floquet[k].multipliers, a.floquet[k].multipliers) < 1e-9);
      CHECK(sweep.points[i].floquet[k].verdict == a.floquet[k].verdict);
    }
  }
}

// Isotropic limit (§10.7: rho = exp(lambda pi/omega)): with K_f = k I, C_f = c I the sweep's
// verdict of each balanced state is the isotropic sweep's, and its decay rate the spectral
// abscissa (to 1e-6 1/s: Magnus' 1e-11 on rho times omega/pi).
TEST_CASE("floquet sweep: the isotropic limit gives the isotropic sweep's verdicts", "[floquet_scan]") {
  for (FrictionLaw law : {FrictionLaw::viscous, FrictionLaw::coulomb}) {
    const ParamsN p = base(law);
    const AnisotropicSupport s = support_of(p, 0.0);
    std::vector<double> values;
    for (double w = 150.0; w <= 2000.0; w += 185.0) values.push_back(w);
    const FloquetSweep sweep = floquet_sweep(p, s, ParamRef{Quantity::omega, -1}, values, {});
    for (std::size_t i = 0; i < values.size(); ++i) {
      ParamsN q = p;
      q.omega = values[i];
      const AnalysisN iso = analyze(q);
      std::size_t k = 0;
      const auto points = iso.equilibria.points();
      for (std::size_t j = 0; j < points.size(); ++j) {
        if (points[j].family != Family::balanced) continue;
        REQUIRE(k < sweep.points[i].floquet.size());
        const BalancedFloquet& f = sweep.points[i].floquet[k++];
        INFO(to_string(law) << " omega " << values[i]);
        CHECK(f.verdict == iso.spectra[j].stability);
        CHECK(std::abs(f.abscissa - iso.spectra[j].abscissa) < 1e-6);
      }
      CHECK(k == sweep.points[i].floquet.size());
    }
  }
}

// A map cell (CellAnalyzerN with the support) holds the balanced states only, with the
// verdict and decay rate of the balanced state's Floquet analysis at the cell's parameters.
TEST_CASE("floquet map: a cell holds the balanced states' Floquet verdicts", "[floquet_scan]") {
  const ParamsN p = base(FrictionLaw::viscous);
  const AnisotropicSupport s = support_of(p, 1.0);
  Axis x{ParamRef{Quantity::omega, -1}, 200.0, 1200.0, 3};
  Axis y{ParamRef{Quantity::unbalance, -1}, 3e-7, 9e-7, 2};
  CellAnalyzerN cells(p, {}, x, y, {}, s);
  MapCellN cell;
  for (int ix = 0; ix < 3; ++ix)
    for (int iy = 0; iy < 2; ++iy) {
      cells.analyze(ix, iy, cell);
      const ParamsN q = cells.cell_params(ix, iy);
      const FloquetAnalysis a = analyze_floquet(q, s, {});
      REQUIRE(cell.equilibria.size() == a.balanced.size());
      CHECK(cell.aligned == 0);
      for (std::size_t k = 0; k < a.balanced.size(); ++k) {
        CHECK(cell.equilibria[k].stable == (a.floquet[k].verdict == Stability::stable));
        CHECK(std::abs(cell.equilibria[k].rho_abs_max - a.floquet[k].max_modulus) < 1e-10);
        CHECK(std::abs(cell.equilibria[k].abscissa - a.floquet[k].abscissa) < 1e-6);
      }
    }
}
