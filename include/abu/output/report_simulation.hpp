// Files of `stability-scan simulate` (model.md §15): the trajectory CSV and the summary
// JSON, and the summary in words for the terminal.
//
//   std::string csv = abu::simulation_csv(result, p, speed, header);
//   std::string json = abu::simulation_json(result, p, speed, command_line, scene_file);
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "abu/dynamics/simulation.hpp"
#include "abu/dynamics/stick_slip.hpp"

namespace abu {

/// `csv` (comment lines, the column names, data rows) with columns appended: the `comment` lines
/// just before the column names, `names` after them, and `row_values(k, out)` appending the
/// k-th data row's values (k = 0, 1, ...). The stick-slip and the shaft's CSVs extend the run's.
std::string with_columns(std::string_view csv, std::string_view comment, std::string_view names,
                         const std::function<void(std::size_t row, std::string& out)>& row_values);

/// One row per sample: t,omega,q1,q2,beta1..beta<n>,dq1,dq2,dbeta1..dbeta<n>,q_abs,x_fixed,y_fixed,
/// beta_rel1..beta_rel<n> (model.md §15.4). Angles beta are continuous (not wrapped);
/// beta_rel_i = beta_i minus the nearest balanced configuration's angle (of the end
/// state), wrapped to [-pi, pi], empty where no balanced state exists. `header` (the
/// provenance block) comes first, then the run's own comment lines. Throws NumericalError
/// for a non-finite value (none reaches the file).
template <int N>
std::string simulation_csv(const SimulationResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                           std::string_view header);

/// The summary as JSON: outcome, pattern, t_end, state_end (2n + 4 values), max_q_abs,
/// t_max_q_abs, settle_time (null unless settled), stalled, stalled_balls, the status and
/// reason of the run, the method and stiffness ratio, steps and evaluations.
template <int N>
std::string simulation_json(const SimulationResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                            std::string_view command_line, std::string_view scene_file);

/// A few lines for the terminal: outcome, settle time, largest |q|, omega_n passages,
/// stall, steps and evaluations.
template <int N>
std::string simulation_text(const SimulationResult<N>& r, const SpeedProfile& speed);

/// Stick-slip runs (`coulomb-set`, model.md §14.5): the CSV of simulation_csv with the
/// columns stick1..stick<n> appended (1: ball i stuck at that sample, 0: slipping).
template <int N>
std::string stick_slip_csv(const StickSlipResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                           std::string_view header);

/// The summary JSON of simulation_json plus an object `stick_slip`: per-ball `stuck` at the end,
/// `beta_end` (wrapped, rad), `s_end` (14.2), `max_abs_s`, `in_stick_set`, `q_abs_static`, and
/// the switch counts.
template <int N>
std::string stick_slip_json(const StickSlipResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                            std::string_view command_line, std::string_view scene_file);

/// simulation_text plus the stick-slip lines.
template <int N>
std::string stick_slip_text(const StickSlipResult<N>& r, const SpeedProfile& speed);

}  // namespace abu
