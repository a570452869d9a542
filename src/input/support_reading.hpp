// Reading [rotor]'s support in a rigid-rotor scene into the scene parser's problem list:
// private to src/input.
#pragma once

#include <optional>
#include <vector>

#include "abu/model/anisotropic_support.hpp"
#include "scene_reading.hpp"

namespace abu::scene_reading {

/// Reads [rotor] into `slots` (mass, stiffness, damping, unbalance) and the anisotropic
/// support's keys: the isotropic stiffness/damping or the fixed-frame matrices (docs/model.md
/// §10.1), never both, the matrices positive (semi)definite. The support if the scene gives
/// the matrices and they obey the rules; nullopt otherwise (a broken rule is in `p`).
std::optional<AnisotropicSupport> read_support(Problems& p, const toml::table& table, std::vector<Slot>& slots);

}  // namespace abu::scene_reading
