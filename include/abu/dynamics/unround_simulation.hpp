// What a run on an unround race ended in (model.md §15.7): a settled run (model.md §15.2)
// is matched against the equilibria of §11.4 at the final speed; the one within the
// settle tolerance (the scaled distance of §15.2) is the outcome `equilibrium`, with its
// residual whirl |q|. The balanced/aligned labels of a round race do not apply there (a
// balanced state generically does not exist, §11.4).
//
//   abu::SimulationOptions o;  o.race = &race;  ...
//   auto r = abu::simulate(p, speed, x0, o);
//   abu::classify_unround_end(r.summary, p_final, race, abu::find_unround_equilibria(p_final, race), o.settle_tolerance);
#pragma once

#include "abu/dynamics/simulation.hpp"
#include "abu/linear/unround_spectrum.hpp"

namespace abu {

/// Scaled distance of §15.2 between a state's configuration and an equilibrium position:
/// max(|q - q*| / L, |beta - beta*| wrapped to (-pi, pi]).
double unround_distance(const ParamsN& p, const State<double, any_balls>& x, const UnroundEquilibrium& e);

/// Rewrites a settled outcome (balanced, aligned, stuck) of a run on an unround race:
/// `equilibrium` with summary.unround_member (1-based in `found.list`, the order `equilibria`
/// prints), unround_q_abs and unround_distance when the end state lies within `tolerance` of
/// one; otherwise `stuck`, with the nearest equilibrium named in the note. Other outcomes
/// (periodic, not settled) are left as they are. p.omega must be the final speed.
void classify_unround_end(SimulationSummary& summary, const ParamsN& p, const UnroundResult& found, double tolerance);

}  // namespace abu
