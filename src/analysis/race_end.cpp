// What a run on an unround race ended in (race_end.hpp).
#include "abu/analysis/race_end.hpp"

#include "abu/analysis/basin_targets.hpp"
#include "abu/dynamics/unround_simulation.hpp"
#include "abu/linear/unround_spectrum.hpp"

namespace abu {

void judge_race_end(SimulationResult<any_balls>& r, const ParamsN& p, const SpeedProfile& speed,
                    const RaceShape& race, const AnisotropicSupport* support, double tolerance) {
  if (race.round() || r.status != SimulationStatus::completed || r.samples.empty()) return;
  ParamsN at = p;
  at.omega = speed.omega(r.t_reached);
  if (support)  // the race's states are periodic orbits there (§20.4): matched at the end's angle
    classify_composed_end(r.summary, at, composed_states(at, race, *support), speed.angle(r.t_reached), tolerance);
  else
    classify_unround_end(r.summary, at, find_unround_equilibria(at, race), tolerance);
}

}  // namespace abu
