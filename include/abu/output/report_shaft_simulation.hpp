// Files of `stability-scan simulate` on a flexible shaft (model.md §18.16): the rigid route's
// CSV, JSON and text (report_simulation.hpp) for the balancer node and the balls, with the
// shaft's own figures added.
//
//   std::string csv = abu::shaft_simulation_csv(result, sys, speed, header);
#pragma once

#include <string>
#include <string_view>

#include "abu/dynamics/shaft_simulation.hpp"

namespace abu {

/// simulation_csv of the balancer node (q1, q2 = its u1, u2) with the columns
/// max_deflection [m] (the largest |(u1_k, u2_k)| over the nodes at the sample) and
/// max_deflection_node appended. Throws NumericalError for a non-finite value.
std::string shaft_simulation_csv(const ShaftSimulationResult& r, const ShaftSystem& sys, const SpeedProfile& speed,
                                 std::string_view header);

/// simulation_json plus an object `shaft`: nodes, balancer_node, state_size, the largest node
/// deflection of the run (located between samples), its node and time, the summary's static
/// stiffness and omega_n, and the whole end state x_end (model.md §18.16, for --from-state).
std::string shaft_simulation_json(const ShaftSimulationResult& r, const ShaftSystem& sys, const SpeedProfile& speed,
                                  std::string_view command_line, std::string_view scene_file);

/// simulation_text plus the shaft's lines.
std::string shaft_simulation_text(const ShaftSimulationResult& r, const ShaftSystem& sys, const SpeedProfile& speed);

}  // namespace abu
