// The verdict of a spectrum without refining what the verdict does not need (map cells,
// model.md §13.8): the QR starting values of compute_spectrum, Newton refinement (the same
// calls, from the same starts) only for the eigenvalues whose QR error bound does not keep
// them clear of the imaginary axis and for those that may be the rightmost (the abscissa
// is written, refined as before). An eigenvalue is clear when
//     |Re z| > 1e-5 |z|   and   |Re z| > 64e4 * eps ||M||           (QR bound, model.md §8)
// with ||M|| the norm of the balanced matrix it came from (scaled through the shift for
// the inverse): the first is more than the band of spectrum.hpp unless the eigenvalue's
// condition exceeds 5e9, 60 times the one flagged ill-conditioned; the second allows the
// QR value an error of 1e4 times eps ||M||. Starts within 1e-3 of another (nearly multiple
// eigenvalues: where Newton can stall and compute_spectrum regroups them or retries from
// shifted inverses) are always refined, as there, and with them every start within 1e-3 of
// a refined one (copies share their band as in compute_spectrum). Whatever does
// not go as in compute_spectrum (a refinement that fails or leaves its basin, a structural
// zero, a numerical issue) falls back to compute_spectrum itself.
//
//   abu::SpectrumVerdict v = abu::spectrum_verdict(lin);   // lin: Linearization<long double, any_balls>
#pragma once

#include "abu/linear/spectrum.hpp"

namespace abu {

struct SpectrumVerdict {
  Stability stability = Stability::marginal;
  int n_unstable = 0;
  int n_structural = 0;
  double abscissa = 0;  ///< max Re lambda [1/s] (refined)
  int refined = 0;      ///< eigenvalues refined (all of them after a fallback)
  bool converged = true;  ///< every refinement converged (compute_spectrum's `converged`)
};

/// The stability, n_unstable and abscissa compute_spectrum(lin, refined, structural_zeros)
/// would give.
SpectrumVerdict spectrum_verdict(const Linearization<long double, any_balls>& lin, int structural_zeros = 0);

}  // namespace abu
