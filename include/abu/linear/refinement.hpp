// Newton refinement of one eigenpair of the quadratic eigenproblem
//
//     T(lambda) x = (lambda^2 A + lambda C + K) x = 0
//
// with a bordered system, and the eigenvalue's componentwise backward error and
// condition number (Higham & Tisseur):
//
//     eta  = max_i |T x|_i / ((|lambda|^2 |A| + |lambda| |C| + |K|) |x|)_i
//     cond = y* (|lambda|^2 |A| + |lambda| |C| + |K|) |x| / (|lambda| |y* T'(lambda) x|)
//
// whose product bounds the relative error to first order. A, C, K are any square
// matrices (A may be singular: the deflated problem of the balanced set has infinite
// eigenvalues, which are never started from). Used by spectrum.cpp for every
// eigenvalue of an equilibrium (S = long double or its complex, from QR starting values)
// and by eigenvalue continuation (S = double or its complex, from extrapolated modes).
//
//   auto r = abu::refine_eigenpair<std::complex<long double>>(lin, start, start_vector);
//   if (r.converged) ... r.value, r.abs_condition * r.backward_error ...
#pragma once

#include <complex>

#include <Eigen/Core>

#include "abu/model/model.hpp"

namespace abu {

/// A position vector x of the quadratic problem (the first half of J's (x, lambda x)).
template <int N>
using QepVector = Eigen::Matrix<std::complex<double>, dof_size<N>, 1, Eigen::ColMajor, dof_capacity<N>, 1>;

/// The stopping rules of refine_eigenpair (defaults are what the analyzer uses; the
/// spectrum's error estimates and the 1e-8 accuracy claim of README rest on them).
struct RefinementTolerances {
  /// Newton steps at most: from a QR start it takes 2-4; 16 leaves room for the slow
  /// linear convergence at a nearly multiple eigenvalue without looping on a stall.
  int max_iterations = 16;
  /// Converged only with componentwise backward error <= this: ~sqrt(eps_double), which
  /// admits multiple eigenvalues (eta ~ 1e-11 at merging equilibria in long double).
  long double backward_error = 1e-8L;
};
inline constexpr RefinementTolerances kRefinementTolerances{};

template <int N>
struct RefinedEigenpair {
  std::complex<long double> value;
  long double backward_error = 0;  ///< componentwise, eta (at least the unit roundoff)
  long double abs_condition = 0;   ///< y* S |x| / |y* T' x|, S = |lambda|^2 |A| + |lambda| |C| + |K|
  bool converged = false;
  QepVector<N> vector;  ///< x, unscaled (SI) and of unit norm
};

/// Newton on T(lambda) x = 0 from (start, start_vector) on the equilibrated problem; the
/// residual T x and the iterate in S's precision (S = double, long double or their
/// complex; real S keeps a real eigenvalue exactly real), the bordered correction in
/// double. Converged: backward error <= 1e-8 and the last step at the rounding level of
/// the eigenvalue or below its first-order error bound.
///
/// `multiplicity` k > 1: the start is a semisimple eigenvalue of that multiplicity (k
/// identical balls at one place: their relative modes). T(lambda) then has a k-dimensional
/// null space and the bordered matrix is singular; Newton runs on the rank-(k-1) update
/// T(lambda) + W Z^T (fixed O(1) vectors in the equilibrated coordinates), whose null space
/// at lambda is generically the one direction of null T(lambda) that Z^T annihilates, so
/// lambda is a simple eigenvalue of the updated problem (the eigenvalue itself does not
/// move: T x = 0 and Z^T x = 0 there). Backward error and condition are those of T.
template <class S, int N>
RefinedEigenpair<N> refine_eigenpair(const Linearization<long double, N>& lin, std::complex<double> start,
                                     const QepVector<N>& start_vector, int multiplicity = 1);

/// Diagonal equilibration R |M| D ~ O(1) by powers of two (two Sinkhorn-style sweeps on
/// the magnitudes): rows and columns of T can differ by 1e10 (tiny balls), which would
/// make pivoting treat the small ones as zero. Eigenvalues, the componentwise backward
/// error and condition number are invariant under it.
template <int N>
void equilibrate(const DofMatrix<long double, N>& magnitude, Coordinates<long double, N>& rows,
                 Coordinates<long double, N>& cols);

}  // namespace abu
