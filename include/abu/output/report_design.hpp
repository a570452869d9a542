// Files of `stability-scan design` (docs/model.md §22): one CSV row per evaluated design, the
// recommendation and the Pareto front as JSON, and the answer in words. They format a study;
// they compute nothing.
#pragma once

#include <string>
#include <string_view>

#include "abu/analysis/design_study.hpp"

namespace abu {

/// `header`, then `design,origin,<variables>,feasible,objective,<g_constraint...>,ball_mass,
/// capacity,runs,balanced,below_limit,below_low,below_high,residual_median,residual_p90,
/// residual_worst,stalled,bare_rotor,pareto,recommended,note` (bare_rotor: the median over the
/// runs of the bare rotor's |q|, (16.5.1)); a figure a design does not have is empty.
std::string design_csv(const DesignStudy& s, std::string_view header);

/// The study: variables, objective, constraints, every design's figures, the recommended one
/// with the binding constraint and its gain over the scene's own design, the Pareto front.
std::string design_json(const DesignStudy& s, std::string_view command_line, std::string_view scene_file);

/// The recommendation in words, first; then the scene's own design and the Pareto front.
std::string design_text(const DesignStudy& s);

}  // namespace abu
