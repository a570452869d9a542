#include "abu/continuation/corrector.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace abu {

namespace {
using ld = long double;
using Vec5 = StaticEquations::Vec5;
using Mat45 = StaticEquations::Mat45;
using Mat5 = Eigen::Matrix<ld, 5, 5>;
constexpr ld kTwoPi = 2 * std::numbers::pi_v<ld>;
ld wrapped_difference(ld a, ld b) { return std::abs(std::remainder(a - b, kTwoPi)); }

}  // namespace

// Distance between two scaled points with the angles compared modulo 2 pi.
ld distance(const Vec5& a, const Vec5& b) {
  return std::max({std::abs(a(0) - b(0)), std::abs(a(1) - b(1)), wrapped_difference(a(2), b(2)),
                   wrapped_difference(a(3), b(3)), std::abs(a(4) - b(4))});
}

// Newton on [F(z); d . (z - z_pred)] = 0: the pseudo-arclength corrector (d the tangent),
// or, with d = e_5, the equilibrium at a fixed parameter. Converged when the steps
// reach the rounding level and F is at the rounding level of double or below.
Corrected correct(const StaticEquations& eq, const Vec5& z_pred, const Vec5& d) {
  Corrected c{z_pred};
  ld last = std::numeric_limits<ld>::infinity();
  for (int it = 0; it < 12; ++it) {
    Mat5 M;
    c.jacobian = eq.jacobian(c.z);
    M.topRows<4>() = c.jacobian;
    M.row(4) = d.transpose();
    Vec5 r;
    r << eq.residual(c.z), d.dot(c.z - z_pred);
    const Vec5 step = M.partialPivLu().solve(-r);
    if (!step.allFinite()) return c;
    c.z += step;
    c.iterations = it + 1;
    const ld size = step.cwiseAbs().maxCoeff();
    const bool small = size <= 1e-15L || (it >= 2 && size > last / 2 && size <= 1e-12L);
    if (small || (it >= 2 && size > last / 2)) {
      c.converged = small && eq.residual(c.z).cwiseAbs().maxCoeff() <= 1e-15L;
      return c;
    }
    if (size > 1) return c;  // diverging: far outside any reasonable step
    last = size;
  }
  return c;
}

// Unit tangent: the null vector of F_u, oriented along `previous`.
Vec5 tangent(const Mat45& DF, const Vec5& previous) {
  Mat5 M;
  M.topRows<4>() = DF;
  M.row(4) = previous.transpose();
  Vec5 e5 = Vec5::Zero();
  e5(4) = 1;
  Vec5 t = M.partialPivLu().solve(e5);
  t.normalize();
  if (t.dot(previous) < 0) t = -t;
  return t;
}

// det [F_u; t^T]: changes sign at a branch point, not at a fold.
ld branch_test(const Mat45& DF, const Vec5& t) {
  Mat5 M;
  M.topRows<4>() = DF;
  M.row(4) = t.transpose();
  return M.partialPivLu().determinant();
}

}  // namespace abu
