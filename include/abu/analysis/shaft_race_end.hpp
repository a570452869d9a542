// What a run of balls on an unround race on a flexible shaft ended in (docs/model.md §18.20,
// the rule of §15.7): a settled run (§15.2, judged on the balancer node's q and the balls) is
// matched against the race's equilibria on the shaft at the final speed (§18.18, in the order
// `equilibria` prints them, with their verdicts); the one within the settle tolerance of the
// scaled distance max(|q - q*| / L, |beta - beta*| wrapped) is the outcome `equilibrium`.
//
//   abu::ShaftSimulationResult r = abu::simulate_shaft(sys, speed, x0, o);   // o.race = &race
//   abu::judge_shaft_race_end(r.run.summary, sys, race, speed.omega(r.run.t_reached),
//                             r.run.displacement_scale, o.settle_tolerance);
#pragma once

#include <string>
#include <vector>

#include "abu/dynamics/simulation.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// One settle target: an equilibrium of the race on the shaft and its verdict (stable,
/// unstable, undetermined, or why it was not computed).
struct ShaftRaceTarget {
  ShaftEquilibrium eq;  ///< eq.member: its number in `equilibria`'s list
  double q_abs = 0;     ///< |q| at the balancer node [m]
  std::string verdict;
};

/// The race's equilibria on the shaft at speed omega with their verdicts (analyze_shaft_race_states
/// with its default spectrum options, as `equilibria` prints them). Where the spectra fail
/// (NumericalError), the equilibria of find_shaft_race_equilibria with the reason as verdict.
std::vector<ShaftRaceTarget> shaft_race_targets(const ShaftSystem& sys, const RaceShape& race, double omega);

/// The scaled distance of §15.7 between the balancer view x (2n + 4 values: q, beta, ...) and
/// an equilibrium s = (u, beta) of the shaft: max(|q - u_b| / L, |beta - beta*| wrapped to (-pi, pi]).
double shaft_race_distance(const ShaftSystem& sys, double L, const std::vector<double>& x, const ShaftEquilibrium& eq);

/// Rewrites a settled outcome (balanced, aligned, stuck) of a run on the race: `equilibrium`
/// with summary.unround_member (the target's member), unround_q_abs and unround_distance when
/// the end state lies within `tolerance` of a target; otherwise `stuck`, naming the nearest.
/// Periodic and not settled runs are left as they are.
void classify_shaft_race_end(SimulationSummary& s, const ShaftSystem& sys, double L,
                             const std::vector<ShaftRaceTarget>& targets, double tolerance);

/// shaft_race_targets at omega_end, then classify_shaft_race_end.
void judge_shaft_race_end(SimulationSummary& s, const ShaftSystem& sys, const RaceShape& race, double omega_end,
                          double L, double tolerance);

}  // namespace abu
