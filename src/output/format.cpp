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

std::string escaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\r') out += "\\r";
    else if (c < 0x20 || c == 0x7f) out += fmt::format("\\x{:02x}", c);
    else out += ch;
  }
  return out;
}

}  // namespace abu
