// `sweep` of balls on an unround race on a flexible shaft (docs/model.md §18.18): per value of
// one parameter, every equilibrium of the race on the shaft with its rightmost eigenvalues and
// verdict (analyze_shaft_race_states), the least-|q| stable one (the design figure), and the
// whirl of the balancer node with the balls held at the node (omega^2 U |h|, (18.8.1)).
//
//   abu::ShaftRaceSweep s = abu::sweep_shaft_race(scenes, races, values, {});
//   for (const auto& pt : s.points) ... pt.states, pt.best, pt.q_bare ...
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "abu/analysis/shaft_states.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// One value of the swept parameter.
struct ShaftRaceSweepPoint {
  double value = 0.0;
  std::vector<ShaftState> states;   ///< by |q| of the race on the equivalent rigid balancer (§18.18)
  std::optional<std::size_t> best;  ///< the stable state of least |q| at the balancer node; none stable: empty
  std::optional<double> q_bare;     ///< omega^2 U |h| [m]: the balls fixed at the node; empty where h is singular
  bool complete = true;             ///< the box search of §11.4 proved its list complete
  std::string warnings;             ///< what analyze_shaft_race_states said, one line each
};

struct ShaftRaceSweep {
  std::vector<ShaftRaceSweepPoint> points;
  int n_balls = 0;
  int balancer_dof = 0;  ///< index of u1 at the balancer node in a state's position (shaft_system.hpp)
  ShaftSpectrumOptions spectrum;
};

/// The stable state of least |q| at the balancer node (the design figure, as the rigid race's
/// best stable state, model.md §11.10); "undetermined" is not stable. None stable: empty.
std::optional<std::size_t> least_stable_state(const std::vector<ShaftState>& states);

/// The balancer node's whirl with the balls held at the node, omega^2 U / |K_eff + i C_eff|
/// (18.8.1) [m]; empty where the rotating-frame stiffness is singular.
std::optional<double> balls_held_whirl(const ShaftSystem& sys);

/// Every value analysed in turn: `scenes[i]` (the shaft scene at `values[i]`) with the balls on
/// `races[i]`. Throws NumericalError where ARPACK finds no eigenvalue of a state, and
/// StopRequested on an interrupt (throw_if_stopped between values).
ShaftRaceSweep sweep_shaft_race(const std::vector<Scene>& scenes, const std::vector<RaceShape>& races,
                                const std::vector<double>& values, const ShaftSpectrumOptions& spectrum);

}  // namespace abu
