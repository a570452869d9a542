// The [simulate] table of a scene (private to src/input): the run-up and the integration
// settings of `simulate` and `basin`, read with the scene's rules (every problem with its
// line and key, the first in the file reported; docs/guide.md "The [simulate] table").
#pragma once

#include <string>

#include <toml++/toml.h>

#include "abu/input/scene.hpp"
#include "scene_reading.hpp"

namespace abu::scene_reading {

/// Reads [simulate] of `file` (n_balls balls: the length of `balls` and `from_state`).
/// A speed_profile file is read relative to the scene file's directory; its own errors
/// are reported at the key, naming the profile file and line.
SimulateSettings read_simulate_table(Problems& p, const toml::table& table, const std::string& file, int n_balls);

}  // namespace abu::scene_reading
