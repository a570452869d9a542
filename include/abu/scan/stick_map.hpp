// Maps of the stick set of `coulomb-set` friction (model.md §14): per cell the stick set's
// figures (area, components, V, V_E, mean |q|, the rotor without balls, the spread of each
// ball) instead of equilibria and spectra. The map driver (map_driver.hpp) tiles, threads
// and resumes these maps like every other; this file is the cell, its rows and the CSVs'
// columns. A cell is `equilibria`'s computation at the cell's parameters with the map's
// resolution (MapJob::stick; the defaults are equilibria's), so `equilibria` with the same
// --stick-columns / --stick-area-tolerance / --stick-grid reproduces it exactly.
//
// Allocation: stick_set() builds its columns, arcs and components in std::vectors per
// call, so a cell allocates; bounded by the resolution (two balls: O(columns x arcs per
// column) plus the seeds' dense windows; n >= 3: O(grid_budget) bytes), freed at the
// cell's end. The cost of the cell (milliseconds to a second) dwarfs the allocations.
//
//   abu::MapJob job;  job.stick_set = true;  job.params_n = ...;  job.stick = options;
//   fmt::memory_buffer rows, summary;
//   abu::write_stick_cell(job, ix, iy, "800", "6e-5", rows, summary);
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <string>
#include <string_view>

#include "abu/core/params.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

/// The long CSV (one row per component per cell) and the summary CSV (one row per cell).
std::string stick_map_csv_header(const MapJob& job);
std::string stick_summary_csv_header(const MapJob& job);
/// Bytes of CSV text per cell, an upper estimate.
std::size_t stick_map_bytes_per_cell(const MapJob& job);
/// The parameters of cell (ix, iy) of a stick-set map.
ParamsN stick_cell_params(const MapJob& job, int ix, int iy);
/// Throws NotSupportedError naming the cell where its set is not defined (mu_i <= 0,
/// K = C = 0, on a shaft an undamped critical speed): the check before any work.
void check_stick_cell_defined(const MapJob& job, int ix, int iy);
/// Computes the stick set of cell (ix, iy) (on a shaft, job.shaft: its equivalent rigid
/// balancer's, and the summary's shaft columns, model.md §18.17) and appends its rows (x, y: the axis values as
/// written); returns the number of components. Throws NumericalError naming the cell if a
/// figure is not finite, NotSupportedError naming it where the set is not defined (K = C = 0).
int write_stick_cell(const MapJob& job, int ix, int iy, std::string_view x, std::string_view y,
                     fmt::memory_buffer& rows, fmt::memory_buffer& summary);

}  // namespace abu
