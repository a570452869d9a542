// An anisotropic elastic support of the rotor (docs/model.md §10): stiffness and damping
// matrices K_f, C_f acting on the rotor centre in the FIXED frame. In the rotating frame
// the support then varies with period pi/omega (§10.2), so the balanced states stay
// equilibria but their linearization is periodic: J(t) = J0 + cos(2 omega t) Jc +
// sin(2 omega t) Js (§10.6), with J0 the isotropic Jacobian of model.md §6 at the mean
// stiffness and damping (k_bar, c_bar).
//
//   abu::AnisotropicSupport s{7875, 7125, 150, 2.3, 1.7, 0.1};
//   abu::ParamsN p = ...;  p.rotor.stiffness = s.mean_stiffness(); p.rotor.damping = s.mean_damping();
//   abu::PeriodicJacobian J = abu::balanced_periodic_jacobian(p, s, position);
#pragma once

#include <complex>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "abu/core/params.hpp"
#include "abu/model/model.hpp"

namespace abu {

/// K_f = [[k_x, k_xy], [k_xy, k_y]] [N/m] and C_f = [[c_x, c_xy], [c_xy, c_y]] [N s/m]
/// on the fixed axes (n1, n2) (model.md §10.1). Invariant checked by the scene reader:
/// K_f positive definite, C_f positive semidefinite (support_violation).
struct AnisotropicSupport {
  double k_x = 0.0, k_y = 0.0, k_xy = 0.0;
  double c_x = 0.0, c_y = 0.0, c_xy = 0.0;

  double mean_stiffness() const { return 0.5 * (k_x + k_y); }  ///< k_bar
  double mean_damping() const { return 0.5 * (c_x + c_y); }    ///< c_bar
  /// |kappa| = |(k_x - k_y)/2 + i k_xy|: the principal stiffnesses are k_bar +- |kappa|.
  double stiffness_anisotropy() const;
  /// |gamma| = |(c_x - c_y)/2 + i c_xy|.
  double damping_anisotropy() const;
  bool isotropic() const { return stiffness_anisotropy() == 0.0 && damping_anisotropy() == 0.0; }
};

/// K_f and C_f (fixed frame) with k_bar, |kappa|, c_bar, |gamma|, on one line (no newline):
/// what reports and map manifests print of the support.
std::string describe_support(const AnisotropicSupport& s);

/// The steady whirl radius of the rigid rotor (mass M, the balls included) at speed omega under a
/// rotating imbalance W [kg m, complex, rotor frame] [m]: the largest |x(t)| of the fixed-frame
/// response (K - M omega^2 I + i omega C) z = omega^2 W (1, -i), x = Re(z e^{i omega t})
/// (model.md (21.1)); `support` null or isotropic: omega^2 |W| / |k - M omega^2 + i c omega| (16.5.1).
double steady_whirl_radius(double mass, double k, double c, const AnisotropicSupport* support, double omega,
                           std::complex<double> W);

/// The rule broken by K_f (not positive definite) or C_f (not positive semidefinite),
/// naming the matrix and the failing minor; nullopt if both hold.
std::optional<std::string> stiffness_matrix_violation(double k_x, double k_y, double k_xy);
std::optional<std::string> damping_matrix_violation(double c_x, double c_y, double c_xy);

/// R(omega t)^T K_f R(omega t) and R(omega t)^T C_f R(omega t): the support on the rotating
/// axes a1, a2 at time t (a1 = n1 at t = 0, model.md §2), §10.2.
Eigen::Matrix2d rotating_stiffness(const AnisotropicSupport& s, double omega, double t);
Eigen::Matrix2d rotating_damping(const AnisotropicSupport& s, double omega, double t);

/// The pi/omega-periodic Jacobian at a balanced state (§10.6): J(t) = mean +
/// cos(2 omega t) cos2 + sin(2 omega t) sin2 [1/s], state order of model.md §2, in the
/// scaled coordinates x_i / scale_i (a similarity: exponents and multipliers unchanged).
/// The scales put metres and radians, positions and rates, on one footing: q by the
/// displacement scale L of model.hpp, rates additionally by omega, so that Hill's matrix
/// is not unbalanced by 1e6 between rows (without it Hill's eigenvalues lose 4 digits).
struct PeriodicJacobian {
  Eigen::MatrixXd mean;  ///< J0: model.md §6 with (k_bar, c_bar)
  Eigen::MatrixXd cos2;  ///< Jc
  Eigen::MatrixXd sin2;  ///< Js
  double omega = 0.0;    ///< spin speed [rad/s]; the period is pi/omega
  Eigen::VectorXd scale;  ///< x_i = scale_i * (coordinate i of the matrices); SI

  double period() const;
  Eigen::MatrixXd at(double t) const;
  Eigen::Index dimension() const { return mean.rows(); }
};

/// J(t) at the balanced state `position` (q = 0, sum m_i l_i e^{i beta_i} = -U). `p` must
/// carry the mean support (p.rotor.stiffness = k_bar, p.rotor.damping = c_bar); its
/// Jacobian is J0. Jc and Js come from the rotor blocks of §10.6 (A^-1 applied to them).
PeriodicJacobian balanced_periodic_jacobian(const ParamsN& p, const AnisotropicSupport& s,
                                            const Coordinates<long double, any_balls>& position);

}  // namespace abu
