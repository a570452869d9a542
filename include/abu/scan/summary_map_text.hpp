// The text of the summary maps whose tiles are columns (the unround race's, the shaft's, the race
// on a shaft's, the composed machine's): a cell's values in shortest round-trip form, never a NaN
// or inf in a CSV — a value that is not finite is a numerical failure naming the map, the cell
// and the value (docs/robustness.md) — and the manifest that ties a run's tiles to its inputs.
//
//   const abu::MapCellPlace cell{"shaft map", job.x_name, job.xs[ix], job.y_name, job.ys[iy]};
//   text += abu::cell_number(q_abs, cell, "|q|");
//   TileStore store(dir, abu::summary_map_manifest(header, job.xs, job.ys), ...);
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace abu {

struct MapCellPlace {
  std::string_view map;  ///< e.g. "unround map"
  std::string_view x_name;
  double x = 0;
  std::string_view y_name;
  double y = 0;
};

/// "MAP cell (X=x, Y=y)": where a failure in a cell happened.
std::string cell_label(const MapCellPlace& cell);
/// fmt's "{}" of v; throws NumericalError("MAP cell (X=x, Y=y): WHAT is not finite") otherwise.
std::string cell_number(double v, const MapCellPlace& cell, std::string_view what);

/// What determines a summary map's bytes: its CSV header (provenance and the numbers of every
/// part) and its axes' values, one "x V" / "y V" line each.
std::string summary_map_manifest(std::string header, const std::vector<double>& xs, const std::vector<double>& ys);

}  // namespace abu
