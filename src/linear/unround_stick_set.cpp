// model.md §20.5: the stick set on an unround race, its seeds and anchor from the race's
// equilibria and their stability (see the header).
#include "abu/linear/unround_stick_set.hpp"

#include <fmt/format.h>

#include <cstddef>
#include <utility>
#include <vector>

#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/unround_spectrum.hpp"

namespace abu {

StickSet stick_set(const ParamsN& p, const RaceShape& race, const StickSetOptions& options) {
  if (race.round()) return stick_set(p, options);
  check_stick_set_defined(p);  // its refusals come before the race's equilibria are searched
  // The race's equilibria (tau = 0, always in E, model.md §11.4) as seeds; the stable one of
  // least |q| anchors V (model.md §20.5). Stable as with viscous rolling resistance: with the
  // rotor's damping too the system is fully damped, and its equilibria are stable exactly
  // where the rotating frame's effective potential has a minimum, whatever d > 0 is.
  ParamsN smooth = p;
  smooth.law = FrictionLaw::viscous;
  for (auto& b : smooth.balls) b.d = 1e-3;
  const UnroundResult found = find_unround_equilibria(smooth, race);
  std::vector<StickSeed> seeds;
  for (std::size_t k = 0; k < found.list.size(); ++k) {
    const UnroundEquilibrium& e = found.list[k];
    StickSeed sd;
    sd.family = fmt::format("equilibrium {}", k + 1);
    for (int i = 0; i < p.n_balls(); ++i) sd.beta.push_back(double(wrap_angle(e.position[2 + i])));
    sd.anchor = found.best_stable && *found.best_stable == k;
    seeds.push_back(sd);
  }
  return stick_set_on_race(p, race, std::move(seeds), options);
}

}  // namespace abu
