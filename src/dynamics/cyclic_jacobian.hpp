// The Newton matrix of a cycle's multiple shooting in its block structure, and the LU of its
// bordered system [J; d^T] (docs/model.md §17.2, §17.7): O(M) for M intervals, where the
// dense LU of the (N M + 2)^2 bordered matrix is O(M^3) (at M = 40 and N = 8, a 322 x 322 LU
// per orbit and per tangent). Internal to src/dynamics (cycle_problem.hpp).
//
// Unknowns u = (u_0 .. u_{M-1}, tau, pi), rows r_0 .. r_{M-1} (N each), the phase row and the
// border row d. Row block j has diag_j at u_j, a diagonal next_j at u_{j+1} (u_M = u_0: the
// cycle closes there), and border_j at (tau, pi); the phase row has entries at u_0 only.
//
// Elimination: u_0 is kept as a corner column; the columns u_1 .. u_{M-1} are eliminated in
// order, each from a 2N-row panel (the N rows carried from the last panel and row block k)
// by LU with partial pivoting within the panel (the banded LU of a multiple shooting matrix);
// the border row d is updated by each panel's pivot rows (it is never a pivot row: its
// multipliers are those of the pivot block's inverse). What is left is the (N + 2)^2 system
// of the carried rows, the phase row and d in (u_0, tau, pi), solved by a dense LU with
// partial pivoting; back substitution gives u_{M-1} .. u_1.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace abu::detail {

template <int N>
struct CyclicJacobian {
  using Block = Eigen::Matrix<double, N, N>;
  using Column = Eigen::Matrix<double, N, 1>;
  using Border = Eigen::Matrix<double, N, 2>;
  std::vector<Block> diag;        ///< d r_j / d u_j
  std::vector<Column> next;       ///< d r_j / d u_{j+1}, a diagonal
  std::vector<Border> border;     ///< d r_j / d (tau, pi)
  Column phase = Column::Zero();  ///< the phase row at u_0

  int blocks() const { return int(diag.size()); }
  void resize(int m) {
    diag.assign(std::size_t(m), Block::Zero());
    next.assign(std::size_t(m), Column::Zero());
    border.assign(std::size_t(m), Border::Zero());
    phase.setZero();
  }
  /// a x + b y (+ c z): the extrapolation and interpolation of Newton matrices along a branch
  /// (the same mesh; the phase row and the diagonals are the caller's to set).
  static CyclicJacobian combination(double a, const CyclicJacobian& x, double b, const CyclicJacobian& y,
                                    double c = 0, const CyclicJacobian* z = nullptr) {
    CyclicJacobian out = x;
    for (std::size_t j = 0; j < x.diag.size(); ++j) {
      out.diag[j] = a * x.diag[j] + b * y.diag[j];
      out.border[j] = a * x.border[j] + b * y.border[j];
      if (z) {
        out.diag[j] += c * z->diag[j];
        out.border[j] += c * z->border[j];
      }
    }
    return out;
  }
};

template <int N>
class CyclicBorderedLu {
 public:
  using Jac = CyclicJacobian<N>;
  using Vec = Eigen::VectorXd;

  CyclicBorderedLu(const Jac& J, const Vec& d) { factor(J, d); }

  Vec solve(const Vec& b) const {
    const int m = m_;
    Vec x = Vec::Zero(N * m + 2);
    if (failed_) return Vec::Constant(N * m + 2, std::numeric_limits<double>::quiet_NaN());
    Eigen::Matrix<double, N, 1> carry = b.template segment<N>(0);
    double d_rhs = b(N * m + 1);
    std::vector<Eigen::Matrix<double, N, 1>> pivot_rhs(static_cast<std::size_t>(m));
    for (int k = 1; k < m; ++k) {
      const Panel& P = panels_[std::size_t(k)];
      Eigen::Matrix<double, 2 * N, 1> g;
      g << carry, b.template segment<N>(N * k);
      for (int c = 0; c < N; ++c) std::swap(g(c), g(P.pivot(c)));
      for (int c = 0; c < N; ++c)
        for (int r = c + 1; r < 2 * N; ++r) g(r) -= P.lower(r, c) * g(c);
      pivot_rhs[std::size_t(k)] = g.template head<N>();
      carry = g.template tail<N>();
      d_rhs -= P.d_multiplier.dot(pivot_rhs[std::size_t(k)]);
    }
    Eigen::Matrix<double, N + 2, 1> rhs;
    rhs << carry, b(N * m), d_rhs;
    const Eigen::Matrix<double, N + 2, 1> z = last_.solve(rhs);
    const Eigen::Matrix<double, N, 1> x0 = z.template head<N>();
    const Eigen::Vector2d tp = z.template tail<2>();
    x.template segment<N>(0) = x0;
    x(N * m) = tp(0);
    x(N * m + 1) = tp(1);
    for (int k = m - 1; k >= 1; --k) {
      const Panel& P = panels_[std::size_t(k)];
      Eigen::Matrix<double, N, 1> r = pivot_rhs[std::size_t(k)] - P.corner * x0 - P.border * tp;
      if (k + 1 < m) r -= P.next * x.template segment<N>(N * (k + 1));
      x.template segment<N>(N * k) = P.upper.template triangularView<Eigen::Upper>().solve(r);
    }
    return x;
  }

