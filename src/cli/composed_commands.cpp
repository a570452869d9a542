// `sweep` and `map` on an unround race with an anisotropic support (composed_commands.hpp,
// model.md §20.6, §20.7).
#include "composed_commands.hpp"

#include <fmt/format.h>

#include "abu/analysis/composed_branches.hpp"
#include "abu/analysis/composed_map.hpp"
#include "abu/analysis/composed_parameter.hpp"
#include "abu/analysis/composed_sweep.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/suggest.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/ranges.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_composed_branches.hpp"
#include "abu/output/report_composed_sweep.hpp"
#include "abu/scan/scan.hpp"
#include "tiled_run.hpp"

namespace abu::cli {

namespace {
constexpr int kMaxComposedSteps = 10000;  // each value costs the orbits of `equilibria` (~0.2 s an orbit)
}  // namespace

int sweep_composed(const Scene& scene, const SceneOptions& options, const UnroundGrid& g) {
  const ComposedParam c = composed_param(scene, g.param, "--param");
  const std::string& name = c.name;
  const std::string& unit_name = c.unit_name;
  if (g.steps < 1 || g.steps > kMaxComposedSteps)
    throw InputError("--steps", 0, "steps", fmt::format("must be in [1, {}] (got {})", kMaxComposedSteps, g.steps));
  if (g.logarithmic && !(g.from > 0 && g.to > 0))
    throw InputError("--log", 0, g.param, fmt::format("a log grid needs both ends > 0 (got {} .. {})", g.from, g.to));
  const std::vector<double> values = grid_values(g.from, g.to, g.steps, g.logarithmic);
  for (double v : {g.from, g.to}) check_composed_value(scene, c, v, "--from/--to");  // the ends decide: every value between keeps the rules
  const ComposedSweep s = composed_sweep(*scene.support, composed_machine_at(scene, c, "--from/--to"), values);

  const ParamsN first = params_of<any_balls>(scene);
  const std::string header = provenance_header(command_line(), scene.file, first);
  const std::filesystem::path dir(g.output_dir);
  const auto csv_path = dir / fmt::format("sweep_{}.csv", name);
  const auto crossings_path = dir / fmt::format("floquet_crossings_{}.csv", name);
  const auto png_path = dir / fmt::format("sweep_{}.png", name);
  OutputTransaction out;
  const auto staged_csv = out.stage(csv_path, composed_sweep_csv(s, name, header));
  const auto staged_crossings = out.stage(crossings_path, composed_crossings_csv(s, name, header));
  if (g.chart)
    run_gnuplot(plots_dir() / "sweep_composed.gp",
                {{"csv", staged_csv.string()},
                 {"crossings", staged_crossings.string()},
                 {"png", out.reserve(png_path).string()},
                 {"param", name},
                 {"unit", unit_name},
                 {"logx", g.logarithmic ? "1" : "0"},
                 {"has_crossings", s.crossings.empty() ? "0" : "1"},
                 {"title", fmt::format("{}: sweep of {} (unround race on an anisotropic support: periodic orbits)",
                                       scene.file, name)},
                 {"subtitle", chart_subtitle(scene, options.overrides, {{name, values.front(), values.back(), unit_name}})}});
  out.commit();
  fmt::print(stderr, "{}", composed_sweep_text(s, name));
  std::size_t rows = 0;
  for (const auto& point : s.points) rows += point.rows.size();
  fmt::print(stderr, "{} orbit(s) followed over {} values ({} rows); wrote {} and {}{}\n", s.tracks, values.size(), rows,
             csv_path.string(), crossings_path.string(), g.chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}

int continue_composed(const Scene& scene, const SceneOptions& options, const std::string& param, double to,
                      const ContinuationOptions& numerics, bool chart, const std::string& output_dir) {
  const ComposedParam c = composed_param(scene, param, "--param");
  const ParamsN first = params_of<any_balls>(scene);
  const double from = composed_start(scene, c);
  ForcedBranchOptions o;
  o.continuation = numerics;
  const ComposedBranches b = continue_composed(scene, c, to, o, "--to");

  const std::string header = provenance_header(command_line(), scene.file, first);
  const std::filesystem::path dir(output_dir);
  const auto csv_path = dir / fmt::format("branch_{}.csv", c.name);
  const auto specials_path = dir / fmt::format("special_{}.csv", c.name);
  const auto png_path = dir / fmt::format("branch_{}.png", c.name);
  std::size_t specials = 0, points = 0;
  for (const auto& br : b.branches) specials += br.branch.specials.size(), points += br.branch.points.size();
  OutputTransaction out;
  const auto staged_csv = out.stage(csv_path, composed_branches_csv(b, c.name, header));
  const auto staged_specials = out.stage(specials_path, composed_specials_csv(b, c.name, header));
  if (chart)
    run_gnuplot(plots_dir() / "continue_composed.gp",
                {{"csv", staged_csv.string()},
                 {"specials", staged_specials.string()},
                 {"png", out.reserve(png_path).string()},
                 {"param", c.name},
                 {"unit", c.unit_name},
                 {"has_specials", specials == 0 ? "0" : "1"},
                 {"title", fmt::format("{}: continuation in {} (unround race on an anisotropic support: periodic orbits)",
                                       scene.file, c.name)},
                 {"subtitle", chart_subtitle(scene, options.overrides,
                                             {{c.name, std::min(from, to), std::max(from, to), c.unit_name}})}});
  out.commit();
  fmt::print(stderr, "{}", composed_branches_text(b, c.name));
  fmt::print(stderr, "{} branch(es) of periodic orbits, {} points ({} orbits at {} = {}, {} at {}); wrote {} and {}{}\n",
             b.branches.size(), points, b.orbits_at_start, c.name, from, b.orbits_at_end, to, csv_path.string(),
             specials_path.string(), chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return b.status.ok() ? exit_ok : exit_numerical;  // a branch that ended early: exit 3, the rest written
}

int map_composed(const Scene& scene, const SceneOptions& options, const UnroundMapRequest& request) {
  const RaceShape race = race_shape(scene);
  // k and c, the support's means, are refused by set_checked (model.md §10.11).
  const UnroundMapAxes axes = unround_map_axes(request.x, request.y, scene, race);
  const UnroundAxis &x = axes.x, &y = axes.y;
  ComposedMapJob job;
  job.x_name = x.name, job.y_name = y.name, job.x_unit = x.unit, job.y_unit = y.unit;
  job.xs = axes.xs, job.ys = axes.ys;
  for (double xv : {job.xs.front(), job.xs.back()})  // the corners decide: every cell between keeps the rules
    for (double yv : {job.ys.front(), job.ys.back()})
      check_numerical_range(unround_cell(scene, x, xv, y, yv).scene, "--x/--y",
                            fmt::format("at {}={}, {}={}", x.name, xv, y.name, yv));
  job.support = *scene.support;
  job.cell_input = [&scene, &x, &y, &job](int ix, int iy) {
    const UnroundCell c = unround_cell(scene, x, job.xs[std::size_t(ix)], y, job.ys[std::size_t(iy)]);
    return ComposedMachineAt{params_of<any_balls>(c.scene), scaled_race(race_shape(c.scene), c.factor)};
  };
  // The support's and the race's numbers: the tiles' manifest is this header, so --resume
  // refuses a changed support or race.
  job.provenance = provenance_header(request.command_line, scene.file, params_of<any_balls>(scene)) +
                   "# anisotropic support: " + describe_support(*scene.support) + "\n" + describe_race(race, "# ");
  SummaryMapRun run{request.output_dir, "summary", "composed_map", x.name, y.name, int(job.xs.size()),
                    composed_map_manifest(job), composed_map_header(job),
                    {request.resume, request.fresh, request.progress, request.quiet, request.threads}, request.chart,
                    "unround_map.gp", axes_chart_variables(x.name, x.unit, x.axis.logarithmic, y.name, y.unit,
                                                           y.axis.logarithmic),
                    "orbits"};
  run.chart_variables.insert(
      run.chart_variables.end(),
      {{"first_order", "0"},
       {"states", "stable periodic orbits"},
       {"qlabel", "log_{10} max |q| over the period of the best stable orbit [m]"},
       {"title", fmt::format("{}: unround race on an anisotropic support, map (periodic orbits)", scene.file)},
       {"subtitle", chart_subtitle(scene, options.overrides, {{x.name, x.axis.from, x.axis.to, x.unit}, {y.name, y.axis.from, y.axis.to, y.unit, "y axis"}})}});
  return run_summary_map(run, [&job](const auto& missing, const auto& run_options, const auto& sink) {
    return compute_composed_map_tiles(job, missing, run_options, sink);
  });
}

}  // namespace abu::cli
