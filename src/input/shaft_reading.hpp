// Reading a flexible-rotor scene's tables ([shaft], [[disc]], [[bearing]], and [rotor] in a
// shaft scene; include/abu/input/shaft_scene.hpp) into the scene parser's problem list:
// private to src/input.
#pragma once

#include <optional>

#include "abu/model/shaft.hpp"
#include "scene_reading.hpp"

namespace abu::scene_reading {

/// The top-level nodes of a shaft scene as the parser met them (nullptr: absent).
struct ShaftInput {
  const toml::node* shaft = nullptr;
  toml::source_position shaft_pos{};
  const toml::node* discs = nullptr;
  toml::source_position discs_pos{};
  const toml::node* bearings = nullptr;
  toml::source_position bearings_pos{};
  bool present() const { return shaft != nullptr; }
};

/// Takes a top-level key if it is one of `shaft`, `disc`, `bearing` (returns false otherwise).
bool take_shaft_key(ShaftInput& in, std::string_view name, const toml::node& node, toml::source_position pos);

/// Checks and reads the shaft's tables; nullopt if any rule is broken (the problem is in `p`)
/// or the scene has no [shaft] (then [[disc]] / [[bearing]] are problems).
std::optional<ShaftSpec> read_shaft(Problems& p, const ShaftInput& in);

/// [rotor] of a shaft scene: `unbalance` only (read into the slot named "unbalance" of
/// `rotor_slots`); mass, stiffness, damping and the anisotropic keys are problems naming
/// the tables that replace them.
void read_shaft_rotor(Problems& p, const toml::table& table, std::vector<Slot>& rotor_slots);

}  // namespace abu::scene_reading
