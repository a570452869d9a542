// Spectra of LuGre equilibria (model.md §12.3-§12.5). Every configuration is an
// equilibrium; at one, each one-sided Jacobian (all balls forward, or all backward) has n
// zero eigenvalues along the family and 2n + 4 others, the normal spectrum, computed two
// ways: (a) the spring-dashpot quadratic problem (12.10) with the refined solver of
// spectrum.hpp (reported), (b) the full (3n + 4) Jacobian restricted to the invariant
// subspace {w = z - C beta = 0} (the n zeros deflated exactly), by QR in long double
// (cross-check). A state is stable if both sides' normal spectra are, non-smooth where
// the sides disagree.
//
//   abu::LugreRest r = abu::analyze_lugre_rest(p, s, /*zero_bristle=*/false);
//   if (r.non_smooth) ...   // leave the decision to simulation
#pragma once

#include <string_view>
#include <vector>

#include "abu/linear/spectrum.hpp"
#include "abu/model/lugre.hpp"

namespace abu {

/// One side's normal spectrum at a LuGre equilibrium.
struct LugreSideSpectrum {
  RestSide side = RestSide::forward;
  SpectrumN normal;  ///< the 2n + 4 eigenvalues of (12.10) [1/s, rotating frame], refined
  int zeros = 0;     ///< n: eigenvalues exactly 0 along the family (not in `normal`)
  /// max_k |lambda_k(a) - lambda_k(b)| / |lambda_k(a)| between the two routes (pairs by
  /// nearest distance); rounding gives ~1e-12 and less.
  double route_deviation = 0.0;
};

/// A LuGre equilibrium and what is known of its stability.
struct LugreRest {
  Coordinates<double, any_balls> position;  ///< s = (q1, q2, beta_1..beta_n) [m, rad]
  std::vector<double> bristle;              ///< z_i [rad], (12.5)
  std::vector<double> load_ratio;           ///< tau_i / mu_s,i: |.| <= 1 reachable from z(0) = 0
  bool reachable = true;                    ///< every |tau_i| <= mu_s,i
  bool zero_bristle = false;                ///< z = 0 (a smooth-law equilibrium): c = 1, one Jacobian
  LugreSideSpectrum forward, backward;      ///< equal when zero_bristle
  bool stable = false;                      ///< both sides' normal spectra stable
  bool non_smooth = false;                  ///< the sides' verdicts differ: simulation decides
  double rotor_residual = 0.0;              ///< rotor rows of b(s, 0) over their scale (q = q(beta))
  std::string_view verdict() const;         ///< stable, unstable, marginal or non-smooth
};

/// The equilibrium at configuration s (q must solve (5.4) for the betas: see
/// lugre_configuration). zero_bristle: the state is one of §5 / §13's (tau = 0 exactly in
/// exact arithmetic), so z = 0 and c = 1 are taken exactly.
LugreRest analyze_lugre_rest(const ParamsN& p, const Coordinates<long double, any_balls>& s, bool zero_bristle);

/// The normal spectrum at a z = 0 equilibrium s of §5 / §13 (model.md §12.8): (12.10) with
/// c = 1, where both one-sided Jacobians coincide; route (a) alone (what a map cell and a
/// continuation point need; analyze_lugre_rest adds the cross-check). No heap per call.
SpectrumN lugre_zero_bristle_spectrum(const ParamsN& p, const Coordinates<long double, any_balls>& s);

/// s = (q(beta), beta) with q from (5.4) in long double.
Coordinates<long double, any_balls> lugre_configuration(const ParamsN& p, const std::vector<double>& beta);

}  // namespace abu
