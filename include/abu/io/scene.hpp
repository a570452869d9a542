// Scene files: TOML, SI units.
//
//   rolling = true       # optional, default true: j = 7/5 (rolling sphere); false: j = 1
//   [rotor]    mass = 0.12  stiffness = 7500.0  damping = 2.0  unbalance = 6.0e-7
//   [[ball]]   mass = 3.3e-5  race_radius = 0.018  radius = 1.0e-3   # one table per ball, >= 2
//              optional per ball: rolling, and the coefficients mu d mu_c mu_s v_s
//   [friction] law = "coulomb"  mu = 0.002  kappa = 1.0e3
//              none: -   viscous: d   coulomb: mu kappa   stribeck: mu_c mu_s v_s kappa
//   [speed]    omega = 900.0
//
// Rules: every key above is required unless marked optional; unknown keys and tables,
// wrong types (booleans and strings are not numbers; integers are reals), non-finite
// numbers and values outside range_violation() are errors, as is radius >= race_radius.
// A coefficient the law does not use is an error, in [friction] or per ball; a per-ball
// coefficient stands in for a missing [friction] one only if every ball has it, and
// otherwise overrides it for that ball.
//
// Loading validates everything up front and reports the violation that comes first in
// the file as one InputError (file as given, 1-based line, dotted key such as
// `rotor.mass`, `ball[2].radius` (1-based), `friction.law`, and the rule). A missing key
// is reported at its table's header line; a missing table (or no [[ball]] at all) at
// the last line of the file; a TOML syntax error at toml++'s line with an empty key; an
// unreadable file at line 0 with an empty key. Nothing downstream re-checks the file.
//
//   abu::Scene scene = abu::load_scene("data/scenes/default.toml");
//   abu::apply_override(scene, "omega=1200");
//   abu::Params p = abu::params_of<2>(scene);
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "abu/core/params.hpp"

namespace abu {

/// A validated scene, for any number of balls (>= 2).
struct Scene {
  std::string file;  ///< the path as given, for messages
  RotorT<double> rotor{};
  double omega = 0.0;
  FrictionLaw law = FrictionLaw::none;
  double kappa = 0.0;                ///< only meaningful for coulomb / stribeck
  std::vector<BallT<double>> balls;  ///< friction coefficients already resolved per ball
};

/// Reads and validates a scene file. Throws InputError (also for an unreadable file).
Scene load_scene(const std::string& path);
/// Parses scene text; `file` is used in messages only.
Scene parse_scene(std::string_view text, const std::string& file);

/// Applies one `NAME=VALUE` command-line override (NAME a model.md symbol, see
/// param_symbols_help(); VALUE a finite real, the whole string) and re-validates.
/// Throws InputError with file "--set", line 0 and key NAME (the whole assignment if it
/// is not of the form NAME=VALUE); the scene is unchanged then.
void apply_override(Scene& scene, std::string_view assignment);

/// Sets a parameter of the scene by reference, checking its physical range, that the
/// scene's friction law uses it, the ball index, and radius < race_radius for `r`/`l`.
/// Throws InputError(origin, 0, symbol, rule) and leaves the scene unchanged then.
void set_checked(Scene& scene, ParamRef ref, double value, const std::string& origin);

/// The parameter set for N balls; throws NotSupportedError if the scene has another
/// number of balls. Instantiated for N = 2, N = 3 and N = any_balls (any count).
template <int N>
ParamsT<double, N> params_of(const Scene& scene);

}  // namespace abu
