// A map of an unround race over two parameters (model.md §11.10), e.g. (omega, the
// unroundness factor): per cell the complete search of §11.4, and its summary row — the
// count of equilibria and of stable ones, the design figure (|q| of the best stable
// state), Lambda of §11.6 and the first-order flag, and whether the search was complete.
// Tiles are columns (one x value each) through the map's TileStore and thread pool
// (map_driver.hpp): threads, --resume, and the same bytes whatever the thread count.
//
//   abu::UnroundMapJob job{...};     // the CLI builds cell_input from the scene
//   abu::compute_unround_map_tiles(job, store.missing(), options, sink);
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "abu/model/unround_race.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

struct UnroundMapJob {
  std::string x_name, y_name, x_unit, y_unit;
  std::vector<double> xs, ys;
  /// The parameters and race of cell (ix, iy); thread-safe (called from the workers).
  std::function<std::pair<ParamsN, RaceShape>(int ix, int iy)> cell_input;
  std::string provenance;  ///< "# " lines
};

/// What determines the map's bytes (the TileStore manifest).
std::string unround_map_manifest(const UnroundMapJob& job);
/// Comment block and column names of summary_X_Y.csv.
std::string unround_map_header(const UnroundMapJob& job);
/// One tile: column ix = tile, its cells' summary rows in iy order (TileText::summary).
TileText compute_unround_map_tile(const UnroundMapJob& job, int tile);
MapRunStats compute_unround_map_tiles(const UnroundMapJob& job, const std::vector<int>& tiles,
                                      const MapRunOptions& options, const TileSink& sink);

}  // namespace abu
