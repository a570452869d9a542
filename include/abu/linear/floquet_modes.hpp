// The Floquet modes of a balanced state on an anisotropic support as the whirl a rotor
// engineer reads in the fixed frame (docs/model.md §10.15): the Campbell view's split
// forward/backward rotor modes.
//
// A Floquet exponent lambda is known modulo 2 i omega only, and the mode's motion is not one
// fixed-frame frequency: with Hill's eigenvector x(t) = e^{lambda t} sum_k x_k e^{2 i omega k t}
// the fixed-frame rotor displacement carries the lines +-(Im lambda + omega + 2 omega k), one
// pair per k (model.md (10.15.2)). The mode's whirl frequency is the line pair with the
// largest mass-weighted amplitude, its sign by which of the two lines dominates; this does
// not depend on which member of the ladder lambda + 2 i omega m represents the exponent, and
// for an isotropic support it is exactly mode_views' (16.2.1).
//
//   abu::FloquetModes m = abu::floquet_mode_views(p, support, e);   // p: mean support
//   for (const abu::ModeView& v : m.modes) ... v.whirl_frequency, v.kind ...
#pragma once

#include <vector>

#include "abu/core/status.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/floquet_hill.hpp"
#include "abu/linear/modes.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu {

struct FloquetModes {
  /// One per conjugate pair of multipliers or real multiplier, in the multipliers' order
  /// (modulus descending; the n - 2 unit multipliers of the balanced set are deflated and
  /// not modes). ModeView::rotating is the Floquet exponent with Im in [0, omega] [1/s,
  /// rotating frame]; index/conjugate index `multipliers`.
  std::vector<ModeView> modes;
  std::vector<std::complex<double>> multipliers;  ///< Hill's, floquet_order
  /// Per mode: the harmonic k of the chosen line pair relative to `rotating`, and the share
  /// of the mass-weighted motion in that pair (1 for an isotropic support)
  std::vector<int> harmonic;
  std::vector<double> line_share;
  int harmonics = 0;  ///< Hill's N
  Status status;      ///< Hill's (double, then long double if double did not converge)
};

/// Campbell truncation: Hill's default growth, but up to N = 48 (at low speed the coupling
/// |kappa| / (4 M omega^2) between harmonics is not small, model.md §10.15).
HillOptions campbell_hill_options();

/// `e` a balanced state of `p` (q = 0), `p` carrying k_bar, c_bar.
FloquetModes floquet_mode_views(const ParamsN& p, const AnisotropicSupport& support, const EquilibriumN& e,
                                const HillOptions& options = campbell_hill_options());

}  // namespace abu
