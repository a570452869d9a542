// Eigenvalues of a large sparse pencil  A v = lambda B v  (docs/model.md §19):
// the k nearest given shifts, and the rightmost ones with the region of the complex plane
// that the search has covered. Generic: any real A (nonsymmetric), any real B (default the
// identity); the flexible rotor's Jacobian (model/shaft.hpp) is one user.
//
// Method (model.md §19.1): ARPACK (arpack-ng, [zd]naupd/[zd]neupd, the implicitly restarted
// Arnoldi method) on the shift-inverted operator
//     OP = (A - sigma B)^-1 B,      OP v = nu v  <=>  A v = lambda B v,  nu = 1 / (lambda - sigma),
// so the eigenvalues of largest |nu| that ARPACK finds first are the lambda nearest sigma.
// One sparse LU (Eigen::SparseLU, complex) of A - sigma B per shift, reused by every
// ARPACK iteration, and kept in a ShiftFactorizations cache for a shift that comes again.
// A complex shift runs the complex ARPACK (znaupd) with a complex LU; a real shift the real
// one (dnaupd) with a real LU: a quarter of the flops, half the memory (§19.1).
// OP is applied with the standard inner product (bmat = 'I'), so B need not be symmetric
// nor definite: B nonsingular is assumed for the residual's scale; a singular B (constraint
// rows) gives infinite eigenvalues, which map to nu = 0 and are never among those returned.
//
// Residual of an eigenpair (lambda, v), reported with it (model.md §19.3):
//     residual = ||A v - lambda B v||_2 / (|lambda| ||B v||_2)      (lambda != 0)
//     residual = ||A v||_2 / (||A||_1 ||v||_2)                       (lambda == 0)
// and the normwise backward error ||A v - lambda B v|| / ((||A||_1 + |lambda| ||B||_1) ||v||).
//
// Deterministic: ARPACK's start vector is a fixed sequence (not LAPACK's random one); the
// reference BLAS and one thread: the same input gives the same bytes out.
//
//   abu::SparseSpectrum s = abu::rightmost_eigenvalues(A, B, 10, {.max_frequency = 2e4});
//   if (!s.status.ok()) ...;   // s.status.reason says why (fewer converged than asked, ...)
//   s.coverage: no eigenvalue other than s.eigenpairs lies in
//       s.coverage.real_min <= Re <= s.coverage.real_max, |Im| <= s.coverage.imag_max.
#pragma once

#include <complex>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "abu/core/status.hpp"

namespace abu {

using SparseRealMatrix = Eigen::SparseMatrix<double>;  ///< column-major, int indices

/// Options of the ARPACK run at each shift. Defaults in the comments.
struct SparseSpectrumOptions {
  /// Arnoldi basis size (ARPACK's ncv); 0: max(2 k + 1, 20), at most n. Larger is more
  /// robust for clustered eigenvalues and costs ncv vectors of n complex numbers.
  int ncv = 0;
  /// ARPACK's stopping tolerance: a Ritz value nu of OP is accepted when its Ritz estimate
  /// is <= tol |nu|. Default 1e-12; 0 means machine precision (ARPACK's convention).
  double tol = 1e-12;
  /// Implicit restarts of the Arnoldi iteration at one shift (ARPACK's mxiter). Default 1000.
  int max_iterations = 1000;
  /// Keep each eigenvector (unit 2-norm) in SparseEigenpair::vector. Default false.
  bool keep_vectors = false;
  /// Refine an eigenpair whose shift is farther from it than its own modulus
  /// (|lambda - sigma| > |lambda|), or whose residual is above 1e-10, by inverse iteration
  /// at the eigenvalue itself (model.md
  /// §19.5): ARPACK's tol acts on nu = 1 / (lambda - sigma), so its lambda is good to about
  /// tol |lambda - sigma|, which for a small eigenvalue found from a far shift (the slow
  /// ball modes from sigma = 1442 i: 1.3e-9 of |lambda|) is far above tol |lambda|. The
  /// refined pair is accurate to its own modulus (measured 1e-14 relative, §19.5); costs one
  /// sparse LU of A - lambda B per refined pair. Kept only if its residual is not larger.
  /// Default true.
  bool refine = true;
};

/// One eigenpair found by shift-invert.
struct SparseEigenpair {
  std::complex<double> value;  ///< lambda [1/s] (frame: whatever A and B are written in)
  std::complex<double> shift;  ///< the shift sigma whose run found it [1/s]
  double residual = 0.0;       ///< ||A v - lambda B v|| / (|lambda| ||B v||), see above
  double backward_error = 0.0; ///< ||A v - lambda B v|| / ((||A||_1 + |lambda| ||B||_1) ||v||)
  /// Inside the region the search certifies (rightmost_eigenvalues' coverage); always
  /// true for eigenvalues_near, whose certificate is the shift's disc.
  bool covered = true;
  bool refined = false;        ///< value and residual are from the refinement (options.refine)
  /// ||B v|| ||w|| / |w^H B v| with w the left eigenvector (model.md §19.3): the first-order
  /// error of lambda is about condition * residual * |lambda|. Computed (one sparse LU at
  /// lambda and three adjoint solves) only where it can decide a sign: |Re lambda| within
  /// 1e4 residual |lambda|; 1 elsewhere.
  double condition = 1.0;
  Eigen::VectorXcd vector;     ///< unit 2-norm; empty unless options.keep_vectors
};

/// What one shift's ARPACK run did.
struct ShiftRun {
  std::complex<double> shift;  ///< sigma [1/s]
  int requested = 0;           ///< k asked for (ARPACK's nev)
  int converged = 0;           ///< ARPACK's nconv (the Ritz values that met tol)
  int iterations = 0;          ///< implicit restarts taken (ARPACK's iparam[2])
  int operator_applications = 0;  ///< solves with the LU (ARPACK's iparam[8])
  /// Radius of the disc |lambda - sigma| < radius that holds no eigenvalue but those this
  /// run returned: the distance of the farthest one, when all `requested` converged; 0
  /// when fewer did (no claim). [1/s]
  double radius = 0.0;
  bool reused_factorization = false;  ///< the LU came from the cache
  int refined = 0;  ///< pairs refined at their own eigenvalue (options.refine), one LU each
  Status status;
};

/// The region the rightmost search has covered (model.md §19.2): every eigenvalue with
///     real_min <= Re lambda <= real_max   and   |Im lambda| <= imag_max
/// is among the returned eigenpairs (up to Krylov's missing an eigenvalue, §19.2). Empty
/// (imag_max < 0) when no shift converged.
struct SpectrumCoverage {
  double real_min = 0.0;   ///< [1/s]
  double real_max = 0.0;   ///< [1/s]
  double imag_max = -1.0;  ///< [1/s]; < 0: nothing covered
  std::string how;         ///< one sentence: the shifts and discs behind the claim
  bool empty() const { return imag_max < 0.0; }
};

struct SparseSpectrum {
  /// Sorted by real part descending, then imaginary part descending.
  std::vector<SparseEigenpair> eigenpairs;
  std::vector<ShiftRun> shifts;  ///< one per shift, in the order run
  SpectrumCoverage coverage;     ///< rightmost_eigenvalues only
  int factorizations = 0;        ///< sparse LUs computed (cache hits not counted)
  /// converged: every shift returned all it was asked for (and, for the rightmost, k
  /// eigenvalues lie in the covered region). Otherwise the reason; the eigenpairs found
  /// are kept.
  Status status;
};

/// Sparse LUs of A - sigma B by shift, for reuse across calls on the same A and B. Holds
/// pointers to nothing: the caller keeps it with the matrices it was built for (a cache
/// used with another pencil is cleared when the pencil's size or nonzero count differs,
/// but not for equal-shaped different values: call clear()).
class ShiftFactorizations {
 public:
  ShiftFactorizations();
  ~ShiftFactorizations();
  ShiftFactorizations(ShiftFactorizations&&) noexcept;
  ShiftFactorizations& operator=(ShiftFactorizations&&) noexcept;
  void clear();
  int size() const;

