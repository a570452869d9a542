#include "tiled_run.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <sstream>

#include "abu/core/cancel.hpp"
#include "abu/output/files.hpp"
#include "abu/output/format.hpp"
#include "abu/output/gnuplot.hpp"
#include "cli.hpp"

namespace abu::cli {

TileStore::Mode tile_store_mode(const TiledRunFlags& flags) {
  return flags.resume ? TileStore::Mode::resume : flags.fresh ? TileStore::Mode::discard : TileStore::Mode::fresh;
}

std::optional<FinishedTiles> run_missing_tiles(const TileStore& store, const std::filesystem::path& tiles_dir, int tiles,
                                               const TiledRunFlags& flags, const TileComputation& compute) {
  const std::vector<int> missing = store.missing();
  ProgressMeter meter(tiles, tiles - int(missing.size()), !flags.quiet && (flags.progress || isatty(STDERR_FILENO)));
  MapRunOptions run;
  run.threads = flags.threads;
  run.stop = &stop_flag();
  run.progress = &meter;
  set_interrupt_note(fmt::format("the finished tiles are kept in {}; rerun the same command with --resume",
                                 escaped(tiles_dir.string())));
  const MapRunStats stats = compute(missing, run, [&store](int tile, TileText&& text) { store.put(tile, text); });
  meter.finish();
  set_interrupt_note({});
  if (!stats.interrupted && !stop_requested()) {
    std::ostringstream rows, summary;
    for (int t = 0; t < tiles; ++t) store.append(t, rows, summary);
    return FinishedTiles{stats, rows.str(), summary.str()};
  }
  fmt::print(stderr, "stability-scan: interrupted: {} of {} tiles are kept in {}; run the same command with --resume\n",
             tiles - int(store.missing().size()), tiles, tiles_dir.string());
  return std::nullopt;
}

std::vector<std::pair<std::string, std::string>> axes_chart_variables(const std::string& x_name, const std::string& x_unit,
                                                                      bool log_x, const std::string& y_name,
                                                                      const std::string& y_unit, bool log_y) {
  return {{"xname", x_name}, {"yname", y_name},          {"xunit", x_unit},
          {"yunit", y_unit}, {"logx", log_x ? "1" : "0"}, {"logy", log_y ? "1" : "0"}};
}

int run_summary_map(const SummaryMapRun& run, const TileComputation& compute) {
  namespace fs = std::filesystem;
  const std::string xy = fmt::format("{}_{}", run.x_name, run.y_name);
  const fs::path csv_path = run.dir / fmt::format("{}_{}.csv", run.stem, xy);
  const fs::path png_path = run.dir / fmt::format("{}_{}.png", run.stem, xy);
  const fs::path tiles_dir = run.dir / fmt::format(".{}_{}.tiles", run.tiles_stem, xy);
  fs::create_directories(run.dir);
  const TileStore store(tiles_dir, run.manifest, run.tiles, tile_store_mode(run.flags));
  const std::optional<FinishedTiles> counts = run_missing_tiles(store, tiles_dir, run.tiles, run.flags, compute);
  if (!counts) return interrupted_exit_code();
  {
    OutputTransaction out;
    const fs::path staged = out.stage(csv_path, run.header + counts->summary);
    if (run.chart) {
      std::vector<std::pair<std::string, std::string>> variables{{"csv", staged.string()},
                                                                 {"png", out.reserve(png_path).string()}};
      variables.insert(variables.end(), run.chart_variables.begin(), run.chart_variables.end());
      run_gnuplot(plots_dir() / run.script, variables);
    }
    out.commit();
  }
  store.remove();
  const MapRunStats& stats = counts->stats;
  if (!run.flags.quiet)
    fmt::print(stderr, "{} cells, {} {}, {} tiles computed in {:.2f} s ({:.3g} cells/s) -> {}{}\n", stats.cells,
               stats.equilibria, run.counted, stats.tiles, stats.seconds,
               stats.seconds > 0 ? double(stats.cells) / stats.seconds : 0.0, csv_path.string(),
               run.chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}

}  // namespace abu::cli
