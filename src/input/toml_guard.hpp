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

/// The dotted key a syntax error on `line` (1-based) belongs to, read from the text: the last
/// table header above it ("rotor", "ball" for [[ball]]) and the line's key (before '=', or
/// its first word when '=' is missing), e.g. "rotor.mass"; "" on a header or an empty line.
std::string key_at_line(std::string_view text, int line);

}  // namespace abu::detail
