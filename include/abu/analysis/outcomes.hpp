// The outcome of a machine in operation (docs/model.md §21): a scene run through its speed
// profile (a run-up, then a hold) from many starts, every ball's start angle and each uncertain
// input drawn from the unit cube (core/sampling.hpp), and what the runs left: the residual
// vibration at the end against the bare rotor and against the balls held where they started,
// the peak on the way, stalls, settle times, balls stuck away from balance; medians, 90th
// percentiles and the worst, with confidence intervals for the sample size.
//
//   abu::OutcomeOptions o;  o.samples = 256;  o.sim.t_end = 3;
//   o.uncertain.push_back({"mu", 1e-3, 3e-3});
//   abu::OutcomeStudy s = abu::analyze_outcomes(scene, abu::SpeedProfile::ramp(1, 1047, 1000), o);
//   fmt::print("{} m\n", s.summary.residual.median.value);
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "abu/core/sampling.hpp"
#include "abu/core/status.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/speed_profile.hpp"

namespace abu {

/// An input known only within a range: uniform on [low, high] (docs/model.md §21.2). `name` is a
/// `--set` symbol (U, k, c, M_r, mu, m, f, mu2, ...) or `unroundness` (the factor in [0, 1] on the
/// scene's [race]: its runout); omega is the speed profile's.
struct UncertainInput {
  std::string name;
  double low = 0, high = 0;
  std::string origin = "--uncertain";  ///< where it was given, for messages: the option, or the scene file
  int line = 0;                        ///< the scene file's line (0: the command line)
};

/// The study's uncertain inputs: the scene's [uncertain] entries, each replaced by a `given` one
/// of the same name (the command line's), then the other given ones, in order.
std::vector<UncertainInput> study_inputs(const Scene& scene, const std::vector<UncertainInput>& given);

/// Sets a study's input on the scene: a `--set` symbol by the scene's rules (set_checked), or
/// `unroundness` (scale_race). Throws InputError naming `origin`.
void set_study_input(Scene& scene, const std::string& name, double value, const std::string& origin);

/// Parses "NAME=LOW:HIGH" (the --uncertain option and the [uncertain] table's form). Throws
/// InputError naming `origin`.
UncertainInput parse_uncertain(const std::string& text, const std::string& origin = "--uncertain");

struct OutcomeOptions {
  int samples = 256;                      ///< runs (starts x inputs), >= 1
  unsigned long seed = 1;                 ///< the points' seed (the same seed, the same study)
  SampleDesign design = SampleDesign::sobol;
  std::vector<UncertainInput> uncertain;  ///< besides every ball's start angle
  SimulationOptions sim;                  ///< t_end, every, rtol, method; record, interrupt and progress are set here
  double confidence = 0.95;               ///< of every interval
  /// The residual that counts as "below the limit" [m]; 0: each run's own bare rotor (16.5.1).
  double residual_limit = 0;
  int threads = 1;                        ///< workers; the result does not depend on it
  const std::atomic<bool>* interrupt = nullptr;  ///< polled between and within runs
  std::function<void(int done, int total)> progress;  ///< called after each run (from a worker, serialized)
};

/// One run: its start, its inputs, and what it left (docs/model.md §21.1).
struct OutcomeSample {
  int index = 0;                 ///< 0-based point of the design
  bool done = false;             ///< false: not run (interrupted before it)
  std::vector<double> beta0;     ///< start angles [rad], one per ball
  std::vector<double> inputs;    ///< the uncertain inputs' values, as OutcomeOptions::uncertain
  std::string outcome;           ///< balanced | aligned:PATTERN | stuck | periodic | slipping | not_settled | failed
  std::string reason;            ///< failed: where and why
  double residual = 0;           ///< largest |q| over the final window [m] (§21.1)
  double bare_rotor = 0;         ///< |q0| of (16.5.1) at the final speed, this run's inputs [m]
  double balls_fixed = 0;        ///< the rotor's |q| with the balls held at beta0 (21.1) [m]
  double peak = 0;               ///< largest |q| of the run [m]
  std::optional<double> peak_run_up;   ///< largest |q| while the speed changes [m]
  bool stalled = false;          ///< a ball whirls near omega_n (§15.3)
  std::optional<double> settle_time;   ///< settled runs (§15.2) [s]
  bool stuck_off_balance = false;  ///< every ball at rest on the rotor, the residual unbalance above 1e-2 of capacity
  unsigned long steps = 0;
};

/// A figure's median, 90th percentile and worst over the runs that have it.
struct FigureStatistics {
  QuantileEstimate median, p90, worst;
  int count = 0;  ///< runs with the figure (0: none, the estimates unset)
};

struct OutcomeSummary {
  int runs = 0, failed = 0;
  FigureStatistics residual;      ///< [m]
  FigureStatistics ratio_bare;    ///< residual / bare_rotor
  FigureStatistics ratio_fixed;   ///< residual / balls_fixed (runs with balls_fixed > 0)
  FigureStatistics peak;          ///< [m]
  FigureStatistics settle_time;   ///< [s], settled runs
  ProportionEstimate balanced, below_limit, stalled, stuck_off_balance, not_settled;
  double bare_rotor_median = 0;   ///< [m], the bare rotor over the inputs
};

struct OutcomeStudy {
  Status status;                  ///< not converged: interrupted; numerical issue: some run failed (its reason)
  std::vector<OutcomeSample> samples;  ///< in design order; `done` false where not run
  OutcomeSummary summary;         ///< over the done runs that did not fail
  int balls = 0;
  double omega_final = 0;         ///< [rad/s]
  std::string speed;              ///< the profile, described
  OutcomeOptions options;         ///< as run (without the callbacks)
  double memory_estimate = 0;     ///< [bytes]
};

/// What a study holds at most [bytes]: each worker's recorded run and every sample's figures.
double outcome_memory_estimate(const OutcomeOptions& o, int balls);

/// A run's default end: the profile's speed change, then two seconds of hold (docs/model.md §21.1).
double default_outcome_end(const SpeedProfile& speed);

/// Runs the study (docs/model.md §21). Throws InputError for bad options (samples < 1, an
/// uncertain input that names no parameter of the scene, low > high, a range the scene's rules
/// refuse at either end, a study larger than the memory available) before any run, and
/// NotSupportedError for a flexible shaft (`basin` and `simulate` answer it start by start).
/// A run that fails numerically is kept as `failed` with its reason, the others summarized.
OutcomeStudy analyze_outcomes(const Scene& scene, const SpeedProfile& speed, const OutcomeOptions& o);

/// The summary of the done, not failed samples (also after an interruption).
OutcomeSummary summarize_outcomes(const std::vector<OutcomeSample>& samples, double residual_limit, double confidence);

/// The rotor's steady whirl radius at speed omega under the rotating imbalance W (kg m, complex,
/// rotor frame) [m]: the largest |q| over a turn of (K - M omega^2 + i omega C) z = omega^2 W (1, -i)
/// (16.5.1) with the support's 2 x 2 matrices (isotropic: omega^2 |W| / |k - M omega^2 + i c omega|).
double steady_whirl_radius(const Scene& scene, double omega, std::complex<double> W);

}  // namespace abu
