// The parameter ranges the numerics handle (docs/robustness.md "Numerical range"), as
// dimensionless groups of the scene: outside them a result could be a hang, a DBL_MAX
// stand-in, a wrong verdict or a row that is no equilibrium, so they are refused as
// input (exit 2) naming the key and the range.
//
//   omega / omega_n in [1e-6, 1e6]             omega_n = sqrt(k / (M_r + sum m_i)), model.md §3
//   zeta = c / (2 sqrt(k (M_r + sum m_i))) <= 1e6   the rotor's damping ratio
//   U = 0 or U >= 1e-12 sum m_i l_i             below, the two balanced states agree to rounding
//   kappa omega_n <= 1e16 (coulomb, stribeck)   the arctan's sharpness: stiff friction modes
//                                               ~ kappa, creep modes ~ 1/kappa; at kappa = 1e20
//                                               refinements failed, at 1e200 a creep mode's sign flipped
#pragma once

#include <optional>
#include <string>

#include "abu/input/scene.hpp"

namespace abu {

inline constexpr double kMinSpeedRatio = 1e-6;      ///< omega / omega_n
inline constexpr double kMaxSpeedRatio = 1e6;
inline constexpr double kMaxDampingRatio = 1e6;     ///< zeta
inline constexpr double kMinUnbalanceRatio = 1e-12;  ///< U / sum m_i l_i, unless U = 0
inline constexpr double kMaxSharpness = 1e16;        ///< kappa omega_n (coulomb, stribeck)

struct RangeViolation {
  std::string key;   ///< the model.md symbol to change (omega, c, U)
  std::string rule;  ///< the range and the value found
};

/// The first group of `scene` outside its range, or nothing.
std::optional<RangeViolation> numerical_range_violation(const Scene& scene);

/// Throws InputError(origin, 0, key, rule) for a violation (`what`: e.g. "at --to").
void check_numerical_range(const Scene& scene, const std::string& origin, const std::string& what = "");

/// A parameter to move, as `continue` and the Python module's continue_branches take it: the
/// symbol given by `option` (--param, --param2, param) must be known (a suggestion otherwise)
/// and not the ball radius (unless `radius_allowed`), its end value `to` (option `to_option`)
/// inside the parameter's range by the scene's own rules (set_checked) and inside the
/// numerical range above. Throws InputError naming the option, the symbol and the rule.
ParamRef checked_param(const Scene& scene, const std::string& option, const std::string& symbol,
                       const std::string& to_option, double to, bool radius_allowed = false);

}  // namespace abu
