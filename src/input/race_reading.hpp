// Reading the [race] table (race_scene.hpp) into the scene parser's problem list:
// private to src/input.
#pragma once

#include "scene_reading.hpp"

namespace abu::scene_reading {

/// Reads [race]; `n_balls` (0 if unknown) bounds race.ball[].ball.
void read_race(Problems& p, const toml::table& table, std::size_t n_balls, RaceSpec& out);

/// Checks every ball's path (path_violation) and throws InputError at the list's line.
void check_race(const Scene& scene);

}  // namespace abu::scene_reading
