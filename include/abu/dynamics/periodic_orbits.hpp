// Periodic orbits (limit cycles) of the two-ball model at constant speed, born at the
// Hopf points of an equilibrium continuation and followed in one parameter with the
// project's pseudo-arclength engine (continuation/arclength.hpp), by multiple shooting
// (docs/model.md §17: the choice argued, the equations, the multipliers, LPC/PD/NS).
//
// Unknowns (scaled, model.md §17.2): the states y_1..y_M at M equally spaced times of
// the orbit (y = D^-1 x, D = diag(L, L, 1, 1, L w_H, L w_H, w_H, w_H)), the period
// T / T_H and the parameter mapped to [0, 1] over the requested interval. Equations:
// phi(y_j, T / M) - y_{j+1} = 0 (cyclic) and a phase condition on y_1. Each flow and its
// transition matrix come from GSL odeiv2 on the variational equations (bsimp with the
// analytic Jacobian when the spectrum is stiff, else rk8pd). The Floquet multipliers
// are the eigenvalues of the product of the M transition matrices, computed factor by
// factor (linear/floquet.hpp).
//
//   abu::ContinuationRun run = abu::continue_branches(p, ref, 2000.0, options);
//   for (const abu::SpecialPoint& hb : hopf points of run)
//     abu::CycleBranch c = abu::continue_cycles(p, ref, hb, run.from, run.to, abu::CycleOptions{});
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "abu/continuation/arclength.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/core/params.hpp"
#include "abu/core/status.hpp"

