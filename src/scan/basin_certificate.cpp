// model.md §15.8: a Lyapunov region of a stable equilibrium for the basin's settle test
// (see basin_certificate.hpp).
#include "abu/scan/basin_certificate.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/core/taylor.hpp"
#include "abu/model/model.hpp"

namespace abu {

namespace {

using Jet = Taylor<long double, 3>;
constexpr int kDim = 8;  // two balls: 2n + 4
constexpr double kTwoPi = 2 * std::numbers::pi;
// Sampled points of the ball besides its centre and the 2 dim points +-rho e_i.
constexpr int kHaltonPoints = 24;
// The sampled supremum of |D^2 g| over the ball is taken twice (model.md §15.8).
constexpr double kSampleSafety = 2.0;

double halton(int index, int base) {
  double f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

// D^2 g(z)[u, u] for every component k (scaled): 2 c_2 of the jet f(x* + S (z + t u)) / S_k.
void second_derivative(const ParamsT<Jet, 2>& pj, const BasinRegion& R, const double* z, const double* u, double* out) {
  State<Jet, 2> X;
  for (int i = 0; i < kDim; ++i) {
    Jet v(static_cast<long double>(R.centre[std::size_t(i)]) +
          static_cast<long double>(R.scale[std::size_t(i)]) * static_cast<long double>(z[i]));
    v.c[1] = static_cast<long double>(R.scale[std::size_t(i)]) * static_cast<long double>(u[i]);
    X(i) = v;
  }
  const State<Jet, 2> f = vector_field(pj, X);
  for (int k = 0; k < kDim; ++k) out[k] = double(2 * f(k).c[2] / static_cast<long double>(R.scale[std::size_t(k)]));
}

double tensor_bound(const ParamsT<Jet, 2>& pj, const BasinRegion& R, const double* z) {
  // T_k[i][j] = D^2 g_k[e_i, e_j]: the diagonal from Q(e_i), the rest by polarization
  // T[i][j] = (Q(e_i + e_j) - Q(e_i - e_j)) / 4 (model.md (6.9)); |D^2 g[u, u]| <=
  // sqrt(sum_k |T_k|_2^2) <= sqrt(sum_k |T_k|_F^2) for |u| = 1.
  double T[kDim][kDim][kDim] = {};
  double u[kDim], qp[kDim], qm[kDim];
  for (int i = 0; i < kDim; ++i) {
    std::fill(u, u + kDim, 0.0);
    u[i] = 1;
    second_derivative(pj, R, z, u, qp);
    for (int k = 0; k < kDim; ++k) T[k][i][i] = qp[k];
    for (int j = i + 1; j < kDim; ++j) {
      u[j] = 1;
      second_derivative(pj, R, z, u, qp);
      u[j] = -1;
      second_derivative(pj, R, z, u, qm);
      u[j] = 0;
      for (int k = 0; k < kDim; ++k) T[k][i][j] = T[k][j][i] = 0.25 * (qp[k] - qm[k]);
    }
  }
  double sum = 0;
  for (int k = 0; k < kDim; ++k)
    for (int i = 0; i < kDim; ++i)
      for (int j = 0; j < kDim; ++j) sum += T[k][i][j] * T[k][i][j];
  return std::sqrt(sum);
}

// K2 over the ball |z| <= rho: the bound at its centre, at +-rho e_i and at Halton points
// (radius rho / 2 and rho alternately), the largest times kSampleSafety.
double ball_bound(const ParamsT<Jet, 2>& pj, BasinRegion& R, double rho) {
  double z[kDim] = {};
  double k2 = tensor_bound(pj, R, z);
  int points = 1;
  for (int i = 0; i < kDim; ++i)
    for (double s : {-1.0, 1.0}) {
      std::fill(z, z + kDim, 0.0);
      z[i] = s * rho;
      k2 = std::max(k2, tensor_bound(pj, R, z));
      ++points;
    }
  static constexpr int primes[kDim] = {2, 3, 5, 7, 11, 13, 17, 19};
  for (int m = 1; m <= kHaltonPoints; ++m) {
    double norm = 0;
    for (int i = 0; i < kDim; ++i) {
      z[i] = 2 * halton(m, primes[i]) - 1;
      norm += z[i] * z[i];
    }
    norm = std::sqrt(norm);
    if (!(norm > 0)) continue;
    const double radius = (m % 2 ? 0.5 : 1.0) * rho;
    for (int i = 0; i < kDim; ++i) z[i] *= radius / norm;
    k2 = std::max(k2, tensor_bound(pj, R, z));
    ++points;
  }
  R.sample_points = points;
  return kSampleSafety * k2;
}

}  // namespace

double second_derivative_bound_at(const Params& p, const BasinRegion& region, const double* z) {
  return tensor_bound(p.cast<Jet>(), region, z);
}

double lyapunov_value(const BasinRegion& R, const double* x) {
  double y[32];
  const int n = (R.dim - 4) / 2;
  for (int i = 0; i < R.dim; ++i) {
    double d = x[i] - R.centre[std::size_t(i)];
    if (i >= 2 && i < n + 2) d = std::remainder(d, kTwoPi);  // angles wrapped to (-pi, pi]
    y[i] = d / R.scale[std::size_t(i)];
  }
  double v = 0;
  for (int i = 0; i < R.dim; ++i) {
    double row = 0;
    for (int j = 0; j < R.dim; ++j) row += R.P[std::size_t(i * R.dim + j)] * y[j];
    v += y[i] * row;
  }
  return v;
}

BasinRegion certify_basin_region(const Params& p, const std::vector<double>& position) {
  BasinRegion R;
  R.dim = kDim;
  const double L = displacement_scale(p), w = p.omega;
  Coordinates<double, 2> s;
  for (int i = 0; i < 4; ++i) s(i) = position[std::size_t(i)];
  const State<double, 2> x0 = at_rest<double, 2>(s);
  R.centre.assign(x0.data(), x0.data() + kDim);
  R.scale = {L, L, 1.0, 1.0, L * w, L * w, w, w};
  // A = S^-1 J S (model.md (15.8.1)).
  const StateMatrix<double, 2> J = jacobian(p, x0);
  Eigen::Matrix<double, kDim, kDim> A;
  for (int i = 0; i < kDim; ++i)
    for (int j = 0; j < kDim; ++j) A(i, j) = J(i, j) * R.scale[std::size_t(j)] / R.scale[std::size_t(i)];
  if (!A.allFinite()) {
    R.reason = "the Jacobian is not finite";
    return R;
  }
  // A^T P + P A = -I as one linear system in vec(P) (column-major): (I (x) A^T + A^T (x) I).
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(kDim * kDim, kDim * kDim);
  for (int a = 0; a < kDim; ++a)
    for (int b = 0; b < kDim; ++b)
      for (int c = 0; c < kDim; ++c) {
        K(a * kDim + b, a * kDim + c) += A(c, b);  // (A^T P)_{b a} = sum_c A(c, b) P(c, a)
        K(a * kDim + b, c * kDim + b) += A(c, a);  // (P A)_{b a} = sum_c P(b, c) A(c, a)
      }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(kDim * kDim);
  for (int i = 0; i < kDim; ++i) rhs(i * kDim + i) = -1.0;
  const Eigen::VectorXd vecP = K.fullPivLu().solve(rhs);
  Eigen::Matrix<double, kDim, kDim> P;
  for (int a = 0; a < kDim; ++a)
    for (int b = 0; b < kDim; ++b) P(b, a) = vecP(a * kDim + b);
  P = (0.5 * (P + P.transpose())).eval();
  const Eigen::Matrix<double, kDim, kDim> residual =
      A.transpose() * P + P * A + Eigen::Matrix<double, kDim, kDim>::Identity();
  R.lyapunov_residual = residual.cwiseAbs().maxCoeff();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, kDim, kDim>> es(P);
  R.p_min = es.eigenvalues().minCoeff();
  R.p_norm = es.eigenvalues().maxCoeff();
  R.P.resize(std::size_t(kDim * kDim));
  for (int i = 0; i < kDim; ++i)
    for (int j = 0; j < kDim; ++j) R.P[std::size_t(i * kDim + j)] = P(i, j);
  // The decrease margin: V' = -|y|^2 + 2 y^T P R(y) needs the residual of the Lyapunov
  // equation well below the 1 of -I, else -I is not what the solved P gives.
  if (!(R.lyapunov_residual <= 1e-3) || !(R.p_min > 0) || !std::isfinite(R.p_norm)) {
    R.reason = fmt::format("the Lyapunov equation has no accurate positive definite solution (residual {:.3g}, "
                           "smallest eigenvalue of P {:.3g}): the linearization is not (well) Hurwitz",
                           R.lyapunov_residual, R.p_min);
    return R;
  }
  // The ball: start at rho = 1 (q ~ L, 1 rad, velocities ~ w) and shrink to the radius the
  // bound allows until it holds on the ball it was taken over (model.md (15.8.4)).
  const ParamsT<Jet, 2> pj = p.cast<Jet>();
  double rho = 1.0;
  for (int iter = 0; iter < 60; ++iter) {
    const double k2 = ball_bound(pj, R, rho);
    if (!(std::isfinite(k2) && k2 > 0)) {
      R.reason = "the second-derivative bound is not finite";
      return R;
    }
    R.second_derivative_bound = k2;
    const double r = 1.0 / (2 * R.p_norm * k2);
    if (r >= rho) break;
    rho = std::max(r, rho / 16);  // K2 of a smaller ball is at most that of the larger one
  }
  R.radius = std::min(rho, 1.0 / (2 * R.p_norm * R.second_derivative_bound));
  if (!(R.radius > 0)) {
    R.reason = "no positive radius";
    return R;
  }
  R.level = R.p_min * R.radius * R.radius;
  R.certified = true;
  return R;
}

}  // namespace abu
