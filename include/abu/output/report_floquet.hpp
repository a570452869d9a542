// Reports of a scene with an anisotropic support (docs/model.md §10): the balanced states
// with their Floquet multipliers over pi/omega (Hill's method, checked by the Magnus
// monodromy), as a table, CSV or JSON. The other equilibria of the mean system are
// pi/omega-periodic orbits of the real system (§10.5); they are not computed yet and the
// reports say so instead of printing the mean-system equilibria as equilibria.
//
//   abu::FloquetAnalysis a = abu::analyze_floquet(p, *scene.support, {});
//   std::string json = abu::floquet_json(a, p, *scene.support, command_line, scene.file);
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "abu/analysis/floquet_states.hpp"

namespace abu {

std::string floquet_table(const FloquetAnalysis& a, const ParamsN& p, const AnisotropicSupport& support);
/// One row per balanced state; `header` is written first (provenance, comment lines).
std::string floquet_csv(const FloquetAnalysis& a, const ParamsN& p, const std::string& header);
/// `periodic_orbits`: the JSON members on the periodic orbits ("periodic_orbits": [...] and
/// their counts) when they were computed (report_forced_orbits.hpp); empty: the note that
/// they were not.
std::string floquet_json(const FloquetAnalysis& a, const ParamsN& p, const AnisotropicSupport& support,
                         std::string_view command_line, std::string_view scene_file,
                         std::string_view periodic_orbits = {});

}  // namespace abu
