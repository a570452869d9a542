// The part every resumable tiled command (`map` of a flexible shaft or an unround race,
// `basin`) shares: run the tiles the store still misses, with a progress meter and the
// interrupt note, and say what is kept when a signal stops the run.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "abu/scan/map_driver.hpp"

namespace abu::cli {

/// The command-line flags of a tiled run.
struct TiledRunFlags {
  bool resume = false;    ///< --resume: continue the tiles of an earlier run
  bool fresh = false;     ///< --fresh: discard them
  bool progress = false;  ///< --progress: a meter even when stderr is not a terminal
  bool quiet = false;     ///< --quiet: no meter
  int threads = 1;        ///< --threads
};

/// The store's mode for the flags (--resume, --fresh, or a new directory).
TileStore::Mode tile_store_mode(const TiledRunFlags& flags);

/// A command's tile computation: `compute_*_tiles(job, tiles, options, sink)` bound to its job.
using TileComputation =
    std::function<MapRunStats(const std::vector<int>& tiles, const MapRunOptions& options, const TileSink& sink)>;

/// Every tile of a finished run, in tile order (TileStore::append), and the run's counts.
struct FinishedTiles {
  MapRunStats stats;
  std::string rows, summary;
};

/// Computes the tiles `store` misses (`tiles_dir` is its directory, `tiles` their count),
/// each put in the store as it is made, then reads every tile back in order. nullopt: a
/// signal stopped the run; the message (how many tiles are kept, rerun with --resume) is
/// printed and the finished tiles stay.
std::optional<FinishedTiles> run_missing_tiles(const TileStore& store, const std::filesystem::path& tiles_dir, int tiles,
                                               const TiledRunFlags& flags, const TileComputation& compute);

/// A map whose tiles are its columns and whose output is one summary CSV with a chart: the
/// unround race's, the flexible shaft's, the race on a shaft's and the composed machine's maps.
struct SummaryMapRun {
  std::filesystem::path dir;  ///< the output directory
  std::string stem;           ///< the files are STEM_X_Y.csv and STEM_X_Y.png
  std::string tiles_stem;     ///< the tiles live in DIR/.TILES_STEM_X_Y.tiles
  std::string x_name, y_name;
  int tiles = 0;              ///< the x values
  std::string manifest;       ///< what determines the bytes (the TileStore's)
  std::string header;         ///< the CSV's comment block and column names
  TiledRunFlags flags;
  bool chart = true;
  std::string script;         ///< plots/SCRIPT draws the chart
  /// The chart's variables besides csv and png (names, units, log flags, title, subtitle).
  std::vector<std::pair<std::string, std::string>> chart_variables;
  std::string counted;        ///< what TileText::equilibria counts, for the closing line
};
/// The chart variables of a map's two axes: xname, yname, xunit, yunit, logx, logy.
std::vector<std::pair<std::string, std::string>> axes_chart_variables(const std::string& x_name, const std::string& x_unit,
                                                                      bool log_x, const std::string& y_name,
                                                                      const std::string& y_unit, bool log_y);
/// Runs the missing tiles, writes the summary and its chart in one transaction, removes the
/// tiles and prints the closing line. Returns the exit code (interrupted_exit_code() when a
/// signal stopped the run; the finished tiles are kept).
int run_summary_map(const SummaryMapRun& run, const TileComputation& compute);

}  // namespace abu::cli
