// The [uncertain] table of a scene (private to src/input): NAME = [LOW, HIGH] per input known only
// within a range (docs/model.md §21.2), read with the scene's rules (every problem with its line
// and key, the first in the file reported).
#pragma once

#include <toml++/toml.h>

#include <vector>

#include "abu/input/scene.hpp"
#include "scene_reading.hpp"

namespace abu::scene_reading {

/// Reads [uncertain] for a scene of n_balls balls: NAME a parameter symbol (parse_param) or
/// `unroundness`, not omega (the speed profile's); [LOW, HIGH] two finite numbers, LOW <= HIGH.
/// Whether the range fits the scene's rules is the study's check (both ends, before any run).
std::vector<SceneUncertainty> read_uncertain_table(Problems& p, const toml::table& table, int n_balls);

}  // namespace abu::scene_reading
