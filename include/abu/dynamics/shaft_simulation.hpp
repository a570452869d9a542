// Trajectories of the flexible rotor with its ball balancer (model.md §18.16): the whole
// finite-element shaft and the balls in the rotating frame, at constant speed (§18.6) or
// during a run-up (the omega' terms of (18.16.2)), integrated by GSL odeiv2 as `simulate`
// (model.md §15.1: the same methods, error control in the model's scaling, rtol, every,
// max_steps, interrupt), with a summary of the balancer node and the balls (§15.2).
//
//   abu::ShaftSystem sys = abu::shaft_system_of(scene);              // analysis/shaft_states.hpp
//   abu::SimulationOptions o;  o.t_end = 1.0;
//   auto x0 = abu::shaft_start_at_rest(sys, {2.0, 4.0});
//   abu::ShaftSimulationResult r = abu::simulate_shaft(sys, abu::SpeedProfile::constant(900), x0, o);
//   r.run.summary.outcome, r.max_deflection, r.x_end ...
//
// The state is x = (u (4 N_nodes), beta_1..beta_n, u', beta_1'..beta_n') (shaft.hpp), dense
// Jacobians: at most shaft_simulation_max_states values.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "abu/dynamics/simulation.hpp"
#include "abu/model/shaft_system.hpp"

namespace abu {

/// The largest state simulate_shaft takes: the implicit steppers factor dense dim x dim
/// Jacobians (model.md §18.16), about 10 of them alive at once.
inline constexpr int shaft_simulation_max_states = 1000;

struct ShaftSimulationResult {
  /// The run as the rigid route reports it, with the balancer node's translation as q: status
  /// and reason (failed: where and why; samples kept up to there), method, stiffness probe
  /// (here spectral_radius is the fastest decay max |Re lambda| of J and stiffness_ratio its
  /// ratio to the fastest motion every stepper follows, model.md §18.16),
  /// samples (q1, q2 = u1, u2 of the balancer node, the balls, their rates: the 2n + 4 values
  /// of model.md (2.2)), counts, and the summary of §15.2 judged on those values with `view`.
  SimulationResult<any_balls> run;
  /// The rigid balancer the summary is judged with: the balls, U, omega; rotor.mass the
  /// balancer disc's, rotor.stiffness the shaft's static stiffness at the balancer node
  /// (1 / (K^-1)_bb), rotor.damping 0. Its L = (U + sum m l) / (M_r + sum m) is the
  /// displacement scale of the error control and of the settle test.
  ParamsN view;
  int nodes = 0;
  int state_size = 0;
  std::vector<double> deflection;  ///< per sample: max_k |(u1_k, u2_k)| [m]
  std::vector<int> deflection_node;  ///< per sample: that node k
  /// The largest node deflection of the run, located between samples (model.md §18.16) [m], s.
  double max_deflection = 0, t_max_deflection = 0;
  int max_deflection_node = 0;
  Eigen::VectorXd x_end;  ///< the whole state at run.t_reached
};

/// The balls at rest in the rotor frame at the angles beta [rad], the shaft at rest and
/// undeflected. Throws InputError (--balls) for a wrong count or a non-finite angle.
Eigen::VectorXd shaft_start_at_rest(const ShaftSystem& sys, const std::vector<double>& beta);

/// The summary's rigid view of the shaft (ShaftSimulationResult::view).
ParamsN shaft_summary_params(const ShaftSystem& sys);
/// The rigid route's 2n + 4 values of a whole state x (size sys.state_size()): the balancer
/// node's (u1, u2) as q, the balls, their rates (model.md (2.2)).
State<double, any_balls> balancer_view(const ShaftSystem& sys, const double* x);

/// Integrates from x0 (size sys.state_size()) at t = 0 to options.t_end with omega(t) of
/// `speed` (sys.balancer.omega is not used). Never throws on numerical trouble (status failed
/// with the reason, samples up to there). Throws InputError for invalid options, a state of
/// the wrong size (naming 2 (4 N_nodes + n)) or above shaft_simulation_max_states, and
/// std::invalid_argument for options of other routes (support, bristles) and for
/// an unround race on anisotropic bearings. options.race (not round): the balls run on its paths
/// (model.md §18.20) and run.unround_race is set; the summary is §15.2's, to be matched against
/// the race's equilibria (analysis/shaft_race_end.hpp, §15.7). options.stop_at_sample sees each
/// sample's balancer view (the 2n + 4 values of run.samples), and ends the run there as on the
/// rigid route (run.stopped_early; x_end the whole state at that sample).
ShaftSimulationResult simulate_shaft(const ShaftSystem& sys, const SpeedProfile& speed, const Eigen::VectorXd& x0,
                                     const SimulationOptions& options);

}  // namespace abu
