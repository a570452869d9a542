// A number with its unit as a JSON object, {"value": v, "unit": "u"} (format_number's text for v),
// as the views' JSON files write them (report_views.cpp, report_ranges.cpp). Internal to
// src/output.
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>

#include "abu/output/format.hpp"

namespace abu::detail {

inline std::string json_quantity(double value, std::string_view unit, std::string_view what) {
  return fmt::format("{{\"value\": {}, \"unit\": {}}}", format_number(value, what), json_string(unit));
}

}  // namespace abu::detail
