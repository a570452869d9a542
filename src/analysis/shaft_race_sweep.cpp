// The sweep of an unround race on a flexible shaft (shaft_race_sweep.hpp, model.md §18.18).
#include "abu/analysis/shaft_race_sweep.hpp"

#include <cmath>
#include <complex>

#include "abu/core/cancel.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"

namespace abu {

// The stable state of least |q| at the balancer node: the design figure (as the rigid race's
// best_stable, model.md §11.10). "undetermined" is not stable.
std::optional<std::size_t> least_stable_state(const std::vector<ShaftState>& states) {
  std::optional<std::size_t> best;
  for (std::size_t k = 0; k < states.size(); ++k)
    if (states[k].verdict == "stable" && (!best || states[k].q_abs < states[*best].q_abs)) best = k;
  return best;
}

// The balancer node's whirl with the balls held there: omega^2 U / |K_eff + i C_eff| (18.8.1);
// the dynamic stiffness already carries the balls' translating mass at the node.
std::optional<double> balls_held_whirl(const ShaftSystem& sys) {
  const auto stiffness = balancer_dynamic_stiffness(sys);
  if (!stiffness || std::abs(*stiffness) == 0.0) return std::nullopt;
  const double omega = sys.balancer.omega;
  return omega * omega * sys.balancer.rotor.unbalance / std::abs(*stiffness);
}

ShaftRaceSweep sweep_shaft_race(const std::vector<Scene>& scenes, const std::vector<RaceShape>& races,
                                const std::vector<double>& values, const ShaftSpectrumOptions& spectrum) {
  ShaftRaceSweep out;
  out.spectrum = spectrum;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    throw_if_stopped("sweep (shaft, unround race)");
    const ShaftSystem sys = shaft_system_of(scenes[i]);
    out.n_balls = sys.n_balls();
    out.balancer_dof = sys.balancer_dof();
    ShaftStates st = analyze_shaft_race_states(sys, races[i], spectrum);
    ShaftRaceSweepPoint pt;
    pt.value = values[i];
    pt.states = std::move(st.states);
    pt.best = least_stable_state(pt.states);
    pt.q_bare = balls_held_whirl(sys);
    pt.complete = st.race_complete;
    pt.warnings = std::move(st.warnings);
    out.points.push_back(std::move(pt));
  }
  return out;
}

}  // namespace abu
