#include "toml_guard.hpp"

#include <fmt/format.h>

#include "abu/core/errors.hpp"

namespace abu::detail {

// A small scanner over TOML's lexical states: comments, the four kinds of strings, table
// headers. Outside strings and comments a scene is ASCII (keys, numbers, booleans); inside
// a header's brackets a '#' is never valid TOML.
void prevalidate_toml(std::string_view text, const std::string& file) {
  enum class State { code, comment, basic, literal, multi_basic, multi_literal };
  State state = State::code;
  int line = 1;
  bool line_start = true;  // only blanks so far on this line
  int header_depth = 0;    // inside [ ] / [[ ]] of a table header
  int array_depth = 0;     // inside a value's array (its lines may start with '[')
  const auto fail = [&](const std::string& rule) { throw InputError(file, line, "", rule); };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const auto u = static_cast<unsigned char>(c);
    const auto next = [&](std::string_view s) { return text.substr(i, s.size()) == s; };
    if (c == '\n') {
      ++line;
      if (state == State::comment) state = State::code;
      if (state == State::code) {
        if (header_depth > 0) fail("a table header must close on its line");
        line_start = true;
      }
      continue;
    }
    switch (state) {
      case State::comment: break;
      case State::basic:
        if (c == '\\') ++i;
        else if (c == '"') state = State::code;
        break;
      case State::literal:
        if (c == '\'') state = State::code;
        break;
      case State::multi_basic:
        if (c == '\\') {
          if (i + 1 < text.size() && text[i + 1] == '\n') break;  // line-ending backslash
          ++i;
        } else if (next("\"\"\"")) {
          state = State::code;
          i += 2;
        }
        break;
      case State::multi_literal:
        if (next("'''")) {
          state = State::code;
          i += 2;
        }
        break;
      case State::code:
        if (u >= 0x80)
          fail(fmt::format("non-ASCII byte 0x{:02x} outside a string or comment (keys and values are ASCII)", u));
        if (c == '#') {
          if (header_depth > 0) fail("'#' inside a table header");
          state = State::comment;
        } else if (next("\"\"\"")) {
          state = State::multi_basic;
          i += 2;
        } else if (next("'''")) {
          state = State::multi_literal;
          i += 2;
        } else if (c == '"') {
          state = State::basic;
        } else if (c == '\'') {
          state = State::literal;
        } else if (c == '[' && array_depth == 0 && (line_start || header_depth > 0)) {
          ++header_depth;
        } else if (c == ']' && header_depth > 0) {
          --header_depth;
        } else if (c == '[') {
          ++array_depth;
        } else if (c == ']' && array_depth > 0) {
          --array_depth;
        }
        if (c != ' ' && c != '\t' && c != '\r' && c != '[') line_start = false;
        break;
    }
  }
}

namespace {

std::string_view trimmed(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// The key of a header line "[rotor]" / "[[ball]]" (comments aside), or "" if not a header.
std::string_view header_of(std::string_view line) {
  line = trimmed(line.substr(0, line.find('#')));
  if (line.size() < 2 || line.front() != '[' || line.back() != ']') return {};
  while (!line.empty() && line.front() == '[') line.remove_prefix(1);
  while (!line.empty() && line.back() == ']') line.remove_suffix(1);
  return trimmed(line);
}

}  // namespace

std::string key_at_line(std::string_view text, int line) {
  std::string_view table, here;
  int at = 1;
  for (std::size_t begin = 0; begin <= text.size() && at <= line; ++at) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view row = text.substr(begin, end - begin);
    if (at == line) here = row;
    else if (const auto h = header_of(row); !h.empty()) table = h;
    begin = end + 1;
  }
  if (!header_of(here).empty()) return {};
  here = trimmed(here.substr(0, here.find('#')));
  const auto eq = here.find('=');
  std::string_view key = trimmed(eq == std::string_view::npos ? here.substr(0, here.find_first_of(" \t")) : here.substr(0, eq));
  if (key.empty()) return {};
  return table.empty() ? std::string(key) : fmt::format("{}.{}", table, key);
}

}  // namespace abu::detail
