// A map of balls on an unround race on a flexible shaft over two parameters (docs/model.md
// §18.18, §11.10): per cell the race's equilibria on the shaft with their rightmost eigenvalues
// and verdicts (analyze_shaft_race_states), summarised as the unround race's map is — the count
// of states and of stable ones, the design figure (|q| of the least-|q| stable state) — with the
// undetermined count and the balls-held whirl omega^2 U |h| beside it. Tiles are columns (one x
// value each) through the map's TileStore and thread pool: threads, --resume, and the same bytes
// whatever the thread count.
//
//   abu::ShaftRaceMapJob job{...};   // the CLI builds cell_input from the scene
//   abu::compute_shaft_race_map_tiles(job, store.missing(), options, sink);
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "abu/analysis/shaft_states.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/model/unround_race.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

struct ShaftRaceMapJob {
  std::string x_name, y_name, x_unit, y_unit;
  std::vector<double> xs, ys;
  /// The shaft system and the race of cell (ix, iy); thread-safe (called from the workers).
  std::function<std::pair<ShaftSystem, RaceShape>(int ix, int iy)> cell_input;
  ShaftSpectrumOptions spectrum;
  std::string provenance;  ///< "# " lines (the shaft's and the race's numbers included)
};

/// What determines the map's bytes (the TileStore manifest).
std::string shaft_race_map_manifest(const ShaftRaceMapJob& job);
/// Comment block and column names of summary_X_Y.csv.
std::string shaft_race_map_header(const ShaftRaceMapJob& job);
/// One tile: column ix = tile, its cells' summary rows in iy order (TileText::summary).
TileText compute_shaft_race_map_tile(const ShaftRaceMapJob& job, int tile);
MapRunStats compute_shaft_race_map_tiles(const ShaftRaceMapJob& job, const std::vector<int>& tiles,
                                         const MapRunOptions& options, const TileSink& sink);

}  // namespace abu
