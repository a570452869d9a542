#include "abu/linear/refinement.hpp"

#include "abu/core/small_lu.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>

namespace abu {

namespace {

using ld = long double;

// |z| without hypot: the componentwise magnitudes below only need a factor-sqrt(2)-
// accurate size, and hypotl is the slowest call in the refinement.
template <class W>
W magnitude_of(W z) {
  return std::abs(z);
}
template <class W>
W magnitude_of(const std::complex<W>& z) {
  return std::abs(z.real()) + std::abs(z.imag());
}

template <class S>
struct Precision {  // S = W or std::complex<W>; D the scalar of the bordered solve
  using W = S;
  using D = double;
};
template <class W_>
struct Precision<std::complex<W_>> {
  using W = W_;
  using D = std::complex<double>;
};

template <class S>
S from_complex(std::complex<double> z) {
  if constexpr (std::is_floating_point_v<S>) {
    return S(z.real());
  } else {
    return S(z.real(), z.imag());
  }
}

// Sizes of the bordered system [T, T' x; c^H, 0] (d + 1) and of its real form.
template <int N>
inline constexpr int bordered_size = N == any_balls ? Eigen::Dynamic : N + 3;
template <int N>
inline constexpr int bordered_real_size = N == any_balls ? Eigen::Dynamic : 2 * (N + 3);
template <class D, int N>
using BorderedMatrix = Eigen::Matrix<D, bordered_size<N>, bordered_size<N>, Eigen::ColMajor, dof_capacity<N> + 1,
                                     dof_capacity<N> + 1>;
template <class D, int N>
using BorderedVector = Eigen::Matrix<D, bordered_size<N>, 1, Eigen::ColMajor, dof_capacity<N> + 1, 1>;
template <int N>
using RealFormMatrix = Eigen::Matrix<double, bordered_real_size<N>, bordered_real_size<N>, Eigen::ColMajor,
                                     2 * (dof_capacity<N> + 1), 2 * (dof_capacity<N> + 1)>;
template <int N>
using RealFormVector = Eigen::Matrix<double, bordered_real_size<N>, 1, Eigen::ColMajor, 2 * (dof_capacity<N> + 1), 1>;

// The bordered matrix factored once, solved with it or its adjoint. Complex systems are
// factored in their real form [[Re, -Im], [Im, Re]]: Eigen's complex LU pivots on |z|,
// i.e. hypot, which made hypot the refinement's most expensive call. (The real form of
// B^H is the transpose of B's real form.) Two balls (fixed sizes 5 and 10): SmallLu, the
// same bits as Eigen's PartialPivLU at a fraction of its cost (core/small_lu.hpp).
template <class M>
class Factored {
 public:
  void compute(const M& B) {
    if constexpr (fixed) {
      small_.compute(B);
    } else {
      eigen_.compute(B);
    }
  }
  template <class V>
  V solve(const V& r, bool adjoint) const {
    if constexpr (fixed) {
      return adjoint ? small_.transpose_solve(r) : small_.solve(r);
    } else {
      return adjoint ? V(eigen_.transpose().solve(r)) : V(eigen_.solve(r));
    }
  }

 private:
  static constexpr bool fixed = M::RowsAtCompileTime != Eigen::Dynamic;
  struct Unused {};
  [[no_unique_address]] std::conditional_t<fixed, SmallLu<M>, Unused> small_;
  [[no_unique_address]] std::conditional_t<fixed, Unused, Eigen::PartialPivLU<M>> eigen_;
};

template <int N>
class BorderedSolver {
 public:
  explicit BorderedSolver(const BorderedMatrix<double, N>& B) { real_.compute(B); }
  explicit BorderedSolver(const BorderedMatrix<std::complex<double>, N>& B) {
    const Eigen::Index m = B.rows();
    RealFormMatrix<N> R(2 * m, 2 * m);
    R << B.real(), -B.imag(), B.imag(), B.real();
    complex_.compute(R);
  }
  BorderedVector<double, N> solve(const BorderedVector<double, N>& r, bool adjoint) const {
    return real_.solve(r, adjoint);
  }
  BorderedVector<std::complex<double>, N> solve(const BorderedVector<std::complex<double>, N>& r, bool adjoint) const {
    const Eigen::Index m = r.rows();
    RealFormVector<N> rr(2 * m);
    rr << r.real(), r.imag();
    const RealFormVector<N> v = complex_.solve(rr, adjoint);
    BorderedVector<std::complex<double>, N> out(m);
    for (Eigen::Index i = 0; i < m; ++i) out(i) = {v(i), v(i + m)};
    return out;
  }

