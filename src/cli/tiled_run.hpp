// The part every resumable tiled command (`map` of a flexible shaft or an unround race,
// `basin`) shares: run the tiles the store still misses, with a progress meter and the
// interrupt note, and say what is kept when a signal stops the run.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
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

}  // namespace abu::cli
