// Reports of the non-balanced states on an anisotropic support (docs/model.md §10.14):
// every aligned equilibrium of the mean system continued to a pi/omega-periodic orbit of
// the scene (dynamics/forced_orbits.hpp), with its |q| over the period, ball angle ranges,
// all 2n + 4 Floquet multipliers and its verdict, as a table, CSV rows and the JSON value
// of the "periodic_orbits" member of `equilibria --format json`. An orbit that did not
// converge is reported with its status and reason, never left out: the count of aligned
// equilibria is given next to the count of orbits found.
//
//   abu::ForcedOrbitAnalysis o = abu::analyze_forced_orbits(p, *scene.support, a.mean_equilibria);
//   std::string json = abu::forced_orbits_json(o);
#pragma once

#include <string>
#include <vector>

#include "abu/analysis/floquet_states.hpp"

namespace abu {

std::string forced_orbits_table(const ForcedOrbitAnalysis& a, const ParamsN& p);
/// Comment lines and a second CSV block (its own header, one row per orbit).
std::string forced_orbits_csv(const ForcedOrbitAnalysis& a, const ParamsN& p);
/// JSON members: "aligned_equilibria": k, "periodic_orbits_found": m, "periodic_orbits": [one
/// object per aligned equilibrium: kind, status, reason, and when found q_abs_max, q_abs_mean,
/// floquet_multipliers ([re, im], modulus descending), stable, ...].
std::string forced_orbits_json(const ForcedOrbitAnalysis& a);

}  // namespace abu
