// Outputs of the stick-set analysis of `coulomb-set` scenes (model.md §14): the
// `equilibria` table, CSV and JSON, the traced boundary as CSV, and the one-line figures
// that `sweep` and `map` write per point.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "abu/core/params.hpp"
#include "abu/analysis/dry_friction.hpp"
#include "abu/equilibria/shaft_stick_set.hpp"
#include "abu/equilibria/stick_set.hpp"

namespace abu {

/// Plain text: the figures, every component and every smooth equilibrium it holds; on a
/// flexible shaft (`shaft`) its dynamic stiffness and largest deflection (model.md §18.17).
std::string stick_set_table(const StickSet& s, const ParamsN& p, const ShaftStickFigures* shaft = nullptr);
/// CSV: `header` (comment lines; the shaft's lines after it), then one row per component.
std::string stick_set_csv(const StickSet& s, const std::string& header, const ShaftStickFigures* shaft = nullptr);
/// The shaft's figures of a stick set as lines, each starting with `prefix` (model.md §18.17).
std::string shaft_stick_lines(const ShaftStickFigures& f, const StickSet& s, std::string_view prefix);
/// The JSON object `shaft` of a stick set on a flexible shaft (no trailing newline).
std::string shaft_stick_json(const ShaftStickFigures& f);
/// The JSON object `stick_set` (no trailing newline).
std::string stick_set_json_object(const StickSet& s);
/// The whole `equilibria --format json` document of a coulomb-set scene.
std::string stick_set_json(const StickSet& s, std::string_view command_line, std::string_view scene_file,
                           const ParamsN& p, const ShaftStickFigures* shaft = nullptr);
/// The traced boundary: one row per point (arc, ball, sign, beta1, beta2); arcs separated
/// by a blank line (gnuplot's index-free line break) and a wrap by 2 pi too.
std::string stick_boundary_csv(const StickSet& s, const std::string& header);
/// The CSV of a sweep of a coulomb-set scene over parameter `name` [unit]: `header`, a
/// comment naming the columns, then one row per value: area, area_fraction, whole_torus,
/// components, balanced_exists, worst_q_abs (V, empty if no balanced state), worst_q_abs_any
/// (V_E), mean_q_abs, bare_rotor_q_abs, worst_over_bare, spread1..spreadN (N the most balls
/// of any value; empty beyond a value's count or without a balanced state); on a flexible
/// shaft (`shaft`, one per value) then K_eff, C_eff, worst_node, worst_deflection,
/// worst_deflection_any (model.md §18.17).
std::string stick_sweep_csv(std::string_view name, std::string_view unit, const std::vector<double>& values,
                            const std::vector<StickSet>& sets, const std::string& header,
                            const std::vector<ShaftStickFigures>* shaft = nullptr);
/// The dry-friction verdict next to a smooth `coulomb` / `stribeck` analysis (model.md §14.10,
/// analysis/dry_friction.hpp), one line per sentence, each line starting with `prefix`. Empty
/// for any other law; a set that is not defined (mu = 0, K = C = 0) is a line saying why.
std::string dry_friction_lines(const DryFrictionVerdict& d, std::string_view prefix);
/// Dry friction first (model.md §14.10): where the verdict applies, its lines, then `smooth` (the
/// smooth law's statement and table) under a line saying what that verdict assumes; otherwise
/// `smooth` alone.
std::string dry_first(const DryFrictionVerdict& d, const std::string& smooth, std::string_view prefix);
/// The same verdict as a JSON member, `"dry_friction": {...},\n` with the same figures
/// (area [rad^n], area_fraction, whole_torus, components, balanced_in_set, worst_q_abs V [m]
/// or null without a balanced point, worst_q_abs_any V_E [m], bare_rotor_q_abs [m], and why
/// not when undefined). Empty for any other law.
std::string dry_friction_json(const DryFrictionVerdict& d);
/// A raster of the set for the chart's fill: rows beta1,beta2,inside (0/1), comma-separated, `cells` per angle.
std::string stick_raster_dat(const ParamsN& p, int cells);

}  // namespace abu
