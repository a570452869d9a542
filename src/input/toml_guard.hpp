// Checks a scene's text before toml++ parses it, for inputs that toml++ 3.3 does not
// refuse cleanly: a non-ASCII byte right after a number reaches __builtin_unreachable,
// and a comment inside a table header (`[# speed]`) fails an assertion. Private to io.
#pragma once

#include <string>
#include <string_view>

namespace abu::detail {

/// Throws InputError (file, line, rule) for a non-ASCII byte outside strings and comments,
/// or a '#' inside a table header's brackets.
void prevalidate_toml(std::string_view text, const std::string& file);

}  // namespace abu::detail
