// The eigenvalues of a product of matrices P = A_m ... A_2 A_1 without forming P: the
// Floquet multipliers of a periodic orbit from its short-interval transition matrices
// (docs/model.md §17.4), accurate when most of them are tiny (stiff ball modes give
// multipliers of 1e-300 and below, which the eigenvalues of an explicitly multiplied P
// lose entirely: their absolute error is eps |P|).
//
// Method (an equivalent of the periodic Schur decomposition of Bojanczyk, Golub and
// Van Dooren, model.md §17.4): orthogonal iteration on the cyclic product carried out
// factor by factor,
//     A_k Q_{k-1} = Q_k R_k   (QR, k = 1..m),   then Q_0 <- Q_m,
// until W = Q_0^T Q_m is block upper triangular: a boundary between the leading j
// columns and the rest converges like |mu_{j+1} / mu_j| per sweep. Every transformation
// is orthogonal and applied to one factor, and dropping the converged lower blocks of W
// perturbs the last factor by |W_21| |A_m|, so the multipliers are exact for factors
// perturbed by a few eps relative to each factor (the backward error of periodic QR),
// not to their product. The eigenvalues of each diagonal block (a cluster of
// comparable moduli, a complex pair) are those of the product of the factors' diagonal
// blocks, multiplied out after scaling each by its norm (the scales kept as logarithms,
// so moduli far below 1e-308 keep their log).
//
//   std::vector<Eigen::MatrixXd> factors = ...;          // A_1 first
//   abu::ProductEigenvalues e = abu::product_eigenvalues(factors);
//   if (e.status.ok()) ... e.values[0] (largest modulus), e.log_moduli[0] ...
#pragma once

#include <cstddef>
#include <complex>
#include <vector>

#include <Eigen/Core>

#include "abu/core/status.hpp"

namespace abu {

struct ProductEigenvalueOptions {
  /// A block of W = Q_0^T Q_m below this (Frobenius) counts as zero: the backward error
  /// it leaves in the last factor, relative to its norm.
  double tolerance = 1e-13;
  /// Sweeps of orthogonal iteration at most; a boundary still above the tolerance then
  /// (moduli within a factor (tolerance)^(1/max_sweeps) of each other, or a complex
  /// pair) joins its neighbours in one cluster.
  int max_sweeps = 120;
  /// A boundary whose observed rate (the ratio of the moduli across it) is at least this
  /// after 8 sweeps joins its neighbours in one cluster: solved from their block product it
  /// loses at most about log10(1 / merge_rate) digits, where separating it would take
  /// ln(tolerance) / ln(rate) sweeps. 1: only the budget decides.
  double merge_rate = 0.3;
};

struct ProductEigenvalues {
  /// The eigenvalues of A_m ... A_1, sorted by modulus, descending (a complex pair:
  /// positive imaginary part first). A modulus below the smallest double shows as 0;
  /// its logarithm is in log_moduli.
  std::vector<std::complex<double>> values;
  std::vector<double> log_moduli;  ///< ln |value|, finite for nonsingular factors (-inf: singular)
  /// arg value in (-pi, pi] [rad], to full accuracy also where value is subnormal or 0.
  std::vector<double> arguments;
  /// Sizes of the clusters whose eigenvalues came from one small explicit product (1: a
  /// real eigenvalue separated from every other by the iteration), largest modulus first.
  std::vector<int> clusters;
  int sweeps = 0;
  /// Largest |W_21| over the boundaries kept: the backward error in the last factor.
  double backward_error = 0;
  Status status;  ///< numerical_issue: empty or mis-sized input, a non-finite entry
};

/// Eigenvalues of factors.back() * ... * factors.front(), all square of one size.
ProductEigenvalues product_eigenvalues(const std::vector<Eigen::MatrixXd>& factors,
                                       const ProductEigenvalueOptions& options = {});

/// The eigenvalues of factors.back() * ... * factors.front() where a chain of vectors is known
/// to be carried along the product, A_k v_{k-1} ~ c_k v_k (k = 1..m, v_m = v_0; chain[k] = v_k,
/// chain.size() == m): a periodic orbit's flow direction f(y_k) at its shooting points, whose
/// multiplier c = prod c_k is the trivial one, 1 (docs/model.md §17.4). Each factor is written
/// in orthonormal bases whose first vectors are v_{k-1} and v_k; c_k is the (1, 1) entry, and the
/// other eigenvalues are those of the product of the trailing (n - 1)^2 blocks
/// (product_eigenvalues). The component of A_k v_{k-1} off v_k (the factor's error along the
/// orbit) is dropped: a backward perturbation of each factor by that much, `chain_error` (the
/// largest, relative to the factor's norm). Where the trivial multiplier's eigenvector nearly
/// coincides with another's (a strongly unstable orbit near a homoclinic end: the flow direction
/// along the saddle's unstable one), the plain product's trivial multiplier is perturbed by the
/// factors' errors times the largest multiplier; deflated, each multiplier keeps the accuracy of
/// the factors. The trivial one is inserted in the descending order, `trivial` its index.
struct DeflatedProductEigenvalues {
  ProductEigenvalues eigen;
  std::size_t trivial = 0;
  double chain_error = 0;
};
DeflatedProductEigenvalues deflated_product_eigenvalues(const std::vector<Eigen::MatrixXd>& factors,
                                                        const std::vector<Eigen::VectorXd>& chain,
                                                        const ProductEigenvalueOptions& options = {});

/// The test functions of the bifurcations of a periodic orbit on its Floquet multipliers
/// (docs/model.md §17.5), generic: any multiplier set with one trivial multiplier (the one
/// closest to 1, the flow direction), in the form product_eigenvalues returns.
struct CycleTestValues {
  std::size_t trivial = 0;      ///< index of the trivial multiplier
  double trivial_distance = 1;  ///< |mu_trivial - 1|
  int unstable = 0;             ///< nontrivial multipliers with |mu| > 1
  double period_doubling = 1;   ///< Re prod_i (1 + mu_i): changes sign where a real mu crosses -1
  double neimark_sacker = 1;    ///< Re prod_{i<j} (mu_i mu_j - 1): a complex pair crosses |mu| = 1
  /// A nontrivial complex multiplier within |ln |mu|| < 0.05 of the unit circle: tells a
  /// Neimark-Sacker sign change from a real pair with mu_i mu_j = 1 (a neutral saddle).
  bool complex_pair_near_circle = false;
};
CycleTestValues cycle_test_values(const std::vector<std::complex<double>>& multipliers,
                                  const std::vector<double>& log_moduli);
/// The same with the trivial multiplier known (its index: deflated_product_eigenvalues).
CycleTestValues cycle_test_values(const std::vector<std::complex<double>>& multipliers,
                                  const std::vector<double>& log_moduli, std::size_t trivial);

/// How far the multipliers moved between two orbits: max over `after` of the distance to
/// the nearest not yet matched multiplier of `before` (greedy matching, both sets of one
/// size; moduli clamped to 2, so escaping multipliers count by their direction). The step
/// control of cycle continuation refuses a step on which it exceeds a limit (§17.5).
double multiplier_jump(const std::vector<std::complex<double>>& before, const std::vector<std::complex<double>>& after);

}  // namespace abu
