// LU factorization with partial pivoting of a small fixed-size real matrix, with the
// arithmetic of Eigen's PartialPivLU (Eigen 3.4, sizes <= 16, unblocked): the same pivot
// (the first entry of largest magnitude in the column), the same row swaps, each
// multiplier a quotient by the pivot, each update a_ij - l_ik u_kj, in the same order; its
// solves and determinant are Eigen's own triangular solves and diagonal product on that
// factor. So it gives the same bits as PartialPivLU (tests/test_small_lu.cpp checks it),
// 25-30 % faster in double (5 x 5: 53 against 77 ns; 10 x 10: 205 against 268 ns,
// measured): Eigen runs its fixed-size factorization through a dynamic-stride kernel (loop
// bounds, block expressions and a visitor per column), the most expensive call of
// eigenvalue tracking along a branch (docs/benchmarks-continuation.md). In long double
// (x87) it is slower than Eigen's (340 against 210 ns for 5 x 5): use it for double.
//
//   abu::SmallLu<Eigen::Matrix<double, 5, 5>> lu(B);
//   x = lu.solve(b);  y = lu.transpose_solve(c);  lu.determinant();
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <type_traits>

namespace abu {

template <class Matrix>
class SmallLu {
 public:
  using Scalar = typename Matrix::Scalar;
  static constexpr int n = Matrix::RowsAtCompileTime;
  static_assert(n != Eigen::Dynamic && n == Matrix::ColsAtCompileTime && n <= 16,
                "fixed-size square matrices up to 16 x 16 (Eigen factors these unblocked)");
  static_assert(std::is_floating_point_v<Scalar>, "real matrices (complex pivoting scores |z| differently)");

  SmallLu() = default;
  explicit SmallLu(const Matrix& a) { compute(a); }

  void compute(const Matrix& a) {
    lu_ = a;
    int swaps = 0;
    Eigen::Matrix<int, n, 1> transposition;
    // Fully unrolled (n is a constant): every loop bound is then a constant too.
#pragma GCC unroll 16
    for (int k = 0; k + 1 < n; ++k) {
      int best = k;
      Scalar biggest = std::abs(lu_(k, k));
#pragma GCC unroll 16
      for (int i = k + 1; i < n; ++i)
        if (std::abs(lu_(i, k)) > biggest) biggest = std::abs(lu_(i, k)), best = i;
      transposition(k) = best;
      if (biggest != Scalar(0)) {
        if (best != k) {
          lu_.row(k).swap(lu_.row(best));
          ++swaps;
        }
        const Scalar pivot = lu_(k, k);
#pragma GCC unroll 16
        for (int i = k + 1; i < n; ++i) lu_(i, k) /= pivot;
      }
#pragma GCC unroll 16
      for (int j = k + 1; j < n; ++j) {
        const Scalar ukj = lu_(k, j);
#pragma GCC unroll 16
        for (int i = k + 1; i < n; ++i) lu_(i, j) -= lu_(i, k) * ukj;
      }
    }
    transposition(n - 1) = n - 1;
    sign_ = swaps % 2 ? -1 : 1;
    p_.setIdentity();
    for (int k = n - 1; k >= 0; --k) p_.applyTranspositionOnTheRight(k, transposition(k));
  }

  /// x with A x = b (as PartialPivLU::solve).
  template <class Vec>
  Vec solve(const Vec& b) const {
    Vec x = p_ * b;
    lu_.template triangularView<Eigen::UnitLower>().solveInPlace(x);
    lu_.template triangularView<Eigen::Upper>().solveInPlace(x);
    return x;
  }
  /// x with A^T x = b (as PartialPivLU::transpose().solve).
  template <class Vec>
  Vec transpose_solve(const Vec& b) const {
    Vec x = lu_.template triangularView<Eigen::Upper>().transpose().solve(b);
    lu_.template triangularView<Eigen::UnitLower>().transpose().solveInPlace(x);
    return p_.transpose() * x;
  }
  Scalar determinant() const { return Scalar(sign_) * lu_.diagonal().prod(); }

 private:
  Matrix lu_;
  Eigen::PermutationMatrix<n, n> p_;
  int sign_ = 1;
};

}  // namespace abu
