// Numbers and strings as the outputs write them (format.hpp).
#include "abu/output/format.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "abu/core/errors.hpp"

namespace abu {

std::string format_number(double value, std::string_view what) {
  if (!std::isfinite(value)) throw NumericalError(fmt::format("non-finite {} ({}) would be written", what, value));
  // +-DBL_MAX is the stand-in of a value that was not computed (an infinite inverse
  // eigenvalue), never a result.
  if (std::abs(value) == std::numeric_limits<double>::max())
    throw NumericalError(fmt::format("{} is the stand-in DBL_MAX (not computed) and would be written", what));
  return fmt::format("{}", value);
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += fmt::format("\\u{:04x}", int(c));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string json_number_or_null(const std::optional<double>& value, std::string_view what) {
  return value ? format_number(*value, what) : std::string("null");
}

}  // namespace abu