 private:
  Factored<BorderedMatrix<double, N>> real_;
  Factored<RealFormMatrix<N>> complex_;
};

}  // namespace

template <int N>
void equilibrate(const DofMatrix<ld, N>& magnitude, Coordinates<ld, N>& rows, Coordinates<ld, N>& cols) {
  // In double: only the orders of magnitude matter, and double's frexp/ldexp are cheap.
  const Eigen::Index d = dofs_of<N>(magnitude.rows());
  const DofMatrix<double, N> m = magnitude.template cast<double>();
  Coordinates<double, N> r = Coordinates<double, N>::Ones(d), c = Coordinates<double, N>::Ones(d);
  const auto inverse_pow2 = [](double v) {  // 2^(1 - e) for v = f 2^e, f in [0.5, 1)
    if (!(v > 0) || !std::isfinite(v)) return 1.0;
    // Normal v: e and 2^(1 - e) straight from the exponent bits (frexp and ldexp, called
    // some 50 times per eigenpair, were a tenth of eigenvalue tracking); the same value.
    const auto bits = std::bit_cast<std::uint64_t>(v);
    const int biased = int(bits >> 52);  // v > 0: no sign bit
    if (biased > 1 && biased < 2046) return std::bit_cast<double>(std::uint64_t(2046 - biased) << 52);
    int e = 0;
    std::frexp(v, &e);
    return std::ldexp(1.0, 1 - e);
  };
  for (int sweep = 0; sweep < 2; ++sweep) {
    for (Eigen::Index i = 0; i < d; ++i) r(i) = inverse_pow2(m.row(i).transpose().cwiseProduct(c).maxCoeff());
    for (Eigen::Index j = 0; j < d; ++j) c(j) = inverse_pow2(m.col(j).cwiseProduct(r).maxCoeff());
  }
  rows = r.template cast<ld>();
  cols = c.template cast<ld>();
}

template <class S, int N>
RefinedEigenpair<N> refine_eigenpair(const Linearization<ld, N>& lin, std::complex<double> start,
                                     const QepVector<N>& start_vector, int multiplicity) {
  using W = typename Precision<S>::W;
  using D = typename Precision<S>::D;
  using Vec = Eigen::Matrix<S, dof_size<N>, 1, Eigen::ColMajor, dof_capacity<N>, 1>;
  using Mat = Eigen::Matrix<S, dof_size<N>, dof_size<N>, Eigen::ColMajor, dof_capacity<N>, dof_capacity<N>>;
  using VecW = Coordinates<W, N>;
  using MatW = DofMatrix<W, N>;
  constexpr W eps = std::numeric_limits<W>::epsilon() / 2;
  const Eigen::Index d = dofs_of<N>(lin.mass.rows());
  S lambda = from_complex<S>(start);
  Coordinates<ld, N> rows, cols;
  {
    const ld a = std::abs(start);
    equilibrate<N>(DofMatrix<ld, N>(a * a * lin.mass.cwiseAbs() + a * lin.damping.cwiseAbs() + lin.stiffness.cwiseAbs()),
                   rows, cols);
  }
  const MatW Ar = (rows.asDiagonal() * lin.mass * cols.asDiagonal()).template cast<W>();
  const MatW Cr = (rows.asDiagonal() * lin.damping * cols.asDiagonal()).template cast<W>();
  const MatW Kr = (rows.asDiagonal() * lin.stiffness * cols.asDiagonal()).template cast<W>();
  const Mat As = Ar.template cast<S>(), Cs = Cr.template cast<S>(), Ks = Kr.template cast<S>();
  const MatW absA = Ar.cwiseAbs(), absC = Cr.cwiseAbs(), absK = Kr.cwiseAbs();
  const auto T = [&](S l) -> Mat { return (l * l) * As + l * Cs + Ks; };
  // The rank-(k-1) update for a k-fold semisimple eigenvalue (see the header): fixed,
  // deterministic O(1) columns that are generic against any physical structure.
  Mat update = Mat::Zero(d, d);
  for (int j = 0; j + 1 < multiplicity; ++j) {
    for (Eigen::Index r = 0; r < d; ++r)
      for (Eigen::Index c = 0; c < d; ++c)
        update(r, c) += S(W(std::cos(1.7 * double(r) + 0.9 * j + 0.3)) * W(std::sin(2.3 * double(c) + 1.1 * j + 0.7)));
  }
  const auto T_updated = [&](S l) -> Mat { return multiplicity > 1 ? Mat(T(l) + update) : T(l); };
  const auto dT = [&](S l) -> Mat { return S(2) * l * As + Cs; };
  const auto magnitude = [&](S l) -> MatW {
    const W a = magnitude_of(l);
    return a * a * absA + a * absC + absK;
  };
  const auto abs_vector = [d](const Vec& v) {
    VecW a(d);
    for (Eigen::Index i = 0; i < d; ++i) a(i) = magnitude_of(v(i));
    return a;
  };
  // The start vector in the equilibrated coordinates; normalization c^H x = 1 with c the
  // start itself (unlike pinning one entry, it cannot pick a component that is noise).
  Vec x(d);
  for (Eigen::Index i = 0; i < d; ++i) x(i) = from_complex<S>(start_vector(i)) / S(W(cols(i)));
  x /= S(x.norm());
  if (multiplicity > 1) {
    // The start vector lies in the k-dimensional null space of T but, in general, not in
    // the kernel of Z^T: inverse iteration on the updated matrix picks the one direction
    // that is a null vector of both (from the given vector, so the choice is stable).
    const Eigen::PartialPivLU<Mat> lu(T_updated(lambda));
    for (int step = 0; step < 2; ++step) {
      const Vec next = lu.solve(x);
      if (!next.allFinite() || next.isZero(0)) break;
      x = next / S(next.norm());
    }
  }
  const Eigen::Matrix<D, dof_size<N>, 1, Eigen::ColMajor, dof_capacity<N>, 1> c = x.template cast<D>();
  // Bordered system B = [T, T' x; c^H, 0], its first d rows weighted by the
  // componentwise magnitude so that pivoting sees comparable rows. Near a simple
  // eigenvalue B is well conditioned even where T itself is singular to working precision.
  VecW weight(d);
  const auto bordered = [&](S l, const Mat& t, const Vec& v) {
    const VecW scale = magnitude(l) * abs_vector(v);
    BorderedMatrix<D, N> B(d + 1, d + 1);
    const Vec tv = dT(l) * v;
    for (Eigen::Index i = 0; i < d; ++i) {
      weight(i) = scale(i) > 0 ? 1 / scale(i) : 1;
      for (Eigen::Index j = 0; j < d; ++j) B(i, j) = D(t(i, j) * S(weight(i)));
      B(i, d) = D(tv(i) * S(weight(i)));
      B(d, i) = Eigen::numext::conj(c(i));
    }
    B(d, d) = D(0);
    return B;
  };
  // Newton converges until its steps stop shrinking (the rounding level); whether that
  // level is good enough is judged below against the error bound. In double the
  // convergence is quadratic: after a step below sqrt(eps) |lambda| the error is at the
  // rounding level already, and the step that would confirm it is skipped.
  W last_step = std::numeric_limits<W>::infinity();
  W final_step = last_step;
  const W enough = std::is_same_v<W, double> ? std::sqrt(eps) : 4 * eps;
  std::optional<BorderedSolver<N>> solver;
  for (int it = 0; it < kRefinementTolerances.max_iterations; ++it) {
    const Mat t = T_updated(lambda);
    solver.emplace(bordered(lambda, t, x));
    const Vec r = t * x;  // in the working precision
    BorderedVector<D, N> rhs(d + 1);
    for (Eigen::Index i = 0; i < d; ++i) rhs(i) = D(-r(i) * S(weight(i)));
    rhs(d) = D(0);
    const BorderedVector<D, N> step = solver->solve(rhs, false);
    if (!step.allFinite()) break;
    const W dl = magnitude_of(S(step(d)));
    lambda += S(step(d));
    for (Eigen::Index i = 0; i < d; ++i) x(i) += S(step(i));
    final_step = std::is_same_v<W, double> && dl <= enough * magnitude_of(lambda) ? dl * dl / magnitude_of(lambda)
                                                                                  : std::min(dl, last_step);
    if (dl <= enough * magnitude_of(lambda) || (it >= 2 && dl > last_step / 2)) break;
    last_step = dl;
  }
  // Left vector from the adjoint bordered system (the last factorization, at the
  // previous iterate, is close enough for a condition estimate): B^H [y; eta] = e_last
  // gives T^H y = -eta c with eta ~ (T x)^H y / (c^H x) ~ 0: y is the left null vector of T.
  const Mat t = T(lambda);
  Vec y = x;
  if (solver) {
    BorderedVector<D, N> e_last = BorderedVector<D, N>::Zero(d + 1);
    e_last(d) = D(1);
    const BorderedVector<D, N> z = solver->solve(e_last, true);
    for (Eigen::Index i = 0; i < d; ++i) y(i) = S(z(i)) * S(weight(i));  // undo the row weighting
    if (!y.allFinite() || y.isZero(0)) y = x;
  }
  const MatW S_mag = magnitude(lambda);
  const Vec r = t * x;
  const VecW denom = S_mag * abs_vector(x);
  W eta = 0;
  for (Eigen::Index i = 0; i < d; ++i) eta = std::max(eta, denom(i) > 0 ? magnitude_of(r(i)) / denom(i) : W(0));
  const W num = abs_vector(y).dot(S_mag * abs_vector(x));
  const W den = std::abs(y.dot(dT(lambda) * x));  // dot() conjugates its first argument
  const W abs_condition = den > 0 ? num / den : std::numeric_limits<W>::infinity();
  eta = std::max(eta, eps);
  // Converged: the backward error is small, and the last Newton step is at the rounding
  // level of the eigenvalue itself or below its first-order error bound (a zero
  // eigenvalue has no relative rounding level). Without the first condition an iterate
  // stalled between two close real eigenvalues passed (eta 4e-4 .. 0.5: its large eta and
  // condition made a large "error bound"; seen tracking a complex pair through its split
  // into two real eigenvalues). The limit 1e-8 ~ sqrt(eps_double) admits multiple
  // eigenvalues, where Newton stalls near sqrt(eps) of the working precision (merging
  // equilibria: eta ~ 1e-11 in long double), and nothing that has not converged.
  const bool converged = std::isfinite(std::abs(lambda)) && eta <= W(kRefinementTolerances.backward_error) &&
                         (final_step <= 1e3 * eps * std::abs(lambda) || final_step <= 8 * abs_condition * eta);
  QepVector<N> unscaled(d);
  for (Eigen::Index i = 0; i < d; ++i) {
    const std::complex<W> xi = std::complex<W>(x(i)) * W(cols(i));
    unscaled(i) = {double(xi.real()), double(xi.imag())};
  }
  RefinedEigenpair<N> out;
  out.value = std::complex<ld>(std::complex<W>(lambda));
  out.backward_error = ld(eta);
  out.abs_condition = ld(abs_condition);
  out.converged = converged;
  out.vector = unscaled.normalized();
  return out;
}

#define ABU_INSTANTIATE_REFINE(N)                                                                                   \
  template void equilibrate<N>(const DofMatrix<ld, N>&, Coordinates<ld, N>&, Coordinates<ld, N>&);                  \
  template RefinedEigenpair<N> refine_eigenpair<ld, N>(const Linearization<ld, N>&, std::complex<double>,           \
                                                       const QepVector<N>&, int);                                   \
  template RefinedEigenpair<N> refine_eigenpair<std::complex<ld>, N>(const Linearization<ld, N>&,                   \
                                                                     std::complex<double>, const QepVector<N>&, int); \
  template RefinedEigenpair<N> refine_eigenpair<double, N>(const Linearization<ld, N>&, std::complex<double>,       \
                                                           const QepVector<N>&, int);                               \
  template RefinedEigenpair<N> refine_eigenpair<std::complex<double>, N>(const Linearization<ld, N>&,               \
                                                                         std::complex<double>, const QepVector<N>&, int);
ABU_INSTANTIATE_REFINE(2)
ABU_INSTANTIATE_REFINE(any_balls)
#undef ABU_INSTANTIATE_REFINE

}  // namespace abu