 private:
  struct Panel {
    Eigen::Matrix<int, N, 1> pivot;            // row swapped with row c at step c
    Eigen::Matrix<double, 2 * N, N> lower;     // unit lower factor's multipliers
    Eigen::Matrix<double, N, N> upper;         // the pivot block U_kk
    Eigen::Matrix<double, N, N> next, corner;  // the pivot rows at u_{k+1} and u_0
    Eigen::Matrix<double, N, 2> border;        // ... and at (tau, pi)
    Eigen::Matrix<double, N, 1> d_multiplier;  // d's row combination of the pivot rows
  };

  void factor(const Jac& J, const Vec& d) {
    const int m = J.blocks();
    m_ = m;
    panels_.assign(std::size_t(m), Panel{});
    using Block = Eigen::Matrix<double, N, N>;
    Block carry_cur = m > 1 ? Block(J.next[0].asDiagonal()) : Block::Zero();
    Block carry_corner = J.diag[0];
    if (m == 1) carry_corner += Block(J.next[0].asDiagonal());
    Eigen::Matrix<double, N, 2> carry_border = J.border[0];
    Eigen::Matrix<double, 1, N> d_corner = d.template segment<N>(0).transpose();
    Eigen::Matrix<double, 1, 2> d_border = d.template tail<2>().transpose();
    Eigen::Matrix<double, 1, N> d_cur = m > 1 ? Eigen::Matrix<double, 1, N>(d.template segment<N>(N).transpose())
                                              : Eigen::Matrix<double, 1, N>::Zero();
    // Columns of a panel row: [u_k | u_{k+1} | u_0 | tau, pi].
    constexpr int W = 3 * N + 2;
    for (int k = 1; k < m; ++k) {
      Panel& P = panels_[std::size_t(k)];
      Eigen::Matrix<double, 2 * N, W> G = Eigen::Matrix<double, 2 * N, W>::Zero();
      G.template block<N, N>(0, 0) = carry_cur;
      G.template block<N, N>(0, 2 * N) = carry_corner;
      G.template block<N, 2>(0, 3 * N) = carry_border;
      G.template block<N, N>(N, 0) = J.diag[std::size_t(k)];
      const Block succ = J.next[std::size_t(k)].asDiagonal();
      if (k + 1 < m) {
        G.template block<N, N>(N, N) = succ;
      } else {
        G.template block<N, N>(N, 2 * N) = succ;  // the last interval closes on u_0
      }
      G.template block<N, 2>(N, 3 * N) = J.border[std::size_t(k)];
      for (int c = 0; c < N; ++c) {
        int p = c;
        for (int r = c + 1; r < 2 * N; ++r)
          if (std::abs(G(r, c)) > std::abs(G(p, c))) p = r;
        P.pivot(c) = p;
        if (p != c) G.row(c).swap(G.row(p));
        const double pivot = G(c, c);
        if (!(std::abs(pivot) > 0) || !std::isfinite(pivot)) {
          failed_ = true;
          return;
        }
        for (int r = c + 1; r < 2 * N; ++r) {
          const double l = G(r, c) / pivot;
          G(r, c) = l;
          G.row(r).tail(W - c - 1) -= l * G.row(c).tail(W - c - 1);
        }
      }
      P.lower = G.template leftCols<N>();
      P.upper = G.template block<N, N>(0, 0).template triangularView<Eigen::Upper>();
      P.next = G.template block<N, N>(0, N);
      P.corner = G.template block<N, N>(0, 2 * N);
      P.border = G.template block<N, 2>(0, 3 * N);
      carry_cur = G.template block<N, N>(N, N);
      carry_corner = G.template block<N, N>(N, 2 * N);
      carry_border = G.template block<N, 2>(N, 3 * N);
      // d's u_k entries eliminated by the pivot rows: d_multiplier^T U_kk = d_cur.
      P.d_multiplier = P.upper.transpose().template triangularView<Eigen::Lower>().solve(d_cur.transpose());
      d_corner -= P.d_multiplier.transpose() * P.corner;
      d_border -= P.d_multiplier.transpose() * P.border;
      if (k + 1 < m)
        d_cur = d.template segment<N>(N * (k + 1)).transpose() - P.d_multiplier.transpose() * P.next;
    }
    Eigen::Matrix<double, N + 2, N + 2> K = Eigen::Matrix<double, N + 2, N + 2>::Zero();
    K.template block<N, N>(0, 0) = carry_corner;
    K.template block<N, 2>(0, N) = carry_border;
    K.template block<1, N>(N, 0) = J.phase.transpose();
    K.template block<1, N>(N + 1, 0) = d_corner;
    K.template block<1, 2>(N + 1, N) = d_border;
    last_.compute(K);
    failed_ = !K.allFinite();
  }

  std::vector<Panel> panels_;
  Eigen::PartialPivLU<Eigen::Matrix<double, N + 2, N + 2>> last_;
  int m_ = 0;
  bool failed_ = false;
};

}  // namespace abu::detail
