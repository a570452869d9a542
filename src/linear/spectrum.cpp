#include "abu/linear/spectrum.hpp"

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
constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff 2^-53
constexpr ld kEpsLong = std::numeric_limits<ld>::epsilon() / 2;

using Vec4c = Eigen::Matrix<std::complex<double>, 4, 1>;
using Mat8Row = Eigen::Matrix<double, 8, 8, Eigen::RowMajor>;

// A matrix after Parlett-Reinsch balancing (GSL; Eigen's EigenSolver does not balance
// and the Jacobian's rows differ by 1e15 in scale), with its QR eigenvalues. `norm` is
// the Frobenius norm of the balanced matrix: each eigenvalue's absolute error is about
// eps * norm.
struct BalancedQr {
  Mat8Row balanced;
  std::array<double, 8> scale{};  // balanced = D^-1 M D, D = diag(scale)
  std::array<std::complex<double>, 8> values{};
  double norm = 0;
};
BalancedQr balanced_qr(const Mat8Row& m) {
  BalancedQr r;
  r.balanced = m;
  gsl_matrix_view view = gsl_matrix_view_array(r.balanced.data(), 8, 8);
  gsl_vector_view dv = gsl_vector_view_array(r.scale.data(), 8);
  gsl_linalg_balance_matrix(&view.matrix, &dv.vector);
  const Eigen::EigenSolver<Eigen::Matrix<double, 8, 8>> solver(r.balanced, false);
  for (int i = 0; i < 8; ++i) r.values[std::size_t(i)] = solver.eigenvalues()(i);
  r.norm = r.balanced.norm();
  return r;
}

// Diagonal equilibration R |T(lambda0)| D ~ O(1) (powers of two, a few Sinkhorn-style
// sweeps): the ball rows of T can be 1e10 smaller than the rotor rows (tiny balls),
// which would make pivoting treat them as zero. Eigenvalues, the componentwise
// backward error and the componentwise condition number are all invariant under it.
void equilibrate(const Mat4& magnitude, Eigen::Matrix<ld, 4, 1>& rows, Eigen::Matrix<ld, 4, 1>& cols) {
  // In double: only the orders of magnitude matter, and double's frexp/ldexp are cheap.
  const Eigen::Matrix4d m = magnitude.cast<double>();
  Eigen::Vector4d r = Eigen::Vector4d::Ones(), c = Eigen::Vector4d::Ones();
  const auto inverse_pow2 = [](double v) {  // the power of two nearest 1 / v
    if (!(v > 0) || !std::isfinite(v)) return 1.0;
    int e = 0;
    std::frexp(v, &e);
    return std::ldexp(1.0, 1 - e);
  };
  for (int sweep = 0; sweep < 2; ++sweep) {
    for (int i = 0; i < 4; ++i) r(i) = inverse_pow2(m.row(i).transpose().cwiseProduct(c).maxCoeff());
    for (int j = 0; j < 4; ++j) c(j) = inverse_pow2(m.col(j).cwiseProduct(r).maxCoeff());
  }
  rows = r.cast<ld>();
  cols = c.cast<ld>();
}

