#include "abu/spectrum.hpp"

#include <gsl/gsl_linalg.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace abu {

namespace {

using ld = long double;
using cld = std::complex<ld>;
using Mat4 = Eigen::Matrix<ld, 4, 4>;
using Mat8d = Eigen::Matrix<double, 8, 8, Eigen::RowMajor>;
constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff 2^-53
constexpr ld kEpsLong = std::numeric_limits<ld>::epsilon() / 2;

// A starting value: an eigenvalue and the position part x of its eigenvector
// v = (x, lambda x), from a double-precision QR.
using Vec4c = Eigen::Matrix<std::complex<double>, 4, 1>;
struct Estimate {
  std::complex<double> value;
  Vec4c vector = Vec4c::Ones();
};

// QR eigenvalues (and eigenvectors) of a matrix after Parlett-Reinsch balancing
// (GSL): Eigen's EigenSolver does not balance, and the Jacobian's rows differ by 1e15
// in scale. `norm` is the Frobenius norm of the balanced matrix: the absolute error of
// each eigenvalue is about eps * norm.
struct QrResult {
  std::array<Estimate, 8> estimates;
  double norm;
};
QrResult balanced_qr(Mat8d m, bool vectors) {
  gsl_matrix_view view = gsl_matrix_view_array(m.data(), 8, 8);
  std::array<double, 8> d{};
  gsl_vector_view dv = gsl_vector_view_array(d.data(), 8);
  gsl_linalg_balance_matrix(&view.matrix, &dv.vector);
  Eigen::EigenSolver<Eigen::Matrix<double, 8, 8>> solver(m, vectors);
  QrResult r{};
  for (int i = 0; i < 8; ++i) {
    auto& e = r.estimates[std::size_t(i)];
    e.value = solver.eigenvalues()(i);
    if (!vectors) continue;
    // Undo the balancing; take x from whichever half of (x, lambda x) is larger.
    Eigen::Matrix<std::complex<double>, 8, 1> v = solver.eigenvectors().col(i);
    for (int k = 0; k < 8; ++k) v(k) *= d[std::size_t(k)];
    e.vector = std::abs(e.value) > 1 ? Vec4c(v.tail<4>() / e.value) : Vec4c(v.head<4>());
    if (!e.vector.allFinite() || e.vector.isZero(0)) e.vector = Vec4c::Ones();
  }
  r.norm = m.norm();
  return r;
}

// First-order form J = [[0, I], [-A^-1 K, -A^-1 C]].
Mat8d companion(const Linearization<ld, 2>& lin) {
  Eigen::Matrix<ld, 8, 8> J = Eigen::Matrix<ld, 8, 8>::Zero();
  J.block<4, 4>(0, 4).setIdentity();
  const Eigen::LLT<Mat4> a(lin.mass);
  J.block<4, 4>(4, 0) = -a.solve(lin.stiffness);
  J.block<4, 4>(4, 4) = -a.solve(lin.damping);
  return J.cast<double>();
}

// Shift-and-invert in structured form: with lambda = sigma + mu the quadratic problem
// keeps its form, mu^2 A + mu (C + 2 sigma A) + T(sigma), so
//   (J - sigma I)^-1 = [[-T(sigma)^-1 (C + 2 sigma A), -T(sigma)^-1 A], [I, 0]],
// formed in long double; its eigenvectors are those of J. sigma = 0 is the plain
// structured inverse of model.md §8. False if T(sigma) is numerically singular.
bool shifted_inverse(const Linearization<ld, 2>& lin, ld sigma, Mat8d& out) {
  const Mat4 t = sigma * sigma * lin.mass + sigma * lin.damping + lin.stiffness;
  const Eigen::PartialPivLU<Mat4> lu(t);
  if (!(lu.rcond() > 64 * kEpsLong)) return false;
  Eigen::Matrix<ld, 8, 8> Ji = Eigen::Matrix<ld, 8, 8>::Zero();
  Ji.block<4, 4>(0, 0) = -lu.solve(Mat4(lin.damping + 2 * sigma * lin.mass));
  Ji.block<4, 4>(0, 4) = -lu.solve(lin.mass);
  Ji.block<4, 4>(4, 0).setIdentity();
  out = Ji.cast<double>();
  return out.allFinite();
}

// Starting values: every eigenvalue from the QR whose error bound relative to it is
// smaller: eps ||J|| from J, eps ||(J - sigma)^-1|| |lambda - sigma|^2 from the inverse.
// Sorting both lists by distance to sigma pairs them; the k closest come from the
// inverse, k counting its values inside the crossover radius sqrt(||J|| / ||J^-1||).
// If K is singular (a zero eigenvalue: U = 0 circles, folds), the shift moves to
// sigma = -eps ||J||, the level below which the direct QR cannot resolve anything.
std::array<Estimate, 8> starting_values(const Linearization<ld, 2>& lin, SpectrumMethod method) {
  const bool vectors = method == SpectrumMethod::refined;
  QrResult direct = balanced_qr(companion(lin), vectors);
  if (method == SpectrumMethod::dense_qr) return direct.estimates;
  Mat8d jinv;
  ld sigma = 0;
  if (!shifted_inverse(lin, sigma, jinv)) {
    sigma = -ld(kEps * direct.norm);
    if (!shifted_inverse(lin, sigma, jinv)) return direct.estimates;
  }
  QrResult inverse = balanced_qr(jinv, vectors);
  const double shift = double(sigma);
  for (auto& e : inverse.estimates)
    e.value = (e.value == 0.0) ? std::complex<double>(std::numeric_limits<double>::max()) : shift + 1.0 / e.value;
  const auto by_distance = [shift](const Estimate& a, const Estimate& b) {
    const double da = std::abs(a.value - shift), db = std::abs(b.value - shift);
    return da < db || (da == db && a.value.imag() > b.value.imag());
  };
  std::sort(direct.estimates.begin(), direct.estimates.end(), by_distance);
  std::sort(inverse.estimates.begin(), inverse.estimates.end(), by_distance);
  const double crossover = std::sqrt(direct.norm / inverse.norm);
  std::size_t k = 0;
  while (k < 8 && std::abs(inverse.estimates[k].value - shift) < crossover) ++k;
  // Keep complex-conjugate pairs on one side of the split.
  const auto splits_pair = [&k](const std::array<Estimate, 8>& v) {
    return k > 0 && k < 8 && v[k - 1].value.imag() != 0 && v[k].value == std::conj(v[k - 1].value);
  };
  if (splits_pair(inverse.estimates)) ++k;
  if (splits_pair(direct.estimates)) --k;
  std::array<Estimate, 8> start{};
  for (std::size_t i = 0; i < 8; ++i) start[i] = i < k ? inverse.estimates[i] : direct.estimates[i];
  return start;
}

// Newton on T(lambda) x = 0 for one eigenvalue, in long double; real arithmetic for a
// real starting value keeps real eigenvalues exactly real.
struct Refined {
  cld value;
  ld backward_error;  // componentwise, eta
  ld abs_condition;   // y* S |x| / |y* T' x|, S = |lambda|^2 |A| + |lambda| |C| + |K|
  bool converged;
};

// Diagonal equilibration R |T(lambda0)| D ~ O(1) (powers of two, a few Sinkhorn-style
// sweeps): the ball rows of T can be 1e10 smaller than the rotor rows (tiny balls),
// which would make pivoting treat them as zero. Eigenvalues, the componentwise
// backward error and the componentwise condition number are all invariant under it.
void equilibrate(const Mat4& magnitude, Eigen::Matrix<ld, 4, 1>& rows, Eigen::Matrix<ld, 4, 1>& cols) {
  rows.setOnes();
  cols.setOnes();
  const auto pow2 = [](ld v) { return v > 0 && std::isfinite(v) ? std::exp2(std::round(std::log2(v))) : ld(1); };
  for (int sweep = 0; sweep < 3; ++sweep) {
    for (int i = 0; i < 4; ++i) rows(i) = pow2(1 / (magnitude.row(i).transpose().cwiseProduct(cols)).maxCoeff());
    for (int j = 0; j < 4; ++j) cols(j) = pow2(1 / (magnitude.col(j).cwiseProduct(rows)).maxCoeff());
  }
}

template <class S>
S from_complex(std::complex<double> z) {
  if constexpr (std::is_same_v<S, ld>) {
    return ld(z.real());
  } else {
    return S(z.real(), z.imag());
  }
}

template <class S>
Refined refine(const Linearization<ld, 2>& lin, const Estimate& start) {
  using Vec4 = Eigen::Matrix<S, 4, 1>;
  using Mat4s = Eigen::Matrix<S, 4, 4>;
  using Mat5s = Eigen::Matrix<S, 5, 5>;
  S lambda = from_complex<S>(start.value);
  Eigen::Matrix<ld, 4, 1> rows, cols;
  {
    const ld a = std::abs(lambda);
    equilibrate(a * a * lin.mass.cwiseAbs() + a * lin.damping.cwiseAbs() + lin.stiffness.cwiseAbs(), rows, cols);
  }
  const Mat4 Ar = rows.asDiagonal() * lin.mass * cols.asDiagonal();
  const Mat4 Cr = rows.asDiagonal() * lin.damping * cols.asDiagonal();
  const Mat4 Kr = rows.asDiagonal() * lin.stiffness * cols.asDiagonal();
  const Mat4s A = Ar.cast<S>(), C = Cr.cast<S>(), K = Kr.cast<S>();
  const Mat4 absA = Ar.cwiseAbs(), absC = Cr.cwiseAbs(), absK = Kr.cwiseAbs();
  const auto T = [&](S l) -> Mat4s { return (l * l) * A + l * C + K; };
  const auto dT = [&](S l) -> Mat4s { return S(2) * l * A + C; };
  const auto magnitude = [&](S l) -> Mat4 {
    const ld a = std::abs(l);
    return a * a * absA + a * absC + absK;
  };
  // The QR's eigenvector in the equilibrated coordinates, sharpened by two steps of
  // inverse iteration (the QR vector can carry rounding noise in components that are
  // exactly zero, e.g. q for the decoupled mode of two equal balls); kept as is where T
  // is singular to working precision.
  Vec4 x;
  for (int i = 0; i < 4; ++i) x(i) = from_complex<S>(start.vector(i)) / S(cols(i));
  x /= S(x.cwiseAbs().maxCoeff());
  for (int i = 0; i < 2; ++i) {
    const Vec4 sharper = T(lambda).partialPivLu().solve(x);
    if (!sharper.allFinite() || sharper.isZero(0)) break;
    x = sharper / S(sharper.cwiseAbs().maxCoeff());
  }
  // Normalization c^H x = 1 with c the starting vector itself: unlike pinning one
  // entry, it cannot select a component that is noise in the start.
  x /= S(x.norm());
  const Vec4 c = x;
  // Bordered Newton: B = [T, T' x; c^H, 0], B [dx; dl] = [-T x; 0], the first four rows
  // scaled by the componentwise magnitude so the pivoting sees comparable rows. Near a
  // simple eigenvalue B is well conditioned even where T is singular to working
  // precision (decoupled ball modes of equal balls).
  const auto bordered = [&](S l, const Vec4& v, Eigen::Matrix<ld, 4, 1>& row_weight) {
    const Eigen::Matrix<ld, 4, 1> scale = magnitude(l) * v.cwiseAbs();
    Mat5s B = Mat5s::Zero();
    B.template topLeftCorner<4, 4>() = T(l);
    B.template topRightCorner<4, 1>() = dT(l) * v;
    for (int i = 0; i < 4; ++i) {
      row_weight(i) = scale(i) > 0 ? 1 / scale(i) : 1;
      B.row(i) *= S(row_weight(i));
    }
    B.template bottomLeftCorner<1, 4>() = c.adjoint();
    return B;
  };
  // Quadratic convergence ends at the rounding level, where the steps stop shrinking;
  // whether that level is good enough is judged below against the error bound.
  ld last_step = std::numeric_limits<ld>::infinity();
  ld final_step = last_step;
  Eigen::Matrix<ld, 4, 1> weight;
  for (int it = 0; it < 16; ++it) {
    const Mat5s B = bordered(lambda, x, weight);
    Eigen::Matrix<S, 5, 1> rhs = Eigen::Matrix<S, 5, 1>::Zero();
    rhs.template head<4>() = -(T(lambda) * x);
    for (int i = 0; i < 4; ++i) rhs(i) *= S(weight(i));
    const Eigen::Matrix<S, 5, 1> step = B.partialPivLu().solve(rhs);
    if (!step.allFinite()) break;
    const ld dl = std::abs(step(4));
    lambda += step(4);
    x += step.template head<4>();
    final_step = std::min(dl, last_step);
    if (dl <= 4 * kEpsLong * std::abs(lambda) || (it >= 2 && dl > last_step / 2)) break;
    last_step = dl;
  }
  // Left vector from the adjoint bordered system: B^H [y; eta] = e_5 gives
  // T^H y = -eta c with eta ~ (T x)^H y / (c^H x) ~ 0: y is the left null vector of T.
  Vec4 y;
  {
    const Mat5s B = bordered(lambda, x, weight);
    Eigen::Matrix<S, 5, 1> e5 = Eigen::Matrix<S, 5, 1>::Zero();
    e5(4) = S(1);
    const Eigen::Matrix<S, 5, 1> z = B.partialPivLu().adjoint().solve(e5);
    for (int i = 0; i < 4; ++i) y(i) = z(i) * S(weight(i));  // undo the row weighting
    if (!y.allFinite() || y.isZero(0)) y = x;
  }
  const Mat4 S_mag = magnitude(lambda);
  const Vec4 r = T(lambda) * x;
  const Eigen::Matrix<ld, 4, 1> denom = S_mag * x.cwiseAbs();
  ld eta = 0;
  for (int i = 0; i < 4; ++i) eta = std::max(eta, denom(i) > 0 ? std::abs(r(i)) / denom(i) : ld(0));
  const ld num = y.cwiseAbs().dot(S_mag * x.cwiseAbs());
  const ld den = std::abs(y.dot(dT(lambda) * x));  // dot() conjugates its first argument
  const ld abs_condition = den > 0 ? num / den : std::numeric_limits<ld>::infinity();
  eta = std::max(eta, kEpsLong);
  // Converged: the last Newton step is at the rounding level of the eigenvalue itself or
  // below its first-order error bound (a zero eigenvalue has no relative rounding level).
  const bool converged = std::isfinite(std::abs(lambda)) &&
                         (final_step <= 1e3L * kEpsLong * std::abs(lambda) || final_step <= 8 * abs_condition * eta);
  return {cld(lambda), eta, abs_condition, converged};
}

void sort_and_classify(Spectrum& sp, const std::array<ld, 8>& band) {
  std::array<int, 8> order{};
  for (int i = 0; i < 8; ++i) order[std::size_t(i)] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto& x = sp.eigenvalues[std::size_t(a)];
    const auto& y = sp.eigenvalues[std::size_t(b)];
    return x.real() > y.real() || (x.real() == y.real() && x.imag() > y.imag());
  });
  Spectrum sorted = sp;
  for (std::size_t i = 0; i < 8; ++i) {
    const auto k = std::size_t(order[i]);
    sorted.eigenvalues[i] = sp.eigenvalues[k];
    sorted.error[i] = sp.error[k];
    sorted.condition[i] = sp.condition[k];
    const double re = sp.eigenvalues[k].real();
    sorted.on_axis[i] = std::abs(re) <= double(band[k]);
  }
  sp = sorted;
  sp.n_unstable = sp.n_marginal = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    if (sp.on_axis[i]) {
      ++sp.n_marginal;
    } else if (sp.eigenvalues[i].real() > 0) {
      ++sp.n_unstable;
    }
  }
  sp.abscissa = sp.eigenvalues[0].real();
  sp.stability = sp.n_unstable > 0 ? Stability::unstable : sp.n_marginal > 0 ? Stability::marginal : Stability::stable;
}

}  // namespace

