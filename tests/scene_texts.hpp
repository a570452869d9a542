// Texts and helpers of the scene tests (test_scene.cpp, test_scene_ring.cpp, test_outcomes.cpp, test_chart_labels.cpp,
// test_design_study.cpp): the source tree
// (ABU_SOURCE_DIR, which tests/CMakeLists.txt sets for these files), the default scene's text
// with one line replaced, and the InputError a call throws.
#pragma once

#include <functional>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "abu/core/errors.hpp"

namespace abu::testing {

inline const std::string kSourceDir = ABU_SOURCE_DIR;
inline const std::string kDefaultScene = kSourceDir + "/data/scenes/default.toml";

// The scene text of the default file with one line replaced (1-based), for small variants.
inline const char* const kBase = R"(rolling = true
[rotor]
mass = 0.12
stiffness = 7500.0
damping = 2.0
unbalance = 6.0e-7
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[friction]
law = "coulomb"
mu = 0.002
kappa = 1.0e3
[speed]
omega = 900.0
)";

// `text` with line n (1-based) replaced (possibly by several lines).
inline std::string line_replaced(const char* text, int n, const std::string& replacement) {
  std::string out, line;
  std::istringstream in(text);
  for (int i = 1; std::getline(in, line); ++i) out += (i == n ? replacement : line) + "\n";
  return out;
}

// Lines [first, last] (1-based) of `text`.
inline std::string lines_of(const char* text, int first, int last) {
  std::string out, line;
  std::istringstream in(text);
  for (int i = 1; std::getline(in, line); ++i)
    if (i >= first && i <= last) out += line + "\n";
  return out;
}

// A three-ball ring of the default balls: kBase with its two [[ball]] tables (lines 7-14) as one
// [balls] table; its line numbers (17 lines) are what the ring tests cite.
inline const std::string kRing = lines_of(kBase, 1, 6) +
                                 "[balls]\ncount = 3\nmass = 3.3e-5\nrace_radius = 0.018\nradius = 1.0e-3\n" +
                                 lines_of(kBase, 15, 20);

inline std::string with_line(int n, const std::string& replacement) { return line_replaced(kBase, n, replacement); }

inline abu::InputError capture(const std::function<void()>& f) {
  try {
    f();
  } catch (const abu::InputError& e) {
    return e;
  }
  FAIL("no InputError thrown");
  return abu::InputError("", -1, "", "");
}

}  // namespace abu::testing
