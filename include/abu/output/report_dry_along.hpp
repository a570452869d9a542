// What dry friction leaves, along a sweep or a branch (model.md §14.10): the columns every row
// of a smooth coulomb / stribeck scene's sweep and continuation carries, and the line that leads
// the command's stderr. Writers only: the figures are analysis/dry_friction.hpp's.
//
//   const abu::DryAlong dry = abu::dry_figures_along(p, param, values);
//   row += abu::dry_cells(dry.figures, value);
//   fmt::print(stderr, "{}", abu::dry_along_lead("omega", "rad/s", dry, "out/sweep_omega.csv"));
#pragma once

#include <string>
#include <string_view>

#include "abu/analysis/dry_friction.hpp"

namespace abu {

/// ",dry_worst_q_abs,dry_whole_set_q_abs,dry_bare_rotor_q_abs,dry_worst_over_bare,dry_stick_fraction"
std::string dry_columns();
/// The CSV comment that says what the dry_* columns are.
std::string dry_columns_doc(std::string_view which);
/// One row's cells, ",V,V_E,bare,V/bare,fraction"; V and V/bare empty when no balanced point is in
/// the set, every cell empty when the set is not defined (never a NaN).
std::string dry_cells(const DryFigures& f);
/// The cells of `value` in `along` (every cell empty when it is absent).
std::string dry_cells(const DryFiguresAlong& along, double value);
/// stderr's first lines: the worst V over the values and where, how many values leave more than
/// the bare rotor, the columns that hold the rest; or, when the request left them out
/// automatically, that and how to have them. Empty for a law without a dry verdict or --dry off.
std::string dry_along_lead(std::string_view name, std::string_view unit, const DryAlong& along, std::string_view file);

}  // namespace abu
