// The [race] table of a scene: an unround race (model.md §11.1).
//
//   [race]
//   unroundness = [{ order = 2, amplitude = 1e-3, phase = 0.3 }, { order = 3, amplitude = 2e-4 }]
//   # or surface_unroundness = [...]: harmonics of the race *surface* (radius l + r),
//   # converted per ball to its centre path (eps = e (l + r) / l, model.md §11.1)
//   [[race.ball]]          # optional, any number: one ball's own race harmonics
//   ball = 2               # 1-based
//   unroundness = [...]    # or surface_unroundness (replaces [race]'s for that ball)
//
// Harmonic keys: order (integer 1..64; 1 is the race centre's offset d = l amplitude,
// exact offset circle), amplitude (>= 0, relative to l), phase (rad, optional, 0). An
// order appears at most once per list. Geometry rules (path_violation: the path radius
// stays > 0; the race wall is smooth for the ball) are checked for every ball.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "abu/model/unround_race.hpp"

namespace abu {

struct Scene;

/// One list of harmonics as written, with where it was written (for messages).
struct RaceHarmonicsInput {
  RaceHarmonics harmonics;
  bool surface = false;  ///< surface_unroundness: converted per ball (surface_to_path)
  int line = 0;
  std::string key;       ///< "race.unroundness", "race.ball[1].surface_unroundness", ...
};

/// The [race] table: for every ball, or per ball (ball = 1-based index).
struct RaceSpec {
  std::optional<RaceHarmonicsInput> all;
  std::vector<std::pair<int, RaceHarmonicsInput>> per_ball;
  /// No [race] table, or no nonzero amplitude: the round race of model.md §3.
  bool round() const;
};

/// The centre-path harmonics of the scene's balls (surface harmonics converted with the
/// current l_i, r_i). Throws InputError (the scene file, the line and key of the list)
/// if a ball's path breaks a rule of path_violation, e.g. after --set l=... .
RaceShape race_shape(const Scene& scene);

/// The parameter that multiplies every amplitude of the scene's race (model.md §11.10).
inline const std::string kUnroundnessParam = "unroundness";

/// The scene's race (`race`, race_shape(scene)) with every amplitude times `factor`; throws
/// InputError at `option` (key `unroundness`) where a ball's path breaks a rule of model.md §11.1.
RaceShape checked_scaled_race(const Scene& scene, const RaceShape& race, double factor, const std::string& option);

/// Multiplies every amplitude of the scene's [race] by `factor` in [0, 1] (the `unroundness` of a
/// study, model.md §21.2: the scene's race is the largest runout). Throws InputError(origin, 0,
/// "unroundness", rule) for a round race or a factor outside [0, 1].
void scale_race(Scene& scene, double factor, const std::string& origin);

}  // namespace abu
