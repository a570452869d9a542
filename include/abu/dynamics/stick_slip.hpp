// Stick-slip trajectories with set-valued Coulomb friction (`coulomb-set`, model.md (4.6)):
// event-driven switching per ball between stick (beta_i' = 0, the friction force the
// constraint needs, |F_i| <= mu_i N_i) and slip (F_i = -sigma_i mu_i N_i against the
// relative velocity), GSL odeiv2 (rk8pd) on the smooth phases and bisection on the switching
// functions (model.md §14.5-§14.8).
//
//   abu::SimulationOptions o;  o.t_end = 5.0;
//   auto r = abu::simulate_stick_slip(p, abu::SpeedProfile::ramp(0, 900, 300), abu::start_at_rest(p, {1.0, 2.0}), o);
//   if (r.end.all_stuck && !r.end.in_set) ...;   // never: every stuck end point lies in E (14.3)
//
// The samples, statistics and outcome are those of a smooth run (simulation.hpp); the
// stick flags per sample and the end point's check against the stick set come beside them.
#pragma once

#include <cstdint>
#include <vector>

#include "abu/dynamics/simulation.hpp"

namespace abu {

/// The end of a stick-slip run against the stick set E of model.md (14.3).
struct StickSlipEnd {
  std::vector<int> stuck;      ///< per ball: 1 stuck, 0 slipping at the end
  std::vector<double> beta;    ///< end angles wrapped to [0, 2 pi) [rad]
  std::vector<double> s;       ///< s_i of (14.2) at the end angles, q from the rotor equations at rest (5.4)
  double max_abs_s = 0;        ///< max_i |s_i|
  double q_abs = 0;            ///< |q| of the end state [m]
  double q_abs_static = 0;     ///< |q(beta_end)| of (5.4) at the final speed [m]
  bool all_stuck = false;      ///< every ball stuck at the end
  bool in_set = false;         ///< all_stuck and max |s_i| <= 1 + set_tolerance
};

/// Tolerance of the membership test |s_i| <= 1 + tol: the rotor's remaining transient at
/// the end changes the force a stuck ball needs by about |q - q_static| / (mu l) (model.md §14.7).
inline constexpr double stick_set_tolerance = 1e-6;

template <int N>
struct StickSlipResult {
  SimulationResult<N> run;              ///< samples, stats, outcome (model.md §15.2)
  std::vector<std::uint32_t> stuck_mask;  ///< per sample: bit i set = ball i + 1 stuck
  unsigned long sticks = 0;             ///< slip -> stick switches
  unsigned long slips = 0;              ///< stick -> slip switches
  unsigned long reversals = 0;          ///< slipping balls that reversed at zero speed (stick not admissible)
  StickSlipEnd end;
};

/// Integrates the stick-slip dynamics from x0 at t = 0 to options.t_end. Balls with
/// beta_i' = 0 at the start stick if the force they need is admissible. options.method:
/// automatic or rk8pd (rk8pd), rkf45; the implicit methods are refused (InputError): the
/// smooth phases are not stiff (model.md §14.6). Failures as simulate(): status failed and
/// the reason, the samples kept; more than max_events switches at one instant (Zeno) fails.
/// Throws InputError for invalid options, NotSupportedError if some mu_i <= 0.
template <int N>
StickSlipResult<N> simulate_stick_slip(const ParamsT<double, N>& p, const SpeedProfile& speed,
                                       const State<double, N>& x0, const SimulationOptions& options);

/// The end check of a state x at speed omega (model.md §14.7), stuck flags given.
template <int N>
StickSlipEnd stick_slip_end(const ParamsT<double, N>& p, double omega, const State<double, N>& x,
                            const std::vector<int>& stuck);

}  // namespace abu
