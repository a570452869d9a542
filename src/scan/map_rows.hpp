// Internal to the scan module: the rows of a two-ball or n-ball map's tile (the long CSV's
// rows, the summary's rows, the grid block), written by map_rows.cpp for map_driver.cpp.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "abu/scan/map_driver.hpp"

namespace abu::map_rows {

/// The text of one tile: the long rows (job.long_rows), the summary rows and the grid block.
struct TileBuffers {
  fmt::memory_buffer rows, summary, grid;
  std::size_t largest() const { return std::max({rows.size(), summary.size(), grid.size()}); }
};

/// The axis values as the CSVs write them, formatted once per tile (not per cell: the
/// shortest round-trip form is most of a summary row's cost), values first .. last - 1.
class AxisText {
 public:
  explicit AxisText(const Axis& a, int first = 0, int last = -1);
  std::string_view operator[](int i) const {
    const std::size_t k = std::size_t(i - first_);
    const std::size_t from = k == 0 ? 0 : end_[k - 1];
    return std::string_view(text_).substr(from, end_[k] - from);
  }

 private:
  std::string text_;
  std::vector<std::size_t> end_;  // value first + k is text_[end_[k - 1] .. end_[k])
  int first_ = 0;
};

/// The two-ball rows of one cell (the columns of map_csv_header / summary_csv_header) and its
/// grid record: the long rows only with job.long_rows (their values are checked either way).
/// Throws NumericalError naming the cell if a value is not finite.
void write_cell(const MapJob& job, int ix, int iy, std::string_view x, std::string_view y, const MapCell& cell,
                TileBuffers& out);
/// The same for an n-ball cell (map_csv_header_n / summary_csv_header_n).
void write_cell_n(const MapJob& job, int ix, int iy, std::string_view x, std::string_view y, const MapCellN& cell,
                  TileBuffers& out);

}  // namespace abu::map_rows
