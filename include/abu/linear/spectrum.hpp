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
//     with a bordered (n+3)x(n+3) system in long double, from A, C, K assembled in long
//     double (refinement.hpp);
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
//   abu::Spectrum sp = abu::equilibrium_spectrum(p, equilibrium);   // equilibria.hpp
//   if (sp.stability == abu::Stability::stable) ...
#pragma once

#include <array>
#include <complex>
#include <optional>
#include <string_view>

#include <Eigen/Core>

#include "abu/core/status.hpp"
#include "abu/linear/refinement.hpp"
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

/// The 2n + 4 eigenvalues of an equilibrium of the N-ball model (N = any_balls: n at run
/// time, in bounded storage).
template <int N>
struct SpectrumT {
  static constexpr int capacity = state_capacity<N>;
  using Vector = QepVector<N>;
  int count = N == any_balls ? 0 : 2 * N + 4;  ///< number of eigenvalues, 2 n + 4
  /// Sorted by real part descending, then imaginary part descending [1/s].
  std::array<std::complex<double>, capacity> eigenvalues{};
  std::array<double, capacity> error{};      ///< estimated absolute error [1/s]
  std::array<double, capacity> condition{};  ///< relative componentwise condition number
  std::array<bool, capacity> on_axis{};      ///< within the marginal band (see above)
  /// Zero by construction: along a set of equilibria (the balanced set of n >= 3 balls,
  /// model.md §13). Printed as exactly 0; not counted as marginal, and left out of the
  /// abscissa and the stability verdict, which are then the set's normal stability.
  std::array<bool, capacity> structural{};
  /// Right eigenvectors x of the quadratic problem (position part of J's (x, lambda x)),
  /// SI coordinates, unit norm; refined method only.
  std::array<Vector, capacity> vectors{};
  double abscissa = 0.0;                 ///< spectral abscissa max Re lambda [1/s] (structural zeros excluded)
  Stability stability = Stability::marginal;
  int n_unstable = 0;    ///< eigenvalues right of the band
  int n_marginal = 0;    ///< eigenvalues inside the band (structural zeros excluded)
  int n_structural = 0;  ///< eigenvalues zero by construction (`structural`)
  /// Some eigenvalue moves by more than 1e-8 of its modulus when the matrix entries
  /// are rounded to double: the inputs themselves do not determine it to 8 digits.
  bool ill_conditioned = false;
  bool converged = true;  ///< every Newton refinement converged (refined method)
  /// > 0: that many eigenvalues stayed inside their error bands, and n_unstable, stability
  /// and abscissa are the characteristic polynomial's certified ones (spectrum_counts.hpp).
  int certified_count = 0;
  /// converged (every eigenvalue refined to its tolerance), not converged (some kept
  /// their QR value: `converged` is false), or a numerical issue (a non-finite matrix, a
  /// QR or GSL's balancing failed: the values are not to be trusted), with the reason.
  Status status{};
};
using Spectrum = SpectrumT<2>;
using SpectrumN = SpectrumT<any_balls>;

/// Spectrum of the linearization A, C, K (model.hpp). `structural_zeros` eigenvalues are
/// known to be exactly zero at an isolated but singular equilibrium (a circle
/// representative, a merging point, a double root: Equilibrium::structural_zeros): the
/// ones of smallest modulus are put on the imaginary axis, whatever rounding made of
/// them. Instantiated for N = 2 and N = any_balls.
template <int N>
SpectrumT<N> compute_spectrum(const Linearization<long double, N>& lin,
                              SpectrumMethod method = SpectrumMethod::refined, int structural_zeros = 0);

/// Spectrum at a point of a set of equilibria with tangent space V_T (model.md §13.4):
/// the eigenvalues normal to the set, each refined as compute_spectrum's, plus the
/// structural zeros, exactly 0. With K V_T = 0 the quadratic problem deflates exactly:
/// writing s = P w + V_T a (P an orthonormal complement of V_T) and substituting
/// a = a~ / lambda,
///     M(lambda) = [T(lambda) P | (lambda A + C) V_T],   det T = lambda^t det M,
/// a quadratic problem whose finite eigenvalues are the normal spectrum. Where also
/// C V_T = 0 (friction without slope: the balls drift along the set, model.md §13.4) the
/// zeros come in Jordan pairs and the columns deflate once more, to A V_T.
SpectrumN compute_normal_spectrum(const Linearization<long double, any_balls>& lin, const TangentBasis& tangent,
                                  SpectrumMethod method = SpectrumMethod::refined);

/// Eigenvalue continuation (two balls): refines each predicted eigenpair (a branch's modes
/// extrapolated from its previous points) by Newton in double precision and keeps the
/// modes' identity: on success `modes[k]` is the new eigenvalue of predicted mode k and
/// `mode_of_sorted[i]` the mode of sorted eigenvalue i. Fails (nullopt) when a mode's
/// Newton leaves its basin (it moves by more than half the predicted distance to the
/// nearest other mode) or does not converge; the caller then computes the spectrum afresh.
struct TrackedSpectrum {
  Spectrum spectrum;
  std::array<std::complex<double>, Spectrum::capacity> modes{};
  std::array<Eigen::Matrix<std::complex<double>, 4, 1>, Spectrum::capacity> mode_vectors{};
};
std::optional<TrackedSpectrum> track_spectrum(
    const Linearization<long double, 2>& lin, const std::array<std::complex<double>, Spectrum::capacity>& values,
    const std::array<Eigen::Matrix<std::complex<double>, 4, 1>, Spectrum::capacity>& vectors);

}  // namespace abu
