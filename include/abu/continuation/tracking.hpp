// Eigenvalue mode tracking along a branch: which eigenvalue of the next point is which
// mode of the last, by eigenvector overlap and distance to the extrapolated eigenvalue,
// and whether that assignment is certain.
#pragma once

#include <array>
#include <complex>

#include <Eigen/Core>

#include "abu/linear/spectrum.hpp"

namespace abu {

using Vec4c = Eigen::Matrix<std::complex<double>, 4, 1>;

/// What a mode is expected to be at the next point: its eigenvalue extrapolated along
/// the branch and its eigenvector (q measured in the displacement scale, so that rotor
/// and ball components weigh alike).
struct ModePrediction {
  std::array<std::complex<double>, 8> values{};
  std::array<Vec4c, 8> vectors{};     ///< q in displacement-scale units, unit norm (overlaps)
  std::array<Vec4c, 8> si_vectors{};  ///< as computed (Newton start vectors)
};

/// |<a, b>| for unit vectors.
double overlap(const Vec4c& a, const Vec4c& b);

/// Assigns the new eigenvalues to the predicted modes, best match first; the cost of a
/// match adds the relative eigenvalue distance and the eigenvector mismatch 1 - |<a, b>|,
/// so that two modes with nearly equal eigenvalues (one per ball) keep their identity.
/// `modes` receives the eigenvalues in mode order, `source[k]` the index in sp of mode k.
void track(const ModePrediction& predicted, const Spectrum& sp, const std::array<Vec4c, 8>& scaled_vectors,
           std::array<std::complex<double>, 8>& modes, std::array<int, 8>& source);

/// The largest landing error / half-separation among uncertain matches (> 1: the step
/// is too long for tracking). A match is certain when its eigenvalue lands within half its
/// predicted distance to the nearest other mode (its own conjugate excluded), or when its
/// eigenvector is nearly the predicted one and clearly unlike that of every eigenvalue that
/// landed as close (two balls' modes with nearly equal eigenvalues moving together).
double tracking_ambiguity(const ModePrediction& predicted, const Spectrum& sp,
                          const std::array<Vec4c, 8>& scaled_vectors, const std::array<int, 8>& source);

}  // namespace abu
