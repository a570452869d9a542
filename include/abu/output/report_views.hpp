// The rotordynamics views and stated answers of the outputs (docs/views.md, docs/model.md
// §16): the answer of one parameter point (omega_n, capacity against U, which states are
// stable, the best one and its reduction against the unbalanced rotor), the parameters as
// a JSON object with units, each eigenvalue's mode (fixed-frame whirl, damping, label,
// eigenvector), the Campbell CSV with its critical speeds, and the stability ranges of a
// sweep or a continuation (summary_NAME.json).
//
//   abu::PointAnswer ans = abu::point_answer(analysis, p);
//   std::string lines = abu::answer_lines(ans, abu::SpeedUnit::rpm, "# ");
//   auto samples = abu::campbell_samples(sweep_result, base);  // omega sweeps only
//   std::string csv = abu::campbell_csv(samples, header, abu::SpeedUnit::rpm);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/core/speed_units.hpp"
#include "abu/output/report.hpp"
#include "abu/linear/modes.hpp"
#include "abu/scan/scan.hpp"

namespace abu {

/// What one parameter point answers (docs/views.md "The answer").
struct PointAnswer {
  double omega = 0, omega_n = 0;   ///< [rad/s]
  double capacity = 0;             ///< sum m_i l_i [kg m]
  double unbalance = 0;            ///< U [kg m]
  bool capacity_exceeded = false;  ///< U > capacity: no balanced state can exist
  bool balanced_exists = false;    ///< a balanced equilibrium was found
  bool balanced_stable = false;    ///< one of them (a sample, n >= 3: normally) is stable
  std::vector<std::string> stable_states;  ///< labels ("balanced 1", "together 2", "aligned +- 1")
  std::optional<std::string> best;         ///< the stable state of least |q|; nullopt: none stable
  double best_q_abs = 0;                   ///< its |q| [m]
  /// |q0| (model.md (16.5.1)): the whirl of the same rotor whose balls cancel each other
  /// (mass M = M_r + sum m_i, unbalance U) [m], and of the rotor without the balls (M_r).
  double q0_balls_neutral = 0, q0_without_balls = 0;
  double reduction = 0;  ///< best_q_abs / q0_balls_neutral (0 when the best state is balanced)
};
PointAnswer point_answer(const Analysis& a, const Params& p);
PointAnswer point_answer(const AnalysisN& a, const ParamsN& p);

/// The answer as text lines, each starting with `prefix` ("# " for CSV headers).
std::string answer_lines(const PointAnswer& ans, SpeedUnit unit, std::string_view prefix);
/// The answer as a JSON object (values with their units).
std::string answer_json(const PointAnswer& ans);

/// Every parameter as {"symbol": {"value": v, "unit": "..."}} (model.md symbols, SI).
std::string parameters_json(const Params& p);
std::string parameters_json(const ParamsN& p);

/// The JSON keys added to eigenvalue k of an equilibrium's spectrum (leading ", "): frame,
/// mode index and label, fixed-frame eigenvalue and whirl, damping ratio, log decrement,
/// participation, and the normalised eigenvector (x = (v, lambda v) in the state order of
/// model.md (2.2), v of unit 2-norm, its largest component real and positive).
template <int N>
std::string eigen_view_json(const ParamsT<double, N>& p, const SpectrumT<N>& sp, int k,
                            const std::vector<ModeView>& modes, const std::vector<int>& mode_of);

/// The table's block of fixed-frame modes: per equilibrium and mode, the label, the signed
/// whirl frequency (in `unit` too), zeta, delta and the rotor share.
std::string modes_table(const Analysis& a, const Params& p, SpeedUnit unit);
std::string modes_table(const AnalysisN& a, const ParamsN& p, SpeedUnit unit);

/// Mode shapes (docs/views.md): for every equilibrium and every mode (structural zeros left
/// out) one cycle of the motion Re(v e^{i theta}), theta = 0 .. 2 pi in 48 steps, of the rotor
/// centre and of each ball's centre in the rotating frame, in race-radius units (ball i drawn at
/// its place l_i e^{i beta_i} / l_1), displacements scaled so that the largest is 0.25:
/// `equilibrium,family,pattern,member,mode,label,whirl_frequency,zeta,body,theta,x0,y0,x,y` (x0, y0 the body's place).
std::string mode_shapes_csv(const Analysis& a, const Params& p, std::string_view header);
std::string mode_shapes_csv(const AnalysisN& a, const ParamsN& p, std::string_view header);
/// The index (0-based) of the equilibrium a mode-shape chart shows: the best stable state,
/// else the first equilibrium; and the chart's per-mode titles.
struct ModeChart {
  int equilibrium = 0;
  std::string label;
  std::vector<std::string> titles;
};
ModeChart mode_chart(const Analysis& a, const Params& p);
ModeChart mode_chart(const AnalysisN& a, const ParamsN& p);

/// The modes of one equilibrium at one speed, one point of a Campbell diagram.
struct CampbellSample {
  int step = 0;        ///< sweep: index of the value; continuation: point index within the branch
  double omega = 0;    ///< [rad/s]
  double omega_n = 0;  ///< [rad/s], at this point (moves with the ball mass)
  std::string family, pattern;
  int member = 0;      ///< sweep: member; continuation: branch number (1-based)
  bool stable = false;
  std::string series;  ///< one equilibrium followed over the speed (critical speeds are per series)
  std::vector<ModeView> modes;
};
/// The samples of an omega sweep (empty if the swept parameter is not omega); `base` the
/// sweep's other parameters, `params[i]` the parameters of value i.
std::vector<CampbellSample> campbell_samples(const SweepResult& s, const Params& base);
std::vector<CampbellSample> campbell_samples(const SweepResultN& s, const std::vector<ParamsN>& params);
/// The same a value at a time: value `step`'s samples appended, then the series made
/// contiguous once every value is in.
void append_campbell_samples(std::vector<CampbellSample>& out, int step, const ParamsN& p, const AnalysisN& a);
void sort_campbell_series(std::vector<CampbellSample>& samples);
/// One two-ball equilibrium's sample at sweep step `step` (p: that value's parameters).
CampbellSample campbell_sample(int step, const Params& p, const Equilibrium& e, const Spectrum& sp);
/// The samples of a continuation in omega (two balls; empty for another parameter).
std::vector<CampbellSample> campbell_samples(const ContinuationRun& run, const Params& p);

/// A speed where a rotor forward-whirl mode crosses the 1X line (fixed-frame whirl = omega,
/// i.e. its rotating-frame frequency passes 0, (16.1.3)): linear interpolation of
/// whirl - omega between the two samples that bracket the sign change.
struct CriticalSpeed {
  std::string series, family, pattern;
  int member = 0;
  double omega = 0;          ///< [rad/s]
  double omega_n = 0;        ///< [rad/s]
  double bracket_from = 0, bracket_to = 0;  ///< the bracketing samples' speeds
  double damping_ratio = 0;  ///< interpolated at the crossing
};
std::vector<CriticalSpeed> critical_speeds(const std::vector<CampbellSample>& samples);

/// `campbell_<param>.csv`: one row per mode per equilibrium per speed.
std::string campbell_csv(const std::vector<CampbellSample>& samples, std::string_view header, SpeedUnit unit);

/// Parameter ranges of a sweep or continuation where a state is stable.
struct Range {
  double from = 0, to = 0;
  /// The ends: "located" (a special point of a continuation, to its accuracy), "grid"
  /// (the true end lies between `from` and the outer neighbour `from_outside`), or
  /// "interval" (the end of the computed interval).
  std::string from_kind, to_kind;
  std::optional<double> from_outside, to_outside;
};
struct StabilityRanges {
  std::vector<Range> balanced_stable;  ///< where a balanced state is stable
  std::vector<Range> nothing_stable;   ///< where no state is stable
  std::vector<Range> some_stable;      ///< where some state is stable
};
/// What stability_ranges collects at one value of a sweep: whether a balanced state is
/// stable, whether any state is.
struct StableAt {
  bool balanced = false, some = false;
};
StableAt stable_at(const Analysis& a);
StableAt stable_at(const AnalysisN& a);
/// The ranges from those flags, one per value (a sweep written as it comes).
StabilityRanges stability_ranges(const std::vector<double>& values, const std::vector<StableAt>& flags);
StabilityRanges stability_ranges(const SweepResult& s);
StabilityRanges stability_ranges(const SweepResultN& s);
StabilityRanges stability_ranges(const ContinuationRun& run);

/// Maximal runs of consecutive grid values where `flag` holds, with grid-bracketed ends.
std::vector<Range> grid_ranges(const std::vector<double>& values, const std::vector<bool>& flag);

/// What the speed ranges of a two-ball map read per cell (output/map_files.hpp builds it
/// from the tiles' grid blocks): the axes' values and, per cell at ix * y.size() + iy,
/// bit 0 = a balanced state is stable (the summary's balanced_stable = 1), bit 1 = some
/// state is stable (n_stable > 0). Empty for the other maps.
struct MapVerdicts {
  std::vector<double> x, y;
  std::vector<std::uint8_t> cells;
  static constexpr std::uint8_t balanced_stable = 1, some_stable = 2;
};

/// A map with an omega axis: per value of the other axis, the omega ranges where a
/// balanced state is stable and where nothing is. `summary_<x>_<y>.json` and stderr lines
/// (at most `max_lines` rows). Empty strings when `v` is empty or neither axis is omega.
struct MapRangesOutput {
  std::string json, text;
};
template <int N>
MapRangesOutput map_ranges(const MapVerdicts& v, std::string_view x, std::string_view y,
                           std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p,
                           SpeedUnit unit, int max_lines);

/// stderr lines: the ranges in the parameter's unit (and the display unit for omega, and as
/// multiples of omega_n when `omega_n` > 0).
std::string ranges_text(const StabilityRanges& r, std::string_view param, std::string_view param_unit,
                        SpeedUnit unit, double omega_n = 0);
/// `summary_<param>.json`: program, command, scene, parameters (object with units), the
/// swept parameter, omega_n, capacity and U, the ranges and the critical speeds.
template <int N>
std::string summary_json(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p,
                         std::string_view param, std::string_view param_unit, double from, double to,
                         const StabilityRanges& r, const std::vector<CriticalSpeed>& critical, SpeedUnit unit);

}  // namespace abu
