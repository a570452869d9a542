// Floquet verdict of a balanced state on an anisotropic support (docs/model.md §10.6).
#include "abu/linear/balanced_floquet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/magnus_monodromy.hpp"

namespace abu {

Eigen::MatrixXd balanced_normal_basis(const ParamsN& p, const EquilibriumN& e) {
  // V_T = (tangent, 0): J(t) V_T = 0 for every t (no q components), so in the basis
  // [V_T, V_N] J(t) is block upper triangular and the normal block carries the rest.
  const TangentBasis T = balanced_tangent_basis(p, e.position);
  const Eigen::Index d = e.position.size(), m = T.cols();
  Eigen::MatrixXd VT = Eigen::MatrixXd::Zero(2 * d, m);
  VT.topRows(d) = T.cast<double>();
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(VT);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(2 * d, 2 * d);
  return Q.rightCols(2 * d - m);
}

BalancedFloquet balanced_floquet(const ParamsN& p, const AnisotropicSupport& support, const EquilibriumN& e,
                                 const FloquetOptions& options) {
  PeriodicJacobian J = balanced_periodic_jacobian(p, support, e.position);
  BalancedFloquet f;
  if (e.on_balanced_set) {
    const Eigen::MatrixXd VN = balanced_normal_basis(p, e);
    f.deflated = int(VN.rows() - VN.cols());
    J = restricted(J, VN);
  }
  // max |rho - rho_check| / max(|rho|, floor), nearest unused partner for each rho.
  auto deviation = [&](const std::vector<std::complex<double>>& primary, const std::vector<std::complex<double>>& check) {
    std::vector<bool> used(check.size(), false);
    double worst = 0.0;
    for (const auto& rho : primary) {
      std::size_t best = 0;
      double dist = 1e300;
      for (std::size_t j = 0; j < check.size(); ++j)
        if (!used[j] && std::abs(check[j] - rho) < dist) dist = std::abs(check[j] - rho), best = j;
      if (best < used.size()) used[best] = true;
      worst = std::max(worst, dist / std::max(std::abs(rho), options.cross_check_floor));
    }
    return worst;
  };
  auto judge = [&](double band) {
    f.max_modulus = f.multipliers.empty() ? 0.0 : std::abs(f.multipliers.front());
    f.abscissa = p.omega / std::numbers::pi * std::log(f.max_modulus);
    f.band = band;
    const double growth = std::log(f.max_modulus);
    f.verdict = growth < -f.band ? Stability::stable : growth > f.band ? Stability::unstable : Stability::marginal;
  };
  if (options.route == FloquetRoute::magnus) {
    // §10.10: Magnus with S and S/2 steps; their difference bounds the S/2 run's error (16
    // times the S run's, fourth order), and eps sigma its rounding on stiff rates. Decided
    // if |ln max|rho|| clears both; else Hill below (the stuck coulomb balls at high speed).
    const int steps = std::max(2, options.monodromy_steps);
    f.multipliers = monodromy_multipliers(magnus_monodromy(J, steps));
    f.monodromy_multipliers = monodromy_multipliers(magnus_monodromy(J, steps / 2));
    f.monodromy_deviation = deviation(f.multipliers, f.monodromy_multipliers);
    const double sigma = J.mean.cwiseAbs().rowwise().sum().maxCoeff() * J.period();
    judge(f.monodromy_deviation + 8.0 * std::ldexp(1.0, -53) * sigma);
    if ((f.verdict != Stability::marginal || !options.hill_when_undecided) && f.monodromy_deviation <= 1e-6) {
      f.by_hill = false;
      f.harmonics = 0;
      f.exponents.clear();
      for (const auto& rho : f.multipliers) {
        // lambda = (omega/pi) ln rho, Im in (-omega, omega] (the principal log's range).
        std::complex<double> l = std::log(rho) * (p.omega / std::numbers::pi);
        if (rho.imag() == 0.0) l = {l.real(), rho.real() >= 0.0 ? 0.0 : p.omega};
        f.exponents.push_back(l);
      }
      f.status = {};
      return f;
    }
  }
  f.by_hill = true;
  // The magnus route's S-step run is this cross-check's (same S): not integrated twice.
  f.monodromy_multipliers = options.route == FloquetRoute::magnus
                                ? f.multipliers
                                : monodromy_multipliers(magnus_monodromy(J, options.monodromy_steps));
  // Double first; long double when the cross-check says double lost digits (stiff rates;
  // 1e-10 is five times Magnus' own error in the viscous cases, §10.6) or when double's
  // band cannot decide the verdict (the stuck coulomb balls, |rho| = 1 - 4e-10).
  auto run = [&](bool extended) {
    HillOptions o = options.hill;
    o.extended = extended;
    const HillResult h = hill_multipliers(J, o);
    f.multipliers = h.multipliers;
    f.exponents = h.exponents;
    f.harmonics = h.harmonics;
    f.status = h.status;
    f.monodromy_deviation = deviation(h.multipliers, f.monodromy_multipliers);
    const double norm = J.mean.cwiseAbs().rowwise().sum().maxCoeff() +
                        2.0 * std::numbers::pi * (f.harmonics + 1) / J.period();  // |H|_inf bound
    judge(64.0 * std::ldexp(1.0, extended ? -64 : -53) * norm * J.period() + h.truncation_change);
  };
  run(options.hill.extended);
  if (!options.hill.extended &&
      (!f.status.ok() || f.monodromy_deviation > 1e-10 || f.verdict == Stability::marginal))
    run(true);
  return f;
}

}  // namespace abu
