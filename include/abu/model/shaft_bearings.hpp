// Anisotropic bearings on a flexible shaft (docs/model.md §18.19): a bearing's fixed-frame
// force -K_f U - C_f U' on its node's fixed-frame translation U = R(theta) u. assemble_shaft
// holds its mean part (k_bar I, c_bar I); the deviatoric part seen on the rotating axes turns
// at 2 theta:
//     g = -K_dev(theta) u - C_dev(theta) (u' + omega J u),
//     K_dev(theta) = R(theta)^T (K_f - k_bar I) R(theta),  C_dev likewise        (18.19.2)
// so the rotating-frame equations are pi/omega-periodic; theta is the spin angle (omega t at
// constant speed, a1 = n1 at t = 0 as model.md §2).
//
//   abu::BearingDeviator d = abu::bearing_deviator(*bearing.anisotropic, theta);
//   Eigen::Vector2d g = -(d.stiffness * u + d.damping * (ud + omega * J * u));
#pragma once

#include <Eigen/Core>

#include "abu/model/anisotropic_support.hpp"

namespace abu {

/// K_dev(theta), C_dev(theta) of (18.19.2) [N/m, N s/m]: symmetric and traceless.
struct BearingDeviator {
  Eigen::Matrix2d stiffness = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d damping = Eigen::Matrix2d::Zero();
};
BearingDeviator bearing_deviator(const AnisotropicSupport& s, double theta);
/// d/dtheta of bearing_deviator: 2 x its value at theta + pi/4 (a pure second harmonic).
BearingDeviator bearing_deviator_rate(const AnisotropicSupport& s, double theta);

/// The deviatoric force's derivatives on the node's (u, u') at spin speed omega (18.19.4):
/// -dg/du = K_dev + omega C_dev J, -dg/du' = C_dev, J = [[0, -1], [1, 0]].
Eigen::Matrix2d deviator_position_stiffness(const BearingDeviator& d, double omega);

}  // namespace abu
