// Scene files: TOML, SI units.
//
//   rolling = true       # optional, default true: j = 7/5 (rolling sphere); false: j = 1
//   [rotor]    mass = 0.12  stiffness = 7500.0  damping = 2.0  unbalance = 6.0e-7
//              or, an anisotropic support (docs/model.md §10), instead of stiffness and
//              damping (never both forms): stiffness_x, stiffness_y, damping_x, damping_y
//              and optional stiffness_xy, damping_xy (default 0) on the fixed axes; K_f
//              must be positive definite, C_f positive semidefinite (reported at the
//              last of the keys that form the matrix). Scene::support is then set and
//              rotor.stiffness / rotor.damping hold the means k_bar, c_bar (the mean
//              system of §10.5); `--set k=` / `c=` are refused on such a scene.
//   [[ball]]   mass = 3.3e-5  race_radius = 0.018  radius = 1.0e-3   # one table per ball, 2..12
//              optional per ball: rolling, and the coefficients mu d mu_c mu_s v_s
//   [friction] law = "coulomb"  mu = 0.002  kappa = 1.0e3
//              none: -   viscous: d   coulomb: mu kappa   stribeck: mu_c mu_s v_s kappa
//              coulomb-set: mu (set-valued, model.md §14: only `equilibria` takes it)
//   [speed]    omega = 900.0
//   [uncertain] optional: NAME = [LOW, HIGH] per input known only within a range (a --set symbol
//              or unroundness; not omega), for `outcomes` and `design` (model.md §21.2)
//
// A ball and its race as an engineer specifies them (docs/model.md §1.1), in a [[ball]]
// table, [balls] or an override: `diameter` (r = diameter/2) with optional `density`
// (default kSteelDensity; m = density pi diameter^3 / 6) instead of mass and radius;
// `surface_radius` (l = surface_radius - r) instead of race_radius; `f`, the
// rolling-resistance length [m] (mu = f / r; also in [friction]; coulomb and coulomb-set
// only) instead of mu. Never both forms of one value for one ball, density only with a
// diameter, mu and f not both in one scene (reported at the later key). The ball keeps
// its specification (BallT::density, rolling_length, surface_radius, `specified`), so
// that a later r moves the values derived from it (set_ball).
//
// Instead of the [[ball]] tables (never both), a ring of `count` equal balls:
//
//   [balls]    count = 11          # an integer 2..12 (11.0 is not an integer)
//              mass = 3.3e-5       # per ball, OR total_mass = 3.63e-4 (m = total_mass / count)
//              race_radius = 0.018  radius = 1.0e-3
//              optional: rolling (overrides the top-level one), mu d mu_c mu_s v_s
//   [[balls.override]]             # optional, any number: one ball that differs
//              ball = 3            # 1-based, 1..count, each ball at most once
//              any key of a [[ball]] table: mass race_radius radius rolling mu d mu_c mu_s v_s
//
// The ring is expanded into Scene::balls (ball i = the template, then its override), so
// code that reads `balls` does not know the difference; Scene::ring keeps the ring itself,
// so that the ball count can be changed later (set_ball_count). On a total_mass ring an
// override's mass replaces only that ball's mass (the balls then no longer sum to
// total_mass). A friction coefficient of [balls] overrides [friction]'s for the ring.
//
// Rules: every key above is required unless marked optional; unknown keys and tables,
// wrong types (booleans and strings are not numbers; integers are reals), non-finite
// numbers and values outside range_violation() are errors, as is radius >= race_radius.
// A scene has 2..12 balls (kSceneMinBalls..kSceneMaxBalls, the analyzer's bound,
// model.md §13): a 13th [[ball]] table is an error at its header line. A coefficient the
// law does not use is an error, in [friction] or per ball; a per-ball coefficient (of a
// [[ball]] table, of [balls], or of an override) stands in for a missing [friction] one
// only if every ball has it, and otherwise overrides it for that ball. For a ring every
// rule is checked on the expanded balls and reported at the key that set the value: a
// radius >= race_radius at the radius, unless only race_radius came from an override.
//
// Loading validates everything up front and reports the violation that comes first in
// the file as one InputError (file as given, 1-based line, dotted key such as
// `rotor.mass`, `ball[2].radius` (1-based), `balls.count`, `balls.override[1].mass` (the
// first [[balls.override]] table), `friction.law`, and the rule). A missing key is
// reported at its table's header line (`balls.mass` if neither mass nor total_mass is
// given); both mass and total_mass, or both [balls] and [[ball]], at the later of the
// two; a missing table (or no balls at all) at the last line of the file; a TOML syntax
// error at toml++'s line with an empty key; an unreadable file at line 0 with an empty
// key. Nothing downstream re-checks the file.
//
// Changing a ring scene keeps the ring consistent with `balls`:
// - set_checked / apply_override of an every-ball symbol (m l r mu d mu_c mu_s v_s rho f
//   R_s) sets the ring's template and drops the ring's overrides of that field and of
//   the other form of its value (m and rho, mu and f, l and R_s; also inactive ones):
//   every ball has the value. `m` on a total_mass ring switches the ring to mass
//   held (total_mass_held = false): the count no longer divides the mass.
// - a one-ball symbol (m3, l2, ...) is recorded as a RingOverride of the ring (replacing
//   an earlier one of the same ball and field), with the caller's origin and line 0.
// - set_ball_count(scene, n, origin) rebuilds `balls` with n balls: the template (mass
//   held: every ball keeps m; total mass held: m = total_mass / n) and the overrides of
//   balls 1..n; overrides of balls beyond n stay in the ring, inactive, and apply again
//   when the count grows back. Every rule is re-checked on the new balls (set_checked
//   checks only the balls there are: an inactive override that no longer fits, say a
//   race radius below a radius set since, is reported by set_ball_count, key `n`).
//
//   abu::Scene scene = abu::load_scene("data/scenes/default.toml");
//   abu::apply_override(scene, "omega=1200");
//   abu::Params p = abu::params_of<2>(scene);
//
//   abu::Scene ring = abu::load_scene("data/scenes/ring11.toml");
//   abu::set_ball_count(ring, 6, "--n");   // ring.balls.size() == 6
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abu/core/params.hpp"
#include "abu/model/speed_profile.hpp"
#include "abu/input/ball_ring.hpp"  // BallRing, ring_balls, set_ball_count (the [balls] ring)
#include "abu/input/race_scene.hpp"  // RaceSpec: the [race] table (unround race, model.md §11)
#include "abu/model/anisotropic_support.hpp"

