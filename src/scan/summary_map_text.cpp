// The text of summary maps (summary_map_text.hpp).
#include "abu/scan/summary_map_text.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abu/core/errors.hpp"

namespace abu {

std::string cell_label(const MapCellPlace& cell) {
  return fmt::format("{} cell ({}={}, {}={})", cell.map, cell.x_name, cell.x, cell.y_name, cell.y);
}

std::string cell_number(double v, const MapCellPlace& cell, std::string_view what) {
  if (!std::isfinite(v))
    throw NumericalError(fmt::format("{}: {} is not finite", cell_label(cell), what));
  return fmt::format("{}", v);
}

std::string summary_map_manifest(std::string header, const std::vector<double>& xs, const std::vector<double>& ys) {
  for (double x : xs) header += fmt::format("x {}\n", x);
  for (double y : ys) header += fmt::format("y {}\n", y);
  return header;
}

}  // namespace abu
