#include "spectrum_starts.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "abu/core/gsl_errors.hpp"

namespace abu::spectrum_detail {

namespace {

using ld = long double;

// GSL's default handler aborts (gsl_errors.hpp): off before main() in every program that
// links the spectra, which is every program that analyses anything.
[[maybe_unused]] const bool gsl_quiet_at_start = (quiet_gsl_errors(), true);

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff 2^-53
constexpr ld kEpsLong = std::numeric_limits<ld>::epsilon() / 2;

template <int N>
using FirstOrderLong = StateMatrix<ld, N>;

// First-order form J = [[0, I], [-A^-1 K, -A^-1 C]].
template <int N>
FirstOrderMatrix<N> companion(const Linearization<ld, N>& lin) {
  const Eigen::Index d = dofs_of<N>(lin.mass.rows());
  FirstOrderLong<N> J = FirstOrderLong<N>::Zero(2 * d, 2 * d);
  J.block(0, d, d, d).setIdentity();
  const Eigen::LLT<DofMatrix<ld, N>> a(lin.mass);
  J.block(d, 0, d, d) = -a.solve(lin.stiffness);
  J.block(d, d, d, d) = -a.solve(lin.damping);
  return J.template cast<double>();
}

// Shift-and-invert in structured form: with lambda = sigma + mu the quadratic problem
// keeps its form, mu^2 A + mu (C + 2 sigma A) + T(sigma), so
//   (J - sigma I)^-1 = [[-T(sigma)^-1 (C + 2 sigma A), -T(sigma)^-1 A], [I, 0]],
// formed in long double; its eigenvectors are those of J. sigma = 0 is the plain
// structured inverse of model.md §8. False if T(sigma) is numerically singular.
template <int N>
bool shifted_inverse(const Linearization<ld, N>& lin, ld sigma, FirstOrderMatrix<N>& out) {
  const Eigen::Index d = dofs_of<N>(lin.mass.rows());
  const DofMatrix<ld, N> t = sigma * sigma * lin.mass + sigma * lin.damping + lin.stiffness;
  // Judge and factor T(sigma) equilibrated, T = R^-1 Te D^-1: unscaled, its rotor rows
  // can be 1e10 larger than the ball rows and rcond would call it singular when it is not.
  Coordinates<ld, N> rows, cols;
  equilibrate<N>(DofMatrix<ld, N>(t.cwiseAbs()), rows, cols);
  const Eigen::PartialPivLU<DofMatrix<ld, N>> lu(DofMatrix<ld, N>(rows.asDiagonal() * t * cols.asDiagonal()));
  if (!(lu.rcond() > 64 * kEpsLong)) return false;
  const auto solve = [&](const DofMatrix<ld, N>& rhs) -> DofMatrix<ld, N> {
    return cols.asDiagonal() * lu.solve(DofMatrix<ld, N>(rows.asDiagonal() * rhs));
  };
  FirstOrderLong<N> Ji = FirstOrderLong<N>::Zero(2 * d, 2 * d);
  Ji.block(0, 0, d, d) = -solve(DofMatrix<ld, N>(lin.damping + 2 * sigma * lin.mass));
  Ji.block(0, d, d, d) = -solve(lin.mass);
  Ji.block(d, 0, d, d).setIdentity();
  out = Ji.template cast<double>();
  return out.allFinite();
}

}  // namespace

template <int N>
bool balanced_qr(const FirstOrderMatrix<N>& m, BalancedQr<N>& r) {
  const auto n = std::size_t(m.rows());
  r.balanced = m;
  // GSL's balancing loops forever once a row or column sum overflows (its scaling loop
  // divides an infinite norm by 4 until it is small): entries beyond 1e150 are refused,
  // their sums stay finite (--set omega=1e155 hung).
  if (!r.balanced.allFinite() || !(r.balanced.cwiseAbs().maxCoeff() <= 1e150)) return false;
  quiet_gsl_errors();  // (a no-op after static initialization)
  gsl_matrix_view view = gsl_matrix_view_array(r.balanced.data(), n, n);
  gsl_vector_view dv = gsl_vector_view_array(r.scale.data(), n);
  if (gsl_linalg_balance_matrix(&view.matrix, &dv.vector) != GSL_SUCCESS) return false;
  using ColMajor = Eigen::Matrix<double, state_size<N>, state_size<N>, Eigen::ColMajor, state_capacity<N>,
                                 state_capacity<N>>;
  const Eigen::EigenSolver<ColMajor> solver(ColMajor(r.balanced), false);
  for (std::size_t i = 0; i < n; ++i) r.values[i] = solver.eigenvalues()(Eigen::Index(i));
  r.norm = r.balanced.norm();
  return solver.info() == Eigen::Success;
}

template <int N>
void combine_starts(int count, bool have_inverse, double shift, Starts<N>& out) {
  const std::size_t m = eigen_count<N>(count);
  out.count = count;
  out.shift = shift;
  std::array<Estimate<N>, state_capacity<N>> direct{};
  for (std::size_t i = 0; i < m; ++i) direct[i] = {out.direct.values[i], out.direct.values[i], &out.direct};
  out.estimates = direct;
  if (!have_inverse) return;
  out.inverse.inverse = true;
  out.inverse.shift = shift;
  std::array<Estimate<N>, state_capacity<N>> inverse{};
  for (std::size_t i = 0; i < m; ++i) {
    const auto mu = out.inverse.values[i];
    inverse[i] = {mu == 0.0 ? std::complex<double>(std::numeric_limits<double>::max()) : shift + 1.0 / mu, mu,
                  &out.inverse};
  }
  const auto by_distance = [shift](const Estimate<N>& a, const Estimate<N>& b) {
    const double da = std::abs(a.value - shift), db = std::abs(b.value - shift);
    return da < db || (da == db && a.value.imag() > b.value.imag());
  };
  const auto end = std::ptrdiff_t(m);
  std::sort(direct.begin(), direct.begin() + end, by_distance);
  std::sort(inverse.begin(), inverse.begin() + end, by_distance);
  const double crossover = std::sqrt(out.direct.norm / out.inverse.norm);
  std::size_t k = 0;
  while (k < m && std::abs(inverse[k].value - shift) < crossover) ++k;
  // Keep complex-conjugate pairs on one side of the split.
  const auto splits_pair = [&k, m](const std::array<Estimate<N>, state_capacity<N>>& v) {
    return k > 0 && k < m && v[k - 1].value.imag() != 0 && v[k].value == std::conj(v[k - 1].value);
  };
  if (splits_pair(inverse)) ++k;
  if (splits_pair(direct)) --k;
  for (std::size_t i = 0; i < m; ++i) out.estimates[i] = i < k ? inverse[i] : direct[i];
}

template <int N>
double apriori_error(const Estimate<N>& e) {
  if (!e.source) return std::numeric_limits<double>::infinity();
  if (!e.source->inverse) return kEps * e.source->norm;
  return kEps * e.source->norm * std::norm(e.value - e.source->shift);
}

template <int N>
bool middle_starts(const Linearization<ld, N>& lin, double sigma, const std::array<bool, state_capacity<N>>& failed,
                   const std::array<std::complex<double>, state_capacity<N>>& kept, Starts<N>& out) {
  const std::size_t m = eigen_count<N>(out.count);
  FirstOrderMatrix<N> jinv;
  if (!shifted_inverse(lin, ld(sigma), jinv) || !balanced_qr<N>(jinv, out.middle)) return false;
  out.middle.inverse = true;
  out.middle.shift = sigma;
  std::array<Estimate<N>, state_capacity<N>> candidate{};
  std::array<bool, state_capacity<N>> taken{};
  for (std::size_t i = 0; i < m; ++i) {
    const auto theta = out.middle.values[i];
    if (theta == 0.0 || !std::isfinite(std::abs(theta))) return false;
    candidate[i] = {sigma + 1.0 / theta, theta, &out.middle};
  }
  // Each kept eigenvalue claims its copy in this QR, the nearest pair first: first among
  // the candidates it is compatible with (within 1e4 times the candidate's a-priori
  // error), then among the rest. (Nearest alone let a kept -8 + 150i claim a creep mode
  // resolved to 1e-31 at 2e-15 rather than the QR's unresolved value 20 away from it, and
  // the failed slot got that unresolved value.)
  std::array<bool, state_capacity<N>> claimed{};
  std::size_t n_failed = 0;
  for (std::size_t j = 0; j < m; ++j) n_failed += failed[j] ? 1 : 0;
  for (const bool compatible_only : {true, false}) {
    for (;;) {
      std::size_t best_i = m, best_j = m;
      double best_distance = 0;
      for (std::size_t j = 0; j < m; ++j) {
        if (failed[j] || claimed[j]) continue;
        for (std::size_t i = 0; i < m; ++i) {
          const double distance = std::abs(candidate[i].value - kept[j]);
          if (taken[i] || (compatible_only && !(distance <= 1e4 * apriori_error(candidate[i])))) continue;
          if (best_i == m || distance < best_distance) best_i = i, best_j = j, best_distance = distance;
        }
      }
      if (best_i == m) break;
      taken[best_i] = claimed[best_j] = true;
    }
  }
  for (std::size_t j = 0; j < m; ++j)
    if (!failed[j] && !claimed[j]) return false;
  // The failed slots get what is left, closest to sigma first (best resolved there).
  std::array<std::size_t, state_capacity<N>> left{};
  std::size_t n_left = 0;
  for (std::size_t i = 0; i < m; ++i)
    if (!taken[i]) left[n_left++] = i;
  if (n_left != n_failed) return false;
  const auto closer = [&](std::size_t a, std::size_t b) {
    const double da = std::abs(candidate[a].value - sigma), db = std::abs(candidate[b].value - sigma);
    return da < db || (da == db && candidate[a].value.imag() > candidate[b].value.imag());
  };
  for (std::size_t i = 1; i < n_left && i < m; ++i)  // (insertion sort: n_left <= 8 .. 26)
    for (std::size_t k = i; k > 0 && closer(left[k], left[k - 1]); --k) std::swap(left[k], left[k - 1]);
  // The kept ones start from their refined values: a QR value that refined far from
  // itself (inside the old basin) would leave the basin the new starts draw.
  std::size_t next = 0;
  for (std::size_t j = 0; j < m; ++j) {
    if (failed[j]) out.estimates[j] = candidate[left[next++]];
    else out.estimates[j].value = kept[j];
  }
  // Conjugate pairs must be whole (the assembly refines one and mirrors the other).
  for (std::size_t j = 0; j < m; ++j) {
    const auto z = out.estimates[j].value;
    if (z.imag() == 0) continue;
    bool partner = false;
    for (std::size_t i = 0; i < m && !partner; ++i) partner = i != j && out.estimates[i].value == std::conj(z);
    if (!partner) return false;
  }
  return true;
}

// If K is singular (a zero eigenvalue: U = 0 circles, folds), the shift moves to
// sigma = -eps ||J||, the level below which the direct QR cannot resolve anything.
template <int N>
void starting_values(const Linearization<ld, N>& lin, SpectrumMethod method, Starts<N>& out) {
  const int count = int(2 * lin.mass.rows());
  if (!balanced_qr<N>(companion(lin), out.direct))
    out.status.merge(Outcome::numerical_issue, "the QR of J failed (J not finite, GSL's balancing or the QR failed)");
  if (method == SpectrumMethod::dense_qr) return combine_starts(count, false, 0, out);
  FirstOrderMatrix<N> jinv;
  ld sigma = 0;
  if (!shifted_inverse(lin, sigma, jinv)) {
    sigma = -ld(kEps * out.direct.norm);
    if (!shifted_inverse(lin, sigma, jinv)) return combine_starts(count, false, 0, out);
  }
  if (!balanced_qr<N>(jinv, out.inverse))
    out.status.merge(Outcome::numerical_issue,
                     "the QR of J's structured inverse failed (GSL's balancing or the QR failed)");
  combine_starts(count, true, double(sigma), out);
}

// On the balanced matrix the decoupled modes of equal balls are as well separated as the
// QR saw them, while T(lambda) can be singular to working precision (its 1e-20 ball
// stiffness lost against the rotor coupling).
template <class S, int N>
QepVector<N> position_vector(const Estimate<N>& e) {
  using MatS = Eigen::Matrix<S, state_size<N>, state_size<N>, Eigen::ColMajor, state_capacity<N>, state_capacity<N>>;
  using VecS = Eigen::Matrix<S, state_size<N>, 1, Eigen::ColMajor, state_capacity<N>, 1>;
  const Eigen::Index d = dofs_of<N>(e.source->balanced.rows() / 2), m = 2 * d;
  S theta;
  if constexpr (std::is_same_v<S, double>) {
    theta = e.theta.real();
  } else {
    theta = e.theta;
  }
  VecS v = VecS::Ones(m);
  for (int attempt = 0; attempt < 3; ++attempt) {
    // Exactly on the eigenvalue the LU can meet a zero pivot: nudge theta off it.
    const S shifted = theta * S(1 + attempt * 1e-13);
    const MatS a = e.source->balanced.template cast<S>() - shifted * MatS::Identity(m, m);
    const Eigen::PartialPivLU<MatS> lu(a);
    VecS w = VecS::Ones(m);
    for (int step = 0; step < 2; ++step) {
      w = lu.solve(w);
      w /= S(w.cwiseAbs().maxCoeff());
    }
    if (w.allFinite()) {
      v = w;
      break;
    }
  }
  Eigen::Matrix<std::complex<double>, state_size<N>, 1, Eigen::ColMajor, state_capacity<N>, 1> full(m);
  for (Eigen::Index k = 0; k < m; ++k) full(k) = std::complex<double>(v(k)) * e.source->scale[std::size_t(k)];
  const std::complex<double> lambda = e.value;
  QepVector<N> x = std::abs(lambda) > 1 ? QepVector<N>(full.segment(d, d) / lambda) : QepVector<N>(full.head(d));
  if (!x.allFinite() || x.isZero(0)) x = QepVector<N>::Ones(d);
  return x;
}

#define ABU_INSTANTIATE_STARTS(N)                                                                   \
  template bool balanced_qr<N>(const FirstOrderMatrix<N>&, BalancedQr<N>&);                         \
  template void combine_starts<N>(int, bool, double, Starts<N>&);                                   \
  template double apriori_error<N>(const Estimate<N>&);                                             \
  template bool middle_starts<N>(const Linearization<ld, N>&, double, const std::array<bool, state_capacity<N>>&, \
                                 const std::array<std::complex<double>, state_capacity<N>>&, Starts<N>&);          \
  template void starting_values<N>(const Linearization<ld, N>&, SpectrumMethod, Starts<N>&);        \
  template QepVector<N> position_vector<double, N>(const Estimate<N>&);                             \
  template QepVector<N> position_vector<std::complex<double>, N>(const Estimate<N>&);
ABU_INSTANTIATE_STARTS(2)
ABU_INSTANTIATE_STARTS(any_balls)
#undef ABU_INSTANTIATE_STARTS

}  // namespace abu::spectrum_detail
