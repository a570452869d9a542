#include "abu/continuation/bifurcation.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <complex>
#include <limits>

#include "abu/core/taylor.hpp"

namespace abu {

namespace {

using ld = long double;
using cld = std::complex<ld>;
using Vec5 = StaticEquations::Vec5;
using Mat4 = Eigen::Matrix<ld, 4, 4>;
using Mat4c = Eigen::Matrix<cld, 4, 4>;
using Vec4c = Eigen::Matrix<cld, 4, 1>;
constexpr ld kEpsLong = std::numeric_limits<ld>::epsilon();
// Central-difference step for the derivative rows of g, in the scaled unknowns (all
// O(1)): truncation ~h^2 and rounding ~eps_ld / h balance near 1e-7; Newton only needs
// the rows to a few digits, the location's accuracy comes from the analytic residuals.
constexpr ld kStep = 1e-7L;
// Newton converges linearly (rate ~1/2) where the augmented system is singular at its
// root, as the fold system is at a pitchfork approached along its fork: up to ~60 steps.
constexpr int kMaxIterations = 80;

// Solves the bordered system [M b; c^H 0] [v; g] = [0; 1] for g (the minimally
// augmented test function); M is equilibrated by the caller. Fixed or bounded sizes.
template <class S, class Mat, class Vec>
S bordered_g(const Mat& m, const Vec& b, const Vec& c) {
  constexpr int size = Mat::RowsAtCompileTime == Eigen::Dynamic ? Eigen::Dynamic : Mat::RowsAtCompileTime + 1;
  constexpr int capacity = Mat::MaxRowsAtCompileTime + 1;
  using Square = Eigen::Matrix<S, size, size, 0, capacity, capacity>;
  using Column = Eigen::Matrix<S, size, 1, 0, capacity, 1>;
  const Eigen::Index n = m.rows();
  Square B = Square::Zero(n + 1, n + 1);
  B.topLeftCorner(n, n) = m;
  B.topRightCorner(n, 1) = b;
  B.bottomLeftCorner(1, n) = c.adjoint();
  Column rhs = Column::Zero(n + 1);
  rhs(n) = S(1);
  return B.partialPivLu().solve(rhs)(n);
}

// Newton with a square Jacobian; stops where the steps stop shrinking. Where the
// system is singular at its root (the fold system at a pitchfork, approached along the
// fork) the steps bounce along the near-null direction while the residual reaches the
// rounding level: there convergence is judged by the residual, and the best iterate kept.
template <int Dim, class Residual, class JacobianFn>
bool newton(Eigen::Matrix<ld, Dim, 1>& y, const Residual& residual, const JacobianFn& jacobian, int& iterations) {
  ld last = std::numeric_limits<ld>::infinity();
  Eigen::Matrix<ld, Dim, 1> best = y;
  ld best_residual = std::numeric_limits<ld>::infinity();
  for (iterations = 0; iterations < kMaxIterations; ++iterations) {
    const Eigen::Matrix<ld, Dim, 1> r = residual(y);
    const ld size_r = r.cwiseAbs().maxCoeff();
    if (size_r < best_residual) best = y, best_residual = size_r;
    const Eigen::Matrix<ld, Dim, Dim> D = jacobian(y);
    const Eigen::Matrix<ld, Dim, 1> step = D.partialPivLu().solve(-r);
    if (!step.allFinite()) break;
    y += step;
    const ld size = step.cwiseAbs().maxCoeff();
    if (size <= 64 * kEpsLong) return true;
    if (iterations >= 3 && size > 0.9L * last) {
      if (size <= 1e-13L) return true;  // stagnated at the rounding level
      break;
    }
    last = size;
  }
  const ld final_residual = residual(y).cwiseAbs().maxCoeff();
  if (final_residual > best_residual) y = best;
  return std::min(final_residual, best_residual) <= 1e-15L;
}

// Central differences of a vector function of y along unit vector k.
template <int Dim, class Fn>
auto central_difference(const Fn& fn, const Eigen::Matrix<ld, Dim, 1>& y, int k) {
  Eigen::Matrix<ld, Dim, 1> yp = y, ym = y;
  yp(k) += kStep;
  ym(k) -= kStep;
  return ((fn(yp) - fn(ym)) / (2 * kStep)).eval();
}

}  // namespace

// The determinant of
// the bialternate product 2J (.) I: its factors are 2 Re lambda for each conjugate pair
// and lambda_i + lambda_j for each pair of real eigenvalues (the rest pair up into
// positive |.|^2). It changes sign where a complex pair crosses the imaginary axis (and
// at neutral saddles, which the location then tells apart). Factors inside their error
// bands are left out: their sign is noise (e.g. the conservative case's centres).
template <int N>
int hopf_test_sign(const SpectrumT<N>& sp) {
  // Structural zeros (along a set of equilibria) are not part of the normal spectrum
  // whose crossings this detects (model.md §13.4).
  const std::size_t count = std::size_t(sp.count);
  int sign = 1;
  for (std::size_t i = 0; i < count; ++i) {
    const auto li = sp.eigenvalues[i];
    if (sp.structural[i]) continue;
    if (li.imag() > 0) {
      if (!sp.on_axis[i] && li.real() < 0) sign = -sign;
      continue;
    }
    if (li.imag() != 0) continue;
    for (std::size_t j = i + 1; j < count; ++j) {
      const auto lj = sp.eigenvalues[j];
      if (lj.imag() != 0 || sp.structural[j]) continue;
      const double sum = li.real() + lj.real();
      if (std::abs(sum) > 8 * (sp.error[i] + sp.error[j]) && sum < 0) sign = -sign;
    }
  }
  return sign;
}
template int hopf_test_sign<2>(const SpectrumT<2>&);
template int hopf_test_sign<any_balls>(const SpectrumT<any_balls>&);

// The complex pair that crosses between two spectra: an upper-half-plane eigenvalue of
// `a`, clear of the real axis, whose nearest counterpart in `b` is too and lies on the
// other side of the imaginary axis.
template <int N>
std::optional<std::pair<std::complex<double>, std::complex<double>>> crossing_pair(const SpectrumT<N>& a,
                                                                                    const SpectrumT<N>& b) {
  const std::size_t count = std::size_t(a.count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto la = a.eigenvalues[i];
    if (!(la.imag() > 8 * a.error[i])) continue;
    std::size_t best = 0;
    for (std::size_t j = 1; j < count; ++j)
      if (std::abs(b.eigenvalues[j] - la) < std::abs(b.eigenvalues[best] - la)) best = j;
    const auto lb = b.eigenvalues[best];
    if (lb.imag() > 8 * b.error[best] && (la.real() > 0) != (lb.real() > 0)) return std::pair{la, lb};
  }
  return std::nullopt;
}
template std::optional<std::pair<std::complex<double>, std::complex<double>>> crossing_pair<2>(const SpectrumT<2>&,
                                                                                                const SpectrumT<2>&);
template std::optional<std::pair<std::complex<double>, std::complex<double>>> crossing_pair<any_balls>(
    const SpectrumT<any_balls>&, const SpectrumT<any_balls>&);

template <int N>
FoldConditionT<N>::FoldConditionT(const StaticEquationsT<N>& eq, const typename StaticEquationsT<N>::Unknowns& z) {
  // Border with the left null vector as column (outside the range of F_s) and the right
  // null vector as row (not orthogonal to its kernel): then the bordered matrix is regular.
  const Eigen::Index d = eq.dofs();
  const DofMatrix<ld, N> Fs = eq.jacobian(z).template leftCols<dof_size<N>>(d);
  const Eigen::JacobiSVD<DofMatrix<ld, N>> svd(Fs, Eigen::ComputeFullU | Eigen::ComputeFullV);
  left_ = svd.matrixU().col(d - 1);
  right_ = svd.matrixV().col(d - 1);
}

template <int N>
long double FoldConditionT<N>::operator()(const StaticEquationsT<N>& eq,
                                          const typename StaticEquationsT<N>::Unknowns& z) const {
  const DofMatrix<ld, N> Fs = eq.jacobian(z).template leftCols<dof_size<N>>(eq.dofs());
  return bordered_g<ld>(Fs, left_, right_);
}

namespace {
template <int N>
DofMatrix<cld, N> hopf_pencil(const StaticEquationsT<N>& eq, const typename StaticEquationsT<N>::Unknowns& z, ld w) {
  const auto lin = eq.linearization(z);
  const cld l(0, w);
  return (l * l) * lin.mass.template cast<cld>() + l * lin.damping.template cast<cld>() +
         lin.stiffness.template cast<cld>();
}
}  // namespace

template <int N>
HopfConditionT<N>::HopfConditionT(const StaticEquationsT<N>& eq, const typename StaticEquationsT<N>::Unknowns& z,
                                  long double omega) {
  const Eigen::Index d = eq.dofs();
  const DofMatrix<cld, N> T0 = hopf_pencil<N>(eq, z, omega);
  rows_.resize(d), cols_.resize(d);
  for (Eigen::Index i = 0; i < d; ++i) rows_(i) = 1 / T0.row(i).cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < d; ++j) cols_(j) = 1 / (rows_.asDiagonal() * T0).col(j).cwiseAbs().maxCoeff();
  const DofMatrix<cld, N> scaled = rows_.template cast<cld>().asDiagonal() * T0 * cols_.template cast<cld>().asDiagonal();
  const Eigen::JacobiSVD<DofMatrix<cld, N>> svd(scaled, Eigen::ComputeFullU | Eigen::ComputeFullV);
  left_ = svd.matrixU().col(d - 1);
  right_ = svd.matrixV().col(d - 1);
}

