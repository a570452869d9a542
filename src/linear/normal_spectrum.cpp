// The spectrum at a point of a set of equilibria, deflated by the set's tangent space
// (spectrum.hpp, compute_normal_spectrum; model.md §13.4).
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>
#include <limits>

#include "abu/linear/spectrum.hpp"
#include "spectrum_starts.hpp"

namespace abu {

namespace {

using ld = long double;
using cld = std::complex<ld>;
constexpr int N = any_balls;
constexpr ld kEpsLong = std::numeric_limits<ld>::epsilon() / 2;

using LongMatrix = StateMatrix<ld, N>;  // up to (2 max_balls + 4)^2

// An orthonormal basis of the complement of span(Z) (columns), by Householder QR.
LongMatrix orthogonal_complement(const LongMatrix& Z) {
  const Eigen::HouseholderQR<LongMatrix> qr(Z);
  const LongMatrix Q = qr.householderQ() * LongMatrix::Identity(Z.rows(), Z.rows());
  return Q.rightCols(Z.rows() - Z.cols());
}

// The deflated quadratic problem M(lambda) = M2 lambda^2 + M1 lambda + M0 in the
// coordinates (w, a~) with s = P w + V_T a~ / lambda^level (spectrum.hpp).
Linearization<ld, N> deflated_problem(const Linearization<ld, N>& lin, const LongMatrix& P, const TangentBasis& V,
                                      int level) {
  const Eigen::Index d = lin.mass.rows(), t = V.cols(), w = d - t;
  Linearization<ld, N> m;
  m.mass = DofMatrix<ld, N>::Zero(d, d);
  m.damping = DofMatrix<ld, N>::Zero(d, d);
  m.stiffness = DofMatrix<ld, N>::Zero(d, d);
  m.mass.leftCols(w) = lin.mass * P;
  m.damping.leftCols(w) = lin.damping * P;
  m.stiffness.leftCols(w) = lin.stiffness * P;
  if (level == 1) {
    m.damping.rightCols(t) = lin.mass * V;
    m.stiffness.rightCols(t) = lin.damping * V;
  } else {
    m.stiffness.rightCols(t) = lin.mass * V;
  }
  return m;
}

// A start vector for Newton on M(lambda0) x = 0: two steps of inverse iteration in
// long double on the equilibrated matrix (the QR's own vectors live in the deflated
// first-order coordinates, not in these).
QepVector<N> inverse_iteration(const Linearization<ld, N>& m, std::complex<double> lambda0) {
  const Eigen::Index d = m.mass.rows();
  using MatC = Eigen::Matrix<cld, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, max_balls + 2, max_balls + 2>;
  using VecC = Eigen::Matrix<cld, Eigen::Dynamic, 1, Eigen::ColMajor, max_balls + 2, 1>;
  const cld l(lambda0.real(), lambda0.imag());
  const ld a = std::abs(l);
  Coordinates<ld, N> rows, cols;
  equilibrate<N>(DofMatrix<ld, N>(a * a * m.mass.cwiseAbs() + a * m.damping.cwiseAbs() + m.stiffness.cwiseAbs()), rows,
                 cols);
  QepVector<N> out = QepVector<N>::Ones(d);
  for (int attempt = 0; attempt < 3; ++attempt) {
    const cld shifted = l * ld(1 + attempt * 1e-13);  // off an exact eigenvalue's zero pivot
    const MatC t = rows.cast<cld>().asDiagonal() *
                   (shifted * shifted * m.mass.cast<cld>() + shifted * m.damping.cast<cld>() + m.stiffness.cast<cld>()) *
                   cols.cast<cld>().asDiagonal();
    const Eigen::PartialPivLU<MatC> lu(t);
    VecC v = VecC::Ones(d);
    for (int step = 0; step < 2; ++step) {
      v = lu.solve(v);
      v /= v.cwiseAbs().maxCoeff();
    }
    if (!v.allFinite()) continue;
    for (Eigen::Index i = 0; i < d; ++i) {
      const cld x = v(i) * cols(i);
      out(i) = {double(x.real()), double(x.imag())};
    }
    break;
  }
  if (!out.allFinite() || out.isZero(0)) out = QepVector<N>::Ones(d);
  return out;
}

}  // namespace

SpectrumN compute_normal_spectrum(const Linearization<ld, N>& lin, const TangentBasis& V, SpectrumMethod method) {
  using namespace spectrum_detail;
  const Eigen::Index d = lin.mass.rows(), t = V.cols();
  // Friction without slope leaves C V_T = 0 (the balls drift along the set): the zeros
  // pair into Jordan chains, J (0, v) = (v, 0) and deflate twice (model.md §13.4).
  const ld cv = (lin.damping * V).norm();
  const int level = cv <= 64 * kEpsLong * lin.damping.norm() ? 2 : 1;
  const int structural = int(level * t);
  // The first-order matrix J on the complement of the deflated invariant subspace, in
  // long double: Z = span{(v, 0)} (and {(0, v)} at level 2), J Z within Z.
  LongMatrix J = LongMatrix::Zero(2 * d, 2 * d);
  J.block(0, d, d, d).setIdentity();
  const Eigen::LLT<DofMatrix<ld, N>> a(lin.mass);
  J.block(d, 0, d, d) = -a.solve(lin.stiffness);
  J.block(d, d, d, d) = -a.solve(lin.damping);
  LongMatrix Z = LongMatrix::Zero(2 * d, structural);
  Z.block(0, 0, d, t) = V;
  if (level == 2) Z.block(d, t, d, t) = V;
  const LongMatrix VN = orthogonal_complement(Z);
  const LongMatrix JN = VN.transpose() * J * VN;
  const int count = int(JN.rows());

  Starts<N> starts;
  if (!balanced_qr<N>(JN.cast<double>(), starts.direct))
    starts.status.merge(Outcome::numerical_issue,
                        "the QR of the deflated J failed (not finite, GSL's balancing or the QR failed)");
  bool have_inverse = false;
  ld sigma = 0;
  if (method != SpectrumMethod::dense_qr) {
    for (int attempt = 0; attempt < 2 && !have_inverse; ++attempt) {
      if (attempt == 1) sigma = -ld(std::numeric_limits<double>::epsilon() / 2 * starts.direct.norm);
      const Eigen::PartialPivLU<LongMatrix> lu(LongMatrix(JN - sigma * LongMatrix::Identity(count, count)));
      if (!(lu.rcond() > 64 * kEpsLong)) continue;
      have_inverse = balanced_qr<N>(lu.inverse().cast<double>(), starts.inverse);
    }
  }
  combine_starts(count, have_inverse, double(sigma), starts);

  // P: an orthonormal complement of V_T in configuration space.
  LongMatrix Vt = V;
  const LongMatrix P = orthogonal_complement(Vt);
  const Linearization<ld, N> deflated = deflated_problem(lin, P, V, level);
  SpectrumN sp;
  sp.count = int(2 * d);
  sp.status = starts.status;
  std::array<ld, SpectrumN::capacity> band{};
  const VectorSource<N> vector_of = [&deflated](const Estimate<N>& e, bool) {
    return inverse_iteration(deflated, e.value);
  };
  assemble_spectrum(deflated, starts, method, vector_of, sp, band);
  // The structural zeros, exactly 0, with their tangent vectors.
  for (int k = 0; k < structural; ++k) {
    const auto i = std::size_t(k);
    sp.eigenvalues[i] = 0;
    sp.structural[i] = true;
    sp.error[i] = 0;
    sp.condition[i] = 0;
    sp.vectors[i] = V.col(k % t).cast<std::complex<double>>();
  }
  // The normal eigenvectors back in configuration space: s = P w + V_T a~ / lambda^level.
  const Eigen::Index w = d - t;
  for (std::size_t i = std::size_t(structural); i < std::size_t(sp.count); ++i) {
    const std::complex<double> l = sp.eigenvalues[i];
    const QepVector<N> z = sp.vectors[i];
    if (z.size() != d || l == 0.0) continue;
    const std::complex<double> lv = level == 1 ? l : l * l;
    const QepVector<N> s = P.cast<std::complex<double>>() * z.head(w) + V.cast<std::complex<double>>() * z.tail(t) / lv;
    sp.vectors[i] = s.normalized();
  }
  finish_spectrum(sp, band, 0);
  return sp;
}

}  // namespace abu
