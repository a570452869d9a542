// A sweep of one parameter on a scene with an anisotropic support (docs/model.md §10.11):
// at every value the balanced states with their Floquet multipliers over pi/omega
// (analyze_floquet, the magnus route of §10.10), and where a state's largest |rho|
// crosses 1 between two values, the crossing located by bisection on the parameter and
// classified by the multiplier that crosses: +1 (fold), -1 (flip, period doubling) or a
// complex pair (Neimark-Sacker).
//
//   abu::FloquetSweep s = abu::floquet_sweep(p, *scene.support, ref, values, sampling);
//   std::string csv = abu::floquet_sweep_csv(s, header);   // one row per balanced state per value
#pragma once

#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abu/analysis/floquet_states.hpp"

namespace abu {

struct FloquetCrossing {
  enum class Kind { fold, flip, neimark_sacker };
  int member = 1;        ///< the balanced state (EquilibriumN::member)
  double value = 0.0;    ///< the parameter where max |rho| = 1 (interpolated in the final bracket)
  double lower = 0.0, upper = 0.0;  ///< the final bracket (sweep order)
  Kind kind = Kind::fold;
  std::complex<double> multiplier;  ///< the largest multiplier at the bracket end nearer to |rho| = 1
  bool to_unstable = true;          ///< |rho| grows through 1 in the sweep's direction
  int evaluations = 0;              ///< Floquet analyses spent in the bisection
};
std::string_view to_string(FloquetCrossing::Kind kind);

struct FloquetSweep {
  ParamRef param;
  std::vector<double> values;
  std::vector<FloquetAnalysis> points;  ///< one per value
  std::vector<FloquetCrossing> crossings;
};

struct FloquetSweepOptions {
  FloquetOptions floquet = [] {
    FloquetOptions o;
    o.route = FloquetRoute::magnus;  // model.md §10.10: ~1 ms a state, Hill where needed
    return o;
  }();
  /// Bisection stops when the bracket is below this, relative to max(|lower|, |upper|);
  /// default 1e-12 (the crossing is then limited by the multipliers' own accuracy)
  double bracket_tolerance = 1e-12;
  int max_bisections = 60;  ///< default 60
};

/// `base` carries the mean support; `values` in sweep order. Throws NumericalError as
/// analyze_floquet does (where: the parameter value).
FloquetSweep floquet_sweep(const ParamsN& base, const AnisotropicSupport& support, ParamRef param,
                           const std::vector<double>& values, const BalancedSampling& sampling,
                           const FloquetSweepOptions& options = {});

/// The crossings between neighbouring entries of s.values/s.points (appended to
/// s.crossings): how floquet_sweep finds them, also for the points of a continuation branch
/// (model.md §10.13), whose values need not be monotone.
void locate_floquet_crossings(FloquetSweep& s, const ParamsN& base, const AnisotropicSupport& support,
                              const BalancedSampling& sampling, const FloquetSweepOptions& options = {});

/// The balanced state `member` at a parameter value, judged with the options given; nullopt
/// where it does not exist (an existence boundary inside the bracket).
using FloquetAt = std::function<std::optional<BalancedFloquet>(double value, int member, const FloquetOptions&)>;
/// The same search with the states at a bisection point given by `floquet_at` (the balanced
/// samples of an n-ball branch, model.md §10.16, whose free angles the branch holds).
void locate_floquet_crossings(FloquetSweep& s, const FloquetAt& floquet_at, const FloquetSweepOptions& options = {});

/// One end of a bracket of the unit-circle search: ln max|rho| of a state and its largest multiplier.
struct GrowthSample {
  double growth = 0.0;
  std::complex<double> leading;
};
/// The same state at a parameter value; nullopt where it is lost (an existence boundary).
using GrowthAt = std::function<std::optional<GrowthSample>(double value)>;
/// The crossing of |rho| = 1 between lo and hi, where the samples `a` (at lo) and `b` (at hi)
/// have ln max|rho| of opposite signs: bisection on the parameter to the options' bracket
/// tolerance, the root interpolated linearly in the last bracket, the kind by the multiplier
/// at the end nearer to |rho| = 1 (member left 1). nullopt where growth_at loses the state
/// inside the bracket (then *lost_at, if given, is where). Any machine whose states have
/// multipliers uses it: the balanced states (above), the composed machine's orbits (§20.6).
std::optional<FloquetCrossing> bisect_unit_circle(double lo, double hi, GrowthSample a, GrowthSample b,
                                                  const GrowthAt& growth_at, const FloquetSweepOptions& options,
                                                  double* lost_at = nullptr);

/// One row per balanced state per value: the parameter, member, stability, rho_abs_max,
/// decay_rate, method, deflated, then mult_re1, mult_im1, ... (modulus descending).
std::string floquet_sweep_csv(const FloquetSweep& s, const std::string& header);
/// One row per crossing: member, value, kind, direction, multiplier, bracket.
std::string floquet_crossings_csv(const FloquetSweep& s, const std::string& header);
/// The crossings as lines for stderr ("none" if there are none).
std::string floquet_crossings_text(const FloquetSweep& s);

}  // namespace abu
