// `map` of balls on an unround race on a flexible shaft (shaft_commands.hpp, model.md §18.18):
// per cell the race's equilibria on the shaft and their verdicts, summarised as the unround race's
// map (analysis/shaft_race_map.hpp). The axes are the unround map's — a scene parameter or the
// unroundness factor — without the rigid rotor's k, c and M_r (the bearings and discs replace them).
#include <fmt/format.h>

#include <filesystem>

#include "abu/analysis/shaft_race_map.hpp"
#include "abu/core/errors.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/report_shaft.hpp"
#include "abu/scan/map.hpp"
#include "shaft_commands.hpp"
#include "tiled_run.hpp"
#include "unround_commands.hpp"

namespace abu::cli {

namespace {
// Cell (xv, yv): the scene's parameters set, the race re-read (surface harmonics follow l and r)
// and scaled by a factor axis, the shaft's system built.
std::pair<ShaftSystem, RaceShape> cell_at(const Scene& scene, const UnroundAxis& x, double xv, const UnroundAxis& y,
                                          double yv) {
  Scene s = scene;
  double factor = 1;
  for (const auto& [a, v] : {std::pair{&x, xv}, std::pair{&y, yv}}) {
    if (a->factor)
      factor = v;
    else
      set_checked(s, a->axis.param, v, "--x/--y");
  }
  return {shaft_system_of(s), scaled_race(race_shape(s), factor)};
}
}  // namespace

int map_shaft_race(const Scene& scene, const ShaftMapRequest& request) {
  const RaceShape race = race_shape(scene);
  // k, c and M_r are refused by set_checked: a shaft scene has none (model.md §18.10).
  const UnroundAxis x = unround_axis(request.x, scene, race, "--x"), y = unround_axis(request.y, scene, race, "--y");
  if (x.name == y.name) throw InputError("--y", 0, request.y, "the two axes are one parameter");
  if (long(x.axis.count) * long(y.axis.count) > kMaxCells)
    throw InputError("--y", 0, request.y, fmt::format("the map would have {} x {} cells; at most {} are allowed",
                                                      x.axis.count, y.axis.count, kMaxCells));
  ShaftRaceMapJob job;
  job.x_name = x.name, job.y_name = y.name, job.x_unit = x.unit, job.y_unit = y.unit;
  for (int i = 0; i < x.axis.count; ++i) job.xs.push_back(x.axis.value(i));
  for (int i = 0; i < y.axis.count; ++i) job.ys.push_back(y.axis.value(i));
  job.cell_input = [&scene, &x, &y, &job](int ix, int iy) {
    return cell_at(scene, x, job.xs[std::size_t(ix)], y, job.ys[std::size_t(iy)]);
  };
  job.spectrum = request.spectrum;
  // The shaft's and the race's numbers: the tiles' manifest is this header, so --resume refuses
  // a changed shaft or race.
  job.provenance = shaft_header_lines(request.command_line, scene.file, shaft_system_of(scene)) +
                   describe_shaft(*scene.shaft, "# ") + describe_race(race, "# ");
  namespace fs = std::filesystem;
  const fs::path dir(request.output_dir);
  const auto summary_path = dir / fmt::format("summary_{}_{}.csv", x.name, y.name);
  const auto png_path = dir / fmt::format("summary_{}_{}.png", x.name, y.name);
  const fs::path tiles_dir = dir / fmt::format(".shaft_race_map_{}_{}.tiles", x.name, y.name);
  fs::create_directories(dir);
  const int tiles = int(job.xs.size());
  const TiledRunFlags flags{request.resume, request.fresh, request.progress, request.quiet, request.threads};
  const TileStore store(tiles_dir, shaft_race_map_manifest(job), tiles, tile_store_mode(flags));
  const std::optional<FinishedTiles> counts =
      run_missing_tiles(store, tiles_dir, tiles, flags, [&job](const auto& missing, const auto& run_options, const auto& sink) {
        return compute_shaft_race_map_tiles(job, missing, run_options, sink);
      });
  if (!counts) return interrupted_exit_code();
  const MapRunStats& stats = counts->stats;
  {
    OutputTransaction out;
    const auto staged = out.stage(summary_path, shaft_race_map_header(job) + counts->summary);
    if (request.chart)
      run_gnuplot(plots_dir() / "unround_map.gp",
                  {{"csv", staged.string()},
                   {"png", out.reserve(png_path).string()},
                   {"xname", x.name},
                   {"yname", y.name},
                   {"xunit", x.unit},
                   {"yunit", y.unit},
                   {"logx", x.axis.logarithmic ? "1" : "0"},
                   {"logy", y.axis.logarithmic ? "1" : "0"},
                   {"first_order", "0"},
                   {"title", fmt::format("{}: unround race on a flexible shaft, map", scene.file)},
                   {"subtitle", chart_subtitle(scene, request.overrides)}});
    out.commit();
  }
  store.remove();
  if (!request.quiet)
    fmt::print(stderr, "{} cells, {} equilibria, {} tiles computed in {:.2f} s -> {}{}\n", stats.cells,
               stats.equilibria, stats.tiles, stats.seconds, summary_path.string(),
               request.chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}

}  // namespace abu::cli
