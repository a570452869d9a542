// Internal to the spectrum module: starting values for the eigenvalue refinement from
// balanced double-precision QRs, and the assembly of refined eigenvalues into a
// spectrum. Shared by compute_spectrum (spectrum.cpp) and the deflated spectrum of a set
// of equilibria (normal_spectrum.cpp).
#pragma once

#include <array>
#include <complex>
#include <functional>

#include <Eigen/Core>

#include "abu/linear/spectrum.hpp"

namespace abu::spectrum_detail {

/// A first-order matrix in double, row-major for GSL's balancing.
template <int N>
using FirstOrderMatrix = Eigen::Matrix<double, state_size<N>, state_size<N>, Eigen::RowMajor, state_capacity<N>,
                                       state_capacity<N>>;

/// The number of eigenvalues: `runtime` for a run-time ball count, else the constant
/// (which lets the compiler see the bounds of the fixed-size loops).
template <int N>
constexpr std::size_t eigen_count(int runtime) {
  if constexpr (N == any_balls) {
    return std::size_t(runtime);
  } else {
    return std::size_t(state_capacity<N>);
  }
}

/// A matrix after Parlett-Reinsch balancing (GSL; Eigen's EigenSolver does not balance
/// and the Jacobian's rows differ by 1e15 in scale), with its QR eigenvalues. `norm` is
/// the Frobenius norm of the balanced matrix: each eigenvalue's absolute error is about
/// eps * norm.
template <int N>
struct BalancedQr {
  FirstOrderMatrix<N> balanced;
  std::array<double, state_capacity<N>> scale{};  // balanced = D^-1 M D, D = diag(scale)
  std::array<std::complex<double>, state_capacity<N>> values{};
  double norm = 0;
  /// The matrix is (J - shift)^-1 (its eigenvalues theta = 1 / (lambda - shift)), not J.
  bool inverse = false;
  double shift = 0;
};
/// Balances and QRs `m` (square, any size up to the capacity). False if the matrix is
/// not finite or the QR does not converge (the values are then not usable).
template <int N>
bool balanced_qr(const FirstOrderMatrix<N>& m, BalancedQr<N>& out);

/// A starting value: an eigenvalue lambda, and where it came from: eigenvalue `theta` of
/// the balanced matrix `source` (the direct matrix, theta = lambda, or the shifted
/// inverse, theta = 1 / (lambda - sigma)).
template <int N>
struct Estimate {
  std::complex<double> value;
  std::complex<double> theta;
  const BalancedQr<N>* source = nullptr;
};

template <int N>
struct Starts {
  BalancedQr<N> direct, inverse;
  BalancedQr<N> middle;  ///< a second shifted inverse, for the retry of failed refinements
  std::array<Estimate<N>, state_capacity<N>> estimates{};
  int count = 0;      ///< eigenvalues, the size of `direct`
  double shift = 0;   ///< sigma of the inverse
  Status status{};    ///< numerical issue if a QR (or its balancing) failed
};

/// Every eigenvalue from the QR whose error bound relative to it is smaller: eps ||J||
/// from the direct matrix, eps ||(J - sigma)^-1|| |lambda - sigma|^2 from the inverse.
/// Sorting both lists by distance to sigma pairs them; the k closest come from the
/// inverse, k counting its values inside the crossover radius sqrt(||J|| / ||J^-1||).
/// `out.direct` (and `out.inverse` if `have_inverse`) are set; fills the estimates.
template <int N>
void combine_starts(int count, bool have_inverse, double shift, Starts<N>& out);

/// Starting values for the quadratic problem of `lin`: J = [[0, I], [-A^-1 K, -A^-1 C]]
/// and its structured shifted inverse (model.md §8).
template <int N>
void starting_values(const Linearization<long double, N>& lin, SpectrumMethod method, Starts<N>& out);

/// A-priori absolute error of an estimate from its QR: eps ||J|| from the direct matrix,
/// eps ||(J - sigma)^-1|| |lambda - sigma|^2 from a shifted inverse.
template <int N>
double apriori_error(const Estimate<N>& e);

/// Second starts for the eigenvalues whose refinement failed (`failed[i]`; the others
/// refined to `kept[i]`): the QR of the structured inverse shifted to `sigma` (model.md
/// §8) resolves eigenvalues near sigma that neither J (norm 1e15 at kappa = 1e12) nor
/// its inverse at 0 (norm 1e15 from the creep modes) can: each kept eigenvalue claims
/// the nearest of its values, and the failed slots get the remaining values closest to
/// sigma (conjugate pairs together); the kept ones start from their refined values. False if T(sigma) is singular, the QR fails or the
/// values cannot be assigned; `out` (a copy of the first starts) then is not usable.
template <int N>
bool middle_starts(const Linearization<long double, N>& lin, double sigma,
                   const std::array<bool, state_capacity<N>>& failed,
                   const std::array<std::complex<double>, state_capacity<N>>& kept, Starts<N>& out);

/// The position part x of the eigenvector (x, lambda x) by inverse iteration on the
/// balanced matrix the estimate came from (J or its structured inverse).
template <class S, int N>
QepVector<N> position_vector(const Estimate<N>& e);

/// Where the refinement's start vectors come from.
template <int N>
using VectorSource = std::function<QepVector<N>(const Estimate<N>&, bool complex)>;

/// Refines the `starts.count` estimates on the quadratic problem `qep` into slots
/// sp.count - starts.count .. sp.count - 1 of `sp`, with their bands (the Newton of
/// refinement.hpp, kept in the basin of its start; QR values only for other methods).
/// `failed_out`, if given: which estimates kept their QR value (refinement failed).
/// `refine_only`, if given: only these estimates are refined (with any start the QR did not
/// tell apart from a failed one, as the grouping does); the others keep their QR value,
/// band 0, and are neither failed nor "not converged" (spectrum_verdict.hpp).
template <int N>
void assemble_spectrum(const Linearization<long double, N>& qep, const Starts<N>& starts, SpectrumMethod method,
                       const VectorSource<N>& vector_of, SpectrumT<N>& sp,
                       std::array<long double, SpectrumT<N>::capacity>& band,
                       std::array<bool, SpectrumT<N>::capacity>* failed_out = nullptr,
                       const std::array<bool, SpectrumT<N>::capacity>* refine_only = nullptr);

/// Sorts and classifies (spectrum.hpp's rules); `structural_zeros` as compute_spectrum's.
template <int N>
void finish_spectrum(SpectrumT<N>& sp, const std::array<long double, SpectrumT<N>::capacity>& band,
                     int structural_zeros);

}  // namespace abu::spectrum_detail