  struct Impl;
  std::unique_ptr<Impl> impl;
};

/// The k eigenvalues of A v = lambda B v nearest each shift (k per shift, in shift order,
/// then all sorted as SparseSpectrum says; a value found by two shifts appears twice, each
/// with its shift). B empty (0 x 0): the identity. A and B square, of one size, k >= 1 and
/// k < n - 1 (ARPACK's limit); otherwise std::invalid_argument.
SparseSpectrum eigenvalues_near(const SparseRealMatrix& A, const SparseRealMatrix& B,
                                std::span<const std::complex<double>> shifts, int k,
                                const SparseSpectrumOptions& options = {},
                                ShiftFactorizations* cache = nullptr);

/// Where rightmost_eigenvalues looks (model.md §19.2). Defaults in the comments.
struct RightmostOptions {
  SparseSpectrumOptions arpack;  ///< per-shift ARPACK options
  /// The band |Im lambda| <= max_frequency [1/s] to cover: the structure's frequencies of
  /// interest. 0 (default): one real shift only, covering what its disc covers.
  double max_frequency = 0.0;
  /// Real part of every shift of the ladder [1/s]; default 0 (on the imaginary axis).
  /// Put it right of the axis to certify a strip there too.
  double shift_real = 0.0;
  /// Eigenvalues asked of each shift; 0: k (at least 6).
  int per_shift = 0;
  /// Next shift's frequency: previous + spacing x previous disc radius. Default 1.2
  /// (consecutive discs of equal radius r then cover a strip of half-width 0.8 r).
  double spacing = 1.2;
  int max_shifts = 200;  ///< the ladder stops here (status not converged if short of the band)
};

/// The k eigenvalues of largest real part in the band |Im| <= max_frequency, by a ladder of
/// shifts sigma_j = shift_real + i omega_j, omega_0 = 0, up the band (conjugates by the
/// pencil's symmetry, A and B real). Returns them sorted (a complex pair that the k-th
/// splits comes whole: k or k + 1 values), with the coverage rectangle; `covered` marks
/// those inside it. Status not converged with the reason when a shift falls short, the
/// ladder stops before the band, or fewer than k found values lie in the covered region.
SparseSpectrum rightmost_eigenvalues(const SparseRealMatrix& A, const SparseRealMatrix& B, int k,
                                     const RightmostOptions& options = {},
                                     ShiftFactorizations* cache = nullptr);

/// Merges copies of one eigenvalue found by different shifts: two values from different
/// shifts closer than `relative` of their modulus are one, and the copy from the nearer
/// shift is kept (shift-invert is most accurate there). rightmost_eigenvalues already merges
/// at 1e-9 (what ARPACK resolves); an eigenvalue resolved worse than that (the slow creep
/// modes of stiff coulomb balls: residuals 1e-8 .. 1e-6, copies 1e-7 apart) can come back
/// once per disc that holds it. Returns how many copies were dropped.
int merge_shift_copies(SparseSpectrum& s, double relative);

}  // namespace abu
