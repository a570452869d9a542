// Anisotropic support (docs/model.md §10): the rotating-frame support and the periodic
// Jacobian at a balanced state.
#include "abu/model/anisotropic_support.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <fmt/format.h>

namespace abu {

double AnisotropicSupport::stiffness_anisotropy() const { return std::hypot(0.5 * (k_x - k_y), k_xy); }
double AnisotropicSupport::damping_anisotropy() const { return std::hypot(0.5 * (c_x - c_y), c_xy); }

std::optional<std::string> stiffness_matrix_violation(double k_x, double k_y, double k_xy) {
  // Sylvester: k_x > 0 and det > 0 (k_y > 0 then follows).
  const double det = k_x * k_y - k_xy * k_xy;
  if (!(k_x > 0.0) || !(k_y > 0.0) || !(det > 0.0))
    return fmt::format("K_f = [[stiffness_x, stiffness_xy], [stiffness_xy, stiffness_y]] must be positive definite "
                       "(stiffness_x > 0, stiffness_y > 0, stiffness_x*stiffness_y - stiffness_xy^2 > 0; got {}, {}, {})",
                       k_x, k_y, det);
  return std::nullopt;
}

std::optional<std::string> damping_matrix_violation(double c_x, double c_y, double c_xy) {
  const double det = c_x * c_y - c_xy * c_xy;
  if (!(c_x >= 0.0) || !(c_y >= 0.0) || !(det >= 0.0))
    return fmt::format("C_f = [[damping_x, damping_xy], [damping_xy, damping_y]] must be positive semidefinite "
                       "(damping_x >= 0, damping_y >= 0, damping_x*damping_y - damping_xy^2 >= 0; got {}, {}, {})",
                       c_x, c_y, det);
  return std::nullopt;
}

namespace {
Eigen::Matrix2d rotated(double a, double b, double ab, double omega, double t) {
  const double th = omega * t;
  Eigen::Matrix2d R;
  R << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
  Eigen::Matrix2d F;
  F << a, ab, ab, b;
  return R.transpose() * F * R;
}

// The time-dependent part of the rotor's -db/ds and -db/ds' at q = 0 (§10.6):
// dK = (K_rot - k_bar I) + omega (C_rot - c_bar I) J2, dC = C_rot - c_bar I, because the
// support force on the rotating axes is -K_rot q - C_rot v with v = q' + omega J2 q.
void support_oscillation(const AnisotropicSupport& s, double omega, double t, Eigen::Matrix2d& dK,
                         Eigen::Matrix2d& dC) {
  Eigen::Matrix2d J2;
  J2 << 0.0, -1.0, 1.0, 0.0;
  dC = rotating_damping(s, omega, t) - s.mean_damping() * Eigen::Matrix2d::Identity();
  dK = rotating_stiffness(s, omega, t) - s.mean_stiffness() * Eigen::Matrix2d::Identity() + omega * dC * J2;
}
}  // namespace

Eigen::Matrix2d rotating_stiffness(const AnisotropicSupport& s, double omega, double t) {
  return rotated(s.k_x, s.k_y, s.k_xy, omega, t);
}
Eigen::Matrix2d rotating_damping(const AnisotropicSupport& s, double omega, double t) {
  return rotated(s.c_x, s.c_y, s.c_xy, omega, t);
}

double PeriodicJacobian::period() const { return std::numbers::pi / omega; }

Eigen::MatrixXd PeriodicJacobian::at(double t) const {
  const double th = 2.0 * omega * t;
  return mean + std::cos(th) * cos2 + std::sin(th) * sin2;
}

PeriodicJacobian balanced_periodic_jacobian(const ParamsN& p, const AnisotropicSupport& s,
                                            const Coordinates<long double, any_balls>& position) {
  const ParamsT<long double, any_balls> pl = p.cast<long double>();
  const State<long double, any_balls> x = at_rest<long double, any_balls>(position);
  const Linearization<long double, any_balls> lin = linearize(pl, x);
  const Eigen::Index d = position.size();  // n + 2
  PeriodicJacobian J;
  J.omega = p.omega;
  J.mean = jacobian(lin).cast<double>();
  const Eigen::MatrixXd Ainv = lin.mass.cast<double>().inverse();  // SPD, (n+2) x (n+2)
  // The oscillating part is exactly first-harmonic in 2 omega t (R^T S R of a traceless
  // symmetric S), so its values at 2 omega t = 0 and pi/2 are Jc and Js.
  for (int which = 0; which < 2; ++which) {
    Eigen::Matrix2d dK, dC;
    support_oscillation(s, p.omega, which == 0 ? 0.0 : std::numbers::pi / (4.0 * p.omega), dK, dC);
    Eigen::MatrixXd Jh = Eigen::MatrixXd::Zero(2 * d, 2 * d);
    Jh.block(d, 0, d, 2) = -Ainv.leftCols(2) * dK;
    Jh.block(d, d, d, 2) = -Ainv.leftCols(2) * dC;
    (which == 0 ? J.cos2 : J.sin2) = Jh;
  }
  const double L = displacement_scale(p);
  J.scale = Eigen::VectorXd::Ones(2 * d);
  J.scale.segment(d, d).setConstant(p.omega);
  J.scale.head(2) *= L;
  J.scale.segment(d, 2) *= L;
  for (Eigen::MatrixXd* M : {&J.mean, &J.cos2, &J.sin2})
    *M = J.scale.cwiseInverse().asDiagonal() * (*M) * J.scale.asDiagonal();
  return J;
}

double steady_whirl_radius(double mass, double k, double c, const AnisotropicSupport* support, double omega,
                           std::complex<double> W) {
  using C = std::complex<double>;
  Eigen::Matrix2d K = k * Eigen::Matrix2d::Identity(), D = c * Eigen::Matrix2d::Identity();
  if (support) {
    K << support->k_x, support->k_xy, support->k_xy, support->k_y;
    D << support->c_x, support->c_xy, support->c_xy, support->c_y;
  }
  const Eigen::Matrix2cd A =
      (K - mass * omega * omega * Eigen::Matrix2d::Identity()).cast<C>() + C(0, omega) * D.cast<C>();
  const Eigen::Vector2cd z = A.partialPivLu().solve(Eigen::Vector2cd(omega * omega * W, C(0, -1) * omega * omega * W));
  // x(t) = a cos - b sin: its largest length is the root of the larger eigenvalue of [a b][a b]^T.
  const Eigen::Vector2d a = z.real(), b = z.imag();
  Eigen::Matrix2d G;
  G << a.dot(a), a.dot(b), a.dot(b), b.dot(b);
  return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(G, Eigen::EigenvaluesOnly).eigenvalues()(1)));
}

std::string describe_support(const AnisotropicSupport& s) {
  return fmt::format("K_f = [[{}, {}], [{}, {}]] N/m, C_f = [[{}, {}], [{}, {}]] N s/m (fixed frame); k_bar = {}, "
                     "|kappa| = {}, c_bar = {}, |gamma| = {}",
                     s.k_x, s.k_xy, s.k_xy, s.k_y, s.c_x, s.c_xy, s.c_xy, s.c_y, s.mean_stiffness(),
                     s.stiffness_anisotropy(), s.mean_damping(), s.damping_anisotropy());
}

}  // namespace abu
