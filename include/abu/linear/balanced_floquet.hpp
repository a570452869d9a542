// The stability of a balanced state on an anisotropic support (docs/model.md §10.6): its
// Floquet multipliers over pi/omega by Hill's method (primary), cross-checked by the
// Magnus monodromy, with the n - 2 unit multipliers of the balanced set of n >= 3 balls
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

struct FloquetOptions {
  HillOptions hill;              ///< Hill's truncation (floquet_hill.hpp)
  int monodromy_steps = 256;     ///< Magnus-4 steps per pi/omega for the cross-check; default 256
  /// Multipliers below this modulus are compared in absolute terms in the cross-check:
  /// they decay by 1e6 per period and do not bear on the verdict; default 1e-6
  double cross_check_floor = 1e-6;
};

struct BalancedFloquet {
  std::vector<std::complex<double>> multipliers;            ///< Hill's, deflated, floquet_order
  std::vector<std::complex<double>> exponents;              ///< lambda [1/s, rotating frame], Im in (-omega, omega]
  std::vector<std::complex<double>> monodromy_multipliers;  ///< Magnus-4's, same deflation and order
  int deflated = 0;             ///< unit multipliers removed: n - 2 on the balanced set, else 0
  int harmonics = 0;            ///< Hill's N
  double monodromy_deviation = 0.0;  ///< max |rho_Hill - rho_Magnus| / max(|rho_Hill|, floor)
  double max_modulus = 0.0;     ///< max |rho|
  double abscissa = 0.0;        ///< (omega/pi) ln max |rho| [1/s]: the decay rate that decides
  /// What |ln max|rho|| must exceed for a verdict other than marginal: 64 roundings (of the
  /// precision Hill ran in) of Hill's matrix norm times pi/omega, plus Hill's last truncation change
  /// (the isotropic path's band is the same idea, spectrum.hpp). A multiplier of the
  /// stuck coulomb balls, 1 - 4e-10, is then still decided.
  double band = 0.0;
  Stability verdict = Stability::marginal;
  Status status;                ///< Hill's
};

/// `e` must be a balanced state of `p` (q = 0) and `p` carry k_bar, c_bar.
BalancedFloquet balanced_floquet(const ParamsN& p, const AnisotropicSupport& support, const EquilibriumN& e,
                                 const FloquetOptions& options = {});

}  // namespace abu
