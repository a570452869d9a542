// `map` of balls on an unround race on a flexible shaft (shaft_commands.hpp, model.md §18.18):
// per cell the race's equilibria on the shaft and their verdicts, summarised as the unround race's
// map (analysis/shaft_race_map.hpp). The axes are the unround map's — a scene parameter or the
// unroundness factor — without the rigid rotor's k, c and M_r (the bearings and discs replace them).
#include <fmt/format.h>

#include "abu/analysis/shaft_race_map.hpp"
#include "abu/core/errors.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/report_shaft.hpp"
#include "abu/scan/map.hpp"
#include "shaft_commands.hpp"
#include "tiled_run.hpp"
#include "unround_commands.hpp"

namespace abu::cli {

int map_shaft_race(const Scene& scene, const ShaftMapRequest& request) {
  const RaceShape race = race_shape(scene);
  // k, c and M_r are refused by set_checked: a shaft scene has none (model.md §18.10).
  const UnroundMapAxes axes = unround_map_axes(request.x, request.y, scene, race);
  const UnroundAxis &x = axes.x, &y = axes.y;
  ShaftRaceMapJob job;
  job.x_name = x.name, job.y_name = y.name, job.x_unit = x.unit, job.y_unit = y.unit;
  job.xs = axes.xs, job.ys = axes.ys;
  job.cell_input = [&scene, &x, &y, &job](int ix, int iy) {
    const UnroundCell c = unround_cell(scene, x, job.xs[std::size_t(ix)], y, job.ys[std::size_t(iy)]);
    return std::pair{shaft_system_of(c.scene), scaled_race(race_shape(c.scene), c.factor)};
  };
  job.spectrum = request.spectrum;
  // The shaft's and the race's numbers: the tiles' manifest is this header, so --resume refuses
  // a changed shaft or race.
  job.provenance = shaft_header_lines(request.command_line, scene.file, shaft_system_of(scene)) +
                   describe_shaft(*scene.shaft, "# ") + describe_race(race, "# ");
  SummaryMapRun run{request.output_dir, "summary", "shaft_race_map", x.name, y.name, int(job.xs.size()),
                    shaft_race_map_manifest(job), shaft_race_map_header(job),
                    {request.resume, request.fresh, request.progress, request.quiet, request.threads}, request.chart,
                    "unround_map.gp", axes_chart_variables(x.name, x.unit, x.axis.logarithmic, y.name, y.unit,
                                                           y.axis.logarithmic),
                    "equilibria"};
  run.chart_variables.insert(run.chart_variables.end(),
                             {{"first_order", "0"},
                              {"title", fmt::format("{}: unround race on a flexible shaft, map", scene.file)},
                              {"subtitle", chart_subtitle(scene, request.overrides, {{x.name, x.axis.from, x.axis.to, x.unit}, {y.name, y.axis.from, y.axis.to, y.unit, "y axis"}})}});
  return run_summary_map(run, [&job](const auto& missing, const auto& run_options, const auto& sink) {
    return compute_shaft_race_map_tiles(job, missing, run_options, sink);
  });
}

}  // namespace abu::cli
