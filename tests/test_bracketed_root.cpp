// The one locator (core/bracketed_root.hpp): Brent's method on a bracket, its ends and its
// failures reported, not guessed.
#include <catch2/catch.hpp>

#include <cmath>
#include <optional>

#include "abu/core/bracketed_root.hpp"

using abu::BracketedRoot;
using abu::RootSearch;

namespace {
RootSearch relative(double width) {
  RootSearch s;
  s.relative_width = width;
  return s;
}
}  // namespace

TEST_CASE("bracketed_root finds the zero to the asked width", "[bracketed_root]") {
  // cos x = x: the Dottie number 0.739085133215160641655312087673873404..., known to many
  // digits independently of this code (the fixed point of cos). A bracket of 1e-15 relative
  // leaves the root within a few ulps of 0.74 (~1.1e-16 each).
  const auto f = [](double x) -> std::optional<double> { return std::cos(x) - x; };
  const BracketedRoot r = abu::bracketed_root(f, 0.0, 1.0, relative(1e-15));
  REQUIRE(r.converged());
  CHECK(std::abs(r.root - 0.7390851332151607) <= 4e-16);
  CHECK(r.lower <= r.root);
  CHECK(r.root <= r.upper);
  CHECK(r.upper - r.lower <= 1e-15 * r.lower + 1e-300);
  CHECK(r.iterations > 3);  // Brent needs several steps from [0, 1]
  CHECK(r.iterations < 60);
}

TEST_CASE("bracketed_root: an absolute width stops earlier", "[bracketed_root]") {
  const auto f = [](double x) -> std::optional<double> { return x * x * x - 2.0; };  // 2^(1/3)
  RootSearch s;
  s.absolute_width = 1e-6;
  const BracketedRoot r = abu::bracketed_root(f, 0.0, 2.0, s);
  REQUIRE(r.converged());
  CHECK(r.upper - r.lower < 1e-6);
  CHECK(std::abs(r.root - std::cbrt(2.0)) < 1e-6);  // inside the final bracket
}

TEST_CASE("bracketed_root reports what ended it", "[bracketed_root]") {
  SECTION("no sign change") {
    const auto f = [](double x) -> std::optional<double> { return 1.0 + x * x; };
    const BracketedRoot r = abu::bracketed_root(f, -1.0, 1.0, relative(1e-12));
    CHECK(r.end == BracketedRoot::End::no_sign_change);
    CHECK(r.iterations == 0);
  }
  SECTION("an evaluation that fails ends the search with the bracket before it") {
    int calls = 0;
    const auto f = [&](double x) -> std::optional<double> {
      if (++calls > 4) return std::nullopt;  // the ends and two iterations, then a failure
      return std::tanh(10.0 * (x - 0.3));     // curved: Brent needs more than two steps
    };
    const BracketedRoot r = abu::bracketed_root(f, 0.0, 1.0, relative(1e-15));
    CHECK(r.end == BracketedRoot::End::evaluation_failed);
    CHECK(r.iterations == 2);
    CHECK(r.lower <= 0.3);
    CHECK(0.3 <= r.upper);
  }
  SECTION("a failure at an end") {
    const auto f = [](double x) -> std::optional<double> {
      if (x == 1.0) return std::nullopt;
      return x - 0.5;
    };
    const BracketedRoot r = abu::bracketed_root(f, 0.0, 1.0, relative(1e-12));
    CHECK(r.end == BracketedRoot::End::evaluation_failed);
  }
  SECTION("too few iterations") {
    RootSearch s = relative(1e-15);
    s.max_iterations = 2;
    const auto f = [](double x) -> std::optional<double> { return std::exp(x) - 2.0; };
    const BracketedRoot r = abu::bracketed_root(f, 0.0, 1.0, s);
    CHECK(r.end == BracketedRoot::End::max_iterations);
    CHECK(r.iterations == 2);
    CHECK(r.lower <= std::log(2.0));
    CHECK(std::log(2.0) <= r.upper);
  }
  SECTION("the caller's stop rule") {
    RootSearch s = relative(1e-15);
    s.stop = [](double root, double previous, int iteration) {
      return iteration > 0 && std::abs(root - previous) <= 1e-3;
    };
    const auto f = [](double x) -> std::optional<double> { return std::atan(x - 0.2); };
    const BracketedRoot r = abu::bracketed_root(f, -1.0, 3.0, s);
    CHECK(r.converged());
    CHECK(std::abs(r.root - 0.2) < 1e-2);  // stopped early, yet near the root
    const BracketedRoot full = abu::bracketed_root(f, -1.0, 3.0, relative(1e-15));
    CHECK(full.iterations > r.iterations);
  }
}
