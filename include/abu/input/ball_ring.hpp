// The [balls] ring of a scene file: `count` copies of one ball, some overridden
// ([[balls.override]]). The file format and how a ring follows changes of the scene
// (set_checked, apply_override, set_ball_count) are documented at the top of scene.hpp,
// which includes this header; src/input/ball_ring.cpp reads the table and rebuilds rings.
#pragma once

#include <string>
#include <vector>

#include "abu/core/params.hpp"

namespace abu {

struct Scene;  // scene.hpp

/// The number of balls a scene may have.
inline constexpr int kSceneMinBalls = 2;
inline constexpr int kSceneMaxBalls = max_balls;  ///< the analyzer's bound (model.md §13)

/// A field of BallT that a ring override sets. `inertia_factor` is the file's `rolling`
/// (value 7/5 rolling, 1 sliding).
enum class BallField {
  mass, race_radius, radius, inertia_factor, mu, d, mu_c, mu_s, v_s, sigma0, sigma1, sigma2,
  density, rolling_length, surface_radius  // the specification, model.md §1.1 (diameter sets radius)
};

/// One ball of a ring that differs from the template in one field.
struct RingOverride {
  int ball = 0;  ///< 0-based index in the ring (the file's `ball = 3` is 2); may be >= count (inactive)
  BallField field = BallField::mass;
  double value = 0.0;
  std::string origin;  ///< the scene file, or set_checked's origin ("--set", ...)
  int line = 0;        ///< 1-based line of the key in `origin`; 0 if not from a file
  std::string key;     ///< what set it: "balls.override[2].mass", or a symbol such as "m3"
};

/// The [balls] shorthand of a scene: `count` copies of one ball, some overridden.
struct BallRing {
  int count = 0;
  /// Every ball not overridden, friction coefficients resolved ([balls]' own, else
  /// [friction]'s; 0 for a coefficient the law does not use; NaN for one the law uses that
  /// only overrides give). mass is the per-ball mass (total_mass / count if that is held).
  BallT<double> ball{};
  bool total_mass_held = false;  ///< the file gave total_mass (m follows the count)
  double total_mass = 0.0;       ///< the sum of the template masses, if total_mass_held
  std::vector<RingOverride> overrides;  ///< in file order, then in order of setting
};

/// The balls of a ring: ring.count copies of ring.ball (mass total_mass / count if that
/// is held), then the overrides of balls < count applied in order. Checks nothing.
std::vector<BallT<double>> ring_balls(const BallRing& ring);

/// Rebuilds the balls of a [balls] ring scene with `count` balls (see the top of
/// scene.hpp) and re-checks them. Throws InputError(origin, 0, "n", rule) if the scene has no
/// ring, count is outside 2..12, or a ball of the new ring breaks a rule; the scene is
/// unchanged then.
void set_ball_count(Scene& scene, int count, const std::string& origin);

}  // namespace abu
