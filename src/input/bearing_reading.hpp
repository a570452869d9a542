// A [[bearing]]'s translational spring and damper in a shaft scene: the isotropic `stiffness`,
// `damping` or the fixed-frame matrices of an anisotropic bearing (docs/model.md §18.19, the keys
// of the rigid [rotor]'s support, §10.1): private to src/input (shaft_scene.cpp reads the keys).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abu/model/anisotropic_support.hpp"
#include "scene_reading.hpp"

namespace abu::scene_reading {

/// One support key of a [[bearing]] table as read (present, its valid value, where).
struct BearingKey {
  std::string_view name;  ///< stiffness, damping, stiffness_x, stiffness_y, stiffness_xy, damping_x, ...
  bool seen = false;
  std::optional<double> value;  ///< set iff present and a finite number
  toml::source_position pos{};
  std::string key;  ///< bearing[i].name
};

/// The support keys a [[bearing]] takes besides node and the tilt spring.
inline constexpr std::string_view kBearingSupportKeys[] = {"stiffness",   "damping",   "stiffness_x", "stiffness_y",
                                                           "stiffness_xy", "damping_x", "damping_y",   "damping_xy"};

/// The bearing's spring and damper read from `keys` (one entry per kBearingSupportKeys name):
/// stiffness, damping (>= 0), or stiffness_x, stiffness_y, damping_x, damping_y with
/// stiffness_xy, damping_xy (default 0), K_f positive definite and C_f positive semidefinite
/// (reported at the matrix's last key) — never both forms (reported at the later key, naming the
/// other and its line). Missing keys are reported at `header` as `path`.key.
struct BearingSupport {
  double stiffness = 0, damping = 0;             ///< k, c; the means of K_f, C_f
  std::optional<AnisotropicSupport> anisotropic;  ///< K_f, C_f in the matrix form
};
std::optional<BearingSupport> read_bearing_support(Problems& p, const std::vector<BearingKey>& keys,
                                                   toml::source_position header, const std::string& path);

}  // namespace abu::scene_reading
