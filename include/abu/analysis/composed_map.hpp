// A map of an unround race on an anisotropic support over two parameters (docs/model.md §20.7):
// per cell every state `equilibria` finds there — the race's equilibria on the mean support, each
// continued in the anisotropy to a pi/omega-periodic orbit (§20.4, composed_orbits_at) — counted
// by verdict, with the design figure: the largest |q| over the period of the stable orbit whose
// largest |q| is least. Tiles are columns (one x value each) through the map's TileStore and
// thread pool: threads, --resume, and the same bytes whatever the thread count.
//
//   abu::ComposedMapJob job{...};   // the CLI builds cell_input from the scene
//   abu::compute_composed_map_tiles(job, store.missing(), options, sink);
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "abu/analysis/composed_sweep.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

struct ComposedMapJob {
  std::string x_name, y_name, x_unit, y_unit;
  std::vector<double> xs, ys;
  AnisotropicSupport support;  ///< the scene's (k and c are not axes: they are its means)
  /// The machine of cell (ix, iy): parameters with the mean support and the race's paths;
  /// thread-safe (called from the workers).
  std::function<ComposedMachineAt(int ix, int iy)> cell_input;
  ForcedOrbitOptions orbit;  ///< the orbits' shooting and continuation in delta (forced_orbits.hpp)
  std::string provenance;    ///< "# " lines (the support's and the race's numbers included)
};

/// One cell's counts (a row of summary_X_Y.csv).
struct ComposedCell {
  int equilibria = 0;  ///< of the race on the mean support (§11.4)
  int orbits = 0;      ///< continued to the scene's support and converged
  int stable = 0, unstable = 0, marginal = 0;  ///< the converged orbits by verdict (§10.18's band)
  int failed = 0;      ///< not converged (continuation in delta or shooting): no verdict
  /// max |q| over the period of the stable orbit whose max |q| is least [m]; absent: none stable.
  std::optional<double> best_q_abs;
  bool complete = false;  ///< the race's box search proved its list complete (§11.4)
};

/// The counts of one value's orbits.
ComposedCell composed_cell(const ComposedSweepPoint& point);

/// What determines the map's bytes (the TileStore manifest).
std::string composed_map_manifest(const ComposedMapJob& job);
/// Comment block and column names of summary_X_Y.csv.
std::string composed_map_header(const ComposedMapJob& job);
/// One tile: column ix = tile, its cells' summary rows in iy order (TileText::summary).
TileText compute_composed_map_tile(const ComposedMapJob& job, int tile);
MapRunStats compute_composed_map_tiles(const ComposedMapJob& job, const std::vector<int>& tiles,
                                       const MapRunOptions& options, const TileSink& sink);

}  // namespace abu
