#include "abu/continuation/tracking.hpp"

#include <limits>

namespace abu {

double overlap(const Vec4c& a, const Vec4c& b) { return std::abs(a.dot(b)); }

// Assigns the new eigenvalues to the predicted modes, best match first; the cost of a
// match adds the relative eigenvalue distance and the eigenvector mismatch 1 - |<a, b>|,
// so that two modes with nearly equal eigenvalues (one per ball) keep their identity.
// `source[k]` is the index in sp of mode k.
void track(const ModePrediction& predicted, const Spectrum& sp, const std::array<Vec4c, 8>& scaled_vectors,
           std::array<std::complex<double>, 8>& modes, std::array<int, 8>& source) {
  std::array<bool, 8> used_mode{}, used_new{};
  for (int round = 0; round < 8; ++round) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t bi = 0, bj = 0;
    for (std::size_t i = 0; i < 8; ++i) {
      if (used_mode[i]) continue;
      for (std::size_t j = 0; j < 8; ++j) {
        if (used_new[j]) continue;
        const auto p = predicted.values[i], l = sp.eigenvalues[j];
        const double d = std::abs(l - p) / (std::abs(l) + std::abs(p) + std::numeric_limits<double>::min()) +
                         (1 - overlap(predicted.vectors[i], scaled_vectors[j]));
        if (d < best) best = d, bi = i, bj = j;
      }
    }
    used_mode[bi] = used_new[bj] = true;
    modes[bi] = sp.eigenvalues[bj];
    source[bi] = int(bj);
  }
}

// The match of mode k is certain when its eigenvalue lands within half its predicted
// distance to the nearest other mode (its own conjugate excluded: that pairing is
// symmetric), or, failing that, when its eigenvector is nearly the predicted one and
// clearly unlike that of every eigenvalue that landed as close to the prediction (two
// modes with nearly equal eigenvalues, one per ball, moving together). Returns the
// largest landing error / half-separation among the uncertain matches.
double tracking_ambiguity(const ModePrediction& predicted, const Spectrum& sp,
                          const std::array<Vec4c, 8>& scaled_vectors, const std::array<int, 8>& source) {
  double worst = 0;
  for (std::size_t k = 0; k < 8; ++k) {
    const auto j = std::size_t(source[k]);
    const auto pk = predicted.values[k];
    const double miss = std::abs(sp.eigenvalues[j] - pk);
    if (miss <= 8 * sp.error[j]) continue;
    double separation = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < 8; ++i)
      if (i != k && predicted.values[i] != std::conj(pk))
        separation = std::min(separation, std::abs(predicted.values[i] - pk));
    if (miss <= separation / 2) continue;
    const double own = overlap(predicted.vectors[k], scaled_vectors[j]);
    double rival = 0;
    for (std::size_t i = 0; i < 8; ++i)
      if (i != j && sp.eigenvalues[i] != std::conj(sp.eigenvalues[j]) && std::abs(sp.eigenvalues[i] - pk) <= 2 * miss)
        rival = std::max(rival, overlap(predicted.vectors[k], scaled_vectors[i]));
    if (own >= 0.9 && rival <= 0.5 * own) continue;
    worst = std::max(worst, miss / (separation / 2));
  }
  return worst;
}

}  // namespace abu