namespace abu {

struct ShaftSpec;  // model/shaft.hpp; the [shaft] tables are input/shaft_scene.hpp's

/// The optional [simulate] table: run-up and integration settings of `simulate` and
/// `basin` (docs/guide.md, model.md §15). Command-line flags override each key.
struct SimulateSettings {
  std::optional<SpeedProfile> speed;  ///< ramp = {omega0, omega1, alpha} or speed_profile = "FILE"
  std::optional<double> t_end;        ///< [s], > 0
  std::optional<double> every;        ///< [s], > 0
  std::optional<double> rtol;         ///< in (0, 0.1)
  std::optional<std::string> method;  ///< auto, bdf, rk8pd, rk4imp, bsimp, rkf45
  std::vector<double> balls;          ///< start: ball angles [rad] (one per ball)
  std::vector<double> from_state;     ///< start: the 2n + 4 values
};

/// One entry of the optional [uncertain] table, `NAME = [LOW, HIGH]`: an input known only within a
/// range, drawn uniformly by `outcomes` and `design` (docs/model.md §21.2). NAME is a `--set` symbol
/// or `unroundness`; the command line's --uncertain of the same NAME replaces it.
struct SceneUncertainty {
  std::string name;
  double low = 0, high = 0;
  int line = 0;  ///< in the scene file
};

/// A validated scene, for any number of balls (2..12).
struct Scene {
  std::string file;  ///< the path as given, for messages
  RotorT<double> rotor{};
  double omega = 0.0;
  FrictionLaw law = FrictionLaw::none;
  int law_line = 0;  ///< line of [friction] law in `file` (0: not from a file), for messages
  double kappa = 0.0;                ///< only meaningful for coulomb / stribeck
  std::vector<BallT<double>> balls;  ///< friction coefficients already resolved per ball
  std::optional<BallRing> ring;      ///< set iff the file has a [balls] ring; `balls` is its expansion
  std::optional<SimulateSettings> simulate;  ///< set iff the file has a [simulate] table
  std::vector<SceneUncertainty> uncertain;   ///< [uncertain], in file order
  RaceSpec race;                     ///< [race]: unround race harmonics (race_scene.hpp); round if absent
  /// Set iff [rotor] gives the fixed-frame matrices (docs/model.md §10); rotor.stiffness
  /// and rotor.damping are then their means.
  std::optional<AnisotropicSupport> support;
  /// Set iff the file has [shaft]: a flexible rotor (io/shaft_scene.hpp, model.md §18.10);
  /// rotor.unbalance is then its only [rotor] value (mass, stiffness, damping are 0: the
  /// discs, shaft and bearings replace them). Shared and immutable: copies of a scene share it.
  std::shared_ptr<const ShaftSpec> shaft;
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
/// scene's friction law uses it, the ball index, and radius < race_radius for every
/// quantity that moves them (`r`, `l`, `R_s`). The balls' specifications follow
/// (set_ball: with f given, `r` moves mu; `mu` itself switches the ball to the direct form).
/// On a ring scene the ring follows (see the top of this file).
/// Throws InputError(origin, 0, symbol, rule) and leaves the scene unchanged then.
void set_checked(Scene& scene, ParamRef ref, double value, const std::string& origin);

/// The parameter set for N balls; throws NotSupportedError if the scene has another
/// number of balls. Instantiated for N = 2, N = 3 and N = any_balls (any count).
template <int N>
ParamsT<double, N> params_of(const Scene& scene);

}  // namespace abu
