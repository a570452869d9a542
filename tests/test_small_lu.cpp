// SmallLu (core/small_lu.hpp) against Eigen's PartialPivLU: the same bits, not merely
// close (tolerance 0). The continuation's outputs rely on it: swapping the factorization
// changed no byte of a branch CSV. Matrices with entries over 20 orders of magnitude (as
// the refinement's bordered systems before equilibration), with tied pivots (equal
// magnitudes: the first one must win, as in Eigen), an exactly zero pivot column, and
// the real form [[Re, -Im], [Im, Re]] of a complex matrix (the refinement's 10 x 10).
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <random>

#include "abu/core/small_lu.hpp"

namespace {

template <class M>
M random_matrix(std::mt19937_64& rng, int kind) {
  using S = typename M::Scalar;
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-10, 10);
  M a;
  for (int j = 0; j < a.cols(); ++j)
    for (int i = 0; i < a.rows(); ++i) a(i, j) = S(u(rng)) * S(std::ldexp(1.0, kind == 1 ? 3 * e(rng) : 0));
  if (kind == 2) {  // ties: whole columns of +-1
    for (int i = 0; i < a.rows(); ++i) a(i, 0) = i % 2 ? S(1) : S(-1), a(i, 2) = S(1);
  }
  if (kind == 3) a.col(1).setZero();  // a zero pivot on the way (singular)
  if (kind == 4 && a.rows() % 2 == 0) {  // real form of a complex matrix
    const int h = int(a.rows()) / 2;
    a.bottomRightCorner(h, h) = a.topLeftCorner(h, h);
    a.topRightCorner(h, h) = -a.bottomLeftCorner(h, h);
  }
  return a;
}

template <class M>
void check_same_bits(int trials) {
  using V = Eigen::Matrix<typename M::Scalar, M::RowsAtCompileTime, 1>;
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < trials; ++trial) {
    const M a = random_matrix<M>(rng, trial % 5);
    V b;
    for (int i = 0; i < b.size(); ++i) b(i) = typename M::Scalar(u(rng));
    const Eigen::PartialPivLU<M> eigen(a);
    const abu::SmallLu<M> small(a);
    const V x_eigen = eigen.solve(b), x_small = small.solve(b);
    const V y_eigen = eigen.transpose().solve(b), y_small = small.transpose_solve(b);
    INFO("trial " << trial << " kind " << trial % 5);
    for (int i = 0; i < b.size(); ++i) {
      // Bitwise: NaN (the singular kind) must be NaN in both.
      CHECK((x_eigen(i) == x_small(i) || (std::isnan(x_eigen(i)) && std::isnan(x_small(i)))));
      CHECK((y_eigen(i) == y_small(i) || (std::isnan(y_eigen(i)) && std::isnan(y_small(i)))));
    }
    CHECK(eigen.determinant() == small.determinant());
  }
}

}  // namespace

TEST_CASE("SmallLu gives the bits of Eigen's PartialPivLU", "[small_lu]") {
  check_same_bits<Eigen::Matrix<double, 5, 5>>(500);
  check_same_bits<Eigen::Matrix<double, 10, 10>>(500);
  check_same_bits<Eigen::Matrix<long double, 5, 5>>(500);
  check_same_bits<Eigen::Matrix<double, 16, 16>>(100);
}
