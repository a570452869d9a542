// Floquet exponents of a pi/omega-periodic linear system x' = J(t) x whose J has only the
// harmonics 0 and +-2 omega (docs/model.md §10.6), by Hill's method (§10.6, "Hill").
//
// With x(t) = e^{lambda t} sum_k x_k e^{2 i omega k t}, k = -N..N, the harmonic balance is
// the eigenproblem of the block-tridiagonal Hill matrix
//   H_kk = J0 - 2 i omega k I,  H_{k,k-1} = (Jc - i Js)/2,  H_{k,k+1} = (Jc + i Js)/2.
// Every physical exponent appears as a ladder lambda + 2 i omega m; the multiplier
// rho = exp(lambda pi/omega) is the same on the whole ladder. Of the (2N+1) dim eigenvalues
// the physical ones are those whose eigenvectors sit in the middle of the harmonic range:
// each eigenvector's centroid c = sum k |x_k|^2 / sum |x_k|^2 moves by exactly 1 along a
// ladder, so a run of `dim` eigenvalues, sorted by centroid, spanning less than 1 holds one
// member of every ladder; the run closest to c = 0 is taken (the best-resolved members).
// N grows until the multipliers stop changing (HillOptions).
//
//   abu::HillResult h = abu::hill_multipliers(J);   // J: abu::PeriodicJacobian
//   if (h.status.ok()) ... h.multipliers ...
#pragma once

#include <complex>
#include <vector>

#include "abu/core/status.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu {

/// Truncation control of Hill's method.
struct HillOptions {
  int first_harmonics = 4;      ///< N of the first try (harmonics -N..N); default 4
  int harmonics_step = 4;       ///< N grows by this; default 4
  int max_harmonics = 32;       ///< give up beyond; default 32 (a 65 dim matrix)
  /// converged when every multiplier moved by <= tol |rho| + tol^2 (long double; double:
  /// 100 tol, its rounding level); default 1e-12
  double tolerance = 1e-12;
  /// Solve in long double (default false: double). balanced_floquet switches it on when
  /// double Hill and the Magnus monodromy disagree (the stiff coulomb laws).
  bool extended = false;
  /// Keep the selected eigenvectors (HillResult::vectors); default false. The Campbell view
  /// of an anisotropic support reads the mode's harmonics from them (model.md §10.15).
  bool keep_vectors = false;
};

struct HillResult {
  std::vector<std::complex<double>> multipliers;  ///< sorted (floquet_order)
  std::vector<std::complex<double>> exponents;    ///< lambda [1/s], Im in (-omega, omega], same order
  int harmonics = 0;            ///< N used
  double truncation_change = 0.0;  ///< max |rho_N - rho_{N-step}| / (|rho| + tol), the convergence measure
  /// With HillOptions::keep_vectors, one per exponent (same order): the Hill eigenvector as a
  /// dim x (2N + 1) matrix, column j the coefficient of e^{2 i omega (first_harmonic[i] + j) t}
  /// in x(t) = e^{lambda t} sum_j x_j e^{...}, lambda = exponents[i] (the harmonic index
  /// follows the reduction of Im lambda into (-omega, omega]); scaled coordinates of J.
  std::vector<Eigen::MatrixXcd> vectors;
  std::vector<int> first_harmonic;
  Status status;
};

/// Hill's method on J (dimension dim). Status not ok (and the last try kept) if the ladder
/// selection fails or N reaches max_harmonics unconverged.
HillResult hill_multipliers(const PeriodicJacobian& J, const HillOptions& options = {});

/// The project's order for multipliers: modulus descending, then imaginary part descending;
/// conjugate pairs of a real system are made exact conjugates first (`rel`: how close two
/// multipliers must be, relative to the larger modulus, to count as a pair).
void floquet_order(std::vector<std::complex<double>>& rho, double rel = 1e-9);

/// The state-space Jacobian restricted to the span of the orthonormal columns V:
/// V^T J(t) V, harmonic by harmonic (the normal system of §10.6 for n >= 3 balls).
PeriodicJacobian restricted(const PeriodicJacobian& J, const Eigen::MatrixXd& V);

}  // namespace abu