// First-order form J = [[0, I], [-A^-1 K, -A^-1 C]].
Mat8Row companion(const Linearization<ld, 2>& lin) {
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
bool shifted_inverse(const Linearization<ld, 2>& lin, ld sigma, Mat8Row& out) {
  const Mat4 t = sigma * sigma * lin.mass + sigma * lin.damping + lin.stiffness;
  // Judge and factor T(sigma) equilibrated, T = R^-1 Te D^-1: unscaled, its rotor rows
  // can be 1e10 larger than the ball rows and rcond would call it singular when it is not.
  Eigen::Matrix<ld, 4, 1> rows, cols;
  equilibrate(t.cwiseAbs(), rows, cols);
  const Eigen::PartialPivLU<Mat4> lu(rows.asDiagonal() * t * cols.asDiagonal());
  if (!(lu.rcond() > 64 * kEpsLong)) return false;
  const auto solve = [&](const Mat4& rhs) -> Mat4 { return cols.asDiagonal() * lu.solve(rows.asDiagonal() * rhs); };
  Eigen::Matrix<ld, 8, 8> Ji = Eigen::Matrix<ld, 8, 8>::Zero();
  Ji.block<4, 4>(0, 0) = -solve(Mat4(lin.damping + 2 * sigma * lin.mass));
  Ji.block<4, 4>(0, 4) = -solve(lin.mass);
  Ji.block<4, 4>(4, 0).setIdentity();
  out = Ji.cast<double>();
  return out.allFinite();
}

// A starting value: an eigenvalue lambda of J, and where it came from: eigenvalue
// `theta` of the balanced matrix `source` (J itself, theta = lambda, or the shifted
// inverse, theta = 1 / (lambda - sigma)).
struct Estimate {
  std::complex<double> value;
  std::complex<double> theta;
  const BalancedQr* source = nullptr;
};

// The position part x of the eigenvector (x, lambda x) by inverse iteration on the
// balanced matrix the estimate came from: there the decoupled modes of equal balls are
// as well separated as the QR saw them, while T(lambda) can be singular to working
// precision (its 1e-20 ball stiffness lost against the rotor coupling).
template <class S>
Vec4c position_vector(const Estimate& e) {
  using Mat8s = Eigen::Matrix<S, 8, 8>;
  using Vec8s = Eigen::Matrix<S, 8, 1>;
  S theta;
  if constexpr (std::is_same_v<S, double>) {
    theta = e.theta.real();
  } else {
    theta = e.theta;
  }
  Vec8s v = Vec8s::Ones();
  for (int attempt = 0; attempt < 3; ++attempt) {
    // Exactly on the eigenvalue the LU can meet a zero pivot: nudge theta off it.
    const S shifted = theta * S(1 + attempt * 1e-13);
    const Mat8s m = e.source->balanced.cast<S>() - shifted * Mat8s::Identity();
    const Eigen::PartialPivLU<Mat8s> lu(m);
    Vec8s w = Vec8s::Ones();
    for (int step = 0; step < 2; ++step) {
      w = lu.solve(w);
      w /= S(w.cwiseAbs().maxCoeff());
    }
    if (w.allFinite()) {
      v = w;
      break;
    }
  }
  Eigen::Matrix<std::complex<double>, 8, 1> full;
  for (int k = 0; k < 8; ++k) full(k) = std::complex<double>(v(k)) * e.source->scale[std::size_t(k)];
  const std::complex<double> lambda = e.value;
  Vec4c x = std::abs(lambda) > 1 ? Vec4c(full.tail<4>() / lambda) : Vec4c(full.head<4>());
  if (!x.allFinite() || x.isZero(0)) x = Vec4c::Ones();
  return x;
}

// Starting values: every eigenvalue from the QR whose error bound relative to it is
// smaller: eps ||J|| from J, eps ||(J - sigma)^-1|| |lambda - sigma|^2 from the inverse.
// Sorting both lists by distance to sigma pairs them; the k closest come from the
// inverse, k counting its values inside the crossover radius sqrt(||J|| / ||J^-1||).
// If K is singular (a zero eigenvalue: U = 0 circles, folds), the shift moves to
// sigma = -eps ||J||, the level below which the direct QR cannot resolve anything.
struct Starts {
  BalancedQr direct, inverse;
  std::array<Estimate, 8> estimates;
};
void starting_values(const Linearization<ld, 2>& lin, SpectrumMethod method, Starts& out) {
  out.direct = balanced_qr(companion(lin));
  std::array<Estimate, 8> direct{};
  for (std::size_t i = 0; i < 8; ++i) direct[i] = {out.direct.values[i], out.direct.values[i], &out.direct};
  out.estimates = direct;
  if (method == SpectrumMethod::dense_qr) return;
  Mat8Row jinv;
  ld sigma = 0;
  if (!shifted_inverse(lin, sigma, jinv)) {
    sigma = -ld(kEps * out.direct.norm);
    if (!shifted_inverse(lin, sigma, jinv)) return;
  }
  out.inverse = balanced_qr(jinv);
  const double shift = double(sigma);
  std::array<Estimate, 8> inverse{};
  for (std::size_t i = 0; i < 8; ++i) {
    const auto mu = out.inverse.values[i];
    inverse[i] = {mu == 0.0 ? std::complex<double>(std::numeric_limits<double>::max()) : shift + 1.0 / mu, mu,
                  &out.inverse};
  }
  const auto by_distance = [shift](const Estimate& a, const Estimate& b) {
    const double da = std::abs(a.value - shift), db = std::abs(b.value - shift);
    return da < db || (da == db && a.value.imag() > b.value.imag());
  };
  std::sort(direct.begin(), direct.end(), by_distance);
  std::sort(inverse.begin(), inverse.end(), by_distance);
  const double crossover = std::sqrt(out.direct.norm / out.inverse.norm);
  std::size_t k = 0;
  while (k < 8 && std::abs(inverse[k].value - shift) < crossover) ++k;
  // Keep complex-conjugate pairs on one side of the split.
  const auto splits_pair = [&k](const std::array<Estimate, 8>& v) {
    return k > 0 && k < 8 && v[k - 1].value.imag() != 0 && v[k].value == std::conj(v[k - 1].value);
  };
  if (splits_pair(inverse)) ++k;
  if (splits_pair(direct)) --k;
  for (std::size_t i = 0; i < 8; ++i) out.estimates[i] = i < k ? inverse[i] : direct[i];
}

// Newton on T(lambda) x = 0 for one eigenvalue; real arithmetic for a real starting
// value keeps real eigenvalues exactly real.
struct Refined {
  cld value;
  ld backward_error;  // componentwise, eta
  ld abs_condition;   // y* S |x| / |y* T' x|, S = |lambda|^2 |A| + |lambda| |C| + |K|
  bool converged;
  Vec4c vector;       // x, unscaled (SI) and of unit norm
};

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

// The 5x5 bordered matrix factored once, solved with it or its adjoint. Complex
// systems are factored in their real 10x10 form [[Re, -Im], [Im, Re]]: Eigen's complex
// LU pivots on |z|, i.e. hypot, which made hypot the refinement's most expensive call.
// (The real form of B^H is the transpose of B's real form.)
class BorderedSolver {
 public:
  explicit BorderedSolver(const Eigen::Matrix<double, 5, 5>& B) : real_(B) {}
  explicit BorderedSolver(const Eigen::Matrix<std::complex<double>, 5, 5>& B) {
    Eigen::Matrix<double, 10, 10> R;
    R << B.real(), -B.imag(), B.imag(), B.real();
    complex_.compute(R);
  }
  Eigen::Matrix<double, 5, 1> solve(const Eigen::Matrix<double, 5, 1>& r, bool adjoint) const {
    return adjoint ? Eigen::Matrix<double, 5, 1>(real_.transpose().solve(r)) : Eigen::Matrix<double, 5, 1>(real_.solve(r));
  }
  Eigen::Matrix<std::complex<double>, 5, 1> solve(const Eigen::Matrix<std::complex<double>, 5, 1>& r,
                                                  bool adjoint) const {
    Eigen::Matrix<double, 10, 1> rr;
    rr << r.real(), r.imag();
    const Eigen::Matrix<double, 10, 1> v = adjoint ? Eigen::Matrix<double, 10, 1>(complex_.transpose().solve(rr))
                                                   : Eigen::Matrix<double, 10, 1>(complex_.solve(rr));
    Eigen::Matrix<std::complex<double>, 5, 1> out;
    for (int i = 0; i < 5; ++i) out(i) = {v(i), v(i + 5)};
    return out;
  }

 private:
  Eigen::PartialPivLU<Eigen::Matrix<double, 5, 5>> real_;
  Eigen::PartialPivLU<Eigen::Matrix<double, 10, 10>> complex_;
};

// Newton on T(lambda) x = 0 from (start, start_vector), on the equilibrated problem.
// The residual T x and the iterate are in S's precision: long double for the analyzer's
// spectra (this is what makes them better than double), double for eigenvalue
// continuation along branches; the bordered correction is always solved in double (its
// errors only slow the convergence by a factor eps_double * cond(B) per step).
template <class S>
Refined refine(const Linearization<ld, 2>& lin, std::complex<double> start, const Vec4c& start_vector) {
  using W = typename Precision<S>::W;
  using D = typename Precision<S>::D;
  using Vec4 = Eigen::Matrix<S, 4, 1>;
  using Mat4s = Eigen::Matrix<S, 4, 4>;
  using Vec4w = Eigen::Matrix<W, 4, 1>;
  using Mat4w = Eigen::Matrix<W, 4, 4>;
  constexpr W eps = std::numeric_limits<W>::epsilon() / 2;
  S lambda = from_complex<S>(start);
  Eigen::Matrix<ld, 4, 1> rows, cols;
  {
    const ld a = std::abs(start);
    equilibrate(a * a * lin.mass.cwiseAbs() + a * lin.damping.cwiseAbs() + lin.stiffness.cwiseAbs(), rows, cols);
  }
  const Mat4w Ar = (rows.asDiagonal() * lin.mass * cols.asDiagonal()).template cast<W>();
  const Mat4w Cr = (rows.asDiagonal() * lin.damping * cols.asDiagonal()).template cast<W>();
  const Mat4w Kr = (rows.asDiagonal() * lin.stiffness * cols.asDiagonal()).template cast<W>();
  const Mat4s As = Ar.template cast<S>(), Cs = Cr.template cast<S>(), Ks = Kr.template cast<S>();
  const Mat4w absA = Ar.cwiseAbs(), absC = Cr.cwiseAbs(), absK = Kr.cwiseAbs();
  const auto T = [&](S l) -> Mat4s { return (l * l) * As + l * Cs + Ks; };
  const auto dT = [&](S l) -> Mat4s { return S(2) * l * As + Cs; };
  const auto magnitude = [&](S l) -> Mat4w {
    const W a = magnitude_of(l);
    return a * a * absA + a * absC + absK;
  };
  const auto abs_vector = [](const Vec4& v) {
    Vec4w a;
    for (int i = 0; i < 4; ++i) a(i) = magnitude_of(v(i));
    return a;
  };
  // The start vector in the equilibrated coordinates; normalization c^H x = 1 with c the
  // start itself (unlike pinning one entry, it cannot pick a component that is noise).
  Vec4 x;
  for (int i = 0; i < 4; ++i) x(i) = from_complex<S>(start_vector(i)) / S(W(cols(i)));
  x /= S(x.norm());
  const Eigen::Matrix<D, 4, 1> c = x.template cast<D>();
  // Bordered system B = [T, T' x; c^H, 0], its first four rows weighted by the
  // componentwise magnitude so that pivoting sees comparable rows. Near a simple
  // eigenvalue B is well conditioned even where T itself is singular to working precision.
  Vec4w weight;
  const auto bordered = [&](S l, const Mat4s& t, const Vec4& v) {
    const Vec4w scale = magnitude(l) * abs_vector(v);
    Eigen::Matrix<D, 5, 5> B;
    const Vec4 tv = dT(l) * v;
    for (int i = 0; i < 4; ++i) {
      weight(i) = scale(i) > 0 ? 1 / scale(i) : 1;
      for (int j = 0; j < 4; ++j) B(i, j) = D(t(i, j) * S(weight(i)));
      B(i, 4) = D(tv(i) * S(weight(i)));
      B(4, i) = Eigen::numext::conj(c(i));
    }
    B(4, 4) = D(0);
    return B;
  };
  // Newton converges until its steps stop shrinking (the rounding level); whether that
  // level is good enough is judged below against the error bound. In double the
  // convergence is quadratic: after a step below sqrt(eps) |lambda| the error is at the
  // rounding level already, and the step that would confirm it is skipped.
  W last_step = std::numeric_limits<W>::infinity();
  W final_step = last_step;
  const W enough = std::is_same_v<W, double> ? std::sqrt(eps) : 4 * eps;
  std::optional<BorderedSolver> solver;
  for (int it = 0; it < 16; ++it) {
    const Mat4s t = T(lambda);
    solver.emplace(bordered(lambda, t, x));
    const Vec4 r = t * x;  // in the working precision
    Eigen::Matrix<D, 5, 1> rhs;
    for (int i = 0; i < 4; ++i) rhs(i) = D(-r(i) * S(weight(i)));
    rhs(4) = D(0);
    const Eigen::Matrix<D, 5, 1> step = solver->solve(rhs, false);
    if (!step.allFinite()) break;
    const W dl = magnitude_of(S(step(4)));
    lambda += S(step(4));
    for (int i = 0; i < 4; ++i) x(i) += S(step(i));
    final_step = std::is_same_v<W, double> && dl <= enough * magnitude_of(lambda) ? dl * dl / magnitude_of(lambda)
                                                                                  : std::min(dl, last_step);
    if (dl <= enough * magnitude_of(lambda) || (it >= 2 && dl > last_step / 2)) break;
    last_step = dl;
  }
  // Left vector from the adjoint bordered system (the last factorization, at the
  // previous iterate, is close enough for a condition estimate): B^H [y; eta] = e_5 gives
  // T^H y = -eta c with eta ~ (T x)^H y / (c^H x) ~ 0: y is the left null vector of T.
  const Mat4s t = T(lambda);
  Vec4 y = x;
  if (solver) {
    Eigen::Matrix<D, 5, 1> e5 = Eigen::Matrix<D, 5, 1>::Zero();
    e5(4) = D(1);
    const Eigen::Matrix<D, 5, 1> z = solver->solve(e5, true);
    for (int i = 0; i < 4; ++i) y(i) = S(z(i)) * S(weight(i));  // undo the row weighting
    if (!y.allFinite() || y.isZero(0)) y = x;
  }
  const Mat4w S_mag = magnitude(lambda);
  const Vec4 r = t * x;
  const Vec4w denom = S_mag * abs_vector(x);
  W eta = 0;
  for (int i = 0; i < 4; ++i) eta = std::max(eta, denom(i) > 0 ? magnitude_of(r(i)) / denom(i) : W(0));
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
  const bool converged = std::isfinite(std::abs(lambda)) && eta <= W(1e-8) &&
                         (final_step <= 1e3 * eps * std::abs(lambda) || final_step <= 8 * abs_condition * eta);
  Vec4c unscaled;
  for (int i = 0; i < 4; ++i) {
    const std::complex<W> xi = std::complex<W>(x(i)) * W(cols(i));
    unscaled(i) = {double(xi.real()), double(xi.imag())};
  }
  return {cld(std::complex<W>(lambda)), ld(eta), ld(abs_condition), converged, unscaled.normalized()};
}

// Sorts, and classifies each eigenvalue against its band; the `structural_zeros`
// eigenvalues of smallest modulus are exactly zero by construction and lie on the axis.
void sort_and_classify(Spectrum& sp, std::array<ld, 8> band, int structural_zeros) {
  for (int z = 0; z < structural_zeros; ++z) {
    std::size_t smallest = 0;
    for (std::size_t i = 1; i < 8; ++i)
      if (band[i] != std::numeric_limits<ld>::infinity() &&
          (band[smallest] == std::numeric_limits<ld>::infinity() ||
           std::abs(sp.eigenvalues[i]) < std::abs(sp.eigenvalues[smallest])))
        smallest = i;
    band[smallest] = std::numeric_limits<ld>::infinity();
  }
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
    sorted.vectors[i] = sp.vectors[k];
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

Spectrum compute_spectrum(const Linearization<ld, 2>& lin, SpectrumMethod method, int structural_zeros) {
  Starts starts;
  starting_values(lin, method, starts);
  const auto& start = starts.estimates;
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
    sort_and_classify(sp, band, structural_zeros);
    return sp;
  }
  std::array<bool, 8> filled{};
  std::array<cld, 8> refined{};
  const auto fill = [&](std::size_t k, cld v, const Refined& r) {
    const ld modulus = std::abs(v);
    refined[k] = v;
    sp.vectors[k] = v == r.value ? r.vector : Vec4c(r.vector.conjugate());
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
      const Refined r = refine<ld>(lin, z, position_vector<double>(start[i]));
      fill(i, r.value, r);
      continue;
    }
    const Refined r = refine<cld>(lin, z, position_vector<std::complex<double>>(start[i]));
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
    const Refined r = refine<cld>(lin, start[i].value, position_vector<std::complex<double>>(start[i]));
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
  sort_and_classify(sp, band, structural_zeros);
  return sp;
}

std::optional<TrackedSpectrum> track_spectrum(const Linearization<ld, 2>& lin,
                                              const std::array<std::complex<double>, 8>& values,
                                              const std::array<Vec4c, 8>& vectors) {
  TrackedSpectrum out;
  Spectrum& sp = out.spectrum;
  std::array<ld, 8> band{};
  std::array<bool, 8> done{};
  for (std::size_t k = 0; k < 8; ++k) {
    if (done[k]) continue;
    const auto z = values[k];
    // Each mode may move by less than half the predicted distance to its nearest
    // neighbour (its conjugate excepted), or tracking would be ambiguous.
    double radius_squared = std::numeric_limits<double>::infinity();  // (std::norm: no hypot)
    for (std::size_t j = 0; j < 8; ++j)
      if (j != k && values[j] != std::conj(z)) radius_squared = std::min(radius_squared, std::norm(values[j] - z) / 4);
    const bool real = z.imag() == 0;
    const Refined r = real ? refine<double>(lin, z, vectors[k]) : refine<std::complex<double>>(lin, z, vectors[k]);
    const std::complex<double> value(double(r.value.real()), double(r.value.imag()));
    // Newton started from this mode's own eigenvector stays on that mode even when the
    // extrapolated eigenvalue misses by more than the gap to a neighbour (two balls'
    // nearly equal fast modes): the eigenvector's alignment identifies it then.
    const bool aligned = std::abs(r.vector.dot(vectors[k].normalized())) >= 0.95;
    if (!r.converged || !(std::norm(value - z) < radius_squared || aligned)) return std::nullopt;
    const auto store = [&](std::size_t m, std::complex<double> v, const Vec4c& x) {
      out.modes[m] = v;
      out.mode_vectors[m] = x;
      sp.eigenvalues[m] = v;
      sp.vectors[m] = x;
      sp.error[m] = double(r.abs_condition * r.backward_error);
      sp.condition[m] = std::abs(v) > 0 ? double(r.abs_condition) / std::abs(v) : std::numeric_limits<double>::infinity();
      band[m] = 8 * r.abs_condition * (r.backward_error + ld(kEps));
      sp.ill_conditioned = sp.ill_conditioned || !(sp.condition[m] * kEps <= 1e-8);
      done[m] = true;
    };
    store(k, value, r.vector);
    if (real) continue;
    std::size_t partner = 8;
    for (std::size_t j = 0; j < 8; ++j)
      if (!done[j] && values[j] == std::conj(z)) partner = j;
    if (partner == 8) return std::nullopt;  // a complex mode without its conjugate
    store(partner, std::conj(value), Vec4c(r.vector.conjugate()));
  }
  // Two modes on one eigenvalue: one of them lost its identity.
  for (std::size_t i = 0; i < 8; ++i)
    for (std::size_t j = i + 1; j < 8; ++j)
      if (std::abs(out.modes[i] - out.modes[j]) <= 1e-9 * std::abs(out.modes[i])) return std::nullopt;
  sort_and_classify(sp, band, 0);
  return out;
}

Spectrum equilibrium_spectrum(const Params& p, const Equilibrium& e, SpectrumMethod method) {
  return compute_spectrum(linearize(p.cast<ld>(), e.state()), method, e.singular ? 1 : 0);
}

}  // namespace abu
