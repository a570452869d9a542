// What a run of balls on a rigid rotor's unround race ended in (docs/model.md §15.7, §20.8):
// the run's end matched against the race's states at the speed at its end — on an isotropic
// support its equilibria (§11.4), on an anisotropic support their periodic orbits at the end's
// spin angle. One call for `simulate` and the Python module's abu.simulate.
//
//   abu::SimulationResult<abu::any_balls> r = abu::simulate(p, speed, x0, o);   // o.race, o.support
//   abu::judge_race_end(r, p, speed, race, o.support, o.settle_tolerance);
#pragma once

#include "abu/dynamics/simulation.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/model/speed_profile.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// On an unround race (nothing on a round one, or for a run that did not complete): the summary's
/// outcome rewritten as classify_unround_end (isotropic support: `equilibrium` or `stuck`) or
/// classify_composed_end (`support` not null: `orbit`) say, with the states found at
/// speed.omega(r.t_reached) (p carrying the mean support). Throws NumericalError where the race's
/// equilibria do not solve their equations (as `equilibria`).
void judge_race_end(SimulationResult<any_balls>& r, const ParamsN& p, const SpeedProfile& speed,
                    const RaceShape& race, const AnisotropicSupport* support, double tolerance);

}  // namespace abu
