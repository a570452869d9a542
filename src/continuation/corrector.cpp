#include "abu/continuation/corrector.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace abu {

namespace {
using ld = long double;
constexpr ld kTwoPi = 2 * std::numbers::pi_v<ld>;
ld wrapped_difference(ld a, ld b) { return std::abs(std::remainder(a - b, kTwoPi)); }
}  // namespace

// Angles are followed continuously along a branch (no jump at 2 pi): two points are the
// same configuration if their angles differ by a multiple of 2 pi.
ld distance(const StaticEquations::Vec5& a, const StaticEquations::Vec5& b) {
  return std::max({std::abs(a(0) - b(0)), std::abs(a(1) - b(1)), wrapped_difference(a(2), b(2)),
                   wrapped_difference(a(3), b(3)), std::abs(a(4) - b(4))});
}

}  // namespace abu
