// The rows of a map's tiles (map_rows.hpp) and the CSVs' headers (map_driver.hpp).
#include "map_rows.hpp"

#include <fmt/compile.h>

#include <array>
#include <cmath>
#include <limits>

#include "abu/core/errors.hpp"
#include "abu/scan/stick_map.hpp"

namespace abu {

namespace {

std::string axis_name(const Axis& a) { return a.name(); }

// Shortest round-trip form, as io's format_number (scan sits below io, so it does not
// call it): a non-finite value is a numerical failure, never a "nan" in a file.
std::string format_number(double value, std::string_view what = "value") {
  if (!std::isfinite(value)) throw NumericalError(fmt::format("non-finite {} ({}) would be written", what, value));
  return fmt::format("{}", value);
}

// No NaN reaches a file: a non-finite value is a numerical failure naming its cell.
void check_finite(double value, const MapJob& job, int ix, int iy, const char* what) {
  if (!std::isfinite(value))
    throw NumericalError(fmt::format("map cell ({}, {}) = ({}={}, {}={}): {} is not finite", ix, iy,
                                     axis_name(job.x), job.x.value(ix), axis_name(job.y), job.y.value(iy), what));
}

std::string_view axis_unit(const Axis& a) { return a.ball_count ? std::string_view("-") : unit(a.param.quantity); }

std::string axis_description(const Axis& a) {
  if (a.ball_count)
    return fmt::format("n [-]: the number of balls, every integer from {} to {}", format_number(a.from),
                       format_number(a.to));
  return fmt::format("{} [{}]: {} values from {} to {}{}", axis_name(a), unit(a.param.quantity), a.count,
                     format_number(a.from), format_number(a.to), a.logarithmic ? ", evenly spaced in log" : "");
}

std::string common_header(const MapJob& job) {
  if (job.any_balls)
    return job.provenance +
           fmt::format("# map: x = {}\n#      y = {}\n#      every cell by the full n-ball analysis (model.md §13.8): "
                       "every aligned equilibrium and refined eigenvalues, the balanced set sampled with {} samples "
                       "per sheet (§13.5) and judged by its normal spectrum\n",
                       axis_description(job.x), axis_description(job.y), job.sampling.samples_per_sheet);
  return job.provenance + fmt::format("# map: x = {}\n#      y = {}\n#      stability decided by the {} method\n",
                                      axis_description(job.x), axis_description(job.y),
                                      job.method == CellMethod::fast ? "fast (characteristic polynomial, Routh)"
                                                                     : "full (refined eigenvalues)");
}

}  // namespace

namespace {

// An anisotropic support changes what the n-ball columns mean (model.md §10.12).
std::string floquet_note(const MapJob& job) {
  if (!job.support) return {};
  return "# anisotropic support (model.md §10.12): only the balanced states, which stay equilibria; the mean "
         "system's other equilibria are pi/omega-periodic orbits and have no row (aligned = 0). stable, n_unstable, "
         "n_structural_zero (the deflated unit multipliers) and spectral_abscissa (the Floquet decay rate "
         "(omega/pi) ln max|rho|, rotating frame, 1/s) come from the Floquet multipliers rho over pi/omega; the "
         "summary's rho_abs_max = max |rho| over the cell's balanced states\n";
}

// The n-ball CSVs' columns (one place: this file writes and documents both).
std::string map_csv_header_n(const MapJob& job) {
  const std::string x = axis_name(job.x), y = axis_name(job.y);
  std::string betas;
  for (int i = 1; i <= job.max_balls_in_map(); ++i) betas += fmt::format(",beta{}", i);
  return common_header(job) +
         fmt::format(
             "# one row per equilibrium per cell (balanced samples, then aligned), cells in order ix outer, iy inner\n"
             "# columns: ix, iy grid indices; {0} [{2}], {1} [{3}]; balls = n; family = balanced|aligned "
             "(two balls: balanced|together|opposite, model.md §13.2); pattern = the ball signs along q ('+-+'), "
             "empty for balanced;\n"
             "#   member = root of the pattern (1 or 2) or the balanced sample's index; stable = 1 if every "
             "eigenvalue but the structural zeros has negative real part, else 0; n_unstable = eigenvalues right "
             "of the axis;\n"
             "#   n_structural_zero = eigenvalues zero by construction (the balanced set's directions, §13.4), "
             "left out of stable and the abscissa; spectral_abscissa [1/s] = largest real part (normal to the "
             "set on it);\n"
             "#   q_abs [m] = |q|, the residual vibration; beta_i [rad] in [0, 2 pi), empty beyond the cell's "
             "ball count\n"
             "{5}"
             "ix,iy,{0},{1},balls,family,pattern,member,stable,n_unstable,n_structural_zero,spectral_abscissa,q_abs"
             "{4}\n",
             x, y, axis_unit(job.x), axis_unit(job.y), betas, floquet_note(job));
}

std::string summary_csv_header_n(const MapJob& job) {
  const std::string x = axis_name(job.x), y = axis_name(job.y);
  return common_header(job) +
         fmt::format(
             "# one row per cell, in order ix outer, iy inner; an empty field: not applicable (no such state)\n"
             "# columns: ix, iy grid indices; {0} [{2}], {1} [{3}]; balls = n; capacity [kg m] = sum m_i l_i, "
             "against U [kg m];\n"
             "#   balanced_exists = 1 if the balanced set exists (polygon inequality, model.md §13.4.2); "
             "balanced_samples = its samples (§13.5);\n"
             "#   balanced_stable_fraction = the fraction of samples normally stable (a marginal sample, an eigenvalue "
             "inside its error band, is not stable), normal_abscissa_max [1/s] = the least stable sample's normal "
             "spectral abscissa (both empty without samples);\n"
             "#   aligned = isolated equilibria with q != 0 (§13.2, at most 2^n), aligned_stable = how many are "
             "stable; n_stable = stable equilibria (samples included);\n"
             "#   best_family, best_pattern, best_member, best_q_abs [m] = the stable state of least |q| (empty if "
             "none is stable);\n"
             "#   degenerate = bit flags (equilibria.hpp, Degeneracy): 1 U = 0, 8 K = C = 0, 64 a pattern's double "
             "root (fold), 128 a pattern with S = 0, 256 a collinear point of the balanced set, 512 no balanced set\n"
             "{4}"
             "ix,iy,{0},{1},balls,capacity,U,balanced_exists,balanced_samples,balanced_stable_fraction,"
             "normal_abscissa_max,aligned,aligned_stable,n_stable,best_family,best_pattern,best_member,best_q_abs,"
             "degenerate{5}\n",
             x, y, axis_unit(job.x), axis_unit(job.y), floquet_note(job), job.support ? ",rho_abs_max" : "");
}

}  // namespace

std::string map_csv_header(const MapJob& job) {
  if (job.stick_set) return stick_map_csv_header(job);
  if (job.any_balls) return map_csv_header_n(job);
  const std::string x = axis_name(job.x), y = axis_name(job.y);
  return common_header(job) +
         fmt::format(
             "# one row per equilibrium per cell, cells in order ix (x index) outer, iy inner; a family absent "
             "from a cell has no row (summary_{0}_{1}.csv counts them)\n"
             "# columns: ix, iy grid indices; {0} [{2}], {1} [{3}]; family = balanced|together|opposite "
             "(model.md §5); member = which root of the family's closed form (1 or 2);\n"
             "#   stable = 1 if every eigenvalue has negative real part, else 0; n_unstable = eigenvalues with "
             "positive real part; spectral_abscissa [1/s] = largest real part;\n"
             "#   q_abs [m] = |q|, the residual vibration: the rotor centre's whirl radius, which is also the "
             "amplitude in the fixed frame (x_fixed = R(omega t) q, model.md §2);\n"
             "#   beta1, beta2 [rad] ball angles from the unbalance direction, in [0, 2 pi);\n"
             "#   n_undecided = eigenvalues within their error bound of the axis that neither the refined "
             "spectrum nor the certified Routh count places (model.md §8): the verdict is undecided, stable is 0 "
             "and n_unstable a lower bound (0 everywhere else)\n"
             "ix,iy,{0},{1},family,member,stable,n_unstable,spectral_abscissa,q_abs,beta1,beta2,n_undecided\n",
             x, y, unit(job.x.param.quantity), unit(job.y.param.quantity));
}

std::string summary_csv_header(const MapJob& job) {
  if (job.stick_set) return stick_summary_csv_header(job);
  if (job.any_balls) return summary_csv_header_n(job);
  const std::string x = axis_name(job.x), y = axis_name(job.y);
  return common_header(job) +
         fmt::format(
             "# one row per cell, in order ix outer, iy inner\n"
             "# columns: ix, iy grid indices; {0} [{2}], {1} [{3}]; balanced, together, opposite = how many "
             "equilibria of the family exist (0 = none);\n"
             "#   balanced_stable = 1 if a balanced equilibrium is stable, 0 if none is, empty if there is no "
             "balanced state; n_stable = stable equilibria in the cell;\n"
             "#   best_family, best_member, best_q_abs [m] = the stable equilibrium with the least residual "
             "vibration |q| (empty if none is stable);\n"
             "#   degenerate = bit flags: 1 U = 0 (circle of balanced states), 2 balanced merges with together, "
             "4 balanced merges with opposite, 8 K = C = 0, 16 together double root, 32 opposite double root;\n"
             "#   undecided = equilibria whose verdict neither the refined eigenvalues nor the certified Routh count "
             "could decide (long CSV n_undecided > 0; counted not stable: n_stable is then a lower bound)\n"
             "ix,iy,{0},{1},balanced,together,opposite,balanced_stable,n_stable,best_family,best_member,best_q_abs,"
             "degenerate,undecided\n",
             x, y, unit(job.x.param.quantity), unit(job.y.param.quantity));
}

namespace {

void append_facts(fmt::memory_buffer& grid, const MapCellFacts& facts) {
  const char* bytes = reinterpret_cast<const char*>(&facts);
  grid.append(bytes, bytes + sizeof facts);
}

// The n-ball rows of one cell (the columns of map_csv_header_n / summary_csv_header_n):
// the long rows only with job.long_rows (their values are checked either way).
void write_rows_n(const MapJob& job, int ix, int iy, std::string_view x, std::string_view y, const MapCellN& cell,
                  fmt::memory_buffer& rows, fmt::memory_buffer& summary, fmt::memory_buffer& grid) {
  const int max_n = job.max_balls_in_map();
  int n_stable = 0;
  for (const MapEquilibriumN& e : cell.equilibria) {
    n_stable += e.stable;
    check_finite(e.abscissa, job, ix, iy, "a spectral abscissa");
    check_finite(e.q_abs, job, ix, iy, "|q|");
    for (int i = 0; i < cell.n_balls; ++i) check_finite(e.beta[std::size_t(i)], job, ix, iy, "a ball angle");
    if (!job.long_rows) continue;
    const std::string pattern = e.family == Family::balanced ? std::string() : pattern_string(e.pattern, cell.n_balls);
    fmt::format_to(fmt::appender(rows), FMT_COMPILE("{},{},{},{},{},{},{},{},{},{},{},{},{}"), ix, iy, x, y,
                   cell.n_balls, to_string(e.family), pattern, e.member, int(e.stable), e.n_unstable,
                   e.n_structural, e.abscissa, e.q_abs);
    for (int i = 0; i < max_n; ++i) {
      if (i < cell.n_balls) {
        fmt::format_to(fmt::appender(rows), FMT_COMPILE(",{}"), e.beta[std::size_t(i)]);
      } else {
        rows.push_back(',');
      }
    }
    rows.push_back('\n');
  }
  MapCellFacts facts;
  facts.balanced_stable_fraction = cell.balanced_samples > 0
                                       ? double(cell.balanced_stable) / double(cell.balanced_samples)
                                       : std::numeric_limits<double>::quiet_NaN();
  if (cell.balanced_exists) {
    const double f = facts.balanced_stable_fraction;
    facts.category = f == 1 ? 3 : f > 0 ? 2 : 1;
  }
  facts.best_q_abs = std::numeric_limits<double>::quiet_NaN();
  check_finite(cell.capacity, job, ix, iy, "the capacity");
  fmt::format_to(fmt::appender(summary), FMT_COMPILE("{},{},{},{},{},{},{},{},{},"), ix, iy, x, y, cell.n_balls,
                 cell.capacity, cell.unbalance, int(cell.balanced_exists), cell.balanced_samples);
  if (cell.balanced_samples > 0) {
    check_finite(cell.normal_abscissa_max, job, ix, iy, "the normal abscissa");
    fmt::format_to(fmt::appender(summary), FMT_COMPILE("{},{}"),
                   double(cell.balanced_stable) / double(cell.balanced_samples), cell.normal_abscissa_max);
  } else {
    summary.push_back(',');
  }
  fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{},{},{},"), cell.aligned, cell.aligned_stable, n_stable);
  if (const int best = cell.best_stable(); best >= 0) {
    const MapEquilibriumN& e = cell.equilibria[std::size_t(best)];
    const std::string pattern = e.family == Family::balanced ? std::string() : pattern_string(e.pattern, cell.n_balls);
    fmt::format_to(fmt::appender(summary), FMT_COMPILE("{},{},{},{}"), to_string(e.family), pattern, e.member,
                   e.q_abs);
    facts.best_q_abs = e.q_abs;
  } else {
    fmt::format_to(fmt::appender(summary), FMT_COMPILE(",,,"));
  }
  fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{}"), cell.degeneracy);
  if (job.support) {  // max |rho| over the balanced states (model.md §10.12); empty without one
    double rho_max = 0.0;
    for (const MapEquilibriumN& e : cell.equilibria) rho_max = std::max(rho_max, e.rho_abs_max);
    if (cell.equilibria.empty())
      summary.push_back(',');
    else
      fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{}"), rho_max);
  }
  summary.push_back('\n');
  append_facts(grid, facts);
}

}  // namespace

namespace map_rows {

AxisText::AxisText(const Axis& a, int first, int last) : first_(first) {
  if (last < 0) last = a.count;
  end_.reserve(std::size_t(std::max(0, last - first)));
  for (int i = first; i < last; ++i) {
    text_ += format_number(a.value(i), "axis value");
    end_.push_back(text_.size());
  }
}

// The two-ball rows of one cell (the columns of map_csv_header / summary_csv_header): the
// long rows only with job.long_rows (their values are checked either way).
void write_cell(const MapJob& job, int ix, int iy, std::string_view x, std::string_view y, const MapCell& cell,
                TileBuffers& out) {
  std::array<int, 3> members{};
  int balanced_stable = -1, n_stable = 0, n_undecided = 0;
  for (int k = 0; k < cell.count; ++k) {
    const MapEquilibrium& e = cell.equilibria[std::size_t(k)];
    ++members[std::size_t(e.family)];
    n_stable += e.stable;
    n_undecided += e.n_undecided > 0;
    if (e.family == Family::balanced) balanced_stable = std::max(balanced_stable, int(e.stable));
    check_finite(e.abscissa, job, ix, iy, "a spectral abscissa");
    check_finite(e.q_abs, job, ix, iy, "|q|");
    check_finite(e.beta1, job, ix, iy, "beta1");
    check_finite(e.beta2, job, ix, iy, "beta2");
    if (job.long_rows)
      fmt::format_to(fmt::appender(out.rows), FMT_COMPILE("{},{},{},{},{},{},{},{},{},{},{},{},{}\n"), ix, iy, x,
                     y, to_string(e.family), int(e.member), int(e.stable), int(e.n_unstable), e.abscissa, e.q_abs,
                     e.beta1, e.beta2, int(e.n_undecided));
  }
  fmt::memory_buffer& summary = out.summary;
  fmt::format_to(fmt::appender(summary), FMT_COMPILE("{},{},{},{},{},{},{},"), ix, iy, x, y, members[0], members[1],
                 members[2]);
  if (balanced_stable >= 0) fmt::format_to(fmt::appender(summary), FMT_COMPILE("{}"), balanced_stable);
  fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{},"), n_stable);
  MapCellFacts facts;
  facts.category = members[0] == 0 ? 0 : balanced_stable == 1 ? 3 : 1;
  facts.best_q_abs = std::numeric_limits<double>::quiet_NaN();
  facts.balanced_stable_fraction = std::numeric_limits<double>::quiet_NaN();
  if (const int best = cell.best_stable(); best >= 0) {
    const MapEquilibrium& e = cell.equilibria[std::size_t(best)];
    fmt::format_to(fmt::appender(summary), FMT_COMPILE("{},{},{}"), to_string(e.family), int(e.member), e.q_abs);
    facts.best_q_abs = e.q_abs;
  } else {
    fmt::format_to(fmt::appender(summary), FMT_COMPILE(",,"));
  }
  fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{},{}\n"), cell.degeneracy, n_undecided);
  append_facts(out.grid, facts);
}

void write_cell_n(const MapJob& job, int ix, int iy, std::string_view x, std::string_view y, const MapCellN& cell,
                  TileBuffers& out) {
  write_rows_n(job, ix, iy, x, y, cell, out.rows, out.summary, out.grid);
}

}  // namespace map_rows
}  // namespace abu
