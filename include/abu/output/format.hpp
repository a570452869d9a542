// Numbers and strings as every output writes them: numbers in shortest round-trip form (no NaN
// reaches a file), JSON string literals, escaped terminal text.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "abu/core/escaped.hpp"  // escaped(): terminal text

namespace abu {

/// Shortest decimal that reads back to the same double (fmt's "{}", locale-free).
/// Throws NumericalError naming `what` for a non-finite value: no NaN reaches a file.
std::string format_number(double value, std::string_view what = "value");
/// format_number of a value that may be absent: JSON `null` then.
std::string json_number_or_null(const std::optional<double>& value, std::string_view what = "value");

/// `s` as a JSON string literal: quotes, `"` and `\\` escaped, \n and \t, every other control
/// character as \u00XX, so that a scene path or command line with any byte is valid JSON.
std::string json_string(std::string_view s);


}  // namespace abu
