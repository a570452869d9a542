// Internal to the equilibria module: the roots of the one scalar equation every
// aligned family reduces to (model.md §5 for two balls, §13.2 for n),
//     K U sin phi + C U cos phi + C S = 0,  i.e.  U R sin(phi + delta) = -C S,
// with R = |K + iC| and delta = arg(K + iC); S is the resultant of the ball pattern.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace abu::equilibria_detail {

/// Two inputs are "equal" when they differ by less than a few roundings of a double:
/// the scene cannot tell them apart, so neither can we.
inline constexpr long double kInputRounding = 8 * (long double)std::numeric_limits<double>::epsilon();

/// Writes the roots in the order phi = r - delta, pi - r - delta (r = asin(-C S / (U R)))
/// and returns their number: 0, 1 (a double root, flagged), or 2. Needs U > 0.
inline int line_roots(long double K, long double C, long double U, long double S, std::array<long double, 2>& roots,
                      bool& double_root) {
  constexpr long double pi = std::numbers::pi_v<long double>;
  const long double R = std::hypot(K, C);
  const long double delta = std::atan2(C, K);
  const long double sine = -C * S / (U * R);
  const long double excess = std::abs(sine) - 1;
  double_root = std::abs(excess) <= kInputRounding;
  if (excess > kInputRounding) return 0;
  if (double_root) {
    roots[0] = std::copysign(pi / 2, sine) - delta;
    return 1;
  }
  const long double r = std::asin(sine);
  roots[0] = r - delta;
  roots[1] = pi - r - delta;
  return 2;
}

}  // namespace abu::equilibria_detail
