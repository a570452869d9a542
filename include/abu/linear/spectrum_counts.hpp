// A second opinion on a two-ball spectrum whose refinement left eigenvalues inside their error
// bands (Spectrum::n_marginal > 0, e.g. at kappa ~ 1e13 .. 1e14 near resonance, where the QR
// resolves nothing below ~10 1/s and a retried start can fail): the certified Routh count of
// the characteristic polynomial (characteristic.hpp, with its error bounds) and an abscissa
// certified as rightmost decide the count and the verdict instead (docs/model.md §8); the
// map's full method does the same per cell.
#pragma once

#include "abu/linear/characteristic.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"

namespace abu {

/// Replaces sp's n_unstable, n_marginal, stability and abscissa by the certified count and
/// abscissa of lin's characteristic polynomial where both are decided and agree with the
/// eigenvalues' bands (n_unstable <= count <= n_unstable + n_marginal); sp.certified_count
/// says how many eigenvalues were left inside their bands. Returns whether it decided. Not for a singular equilibrium (structural zeros).
bool certify_counts(Spectrum& sp, const Linearization<long double, 2>& lin);
/// The same from the polynomial itself (a map cell's, combined from its friction split).
bool certify_counts(Spectrum& sp, const Polynomial& p);

}  // namespace abu