namespace abu {

struct CycleOptions {
  /// M shooting intervals per period at the first orbit; with adapt_intervals the fewest.
  int intervals = 5;
  /// The shooting mesh re-chosen along the branch (model.md §17.9): about (ln |mu_max| +
  /// interval_growth) / interval_growth intervals (mu_max the largest Floquet multiplier), placed
  /// so that each holds an equal share of ln max(1, |Phi_j|) + interval_growth times its fraction
  /// of the period: each interval's transition matrix grows by at most about
  /// e^interval_growth; at most max_intervals. A mesh is re-chosen when the number changes or an
  /// interval holds 1.5 times the average. Not on the stiff route (uniform, fixed M).
  bool adapt_intervals = true;
  double interval_growth = 7.0;
  int max_intervals = 400;
  /// Newton's matrix kept from the predicted orbit, the iterations integrating the state
  /// only (model.md §17.7); false: full Newton, the variational equations every iteration.
  bool chord_corrector = true;
  /// The kept Newton matrices moved to the predicted orbit's period by the linearized flow at
  /// each interval's end before they are extrapolated (model.md §17.7, the fast modes'
  /// rotation with the period).
  bool shift_newton_matrix = true;
  double rtol = 1e-13;         ///< integrator tolerance on the scaled state (the residuals: the orbit's accuracy)
  /// Tolerances of the variational equations (model.md §17.8), never tighter than rtol:
  /// the chord corrector's Newton matrix at the predicted orbit (it sets only the corrector's
  /// contraction rate, not the orbit), and the transition matrices at a converged orbit (its
  /// Floquet multipliers and the next tangent). Used by the chord corrector only.
  double newton_rtol = 1e-6;
  double floquet_rtol = 1e-11;
  /// The chord corrector's Newton matrix at a predicted orbit extrapolated along the branch
  /// (quadratic through the last three accepted orbits' accurate ones, linear through two)
  /// instead of integrated at newton_rtol (model.md §17.7); integrated at the first two
  /// orbits, on the stiff route, and for a retried step. False: always integrated.
  bool extrapolate_newton_matrix = true;
  /// LPC, PD and NS located on the branch (the test function's zero, model.md §17.5); false:
  /// interpolated between the two orbits around the sign change. The stiff route's PD and NS
  /// are always interpolated.
  bool locate_specials = true;
  /// Scaled amplitude |z| ||D^-1 q_H|| of the first orbit (model.md (17.3)): small enough
  /// for the normal form, large enough to stay off the Hopf point's singular Jacobian.
  double first_amplitude = 2e-3;
  double max_period_factor = 50;  ///< the branch ends where T > this * 2 pi / w_H (homoclinic approach)
  int samples_per_interval = 16;  ///< for the amplitude and the ball angle range
  /// Each orbit's shooting points kept in CycleOrbit::profile (the start of an independent
  /// recomputation); off, a branch holds ~1 kB an orbit whatever the mesh.
  bool keep_profiles = false;
  /// A step on which a Floquet multiplier moves farther than this (in the complex plane,
  /// moduli clamped at 2) is retried shorter: a PD or NS crossing and its return within one
  /// step would leave the test functions' signs unchanged (model.md §17.5). 0: no check.
  double max_multiplier_jump = 0.25;
  /// Steps in the weighted unknowns (model.md §17.7: the orbit's L2 norm, whatever the mesh).
  ContinuationOptions continuation{0.01, 1e-7, 0.05, 300, 1};
  /// The stiff route (model.md §17.11), taken where the fastest mode at the Hopf point is
  /// over 1e6 times its frequency (coulomb balls): fixed Radau IIA steps, stiff_steps per
  /// interval at first, doubled at the first orbit until its period and resolved multipliers
  /// change by at most stiff_accuracy (relative; multipliers relative to max(|mu|, 1e-6)),
  /// at most max_stiff_steps; then kept along the branch.
  int stiff_intervals = 16;
  int stiff_steps = 32;
  int max_stiff_steps = 1024;
  double stiff_accuracy = 1e-9;
};

/// One converged orbit.
struct CycleOrbit {
  double parameter = 0;
  double period = 0;     ///< [s]
  double amplitude = 0;  ///< max |q| over the orbit [m] (rotating frame: |q| is the fixed-frame whirl radius, §2)
  std::vector<double> ball_min, ball_max;  ///< range of each ball angle beta_i over the orbit [rad]
  /// All 2n + 4 multipliers, by modulus, descending; log_moduli keeps moduli below 1e-308.
  std::vector<std::complex<double>> multipliers;
  std::vector<double> log_moduli;
  double trivial_distance = 0;  ///< |mu - 1| of the multiplier closest to 1 (the flow direction)
  int unstable = 0;             ///< nontrivial multipliers with |mu| > 1
  bool stable() const { return unstable == 0; }
  Status floquet_status;
  /// The stiff route (model.md §17.11-§17.13): Radau steps per interval, how many multipliers
  /// came from the frozen spectra along the orbit (not represented by the discrete map), and
  /// Liouville's check |sum ln|mu| - integral of trace J| / |integral| of all of them.
  int steps_per_interval = 0;
  int unresolved_multipliers = 0;
  double liouville_error = 0;
  std::vector<double> state0;   ///< x(0) in SI (model.md (2.2)), the orbit's phase origin
  /// The shooting points: per point its phase theta_j in [0, 1) and x(theta_j T) in SI (the
  /// start of an independent recomputation, tests/reference/cycle_orbit_reference.py); only
  /// with CycleOptions::keep_profiles.
  std::vector<std::vector<double>> profile;
};

/// A located special point of a cycle branch: LPC (fold of cycles), PD (a multiplier
/// crosses -1), NS (a complex pair crosses the unit circle).
struct CycleSpecial {
  std::string label;  ///< "LPC", "PD", "NS"
  double parameter = 0, period = 0, amplitude = 0;
  /// True: the orbit where the test function is zero, on the branch (Brent's method to ~1e-8
  /// of the step, model.md §17.5); false: interpolated between the two orbits around it.
  bool located = false;
  std::string note;
};

struct CycleBranch {
  // The Hopf point it starts from.
  double hopf_parameter = 0, hopf_frequency = 0, lyapunov = 0;
  double real_part_slope = 0;  ///< d Re(lambda) / dp at the Hopf point [1/s per unit of p]
  /// |z|^2 = -slope (p - p_H) / (w_H l1): the normal form's amplitude law (model.md (17.3))
  std::vector<CycleOrbit> orbits;
  std::vector<CycleSpecial> specials;
  arclength::End end = arclength::End::max_steps;
  Status status;
  std::string reason;  ///< where and why it ended when not at the interval's end
  long steps = 0, newton_iterations = 0;
  long flow_evaluations = 0;        ///< interval flows with the variational equations (8 + 72 components)
  long state_flow_evaluations = 0;  ///< interval flows of the state alone (the chord corrector's residuals)
  /// The stiff route (model.md §17.11): fixed Radau steps; intervals and steps per interval
  /// chosen at the first orbit, with the relative change of its period and resolved
  /// multipliers at the last doubling (the discretization error's estimate).
  bool stiff = false;
  int intervals = 0, steps_per_interval = 0;
  double discretization_change = 0;
  /// Integrator steps (accepted and rejected) over the whole branch: the state alone, the
  /// variational equations for the Newton matrix, for the Floquet multipliers.
  long state_steps = 0, newton_steps = 0, floquet_steps = 0;
  long extrapolated_matrices = 0;  ///< Newton matrices extrapolated, not integrated (extrapolate_newton_matrix)
  long remeshes = 0;               ///< meshes re-chosen along the branch (adapt_intervals)
};

/// What one cycle branch holds at most [bytes]: ~1.5 kB an orbit (its multipliers, ranges and
/// state; with keep_profiles also 120 bytes a shooting point) for continuation.max_steps orbits,
/// and the mesh's working matrices (transition, Newton and kept matrices: 32 kB an interval
/// for the most intervals the branch may use; on the stiff route 1 kB a Radau step of every
/// interval) plus 10 MB. Measured (/usr/bin/time, whole process): 10,000 intervals 237 MB
/// (estimate 347 MB), the default coulomb branch 13 MB.
double cycle_branch_memory_estimate(const CycleOptions& options);

/// Starts the cycle branch at a Hopf point (label HB) of a two-ball continuation in
/// `param` and follows it within [from, to] (either order).
CycleBranch continue_cycles(const Params& p, ParamRef param, const SpecialPoint& hopf, double from, double to,
                            const CycleOptions& options);

/// One orbit at the fixed parameter value guess.parameter (within [from, to]), corrected
/// from `guess` (its state0 and period: an orbit of a branch, perhaps computed with other
/// options) with the options' intervals and tolerances; the Hopf point of the branch gives
/// the scaling (model.md §17.2). The orbit's multipliers as on a branch. For comparing
/// options at one parameter (the speed against error table, model.md §17.9).
struct CycleCorrection {
  CycleOrbit orbit;
  Status status;
  std::string reason;  ///< why it did not converge
};
CycleCorrection correct_cycle(const Params& p, ParamRef param, const SpecialPoint& hopf, const CycleOrbit& guess,
                              double from, double to, const CycleOptions& options);

/// The normal-form prediction at a Hopf point: the orbit x_H + 2 Re(z q e^{i w t}) at
/// p_H + dp, q the critical eigenvector with <q, q> = 1 (model.md (17.3)); false if the
/// Hopf point is degenerate (l1 = 0 or the crossing not transversal).
struct HopfPrediction {
  std::vector<std::complex<double>> eigenvector;  ///< q, SI state order
  double slope = 0;                               ///< d Re lambda / dp
  /// The predicted max |q| for a given p: sqrt(-slope (p - p_H) / (w l1)) * (the largest
  /// 2|Re(q_12 e^{i theta})|), the coefficient being `amplitude_coefficient`.
  double amplitude_coefficient = 0;
  bool ok = false;
};
HopfPrediction predict_from_hopf(const Params& p, ParamRef param, const SpecialPoint& hopf);

}  // namespace abu
