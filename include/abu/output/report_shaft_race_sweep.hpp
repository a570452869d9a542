// The files of `sweep` on an unround race on a flexible shaft (analysis/shaft_race_sweep.hpp,
// docs/model.md §18.18, docs/cli.md): every state per value, and a summary per value. Writers
// only: they format the sweep, they compute nothing.
#pragma once

#include <string>
#include <string_view>

#include "abu/analysis/shaft_race_sweep.hpp"

namespace abu {

/// sweep_NAME.csv: one row per state per value (`name` the swept parameter, `unit` its unit;
/// `header` the provenance lines, already '#'-prefixed).
std::string shaft_race_sweep_csv(const ShaftRaceSweep& s, std::string_view name, std::string_view unit,
                                 const std::string& header);

/// summary_NAME.csv: one row per value: the counts, the design figure and the balls-held whirl.
std::string shaft_race_sweep_summary_csv(const ShaftRaceSweep& s, std::string_view name, std::string_view unit,
                                         const std::string& header);

}  // namespace abu
