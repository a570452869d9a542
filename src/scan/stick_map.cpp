// The cells of a stick-set map (model.md §14); see the header.
#include "abu/scan/stick_map.hpp"

#include <fmt/compile.h>

#include <cmath>
#include <optional>

#include "abu/core/errors.hpp"
#include "abu/equilibria/shaft_stick_set.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/linear/unround_stick_set.hpp"

namespace abu {

namespace {

std::string_view axis_unit(const Axis& a) { return unit(a.param.quantity); }

std::string resolution_line(const MapJob& job) {
  if (!job.race.round())
    return fmt::format("on the paths of an unround race (model.md §20.5, its harmonics above): a grid of at most {} "
                       "points (floor(budget^(1/n)) per angle), flood fill (§14.3); V connected to the race's "
                       "least-|q| stable equilibrium (balanced_exists, spread: that equilibrium's components)",
                       job.stick.grid_budget);
  if (job.params_n.n_balls() == 2)
    return fmt::format("two balls: {} beta_1 columns, {} beta_2 samples per column (plus the dense windows at the "
                       "smooth equilibria), area by adaptive Simpson, maxima refined (§14.3)",
                       job.stick.columns, job.stick.samples);
  return fmt::format("n = {} balls: a grid of at most {} points (floor(budget^(1/n)) per angle), flood fill (§14.3)",
                     job.params_n.n_balls(), job.stick.grid_budget);
}

std::string common_stick_header(const MapJob& job) {
  const auto axis = [](const Axis& a) {
    return fmt::format("{} [{}]: {} values from {} to {}{}", a.name(), axis_unit(a), a.count, a.from, a.to,
                       a.logarithmic ? ", evenly spaced in log" : "");
  };
  return job.provenance + fmt::format("# map: x = {}\n#      y = {}\n#      every cell: the stick set of coulomb-set "
                                      "friction (model.md §14) at the cell's parameters; {}\n",
                                      axis(job.x), axis(job.y), resolution_line(job));
}

// The common header, then `text` with {0}, {1} the axis names, {2}, {3} their units, {4} the
// ball count and {5} one column per ball named by `per_ball` ("{}" the 1-based index); on a shaft
// {6} the comment on its columns and {7} their names (the summary's).
std::string stick_header(const MapJob& job, std::string_view per_ball, std::string_view text) {
  const int n = job.params_n.n_balls();
  std::string columns;
  for (int i = 1; i <= n; ++i) columns += fmt::format(fmt::runtime(per_ball), i);
  const bool shaft = job.shaft != nullptr;  // the summary's shaft columns (model.md §18.17)
  return common_stick_header(job) +
         fmt::format(fmt::runtime(text), job.x.name(), job.y.name(), axis_unit(job.x), axis_unit(job.y), n, columns,
                     shaft ? "# flexible shaft (model.md §18.17): q is the balancer node's; K_eff, C_eff [N/m] its "
                             "dynamic stiffness (18.8.1); worst_node = the node deflecting most per unit q (18.17.2); "
                             "worst_deflection [m] = its deflection where V is attained (empty if no balanced state), "
                             "worst_deflection_any [m] where V_E is\n"
                           : "",
                     shaft ? ",K_eff,C_eff,worst_node,worst_deflection,worst_deflection_any" : "");
}

void check_finite(double value, const MapJob& job, int ix, int iy, const char* what) {
  if (!std::isfinite(value))
    throw NumericalError(fmt::format("map cell ({}, {}) = ({}={}, {}={}): {} of the stick set is not finite", ix, iy,
                                     job.x.name(), job.x.value(ix), job.y.name(), job.y.value(iy), what));
}

}  // namespace

std::string stick_map_csv_header(const MapJob& job) {
  return stick_header(job, ",beta{}_at_max",
                      "# one row per connected component of the stick set per cell, cells in order ix outer, iy inner\n"
                      "# columns: ix, iy grid indices; {0} [{2}], {1} [{3}]; component = its index in the cell; area "
                      "[rad^{4}]; q_abs_max [m] = max |q| over it (rotating frame; the whirl radius in the fixed frame), "
                      "at beta_i_at_max [rad];\n"
                      "#   balanced_points, smooth_equilibria = how many of each it holds; mean_q_abs [m] = mean |q| "
                      "over it\n"
                      "ix,iy,{0},{1},component,area,q_abs_max,balanced_points,smooth_equilibria,mean_q_abs{5}\n");
}

std::string stick_summary_csv_header(const MapJob& job) {
  return stick_header(job, ",spread{}",
                      "# one row per cell, in order ix outer, iy inner\n"
                      "# columns: ix, iy grid indices; {0} [{2}], {1} [{3}]; area [rad^{4}] of the stick set E, "
                      "area_fraction = area / (2 pi)^{4}; whole_torus = 1 if every arrangement sticks; components = "
                      "connected components of E;\n"
                      "#   balanced_exists = 1 if a component holds a balanced point; worst_q_abs [m] = V, max |q| over "
                      "the components holding a balanced point (empty if none does); worst_q_abs_any [m] = V_E, max "
                      "|q| over E;\n"
                      "#   mean_q_abs [m] = mean |q| over E; bare_rotor_q_abs [m] = omega^2 U / |K + iC|, the rotor "
                      "without balls; spread_i [rad] = the largest angular spread of ball i over a balanced component "
                      "(empty if none); |q| is in the rotating frame, the whirl radius in the fixed frame\n"
                      "{6}ix,iy,{0},{1},area,area_fraction,whole_torus,components,balanced_exists,worst_q_abs,"
                      "worst_q_abs_any,mean_q_abs,bare_rotor_q_abs{5}{7}\n");
}

std::size_t stick_map_bytes_per_cell(const MapJob& job) {
  // summary ~ 13 numbers of up to 24 characters plus n spreads; long rows: a few
  // components (the scenes of tests/scenes/stick have up to 7), each ~10 + n numbers.
  const int n = job.params_n.n_balls();
  return std::size_t((19 + n) * 25 + 8 * (10 + n) * 25);  // + the shaft's 5 columns, if any
}

ParamsN stick_cell_params(const MapJob& job, int ix, int iy) {
  ParamsN p = job.params_n;
  set(p, job.x.param, job.x.value(ix));
  set(p, job.y.param, job.y.value(iy));
  return p;
}

namespace {
std::string cell_name(const MapJob& job, int ix, int iy) {
  return fmt::format("map cell ({}, {}) = ({}={}, {}={})", ix, iy, job.x.name(), job.x.value(ix), job.y.name(),
                     job.y.value(iy));
}
}  // namespace

void check_stick_cell_defined(const MapJob& job, int ix, int iy) {
  const ParamsN p = stick_cell_params(job, ix, iy);
  try {
    if (job.shaft) {
      check_shaft_stick_set_defined(stuck_balls_shaft(*job.shaft, p));
    } else {
      check_stick_set_defined(p);
    }
  } catch (const NotSupportedError& e) {
    throw NotSupportedError(fmt::format("{}: {}", cell_name(job, ix, iy), e.what()));
  }
}

int write_stick_cell(const MapJob& job, int ix, int iy, std::string_view x, std::string_view y,
                     fmt::memory_buffer& rows, fmt::memory_buffer& summary) {
  const ParamsN p = stick_cell_params(job, ix, iy);
  StickSetOptions options = job.stick;
  options.trace = false;  // the boundary curves are not written per cell
  StickSet s;
  std::optional<ShaftStickFigures> shaft;
  try {
    if (job.shaft) {  // through the shaft (model.md §18.17)
      ShaftStickSet ss = shaft_stick_set(stuck_balls_shaft(*job.shaft, p), options);
      s = std::move(ss.set);
      shaft = std::move(ss.shaft);
    } else {
      s = stick_set(p, job.race, options);  // on the race's paths when unround (model.md §20.5)
    }
  } catch (const NotSupportedError& e) {
    throw NotSupportedError(fmt::format("{}: {}", cell_name(job, ix, iy), e.what()));
  }
  const int n = s.n_balls;
  for (std::size_t c = 0; c < s.components.size(); ++c) {
    const StickComponent& comp = s.components[c];
    const double mean = comp.area > 0 ? comp.q_abs_integral / comp.area : 0.0;
    check_finite(comp.area, job, ix, iy, "a component's area");
    check_finite(comp.q_abs_max, job, ix, iy, "a component's max |q|");
    check_finite(mean, job, ix, iy, "a component's mean |q|");
    fmt::format_to(fmt::appender(rows), FMT_COMPILE("{},{},{},{},{},{},{},{},{},{}"), ix, iy, x, y, c + 1, comp.area,
                   comp.q_abs_max, comp.balanced_points.size(), comp.seeds.size(), mean);
    for (double b : comp.beta_at_max) {
      check_finite(b, job, ix, iy, "an angle");
      fmt::format_to(fmt::appender(rows), FMT_COMPILE(",{}"), b);
    }
    rows.push_back('\n');
  }
  for (double v : {s.area, s.area_fraction, s.worst_q_abs, s.worst_q_abs_any, s.mean_q_abs, s.bare_rotor_q_abs})
    check_finite(v, job, ix, iy, "a figure");
  fmt::format_to(fmt::appender(summary), FMT_COMPILE("{},{},{},{},{},{},{},{},{},"), ix, iy, x, y, s.area,
                 s.area_fraction, int(s.whole_torus), s.components.size(), int(s.balanced_exists));
  if (s.balanced_exists) fmt::format_to(fmt::appender(summary), FMT_COMPILE("{}"), s.worst_q_abs);
  fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{},{},{}"), s.worst_q_abs_any, s.mean_q_abs,
                 s.bare_rotor_q_abs);
  for (int i = 0; i < n; ++i) {
    summary.push_back(',');
    if (s.balanced_exists) {
      check_finite(s.spread[std::size_t(i)], job, ix, iy, "a spread");
      fmt::format_to(fmt::appender(summary), FMT_COMPILE("{}"), s.spread[std::size_t(i)]);
    }
  }
  if (shaft) {
    for (double v : {shaft->dynamic_stiffness.real(), shaft->dynamic_stiffness.imag(), shaft->worst_deflection,
                     shaft->worst_deflection_any})
      check_finite(v, job, ix, iy, "a shaft figure");
    fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{},{},{},"), shaft->dynamic_stiffness.real(),
                   shaft->dynamic_stiffness.imag(), shaft->worst_node);
    if (s.balanced_exists) fmt::format_to(fmt::appender(summary), FMT_COMPILE("{}"), shaft->worst_deflection);
    fmt::format_to(fmt::appender(summary), FMT_COMPILE(",{}"), shaft->worst_deflection_any);
  }
  summary.push_back('\n');
  return int(s.components.size());
}

}  // namespace abu
