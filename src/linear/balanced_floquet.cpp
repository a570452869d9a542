// Floquet verdict of a balanced state on an anisotropic support (docs/model.md §10.6).
#include "abu/linear/balanced_floquet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/magnus_monodromy.hpp"

namespace abu {

BalancedFloquet balanced_floquet(const ParamsN& p, const AnisotropicSupport& support, const EquilibriumN& e,
                                 const FloquetOptions& options) {
  PeriodicJacobian J = balanced_periodic_jacobian(p, support, e.position);
  BalancedFloquet f;
  if (e.on_balanced_set) {
    // V_T = (tangent, 0): J(t) V_T = 0 for every t (no q components), so in the basis
    // [V_T, V_N] J(t) is block upper triangular and the normal block carries the rest.
    const TangentBasis T = balanced_tangent_basis(p, e.position);
    const Eigen::Index d = e.position.size(), m = T.cols();
    Eigen::MatrixXd VT = Eigen::MatrixXd::Zero(2 * d, m);
    VT.topRows(d) = T.cast<double>();
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(VT);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(2 * d, 2 * d);
    J = restricted(J, Q.rightCols(2 * d - m));
    f.deflated = int(m);
  }
  const HillResult h = hill_multipliers(J, options.hill);
  f.multipliers = h.multipliers;
  f.exponents = h.exponents;
  f.harmonics = h.harmonics;
  f.status = h.status;
  f.monodromy_multipliers = monodromy_multipliers(magnus_monodromy(J, options.monodromy_steps));
  std::vector<bool> used(f.monodromy_multipliers.size(), false);
  for (const auto& rho : f.multipliers) {
    std::size_t best = 0;
    double dist = 1e300;
    for (std::size_t j = 0; j < f.monodromy_multipliers.size(); ++j)
      if (!used[j] && std::abs(f.monodromy_multipliers[j] - rho) < dist)
        dist = std::abs(f.monodromy_multipliers[j] - rho), best = j;
    if (best < used.size()) used[best] = true;
    f.monodromy_deviation = std::max(f.monodromy_deviation, dist / std::max(std::abs(rho), options.cross_check_floor));
  }
  f.max_modulus = f.multipliers.empty() ? 0.0 : std::abs(f.multipliers.front());
  f.abscissa = p.omega / std::numbers::pi * std::log(f.max_modulus);
  const double norm = J.mean.cwiseAbs().rowwise().sum().maxCoeff() +
                      2.0 * std::numbers::pi * (f.harmonics + 1) / J.period();  // |H|_inf bound
  f.band = 64.0 * std::ldexp(1.0, -64) * norm * J.period() + h.truncation_change;
  const double growth = std::log(f.max_modulus);
  f.verdict = growth < -f.band ? Stability::stable : growth > f.band ? Stability::unstable : Stability::marginal;
  return f;
}

}  // namespace abu
