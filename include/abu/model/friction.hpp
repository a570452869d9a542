// Friction force between ball i and the race, along +beta_i (model.md §4), its slope
// with respect to the ball's relative speed and its derivatives with respect to the
// parameters. All smooth laws vanish at beta_dot = 0, so friction never moves an
// equilibrium; it only enters the spectrum through the slope at 0.
//
//   none      F = 0
//   viscous   F = -d l beta_dot
//   coulomb   F = -mu N (2/pi) atan(kappa beta_dot),                     N = m l omega^2
//   stribeck  F = -N [mu_c + (mu_s - mu_c) exp(-(beta_dot/v_s)^2)] (2/pi) atan(kappa beta_dot)
//
// `lugre` (model.md §12) is not a function of beta_dot alone: these functions throw
// NotSupportedError for it; its force is model/lugre.hpp's.
//
// Templated on the scalar (double, long double, complex for complex-step checks).
#pragma once

#include "abu/core/params.hpp"

namespace abu {

/// F_i(beta_dot) [N]. Model.md §4 table.
template <class T, int N>
T friction_force(const ParamsT<T, N>& p, int ball, const T& beta_dot);

/// dF_i/d(beta_dot_i) [N s/rad]. At beta_dot = 0 this is -(2/pi) mu N kappa for
/// coulomb (and with mu = mu_s for stribeck), the stiff entry of model.md §8.
template <class T, int N>
T friction_slope(const ParamsT<T, N>& p, int ball, const T& beta_dot);

/// dF_i/dq for a quantity q of ball `ball` or a global one (omega, kappa); zero for
/// quantities F_i does not depend on. Used by the analytic parameter derivative.
template <class T, int N>
T friction_partial(const ParamsT<T, N>& p, int ball, const T& beta_dot, Quantity q);

}  // namespace abu
