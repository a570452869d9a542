// The reports of a flexible shaft's states (analysis/shaft_states.hpp): the table, CSV and JSON
// of `equilibria`, and the provenance lines every shaft output starts with.
#pragma once

#include <string>
#include <string_view>

#include "abu/analysis/shaft_states.hpp"

namespace abu {

/// "N nodes (E elements, length L m), ... balancer at node B ...": the system in one line.
std::string shaft_line(const ShaftSystem& sys);
/// The provenance comment lines of a shaft output (the rigid rotor's k, c, M_r said unused).
std::string shaft_header_lines(std::string_view command_line, std::string_view scene_file, const ShaftSystem& sys);

std::string shaft_states_table(const ShaftStates& st, std::string_view file);
std::string shaft_states_csv(const ShaftStates& st, std::string_view command_line, std::string_view scene_file);
std::string shaft_states_json(const ShaftStates& st, std::string_view command_line, std::string_view scene_file);

}  // namespace abu
