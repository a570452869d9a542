#include "abu/output/report_dry_along.hpp"

#include <fmt/format.h>

#include "abu/output/format.hpp"

namespace abu {

std::string dry_columns() {
  return ",dry_worst_q_abs,dry_whole_set_q_abs,dry_bare_rotor_q_abs,dry_worst_over_bare,dry_stick_fraction";
}

std::string dry_columns_doc(std::string_view which) {
  return fmt::format(
      "# dry_* columns: dry friction as it is at the row's value (coulomb-set with {}, model.md §14.10), the same for "
      "every state of a value:\n#   dry_worst_q_abs [m] = V, the largest |q| where the balls stick around balance "
      "(empty: no balanced point in the stick set); dry_whole_set_q_abs [m] = V_E over the whole set;\n"
      "#   dry_bare_rotor_q_abs [m] = the rotor without balls, |q0| of (16.5.1) (the balls' mass, not their force); "
      "dry_worst_over_bare = V / that; dry_stick_fraction = "
      "the set's share of the arrangements (every cell empty where the set is not defined)\n",
      which);
}

std::string dry_cells(const DryFigures& f) {
  if (!f.defined) return ",,,,,";
  const bool v = f.balanced_exists;
  return fmt::format(",{},{},{},{},{}", v ? format_number(f.worst_q_abs, "V") : std::string(), format_number(f.whole_set_q_abs, "V_E"),
                     format_number(f.bare_rotor_q_abs, "bare rotor |q|"),
                     v && f.bare_rotor_q_abs > 0 ? format_number(f.worst_q_abs / f.bare_rotor_q_abs, "V / bare") : std::string(),
                     format_number(f.area_fraction, "stick fraction"));
}

std::string dry_cells(const DryFiguresAlong& along, double value) {
  const auto it = along.find(value);
  return it == along.end() ? dry_cells(DryFigures{}) : dry_cells(it->second);
}

std::string dry_along_lead(std::string_view name, std::string_view unit, const DryAlong& dry, std::string_view file) {
  const std::string_view which = dry.which;
  if (dry.skipped())
    return fmt::format("dry friction as it is (coulomb-set with {}, model.md §14.10): not computed here: {} of the {} "
                       "values of {} need a scan of the stick set (0.2-2 s each; more than {}); --dry on adds them to "
                       "the rows, `equilibria` with --set gives one value's\n",
                       which, dry.scans, dry.values, name, dry.scan_limit);
  if (!dry.computed()) return {};
  const DryFiguresAlong& along = dry.figures;
  const DryFigures* worst = nullptr;
  double worst_at = 0;
  int above_bare = 0, undefined = 0, unbalanced = 0;
  for (const auto& [value, f] : along) {
    if (!f.defined) {
      ++undefined;
      continue;
    }
    if (!f.balanced_exists) {
      ++unbalanced;
      continue;
    }
    above_bare += f.worst_q_abs > f.bare_rotor_q_abs;
    if (!worst || f.worst_q_abs > worst->worst_q_abs) worst = &f, worst_at = value;
  }
  std::string out = fmt::format("dry friction as it is (coulomb-set with {}, model.md §14.10), over {} = {:.6g} .. {:.6g}{} "
                                "({} values): ",
                                which, name, along.begin()->first, along.rbegin()->first,
                                unit.empty() || unit == "-" ? std::string() : fmt::format(" {}", unit), along.size());
  if (worst)
    out += fmt::format("the balls stick with a residual vibration of at most V = {:.6g} m ({:.3g} x the rotor without "
                       "balls) at {} = {:.6g}; V exceeds the bare rotor at {} of the {} values",
                       worst->worst_q_abs,
                       worst->bare_rotor_q_abs > 0 ? worst->worst_q_abs / worst->bare_rotor_q_abs : 0.0, name, worst_at,
                       above_bare, along.size());
  else
    out += "no value has a balanced point in its stick set";
  if (unbalanced > 0 && worst) out += fmt::format("; {} values have no balanced point in the set", unbalanced);
  if (undefined > 0) out += fmt::format("; the set is not defined at {} values", undefined);
  out += fmt::format("\n  per value: the dry_* columns of {}; the smooth law's verdict below is that of balls creeping "
                     "where dry balls stick\n",
                     file);
  return out;
}

}  // namespace abu
