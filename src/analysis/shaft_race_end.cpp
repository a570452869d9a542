// model.md §18.20 (§15.7 on a shaft): what a run on an unround race on a shaft ended in.
#include "abu/analysis/shaft_race_end.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/analysis/shaft_states.hpp"
#include "abu/core/errors.hpp"
#include "abu/equilibria/shaft_race_equilibria.hpp"

namespace abu {

std::vector<ShaftRaceTarget> shaft_race_targets(const ShaftSystem& sys, const RaceShape& race, double omega) {
  ShaftSystem at = sys;
  at.balancer.omega = omega;
  std::vector<ShaftRaceTarget> out;
  try {
    for (const ShaftState& s : analyze_shaft_race_states(at, race, {}).states)
      out.push_back({s.eq, s.q_abs, s.verdict});
  } catch (const NumericalError& e) {  // the spectra, not the equilibria: keep these, say why
    out.clear();
    const int b = sys.balancer_dof();
    for (const ShaftEquilibrium& eq : find_shaft_race_equilibria(at, race).list)
      out.push_back({eq, std::hypot(eq.position(b), eq.position(b + 1)),
                     fmt::format("stability not computed ({})", e.what())});
  }
  return out;
}

double shaft_race_distance(const ShaftSystem& sys, double L, const std::vector<double>& x, const ShaftEquilibrium& eq) {
  const int b = sys.balancer_dof(), ns = sys.shaft_dofs();
  double d = std::max(std::abs(x[0] - eq.position(b)), std::abs(x[1] - eq.position(b + 1))) / L;
  for (int i = 0; i < sys.n_balls(); ++i)
    d = std::max(d, std::abs(std::remainder(x[std::size_t(2 + i)] - eq.position(ns + i), 2 * std::numbers::pi)));
  return d;
}

void classify_shaft_race_end(SimulationSummary& s, const ShaftSystem& sys, double L,
                             const std::vector<ShaftRaceTarget>& targets, double tolerance) {
  if (s.outcome != SimulationOutcome::balanced && s.outcome != SimulationOutcome::aligned &&
      s.outcome != SimulationOutcome::rest)
    return;
  if (s.state_end.size() != std::size_t(2 * sys.n_balls() + 4)) return;
  const ShaftRaceTarget* best = nullptr;
  double best_d = HUGE_VAL;
  for (const ShaftRaceTarget& t : targets)
    if (const double d = shaft_race_distance(sys, L, s.state_end, t.eq); d < best_d) best_d = d, best = &t;
  s.pattern.clear();
  if (best != nullptr && best_d <= tolerance) {
    s.outcome = SimulationOutcome::equilibrium;
    s.unround_member = best->eq.member;
    s.unround_q_abs = best->q_abs;
    s.unround_distance = best_d;
    s.note = fmt::format("at rest at equilibrium {} of {} of the unround race on the shaft (model.md §18.18), {}: "
                         "residual whirl of the balancer node |q| = {:.6g} m, scaled distance {:.3g}",
                         best->eq.member, targets.size(), best->verdict, best->q_abs, best_d);
    return;
  }
  s.outcome = SimulationOutcome::rest;
  s.note = best == nullptr ? "at rest, and the unround race on the shaft has no equilibrium at the final speed"
                           : fmt::format("at rest off every equilibrium of the unround race on the shaft (the nearest, {} "
                                         "of {}, at scaled distance {:.3g}): the balls creep too slowly to move within "
                                         "the window",
                                         best->eq.member, targets.size(), best_d);
}

void judge_shaft_race_end(SimulationSummary& s, const ShaftSystem& sys, const RaceShape& race, double omega_end,
                          double L, double tolerance) {
  if (s.outcome != SimulationOutcome::balanced && s.outcome != SimulationOutcome::aligned &&
      s.outcome != SimulationOutcome::rest)
    return;  // periodic, not settled: §15.2 stands; no search needed
  classify_shaft_race_end(s, sys, L, shaft_race_targets(sys, race, omega_end), tolerance);
}

}  // namespace abu
