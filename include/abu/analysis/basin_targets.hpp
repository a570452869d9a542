// The attractors of a basin for any machine the basin integrates (model.md §15.5): the scan's
// targets (stable equilibria by their spectra, certified regions for two balls); on an
// anisotropic support the balanced states whose Floquet multipliers say stable (§10.5, §10.6);
// with an unround race on it, the race's states continued to pi/omega-periodic orbits whose
// multipliers say stable, sampled over their period (§20.8) — which also name where a
// `simulate` run on that machine ended.
//
//   abu::BasinAttractors a = abu::machine_basin_targets(job);
//   for (const auto& why : a.unresolved) ...   // states with no verdict: not attractors
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "abu/dynamics/forced_orbits.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/scan/basin.hpp"

namespace abu {

struct BasinAttractors {
  std::vector<BasinTarget> targets;
  /// States that may attract but have no verdict, each with where and why (an orbit that did not
  /// converge or whose sampled period does not close; the race search's doubt): a cell that ends
  /// near one is judged at t_end (§15.2).
  std::vector<std::string> unresolved;
};

/// basin_targets(job); on an anisotropic support (job.support; job.params_n carrying its mean)
/// the balanced states at the final speed judged by analyze_floquet: each stable one a target
/// (two balls: the mirror states; n >= 3: the balanced set when every sample is stable), found by
/// the settle radius test (no certified region: the linearization is periodic). Its aligned states
/// are pi/omega-periodic orbits, not targets: a cell that ends on one is judged at t_end by §15.2
/// (`periodic`). With an unround race too (§20.8): every orbit of composed_states at the final
/// speed whose multipliers say stable, label "orbit", member its number in `equilibria`. Throws
/// NumericalError where Hill's method fails.
BasinAttractors machine_basin_targets(const BasinJob& job, const BalancedSampling& sampling = {});

/// One state of an unround race on an anisotropic support, sampled over its period (§20.8).
struct SampledOrbit {
  int member = 0;  ///< its number in `equilibria`'s list (the race's equilibrium it continues)
  Stability verdict = Stability::marginal;
  double q_abs_max = 0;  ///< [m], over the period
  std::shared_ptr<const BasinOrbit> orbit;
};

struct ComposedStates {
  std::vector<SampledOrbit> orbits;     ///< the converged orbits, in `equilibria`'s order
  std::vector<std::string> unresolved;  ///< as BasinAttractors::unresolved
};

/// Every state `equilibria` finds on `race` with `support` at p.omega (composed_orbits_at; p
/// carrying the mean support), each converged orbit sampled at 128 spin angles over its period:
/// one run of the composed field (model.md §20.3) from its state at theta = 0, rtol 1e-11, which
/// must return to that state within 1e-7 (scaled; a converged orbit closes to ~1e-10), else the
/// orbit is unresolved with that reason. Throws NumericalError where the race's equilibria do not
/// solve their equations (as `equilibria`).
ComposedStates composed_states(const ParamsN& p, const RaceShape& race, const AnisotropicSupport& support);

/// A run on an unround race with an anisotropic support (model.md §20.8): when the summary says
/// `periodic` or `not_settled` and the end state lies within `tolerance` (scaled as the settle
/// test) of one of `states`' orbits at the run's end spin angle theta_end, the outcome becomes
/// `orbit` with summary.orbit_member, orbit_q_abs_max and orbit_distance, and a note with the
/// orbit's verdict. `p` at the final speed (its displacement scale L).
void classify_composed_end(SimulationSummary& s, const ParamsN& p, const ComposedStates& states, double theta_end,
                           double tolerance);

}  // namespace abu
