// Eigenvalues of the linearization at an equilibrium, each accurate relative to its own
// modulus, with a condition number, an error estimate and a stability verdict.
//
// Why not just QR on J: with coulomb friction the spectrum spans up to 16 orders of
// magnitude (model.md §8). A dense QR in double has absolute errors ~ eps ||J||, which
// can flip the sign of the slow ball modes that decide stability. The method here
// (SpectrumMethod::refined):
//
//  1. starting values from two balanced double-precision QRs: of J (accurate for the
//     large eigenvalues) and of the structured inverse
//        J^-1 = [[-K^-1 C, -K^-1 A], [I, 0]]
//     (accurate for the small ones); each eigenvalue is taken from the one whose
//     error bound eps ||.|| is smaller relative to it;
//  2. Newton on the quadratic eigenproblem T(lambda) x = (lambda^2 A + lambda C + K) x = 0
//     with a bordered 5x5 system in long double, from A, C, K assembled in long double;
//  3. for each eigenvalue the componentwise backward error
//        eta = max_i |T x|_i / ((|lambda|^2 |A| + |lambda| |C| + |K|) |x|)_i
//     and the componentwise condition number (Higham & Tisseur)
//        cond = y* (|lambda|^2 |A| + |lambda| |C| + |K|) |x| / (|lambda| |y* T'(lambda) x|),
//     whose product bounds the relative error to first order.
//
// Stability: eigenvalue k is on the imaginary axis ("marginal") when
//     |Re lambda_k| <= 8 cond_k |lambda_k| (eta_k + 2^-53),
// i.e. within eight times the first-order change that the computation's backward error
// plus one rounding of every matrix entry to double can cause; unstable above, stable
// below. The equilibrium is unstable if any eigenvalue is, else marginal if any is,
// else stable. An eigenvalue that is zero by construction (circles of equilibria at
// U = 0, merging points, double roots) is on the axis whatever its computed value.
//
//   abu::Spectrum sp = abu::equilibrium_spectrum(p, equilibrium);
//   if (sp.stability == abu::Stability::stable) ...
#pragma once

#include <array>
#include <complex>
#include <optional>
#include <string_view>

#include <Eigen/Core>

#include "abu/equilibria/equilibria.hpp"
#include "abu/model/model.hpp"

namespace abu {

enum class Stability { stable, unstable, marginal };
std::string_view to_string(Stability s);

/// How eigenvalues are computed; `refined` is the analyzer's, the others exist for the
/// benchmark's speed-against-error comparison.
enum class SpectrumMethod {
  dense_qr,    ///< QR of the balanced J in double (what numpy.linalg.eigvals does)
  structured,  ///< QR of J and of the structured J^-1 in double, best of both
  refined,     ///< structured + long-double Newton on the quadratic eigenproblem
};
std::string_view to_string(SpectrumMethod m);

struct Spectrum {
  static constexpr int size = 8;
  /// Sorted by real part descending, then imaginary part descending [1/s].
  std::array<std::complex<double>, size> eigenvalues{};
  std::array<double, size> error{};      ///< estimated absolute error [1/s]
  std::array<double, size> condition{};  ///< relative componentwise condition number
  std::array<bool, size> on_axis{};      ///< within the marginal band (see above)
  /// Right eigenvectors x of the quadratic problem (position part of J's (x, lambda x)),
  /// SI coordinates, unit norm; refined method only.
  std::array<Eigen::Matrix<std::complex<double>, 4, 1>, size> vectors{};
  double abscissa = 0.0;                 ///< spectral abscissa max Re lambda [1/s]
  Stability stability = Stability::marginal;
  int n_unstable = 0;  ///< eigenvalues right of the band
  int n_marginal = 0;  ///< eigenvalues inside the band
  /// Some eigenvalue moves by more than 1e-8 of its modulus when the matrix entries
  /// are rounded to double: the inputs themselves do not determine it to 8 digits.
  bool ill_conditioned = false;
  bool converged = true;  ///< every Newton refinement converged (refined method)
};

/// Spectrum of the linearization A, C, K (model.hpp) of the two-ball model.
/// `structural_zeros` eigenvalues are known to be exactly zero (a singular equilibrium,
/// Equilibrium::singular): the ones of smallest modulus are put on the imaginary axis,
/// whatever rounding made of them.
Spectrum compute_spectrum(const Linearization<long double, 2>& lin,
                          SpectrumMethod method = SpectrumMethod::refined, int structural_zeros = 0);

/// Eigenvalue continuation: refines each predicted eigenpair (a branch's modes
/// extrapolated from its previous points) by Newton in double precision and keeps the
/// modes' identity: on success `modes[k]` is the new eigenvalue of predicted mode k and
/// `mode_of_sorted[i]` the mode of sorted eigenvalue i. Fails (nullopt) when a mode's
/// Newton leaves its basin (it moves by more than half the predicted distance to the
/// nearest other mode) or does not converge; the caller then computes the spectrum afresh.
struct TrackedSpectrum {
  Spectrum spectrum;
  std::array<std::complex<double>, Spectrum::size> modes{};
  std::array<Eigen::Matrix<std::complex<double>, 4, 1>, Spectrum::size> mode_vectors{};
};
std::optional<TrackedSpectrum> track_spectrum(
    const Linearization<long double, 2>& lin, const std::array<std::complex<double>, Spectrum::size>& values,
    const std::array<Eigen::Matrix<std::complex<double>, 4, 1>, Spectrum::size>& vectors);

/// Spectrum at an equilibrium (linearized in long double at its exact position).
Spectrum equilibrium_spectrum(const Params& p, const Equilibrium& e,
                              SpectrumMethod method = SpectrumMethod::refined);

}  // namespace abu
