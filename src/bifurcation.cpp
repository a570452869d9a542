#include "abu/bifurcation.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <complex>
#include <limits>

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
constexpr int kMaxIterations = 40;

// Solves the bordered system [M b; c^H 0] [v; g] = [0; 1] for g (the minimally
// augmented test function); M is equilibrated by the caller.
template <class S>
S bordered_g(const Eigen::Matrix<S, 4, 4>& m, const Eigen::Matrix<S, 4, 1>& b, const Eigen::Matrix<S, 4, 1>& c) {
  Eigen::Matrix<S, 5, 5> B = Eigen::Matrix<S, 5, 5>::Zero();
  B.template topLeftCorner<4, 4>() = m;
  B.template topRightCorner<4, 1>() = b;
  B.template bottomLeftCorner<1, 4>() = c.adjoint();
  Eigen::Matrix<S, 5, 1> rhs = Eigen::Matrix<S, 5, 1>::Zero();
  rhs(4) = S(1);
  return B.partialPivLu().solve(rhs)(4);
}

// Newton with a square Jacobian; stops where the steps stop shrinking.
template <int Dim, class Residual, class JacobianFn>
bool newton(Eigen::Matrix<ld, Dim, 1>& y, const Residual& residual, const JacobianFn& jacobian, int& iterations) {
  ld last = std::numeric_limits<ld>::infinity();
  for (iterations = 0; iterations < kMaxIterations; ++iterations) {
    const Eigen::Matrix<ld, Dim, 1> r = residual(y);
    const Eigen::Matrix<ld, Dim, Dim> D = jacobian(y);
    const Eigen::Matrix<ld, Dim, 1> step = D.partialPivLu().solve(-r);
    if (!step.allFinite()) return false;
    y += step;
    const ld size = step.cwiseAbs().maxCoeff();
    if (size <= 64 * kEpsLong) return true;
    if (iterations >= 3 && size > last / 2) return size <= 1e-13L;  // stagnated at rounding level
    last = size;
  }
  return false;
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

Located locate_fold(const StaticEquations& eq, const Vec5& z_guess) {
  // b, c: the right and left singular vectors of F_s for its smallest singular value at
  // the guess; fixed during the iteration so that g is one smooth function.
  const Mat4 Fs0 = eq.jacobian(z_guess).leftCols<4>();
  const Eigen::JacobiSVD<Mat4> svd(Fs0, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // Border with the left null vector as column (outside the range of F_s) and the right
  // null vector as row (not orthogonal to its kernel): then the bordered matrix is regular.
  const Eigen::Matrix<ld, 4, 1> left = svd.matrixU().col(3), right = svd.matrixV().col(3);
  const auto g = [&](const Vec5& z) { return bordered_g<ld>(eq.jacobian(z).leftCols<4>(), left, right); };
  const auto residual = [&](const Vec5& z) {
    Vec5 r;
    r << eq.residual(z), g(z);
    return r;
  };
  const auto jacobian = [&](const Vec5& z) {
    Eigen::Matrix<ld, 5, 5> D;
    D.topRows<4>() = eq.jacobian(z);
    for (int k = 0; k < 5; ++k) D(4, k) = central_difference<5>([&](const Vec5& y) {
                                           Eigen::Matrix<ld, 1, 1> v;
                                           v << g(y);
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
  // Unknowns y = (z, w / w_guess). T(i w) equilibrated once at the guess; b, c its
  // smallest singular vectors there.
  const auto pencil = [&](const Vec5& z, ld w) -> Mat4c {
    const auto lin = eq.linearization(z);
    const cld l(0, w);
    return (l * l) * lin.mass.cast<cld>() + l * lin.damping.cast<cld>() + lin.stiffness.cast<cld>();
  };
  const Mat4c T0 = pencil(z_guess, omega_guess);
  Eigen::Matrix<ld, 4, 1> rows, cols;
  for (int i = 0; i < 4; ++i) rows(i) = 1 / T0.row(i).cwiseAbs().maxCoeff();
  for (int j = 0; j < 4; ++j) cols(j) = 1 / (rows.asDiagonal() * T0).col(j).cwiseAbs().maxCoeff();
  const auto scaled = [&](const Vec5& z, ld w) -> Mat4c {
    return rows.cast<cld>().asDiagonal() * pencil(z, w) * cols.cast<cld>().asDiagonal();
  };
  const Eigen::JacobiSVD<Mat4c> svd(scaled(z_guess, omega_guess), Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec4c left = svd.matrixU().col(3), right = svd.matrixV().col(3);
  using Vec6 = Eigen::Matrix<ld, 6, 1>;
  const auto split = [&](const Vec6& y) {
    Vec5 z = y.head<5>();
    return std::pair<Vec5, ld>(z, y(5) * omega_guess);
  };
  const auto g = [&](const Vec6& y) {
    const auto [z, w] = split(y);
    const cld v = bordered_g<cld>(scaled(z, w), left, right);
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
  using Mat8c = Eigen::Matrix<cld, 8, 8>;
  const auto pl = p.cast<ld>();
  const State<ld, 2> x0 = at_rest<ld, 2>(s);
  const StateMatrix<ld, 2> J = jacobian(pl, x0);
  const Mat8c Jc = J.cast<cld>();
  const cld iw(0, omega);
  // Critical eigenvectors by inverse iteration: J q = i w q, J^T p = -i w p.
  const auto null_vector = [](const Mat8c& m) {
    const Eigen::PartialPivLU<Mat8c> lu(m);
    Vec8c v = Vec8c::Ones();
    for (int k = 0; k < 3; ++k) {
      v = lu.solve(v);
      v /= v.norm();
    }
    return v;
  };
  const ld nudge = 1 + 1e-14L;  // exactly on the eigenvalue the LU could meet a zero pivot
  Vec8c q = null_vector(Jc - iw * nudge * Mat8c::Identity());
  Vec8c pv = null_vector(Mat8c(Jc.transpose()) + iw * nudge * Mat8c::Identity());
  q /= q.norm();
  pv /= std::conj(pv.dot(q));  // <p, q> = p^H q = 1
  // Directional differences with a step that is h0 in the natural scales of the state
  // (displacement scale for q, 1 for angles, omega times those for the rates).
  const ld length = displacement_scale(pl);
  Vec8 scale;
  scale << length, length, 1, 1, length * omega, length * omega, omega, omega;
  const auto f = [&](const Vec8& x) -> Vec8 { return vector_field(pl, State<ld, 2>(x)); };
  const auto step_for = [&](std::initializer_list<const Vec8*> dirs, ld h0) {
    ld size = 0;
    for (const Vec8* d : dirs) size = std::max(size, d->cwiseQuotient(scale).cwiseAbs().maxCoeff());
    return size > 0 ? h0 / size : h0;
  };
  // Symmetric bilinear and trilinear forms of f at x0 (exact for quadratic resp. cubic
  // terms, error O(h^2)).
  const auto B = [&](const Vec8& u, const Vec8& v) -> Vec8 {
    const ld h = step_for({&u, &v}, 1e-5L);
    const Vec8 x = x0;
    return (f(x + h * u + h * v) - f(x + h * u - h * v) - f(x - h * u + h * v) + f(x - h * u - h * v)) / (4 * h * h);
  };
  const auto C = [&](const Vec8& u, const Vec8& v, const Vec8& w) -> Vec8 {
    const ld h = step_for({&u, &v, &w}, 1e-4L);
    Vec8 sum = Vec8::Zero();
    for (int a = -1; a <= 1; a += 2)
      for (int b = -1; b <= 1; b += 2)
        for (int c = -1; c <= 1; c += 2)
          sum += ld(a * b * c) * f(x0 + h * (ld(a) * u + ld(b) * v + ld(c) * w));
    return sum / (8 * h * h * h);
  };
  const Vec8 qr = q.real(), qi = q.imag();
  const auto Bc = [&](const Vec8c& u, const Vec8c& v) -> Vec8c {  // complex bilinear extension
    const Vec8 ur = u.real(), ui = u.imag(), vr = v.real(), vi = v.imag();
    const Vec8 re = B(ur, vr) - B(ui, vi), im = B(ur, vi) + B(ui, vr);
    return re.cast<cld>() + cld(0, 1) * im.cast<cld>();
  };
  // C(q, q, conj q) = C(a,a,a) + C(a,b,b) + i (C(a,a,b) + C(b,b,b)) for q = a + i b.
  const Vec8c Cqqq = (C(qr, qr, qr) + C(qr, qi, qi)).cast<cld>() + cld(0, 1) * (C(qr, qr, qi) + C(qi, qi, qi)).cast<cld>();
  const Vec8c Bqq = Bc(q, q), Bqqbar = Bc(q, q.conjugate());
  const Vec8c r1 = Jc.partialPivLu().solve(Bqqbar);
  const Vec8c r2 = (cld(0, 2 * omega) * Mat8c::Identity() - Jc).partialPivLu().solve(Bqq);
  const cld sum = pv.dot(Cqqq) - cld(2) * pv.dot(Bc(q, r1)) + pv.dot(Bc(q.conjugate(), r2));
  return double(sum.real() / (2 * omega));
}

}  // namespace abu
