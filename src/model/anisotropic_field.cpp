// The balancer's field on an anisotropic support with the homotopy parameter delta
// (anisotropic_field.hpp, docs/model.md §10.14).
#include "abu/model/anisotropic_field.hpp"

#include <numbers>

#include <Eigen/Cholesky>

#include "abu/model/mass_derivative.hpp"

namespace abu {

namespace {

using Dof = Coordinates<double, any_balls>;

// The anisotropic part of the support on the rotating axes at t: dK = K_rot - k_bar I and
// dC = C_rot - c_bar I (model.md §10.2).
void anisotropy_at(const AnisotropicSupport& s, double omega, double t, Eigen::Matrix2d& dK, Eigen::Matrix2d& dC) {
  dK = rotating_stiffness(s, omega, t) - s.mean_stiffness() * Eigen::Matrix2d::Identity();
  dC = rotating_damping(s, omega, t) - s.mean_damping() * Eigen::Matrix2d::Identity();
}

// g of (10.14.1) at full anisotropy: -dK q - dC (q' + omega J2 q), J2 q = (-q2, q1).
Eigen::Vector2d anisotropy_force(const Eigen::Matrix2d& dK, const Eigen::Matrix2d& dC, double omega,
                                 const Eigen::Vector2d& q, const Eigen::Vector2d& qdot) {
  const Eigen::Vector2d v = qdot + omega * Eigen::Vector2d(-q(1), q(0));
  return -dK * q - dC * v;
}

}  // namespace

void anisotropic_field(const ParamsN& p, const AnisotropicSupport& s, const State<double, any_balls>& x, double t,
                       double delta, AnisotropicFieldValue& out, bool derivatives) {
  const Eigen::Index d = x.size() / 2;
  const double w = p.omega;
  const Dof pos = x.head(d);
  const Eigen::Vector2d q = x.head<2>(), qdot = x.segment<2>(d);
  const DofMatrix<double, any_balls> A = mass_matrix(p, pos);
  const Eigen::LLT<DofMatrix<double, any_balls>> llt(A);  // A is SPD (model.md §3)
  Eigen::Matrix2d dK, dC;
  anisotropy_at(s, w, t, dK, dC);
  Dof g = Dof::Zero(d);
  g.head<2>() = anisotropy_force(dK, dC, w, q, qdot);
  const Dof accel = llt.solve(g);  // A^-1 g: the full anisotropy's acceleration
  out.field = vector_field(p, x);
  out.field.segment(d, d) += delta * accel;
  if (!derivatives) return;
  out.delta_derivative = State<double, any_balls>::Zero(2 * d);
  out.delta_derivative.segment(d, d) = accel;
  // d/dt: dK, dC are pure first harmonics in 2 omega t, so their derivative is 2 omega times
  // their value a quarter of their period later.
  Eigen::Matrix2d dKt, dCt;
  anisotropy_at(s, w, t + std::numbers::pi / (4.0 * w), dKt, dCt);
  Dof gt = Dof::Zero(d);
  gt.head<2>() = 2.0 * w * anisotropy_force(dKt, dCt, w, q, qdot);
  out.time_derivative = State<double, any_balls>::Zero(2 * d);
  out.time_derivative.segment(d, d) = delta * llt.solve(gt);
  // (10.14.2): d(delta g)/dq = -delta (dK + omega dC J2), d(delta g)/dq' = -delta dC, and
  // the change of A(beta) at fixed delta g: -(dA/ds) A^-1 delta g.
  Eigen::Matrix2d J2;
  J2 << 0.0, -1.0, 1.0, 0.0;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, dof_capacity<any_balls>,
                2 * dof_capacity<any_balls>>
      rhs = Eigen::MatrixXd::Zero(d, 2 * d);
  rhs.block(0, 0, 2, 2) = -delta * (dK + w * dC * J2);
  rhs.block(0, d, 2, 2) = -delta * dC;
  rhs.leftCols(d) -= mass_derivative_times(p, pos, Dof(delta * accel));
  out.jacobian = jacobian(p, x);
  out.jacobian.block(d, 0, d, 2 * d) += llt.solve(rhs);
}

}  // namespace abu
