// The stability of a balanced state on an anisotropic support (docs/model.md §10.6): its
// Floquet multipliers over pi/omega. Two routes (FloquetRoute): Hill's method (primary)
// cross-checked by the Magnus monodromy, for `equilibria`'s reported digits; or, for the
// scans (sweep, map, continue), the Magnus monodromy first, judged by its own step-halving
// error and the stiffness floor of §10.10, with Hill only where that cannot decide.
// Both with the n - 2 unit multipliers of the balanced set of n >= 3 balls
// deflated (the normal system y' = V_N^T J(t) V_N y).
//
//   abu::BalancedFloquet f = abu::balanced_floquet(p, support, e);  // p: mean support
//   f.verdict == abu::Stability::stable, f.multipliers (sorted by modulus, descending)
#pragma once

#include <complex>
#include <vector>

#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/floquet_hill.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu {

/// Which method gives the multipliers (docs/model.md §10.10).
enum class FloquetRoute {
  hill,    ///< Hill primary, Magnus cross-check: 1e-12 digits, ~10-200 ms (equilibria)
  magnus,  ///< Magnus-4 primary (S and S/2 steps, ~0.7 ms); Hill where Magnus cannot decide
};

struct FloquetOptions {
  FloquetRoute route = FloquetRoute::hill;  ///< default hill (equilibria's digits)
  /// magnus route: run Hill when Magnus' band cannot decide (default true). A bisection on
  /// |rho| = 1 sets it false: near the root every verdict is marginal, and Magnus' sign of
  /// ln|rho| is what it follows.
  bool hill_when_undecided = true;
  HillOptions hill;              ///< Hill's truncation (floquet_hill.hpp)
  int monodromy_steps = 256;     ///< Magnus-4 steps per pi/omega for the cross-check; default 256
  /// Multipliers below this modulus are compared in absolute terms in the cross-check:
  /// they decay by 1e6 per period and do not bear on the verdict; default 1e-6
  double cross_check_floor = 1e-6;
};

struct BalancedFloquet {
  /// The primary method's (Hill's, or Magnus' with `monodromy_steps` on the magnus route),
  /// deflated, floquet_order
  std::vector<std::complex<double>> multipliers;
  std::vector<std::complex<double>> exponents;              ///< lambda [1/s, rotating frame], Im in (-omega, omega]
  /// The check's: Magnus-4 with monodromy_steps (hill route) or monodromy_steps / 2 (magnus
  /// route, the step-halving estimate); same deflation and order
  std::vector<std::complex<double>> monodromy_multipliers;
  bool by_hill = true;          ///< the multipliers are Hill's (false: Magnus', §10.10)
  int deflated = 0;             ///< unit multipliers removed: n - 2 on the balanced set, else 0
  int harmonics = 0;            ///< Hill's N (0 when Magnus decided)
  /// max |rho - rho_check| / max(|rho|, floor): Hill against Magnus, or (magnus route) Magnus
  /// with S steps against S/2 steps
  double monodromy_deviation = 0.0;
  double max_modulus = 0.0;     ///< max |rho|
  double abscissa = 0.0;        ///< (omega/pi) ln max |rho| [1/s]: the decay rate that decides
  /// What |ln max|rho|| must exceed for a verdict other than marginal: 64 roundings (of the
  /// precision Hill ran in) of Hill's matrix norm times pi/omega, plus Hill's last truncation change
  /// (the isotropic path's band is the same idea, spectrum.hpp). A multiplier of the
  /// stuck coulomb balls, 1 - 4e-10, is then still decided. Magnus (§10.10): the step-halving
  /// change plus 8 eps sigma, sigma = |J0|_inf pi/omega (its rounding floor on stiff rates).
  double band = 0.0;
  Stability verdict = Stability::marginal;
  Status status;                ///< Hill's (ok when Magnus decided)
};

/// For `e` on the balanced set of n >= 3 balls: orthonormal columns V_N (2d x (2d - (n - 2)),
/// d = n + 2) completing the set's tangent directions (tangent, 0) in the state space, so
/// that the normal system is V_N^T J(t) V_N (§10.4). The state space's coordinates are those
/// of J (the tangent has no q component, so J's scaling does not change it).
Eigen::MatrixXd balanced_normal_basis(const ParamsN& p, const EquilibriumN& e);

/// `e` must be a balanced state of `p` (q = 0) and `p` carry k_bar, c_bar.
BalancedFloquet balanced_floquet(const ParamsN& p, const AnisotropicSupport& support, const EquilibriumN& e,
                                 const FloquetOptions& options = {});

}  // namespace abu
