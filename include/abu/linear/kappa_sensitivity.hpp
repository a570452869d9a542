// What the arctan sharpness kappa of the smooth coulomb and stribeck laws does to each
// eigenvalue: the logarithmic sensitivity
//     s_k = d log|lambda_k| / d log kappa
// from first-order perturbation of the quadratic eigenproblem (model.md (6.11)). At an
// equilibrium every ball is at rest in the rotor frame, so the friction slope, the only
// place kappa enters the linearization, is exactly proportional to kappa (model.md §4):
// dC/dkappa = C_f / kappa with C_f the friction part of C's ball diagonal, and
//     s_k = -Re[ y^T C_f x / (y^T (2 lambda A + C) x) ],   T(lambda) x = 0,  y^T T(lambda) = 0.
// s = -1: a creep mode of the regularization (lambda ~ 1/kappa: its time constant is
// set by kappa, not by physics, and grows without bound as the law approaches true
// Coulomb friction); s = +1: a fast ball mode (lambda ~ kappa); s ~ 0: a mode kappa
// does not move (rotor modes). A mode is flagged creep when |s + 1| <= 0.1.
//
//   abu::KappaSensitivity<2> ks = abu::kappa_sensitivity(p, lin, spectrum);
//   if (ks.defined && ks.creep[k]) ...   // eigenvalue k of spectrum scales like 1/kappa
#pragma once

#include <array>

#include "abu/core/params.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"

namespace abu {

/// |s + 1| at or below this flags a creep mode (model.md (6.11)).
inline constexpr double creep_tolerance = 0.1;

template <int N>
struct KappaSensitivity {
  /// False when the law has no kappa (none, viscous) or the spectrum carries no vectors:
  /// then no value below means anything.
  bool defined = false;
  /// s_k for eigenvalue k of the spectrum (same order); 0 where not computable (a zero or
  /// structural eigenvalue: `computed` false).
  std::array<double, SpectrumT<N>::capacity> log_slope{};
  std::array<bool, SpectrumT<N>::capacity> computed{};
  std::array<bool, SpectrumT<N>::capacity> creep{};
  int n_creep = 0;
};

/// The sensitivities of every eigenvalue of `spectrum` (refined, at the equilibrium whose
/// linearization is `lin`, parameters `p`). Instantiated for N = 2 and any_balls.
template <int N>
KappaSensitivity<N> kappa_sensitivity(const ParamsT<double, N>& p, const Linearization<long double, N>& lin,
                                      const SpectrumT<N>& spectrum);

}  // namespace abu
