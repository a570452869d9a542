// Trajectories of the ball balancer (model.md §3 at constant speed, §9 during a run-up),
// integrated by GSL odeiv2 with the analytic Jacobian, and what they end in
// (model.md §15: the method choice, the outcome, settle and stall criteria).
//
//   abu::SimulationOptions o;  o.t_end = 2.0;  o.every = 1e-3;
//   auto speed = abu::SpeedProfile::ramp(100, 400, 200);
//   abu::SimulationResult<2> r = abu::simulate(p, speed, abu::start_at_rest(p, {2.0, 4.0}), o);
//   if (r.status != abu::SimulationStatus::completed) fmt::print("{}\n", r.reason);
//   fmt::print("{}\n", abu::to_string(r.summary.outcome));
//
// N = 2 (fixed-size types) and N = any_balls (bounded-dynamic, any 2 <= n <= 12); no
// allocation per step: GSL's stepper, control and evolve objects are allocated once,
// the callbacks work on the model's fixed or bounded storage.
#pragma once

#include <atomic>
#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abu/model/speed_profile.hpp"
#include "abu/model/model.hpp"

namespace abu {

struct RaceShape;           // model/unround_race.hpp
struct AnisotropicSupport;  // model/anisotropic_support.hpp

/// GSL odeiv2 steppers the simulation offers (`--method`).
enum class IntegrationMethod {
  automatic,  ///< bsimp if the start's stiffness ratio exceeds the threshold, else rk8pd (model.md §15.1)
  bdf,        ///< gsl msbdf: variable-order (1..5) BDF, analytic Jacobian (unreliable at kappa = 1e6, model.md §15.1)
  rk8pd,      ///< explicit Runge-Kutta Prince-Dormand 8(9); non-stiff problems
  rk4imp,     ///< implicit Gauss-Legendre 4th order (A-stable), analytic Jacobian
  bsimp,      ///< semi-implicit extrapolation (Bader-Deuflhard), analytic Jacobian: the stiff default
  rkf45,      ///< explicit Runge-Kutta-Fehlberg 4(5)
};
std::string_view to_string(IntegrationMethod m);
std::optional<IntegrationMethod> integration_method_from_string(std::string_view name);

struct SimulationOptions {
  double t_end = 1.0;   ///< [s], > 0
  double every = 0.0;   ///< output interval [s]; 0: t_end / 2000. Samples at k * every and t_end (dense output, model.md §15.1)
  /// Local error per component <= rtol * (scale_i + |x_i|), scale_i the model's scaling:
  /// q in the displacement scale L, q' in L omega_max, beta' in omega_max; angles
  /// absolutely, <= rtol rad (model.md §15.1). bsimp's error control gets rtol / 30, so that
  /// the global error of every method stays within a small factor of rtol (measured: 0.4 to 8);
  /// the samples between steps are interpolated to rtol.
  double rtol = 1e-7;
  IntegrationMethod method = IntegrationMethod::automatic;
  /// automatic: implicit when rho(J) / (omega_max + omega_n) exceeds this (model.md §15.1).
  double stiffness_threshold = 300.0;
  unsigned long max_steps = 200'000'000;  ///< then the run fails (exit 3), keeping its samples
  double settle_tolerance = 1e-3;   ///< scaled distance for "settled" and the settle time (model.md §15.2)
  double final_window = 0.1;        ///< fraction of the run judged for the outcome and stall (model.md §15.2)
  bool record = true;               ///< keep the samples and summarize (the benchmark turns it off)
  const std::atomic<bool>* interrupt = nullptr;  ///< polled after every step (Ctrl-C)
  std::function<void(double t)> progress;        ///< called at every sample
  /// Called at every recorded sample with t and the 2n + 4 state values; returning true
  /// ends the run there (status completed, SimulationResult::stopped_early): the settle
  /// test of `basin` (model.md §15.5).
  std::function<bool(double t, const double* x)> stop_at_sample;
  /// Friction law `lugre` only: the bristle states z_i(0) [rad], one per ball; empty: 0
  /// (model.md §12.7).
  std::vector<double> bristle_start;
  /// An unround race (model.md §11, §15.6): the balls' centre paths; null (or a round race):
  /// the round race of §3. N = any_balls only. Not owned: it must outlive the run.
  const RaceShape* race = nullptr;
  /// An anisotropic support (model.md §10, §20): the rotor's support force turns with the
  /// spin angle theta(t); `p` must carry its mean (k_bar, c_bar). Null (or isotropic): p's
  /// isotropic support. N = any_balls only. Not owned: it must outlive the run.
  const AnisotropicSupport* support = nullptr;
};

enum class SimulationStatus { completed, interrupted, failed };
std::string_view to_string(SimulationStatus s);

/// What a run ended in (model.md §15.2).
/// equilibrium: at rest at an equilibrium of an unround race (model.md §11.4, §15.7); orbit: on
/// one of its states as a periodic orbit on an anisotropic support (§20.4, §20.8).
enum class SimulationOutcome { balanced, aligned, rest, periodic, not_settled, equilibrium, orbit };  // rest is written "stuck"
std::string_view to_string(SimulationOutcome o);

template <int N>
struct TrajectorySample {
  double t = 0;      ///< [s]
  double omega = 0;  ///< omega(t) [rad/s]
  State<double, N> x;
};

struct IntegrationStats {
  unsigned long steps = 0;           ///< accepted steps
  unsigned long rejected = 0;        ///< steps rejected by the error control
  unsigned long rhs_evaluations = 0;
  unsigned long jacobian_evaluations = 0;
  unsigned long restarts = 0;        ///< at breakpoints of the speed profile (omega' jumps)
  /// Steps discarded and taken again shorter because the dense output's interpolant missed the
  /// tolerance (model.md §15.1); counted in `rejected` too.
  unsigned long retaken = 0;
  double wall_seconds = 0;
};

struct SimulationSummary {
  SimulationOutcome outcome = SimulationOutcome::not_settled;
  std::string pattern;              ///< aligned: "+-" etc. (ball 1 is +), else empty
  std::string note;                 ///< why, in words
  double t_end = 0;                 ///< the last sample's time (< the requested end if interrupted or failed)
  std::vector<double> state_end;    ///< the 2n + 4 values at t_end
  double max_q_abs = 0, t_max_q_abs = 0;  ///< the largest |q| of the run, located between samples (model.md §15.4) [m], [s]
  std::optional<double> settle_time;      ///< settled outcomes only [s]
  double window_from = 0;           ///< start of the final window [s]
  bool stalled = false;             ///< some ball whirls near omega_n instead of following the rotor (§15.3)
  std::vector<int> stalled_balls;   ///< 1-based
  std::vector<double> ball_speed_fixed;  ///< mean fixed-frame angular speed of each ball over the window [rad/s]
  double omega_mean_window = 0;     ///< mean spin speed over the window [rad/s]
  double omega_n = 0;               ///< sqrt(k / M) [rad/s]
  std::vector<double> t_omega_n;    ///< times at which omega(t) = omega_n
  std::optional<double> max_q_abs_run_up;  ///< largest |q| while omega' != 0, located as max_q_abs [m]
  /// What the run leaves (model.md §21.1): the largest |q| over the final window [m]; the same
  /// rotor's whirl at the last speed under U alone (16.5.1, (21.1) on an anisotropic support) and
  /// with the balls held at their start angles [m].
  double residual_q_abs = 0, bare_rotor_q_abs = 0, balls_held_q_abs = 0;
  bool speed_changing_at_end = false;
  /// Unround race (model.md §15.7): the equilibrium of §11.4 the run ended at (1-based in the
  /// list `equilibria` prints, sorted by |q|), its |q| [m] and the scaled distance to it.
  int unround_member = 0;
  double unround_q_abs = 0, unround_distance = 0;
  /// Unround race on an anisotropic support (model.md §20.8): the orbit the run ended on (its
  /// number in `equilibria`'s list), its largest |q| over the period [m] and the scaled distance
  /// to it at the end's spin angle.
  int orbit_member = 0;
  double orbit_q_abs_max = 0, orbit_distance = 0;
};

template <int N>
struct SimulationResult {
  SimulationStatus status = SimulationStatus::completed;
  std::string reason;  ///< interrupted or failed: where and why
  IntegrationMethod method = IntegrationMethod::bsimp;  ///< the one used
  double spectral_radius = 0;   ///< rho(J) [1/s] at the stiffness probe (model.md §15.1)
  double stiffness_ratio = 0;   ///< rho(J) / (omega_max + omega_n)
  double displacement_scale = 0;  ///< L [m]
  /// Start components nonzero but below 1e-3 of their absolute tolerance (rtol times their
  /// scale, model.md §15.1), integrated as 0: below what the run resolves, and GSL's bsimp
  /// takes any change of so tiny a component for a runaway (its weights are |y_i|).
  int start_below_resolution = 0;
  double memory_estimate = 0;  ///< simulation_memory_estimate of the run [bytes] (0: not recording)
  std::vector<TrajectorySample<N>> samples;
  IntegrationStats stats;
  SimulationSummary summary;
  State<double, N> x_end;       ///< the state at the last time reached
  double t_reached = 0;
  bool stopped_early = false;   ///< options.stop_at_sample ended the run at t_reached
  bool unround_race = false;    ///< integrated on an unround race (options.race, model.md §15.6)
  bool anisotropic_support = false;  ///< integrated on an anisotropic support (options.support, model.md §20)
  /// Friction law `lugre` (model.md §12.7): the n bristle states integrated beside x; the
  /// z_i of every sample (bristle_count per sample, in sample order) and at t_reached.
  int bristle_count = 0;
  std::vector<double> bristle;
  std::vector<double> bristle_end;
};

/// Balls at rest in the rotor frame at the given angles [rad], rotor at rest (q = q' = 0).
template <int N>
State<double, N> start_at_rest(const ParamsT<double, N>& p, const std::vector<double>& beta);

/// The equilibrium `position` displaced by eps (in the scaled max norm: q / L, angles in
/// rad, q' / (L |lambda|), beta' / |lambda|) along the real part of the eigenmode (v, lambda v)
/// of eigenvalue lambda: the mode that decays slowest (or grows fastest) for the rightmost one.
template <int N>
using ModeVector = Eigen::Matrix<std::complex<double>, dof_size<N>, 1, Eigen::ColMajor, dof_capacity<N>, 1>;
template <int N>
State<double, N> perturbed_equilibrium(const ParamsT<double, N>& p, const Coordinates<double, N>& position,
                                       std::complex<double> lambda, const ModeVector<N>& mode, double eps);

/// What a run of `balls` balls holds while it records (options.record) [bytes], an upper
/// bound: per sample (t_end / every + 2 of them) the sample itself (the 2n + 4 values at
/// capacity), a bristle or deflection value per ball, and twice its CSV row (3n + 9 columns
/// at 24 characters; the text grows by doubling). Measured on 11 balls and 1e6 samples:
/// 1.34 GB peak for an estimate of 2.3 GB (tests/cli/check_simulate.sh). `with_text` false:
/// a run whose samples are not written (a basin cell's).
double simulation_memory_estimate(const SimulationOptions& options, int balls, bool with_text = true);

/// Throws InputError for invalid options or start (t_end <= 0, every, rtol outside (0, 0.1),
/// a state of the wrong length or not finite, samples that would not fit in the memory this
/// machine has available): the checks of simulate(), shared.
void check_simulation_input(const SimulationOptions& options, int dim, const double* x0, int size, int balls);

/// Integrates from x0 at t = 0 to options.t_end. Never throws on numerical trouble: a
/// step-size underflow, a non-finite right-hand side or too many steps end the run with
/// status failed and the reason (where and why); samples up to there are kept. Throws
/// InputError for invalid options (t_end <= 0, every <= 0 beyond t_end, rtol outside
/// (0, 0.1), a state of the wrong length or not finite).
template <int N>
SimulationResult<N> simulate(const ParamsT<double, N>& p, const SpeedProfile& speed, const State<double, N>& x0,
                             const SimulationOptions& options);

/// The outcome and the other figures of a recorded run (model.md §15.2, §15.3).
template <int N>
SimulationSummary summarize(const ParamsT<double, N>& p, const SpeedProfile& speed,
                            const std::vector<TrajectorySample<N>>& samples, const SimulationOptions& options);

/// The point of the balanced set W(beta) = 0 nearest to beta (minimal-norm Gauss-Newton,
/// model.md §15.2); nullopt if the set does not exist or the projection does not converge.
template <int N>
std::optional<std::vector<double>> nearest_balanced_angles(const ParamsT<double, N>& p, const std::vector<double>& beta);

}  // namespace abu
