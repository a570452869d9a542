// Anisotropic bearings on a flexible shaft (shaft_bearings.hpp, docs/model.md §18.19).
#include "abu/model/shaft_bearings.hpp"

#include <numbers>

namespace abu {

BearingDeviator bearing_deviator(const AnisotropicSupport& s, double theta) {
  // rotating_stiffness(s, omega, t) is R(omega t)^T K_f R(omega t): omega = 1, t = theta.
  BearingDeviator d;
  d.stiffness = rotating_stiffness(s, 1.0, theta) - s.mean_stiffness() * Eigen::Matrix2d::Identity();
  d.damping = rotating_damping(s, 1.0, theta) - s.mean_damping() * Eigen::Matrix2d::Identity();
  return d;
}

BearingDeviator bearing_deviator_rate(const AnisotropicSupport& s, double theta) {
  // R^T S R of a traceless symmetric S is S's second harmonic e^{-2 i theta}: its derivative is
  // twice its value a quarter of that period (pi/4 in theta) later.
  BearingDeviator d = bearing_deviator(s, theta + 0.25 * std::numbers::pi);
  d.stiffness *= 2.0;
  d.damping *= 2.0;
  return d;
}

Eigen::Matrix2d deviator_position_stiffness(const BearingDeviator& d, double omega) {
  Eigen::Matrix2d J;
  J << 0.0, -1.0, 1.0, 0.0;
  return d.stiffness + omega * d.damping * J;
}

}  // namespace abu