std::string_view to_string(Stability s) {
  switch (s) {
    case Stability::stable: return "stable";
    case Stability::unstable: return "unstable";
    case Stability::marginal: return "marginal";
  }
  return "?";
}

std::string_view to_string(SpectrumMethod m) {
  switch (m) {
    case SpectrumMethod::dense_qr: return "dense-qr";
    case SpectrumMethod::structured: return "structured";
    case SpectrumMethod::refined: return "refined";
  }
  return "?";
}

Spectrum compute_spectrum(const Linearization<ld, 2>& lin, SpectrumMethod method) {
  const auto start = starting_values(lin, method);
  Spectrum sp;
  std::array<ld, 8> band{};
  if (method != SpectrumMethod::refined) {
    // QR only: the a-priori bound eps |lambda| stands in for the error estimate.
    for (std::size_t i = 0; i < 8; ++i) {
      sp.eigenvalues[i] = start[i].value;
      sp.error[i] = kEps * std::abs(start[i].value);
      sp.condition[i] = 1;
      band[i] = ld(8 * kEps * std::abs(start[i].value));
    }
    sp.converged = false;
    sort_and_classify(sp, band);
    return sp;
  }
  std::array<bool, 8> filled{};
  std::array<cld, 8> refined{};
  const auto fill = [&](std::size_t k, cld v, const Refined& r) {
    const ld modulus = std::abs(v);
    refined[k] = v;
    sp.eigenvalues[k] = {double(v.real()), double(v.imag())};
    sp.error[k] = double(r.abs_condition * r.backward_error);
    sp.condition[k] = modulus > 0 ? double(r.abs_condition / modulus) : std::numeric_limits<double>::infinity();
    // Eight first-order error bounds, with every entry of A, C, K rounded to double.
    band[k] = 8 * r.abs_condition * (r.backward_error + ld(kEps));
    sp.converged = sp.converged && r.converged;
    sp.ill_conditioned = sp.ill_conditioned || !(sp.condition[k] * kEps <= 1e-8);
    filled[k] = true;
  };
  for (std::size_t i = 0; i < 8; ++i) {
    const auto z = start[i].value;
    if (filled[i] || z.imag() < 0) continue;  // lower half-plane: the conjugate partner
    if (z.imag() == 0) {
      const Refined r = refine<ld>(lin, start[i]);
      fill(i, r.value, r);
      continue;
    }
    const Refined r = refine<cld>(lin, start[i]);
    fill(i, r.value, r);
    for (std::size_t j = 0; j < 8; ++j) {
      if (!filled[j] && start[j].value == std::conj(z)) {
        fill(j, std::conj(r.value), r);
        break;
      }
    }
  }
  for (std::size_t i = 0; i < 8; ++i) {  // a lower-half value whose partner was not found
    if (filled[i]) continue;
    const Refined r = refine<cld>(lin, start[i]);
    fill(i, r.value, r);
  }
  // Newton must stay in the basin of its starting value: a refined eigenvalue that moved
  // by more than half the distance to the nearest other starting value (which is also
  // how two starts would end on one eigenvalue) keeps its QR value, and the refinement
  // is reported as failed.
  const auto as_ld = [](std::complex<double> z) { return cld(z.real(), z.imag()); };
  for (std::size_t i = 0; i < 8; ++i) {
    ld radius = std::numeric_limits<ld>::infinity();
    for (std::size_t j = 0; j < 8; ++j)
      if (start[j].value != start[i].value) radius = std::min(radius, std::abs(as_ld(start[j].value - start[i].value)) / 2);
    const ld moved = std::abs(refined[i] - as_ld(start[i].value));
    if (moved > radius) {
      sp.eigenvalues[i] = start[i].value;
      sp.error[i] = double(moved);
      sp.converged = false;
    }
  }
  sort_and_classify(sp, band);
  return sp;
}

Spectrum equilibrium_spectrum(const Params& p, const Equilibrium& e, SpectrumMethod method) {
  return compute_spectrum(linearize(p.cast<ld>(), e.state()), method);
}

}  // namespace abu
