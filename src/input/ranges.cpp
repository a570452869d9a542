#include "abu/input/ranges.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abu/core/errors.hpp"
#include "abu/core/suggest.hpp"

namespace abu {

namespace {
std::optional<RangeViolation> unbalance_violation(double u, double capacity) {
  if (u != 0 && !(u >= kMinUnbalanceRatio * capacity))
    return RangeViolation{"U", fmt::format("U must be 0 or >= {:g} of the balls' capacity sum m_i l_i = {:.6g} kg m "
                                           "(U >= {:.6g} kg m; below, the balanced states agree to rounding: give U = 0 "
                                           "for a balanced rotor); got U = {:g} kg m",
                                           kMinUnbalanceRatio, capacity, kMinUnbalanceRatio * capacity, u)};
  return std::nullopt;
}
}  // namespace

std::optional<RangeViolation> numerical_range_violation(const Scene& scene) {
  double balls_mass = 0, capacity = 0;
  for (const auto& b : scene.balls) {
    balls_mass += b.mass;
    capacity += b.mass * b.race_radius;
  }
  const double total = scene.rotor.mass + balls_mass;
  // A flexible shaft has no single omega_n (model.md §18.11, rule 9): only the unbalance's rule.
  if (scene.shaft) return unbalance_violation(scene.rotor.unbalance, capacity);
  const double omega_n = std::sqrt(scene.rotor.stiffness / total);
  const double ratio = scene.omega / omega_n;
  if (!(ratio >= kMinSpeedRatio && ratio <= kMaxSpeedRatio))
    return RangeViolation{"omega", fmt::format("omega / omega_n must lie in [{:g}, {:g}] (omega_n = {:.6g} rad/s, so "
                                               "omega in [{:.6g}, {:.6g}] rad/s); got omega = {:g} rad/s",
                                               kMinSpeedRatio, kMaxSpeedRatio, omega_n, kMinSpeedRatio * omega_n,
                                               kMaxSpeedRatio * omega_n, scene.omega)};
  const double zeta = scene.rotor.damping / (2 * std::sqrt(scene.rotor.stiffness * total));
  if (!(zeta <= kMaxDampingRatio))
    return RangeViolation{"c", fmt::format("the damping ratio c / (2 sqrt(k M)) must be <= {:g} (c <= {:.6g} N s/m); "
                                           "got c = {:g} N s/m",
                                           kMaxDampingRatio, kMaxDampingRatio * 2 * std::sqrt(scene.rotor.stiffness * total),
                                           scene.rotor.damping)};
  if ((scene.law == FrictionLaw::coulomb || scene.law == FrictionLaw::stribeck) &&
      !(scene.kappa * omega_n <= kMaxSharpness))
    return RangeViolation{"kappa", fmt::format("kappa omega_n must be <= {:g} (omega_n = {:.6g} rad/s, so kappa <= "
                                               "{:.6g} s/rad; beyond, the stiff friction modes and the creep modes "
                                               "are too far apart for double precision); got kappa = {:g} s/rad",
                                               kMaxSharpness, omega_n, kMaxSharpness / omega_n, scene.kappa)};
  return unbalance_violation(scene.rotor.unbalance, capacity);
}

void check_numerical_range(const Scene& scene, const std::string& origin, const std::string& what) {
  if (const auto v = numerical_range_violation(scene))
    throw InputError(origin, 0, v->key, what.empty() ? v->rule : fmt::format("{} ({})", v->rule, what));
}

ParamRef checked_param(const Scene& scene, const std::string& option, const std::string& symbol,
                       const std::string& to_option, double to, bool radius_allowed) {
  const auto ref = parse_param(symbol, int(scene.balls.size()));
  if (!ref)
    throw InputError(option, 0, symbol,
                     unknown_name_rule("unknown parameter", closest_param(symbol), "known", param_symbols_help()));
  if (!radius_allowed && ref->quantity == Quantity::ball_radius)
    throw InputError(option, 0, symbol, "the ball radius does not enter the equations of motion (model.md §3)");
  Scene probe = scene;
  set_checked(probe, *ref, to, to_option);
  check_numerical_range(probe, to_option);
  return *ref;
}

}  // namespace abu
