// Hostile scene text: the inputs toml++ 3.3 does not refuse cleanly are refused
// by the pre-check (src/input/toml_guard.cpp) with a line number, never reach the parser.
#include <catch2/catch.hpp>

#include <string>

#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"

namespace {
int refused_at(const std::string& text) {
  try {
    (void)abu::parse_scene(text, "hostile.toml");
  } catch (const abu::InputError& e) {
    return e.line();
  }
  return -1;
}
std::string refusal(const std::string& text) {
  try {
    (void)abu::parse_scene(text, "hostile.toml");
  } catch (const abu::InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("a non-ASCII byte right after a number is refused at its line", "[robustness]") {
  CHECK(refused_at("[rotor]\nmass = 1\xc3\xa9\n") == 2);
  CHECK(refused_at("[speed]\nomega = 250\xe2\x80\x8b\n") == 2);
}

TEST_CASE("a comment inside a table header is refused at its line", "[robustness]") {
  CHECK(refused_at("[# speed]\nomega = 1\n") == 1);
  CHECK(refused_at("[rotor]\nmass = 1\n[[ball # x]]\n") == 3);
}

TEST_CASE("non-ASCII text inside strings and comments is not refused by the pre-check", "[robustness]") {
  // The scene is still incomplete (refused for that), but not for the characters.
  const std::string why = refusal("# Ballausgleich f\xc3\xbcr den Rotor\n[friction]\nlaw = \"none\" # ohne Reibung \xc3\xa9\n");
  CHECK(why.find("non-ASCII") == std::string::npos);
  CHECK(why.find("table header") == std::string::npos);
}

TEST_CASE("nested arrays whose lines start with an opening bracket are not table headers", "[robustness]") {
  // Unknown key "x": refused by the scene rules, not by the pre-check.
  CHECK(refusal("x = [\n  [1, 2], # a comment\n  [3, 4],\n]\n").find("table header") == std::string::npos);
}