template <int N>
std::complex<long double> HopfConditionT<N>::operator()(const StaticEquationsT<N>& eq,
                                                        const typename StaticEquationsT<N>::Unknowns& z,
                                                        long double omega) const {
  const DofMatrix<cld, N> scaled =
      rows_.template cast<cld>().asDiagonal() * hopf_pencil<N>(eq, z, omega) * cols_.template cast<cld>().asDiagonal();
  return bordered_g<cld>(scaled, left_, right_);
}

template class FoldConditionT<2>;
template class FoldConditionT<any_balls>;
template class HopfConditionT<2>;
template class HopfConditionT<any_balls>;

FoldCoefficients fold_coefficients(const StaticEquations& eq, const Vec5& z, const FoldCoefficients* previous) {
  const Eigen::JacobiSVD<Mat4> svd(eq.jacobian(z).leftCols<4>(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix<ld, 4, 1> w = svd.matrixU().col(3), v = svd.matrixV().col(3);
  if (previous && w.dot(previous->left) < 0) w = -w;
  if (previous && v.dot(previous->right) < 0) v = -v;
  // F_ss[v, v] by a central second difference along v in the scaled unknowns (the
  // parameter fixed), with the row scaling of z for all three values.
  constexpr ld h = 1e-5L;
  Vec5 dz = Vec5::Zero();
  dz.head<4>() = v;
  const Eigen::Matrix<ld, 4, 1> scale = eq.residual_scale(z);
  // The unscaled b(y) measured in the fixed sizes at z (returned by value: an Eigen
  // expression would outlive the temporaries it refers to).
  const auto raw = [&](const Vec5& y) -> Eigen::Matrix<ld, 4, 1> {
    return eq.residual(y).cwiseProduct(eq.residual_scale(y)).cwiseQuotient(scale);
  };
  const Eigen::Matrix<ld, 4, 1> second = (raw(z + h * dz) - 2 * raw(z) + raw(z - h * dz)) / (h * h);
  FoldCoefficients c;
  c.right = v;
  c.left = w;
  c.cusp = w.dot(second);
  // w^T C v with w, v mapped back to the unscaled equations and unknowns.
  const auto lin = eq.linearization(z);
  const Eigen::Matrix<ld, 4, 1> w_raw = scale.cwiseInverse().cwiseProduct(w);
  const Eigen::Matrix<ld, 4, 1> v_raw(v(0) * eq.length(), v(1) * eq.length(), v(2), v(3));
  c.bogdanov_takens = w_raw.dot(lin.damping * v_raw);
  return c;
}

Located locate_fold(const StaticEquations& eq, const Vec5& z_guess) {
  const FoldCondition g(eq, z_guess);
  const auto residual = [&](const Vec5& z) {
    Vec5 r;
    r << eq.residual(z), g(eq, z);
    return r;
  };
  const auto jacobian = [&](const Vec5& z) {
    Eigen::Matrix<ld, 5, 5> D;
    D.topRows<4>() = eq.jacobian(z);
    for (int k = 0; k < 5; ++k) D(4, k) = central_difference<5>([&](const Vec5& y) {
                                           Eigen::Matrix<ld, 1, 1> v;
                                           v << g(eq, y);
                                           return v;
                                         }, z, k)(0);
    return D;
  };
  Located out;
  out.z = z_guess;
  out.converged = newton<5>(out.z, residual, jacobian, out.iterations) &&
                  eq.residual(out.z).cwiseAbs().maxCoeff() <= 1e-15L;
  return out;
}

Located locate_hopf(const StaticEquations& eq, const Vec5& z_guess, long double omega_guess) {
  // Unknowns y = (z, w / w_guess).
  const HopfCondition condition(eq, z_guess, omega_guess);
  using Vec6 = Eigen::Matrix<ld, 6, 1>;
  const auto split = [&](const Vec6& y) {
    Vec5 z = y.head<5>();
    return std::pair<Vec5, ld>(z, y(5) * omega_guess);
  };
  const auto g = [&](const Vec6& y) {
    const auto [z, w] = split(y);
    const cld v = condition(eq, z, w);
    Eigen::Matrix<ld, 2, 1> out;
    out << v.real(), v.imag();
    return out;
  };
  const auto residual = [&](const Vec6& y) {
    Vec6 r;
    r << eq.residual(split(y).first), g(y);
    return r;
  };
  const auto jacobian = [&](const Vec6& y) {
    Eigen::Matrix<ld, 6, 6> D = Eigen::Matrix<ld, 6, 6>::Zero();
    D.topLeftCorner<4, 5>() = eq.jacobian(split(y).first);
    for (int k = 0; k < 6; ++k) D.block<2, 1>(4, k) = central_difference<6>(g, y, k);
    return D;
  };
  Vec6 y;
  y << z_guess, 1;
  Located out;
  out.converged = newton<6>(y, residual, jacobian, out.iterations) &&
                  eq.residual(split(y).first).cwiseAbs().maxCoeff() <= 1e-15L && y(5) > 0;
  out.z = split(y).first;
  out.frequency = split(y).second;
  return out;
}

double first_lyapunov_coefficient(const Params& p, const Coordinates<long double, 2>& s, long double omega) {
  using Vec8 = Eigen::Matrix<ld, 8, 1>;
  using Vec8c = Eigen::Matrix<cld, 8, 1>;
  const auto pl = p.cast<ld>();
  const State<ld, 2> x0 = at_rest<ld, 2>(s);
  const Linearization<ld, 2> lin = linearize(pl, x0);
  const Mat4c A = lin.mass.cast<cld>(), Cm = lin.damping.cast<cld>(), K = lin.stiffness.cast<cld>();
  const auto pencil = [&](cld mu) -> Mat4c { return (mu * mu) * A + mu * Cm + K; };
  // Everything through the 4x4 pencil T(mu) = mu^2 A + mu C + K (equilibrated), never the
  // stiff 8x8 J: J = [[0, I], [-A^-1 K, -A^-1 C]] gives
  //   right eigenvector q = (x, i w x),           T(i w) x = 0,
  //   left eigenvector  p = conj(i w v A + v C, v A),  v T(i w) = 0 (v a row),
  //   resolvent (mu - J)^-1 r = (z1, mu z1 - r1), z1 = T(mu)^-1 (A r2 + (mu A + C) r1).
  const cld iw(0, omega);
  const Mat4c T = pencil(iw);
  Eigen::Matrix<ld, 4, 1> rows, cols;
  for (int i = 0; i < 4; ++i) rows(i) = 1 / T.row(i).cwiseAbs().maxCoeff();
  for (int j = 0; j < 4; ++j) cols(j) = 1 / (rows.asDiagonal() * T).col(j).cwiseAbs().maxCoeff();
  const Mat4c Ts = rows.cast<cld>().asDiagonal() * T * cols.cast<cld>().asDiagonal();
  const Eigen::JacobiSVD<Mat4c> svd(Ts, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec4c x = cols.cast<cld>().asDiagonal() * svd.matrixV().col(3);                 // T x = 0
  const Vec4c v = (rows.cast<cld>().asDiagonal() * svd.matrixU().col(3).conjugate());   // v^T T = 0
  Vec8c q;
  q << x, iw * x;
  const Eigen::Matrix<cld, 1, 4> vr = v.transpose();
  Vec8c pv;
  pv << (iw * vr * A + vr * Cm).transpose().conjugate(), (vr * A).transpose().conjugate();
  q /= q.norm();
  pv /= std::conj(pv.dot(q));  // <p, q> = p^H q = 1
  const auto resolvent = [&](cld mu, const Vec8c& r) -> Vec8c {
    const Vec4c r1 = r.head<4>(), r2 = r.tail<4>();
    const Vec4c z1 = pencil(mu).partialPivLu().solve(Vec4c(A * r2 + (mu * A + Cm) * r1));
    Vec8c z;
    z << z1, mu * z1 - r1;
    return z;
  };
  // Symmetric bilinear and trilinear forms of f at x0 (model.md (6.8)-(6.10)), exact: f evaluated
  // at x0 + t u in truncated Taylor series (include/abu/core/taylor.hpp) has the
  // coefficients f(x0), J u, B(u, u)/2 and C(u, u, u)/6, to the rounding of long double.
  // The mixed forms follow by polarization,
  //   B(u, w)    = (B(u+w, u+w) - B(u-w, u-w)) / 4,
  //   C(u, w, y) = (1/24) sum_{e, e' = +-1} e e' C(u + e w + e' y, ...),
  // which is exact algebra, not an approximation (no step size, no truncation error). The
  // finite differences this replaces agreed with themselves to 1.1e-5 only.
  using Jet = Taylor<ld, 3>;
  const ParamsT<Jet, 2> pj = p.cast<Jet>();
  const auto series = [&](const Vec8& u) {  // the Taylor coefficients of f(x0 + t u)
    State<Jet, 2> xt;
    for (int k = 0; k < 8; ++k) {
      xt(k) = Jet(x0(k));
      xt(k).c[1] = u(k);
    }
    return vector_field(pj, xt);
  };
  const auto second = [&](const Vec8& u) -> Vec8 {  // B(u, u) = 2 c_2
    const State<Jet, 2> y = series(u);
    Vec8 out;
    for (int k = 0; k < 8; ++k) out(k) = 2 * y(k).c[2];
    return out;
  };
  const auto third = [&](const Vec8& u) -> Vec8 {  // C(u, u, u) = 6 c_3
    const State<Jet, 2> y = series(u);
    Vec8 out;
    for (int k = 0; k < 8; ++k) out(k) = 6 * y(k).c[3];
    return out;
  };
  const auto B = [&](const Vec8& u, const Vec8& w) -> Vec8 {
    return (second(u + w) - second(u - w)) / 4;
  };
  const auto C3 = [&](const Vec8& u, const Vec8& w, const Vec8& y) -> Vec8 {
    return (third(u + w + y) - third(u + w - y) - third(u - w + y) + third(u - w - y)) / 24;
  };
  const auto Bc = [&](const Vec8c& u, const Vec8c& w) -> Vec8c {  // complex bilinear extension
    const Vec8 ur = u.real(), ui = u.imag(), wr = w.real(), wi = w.imag();
    const Vec8 re = B(ur, wr) - B(ui, wi), im = B(ur, wi) + B(ui, wr);
    return re.cast<cld>() + cld(0, 1) * im.cast<cld>();
  };
  const Vec8 qr = q.real(), qi = q.imag();
  // C(q, q, conj q) = C(a,a,a) + C(a,b,b) + i (C(a,a,b) + C(b,b,b)) for q = a + i b.
  const Vec8c Cqqq =
      (C3(qr, qr, qr) + C3(qr, qi, qi)).cast<cld>() + cld(0, 1) * (C3(qr, qr, qi) + C3(qi, qi, qi)).cast<cld>();
  const Vec8c Bqq = Bc(q, q), Bqqbar = Bc(q, q.conjugate());
  const Vec8c r1 = -resolvent(0, Bqqbar);             // J^-1 B(q, conj q)
  const Vec8c r2 = resolvent(cld(0, 2 * omega), Bqq);  // (2 i w - J)^-1 B(q, q)
  const cld sum = pv.dot(Cqqq) - cld(2) * pv.dot(Bc(q, r1)) + pv.dot(Bc(q.conjugate(), r2));
  return double(sum.real() / (2 * omega));
}

}  // namespace abu
