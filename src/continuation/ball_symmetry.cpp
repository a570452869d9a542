#include "ball_symmetry.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "abu/equilibria/equilibria.hpp"  // wrap_angle

namespace abu::n_balls {

using ld = long double;

// Balls with bit-identical parameters are interchangeable: the equations of model.md §3
// are invariant under permuting them, so a permuted equilibrium is an equilibrium with
// the same spectrum along the same parameter values (§13.7). class_of[i]: the first ball
// equal to ball i.
std::vector<int> ball_classes(const ParamsN& p) {
  const auto same = [](const BallT<double>& a, const BallT<double>& b) {
    return a.mass == b.mass && a.race_radius == b.race_radius && a.radius == b.radius &&
           a.inertia_factor == b.inertia_factor && a.mu == b.mu && a.d == b.d && a.mu_c == b.mu_c &&
           a.mu_s == b.mu_s && a.v_s == b.v_s && a.sigma0 == b.sigma0 && a.sigma1 == b.sigma1 &&
           a.sigma2 == b.sigma2;
  };
  std::vector<int> class_of(std::size_t(p.n_balls()));
  for (int i = 0; i < p.n_balls(); ++i) {
    class_of[std::size_t(i)] = i;
    for (int j = 0; j < i; ++j)
      if (same(p.balls[std::size_t(j)], p.balls[std::size_t(i)])) {
        class_of[std::size_t(i)] = j;
        break;
      }
  }
  return class_of;
}

// The canonical image of s: among balls first_ball.., the angles of each class of
// interchangeable balls sorted by wrapped value (ascending), the rest unchanged.
Coordinates<ld, any_balls> canonical(const Coordinates<ld, any_balls>& s, const std::vector<int>& class_of,
                                     int first_ball) {
  Coordinates<ld, any_balls> out = s;
  const int n = int(class_of.size());
  for (int c = 0; c < n; ++c) {
    std::array<int, max_balls> members{};
    std::array<ld, max_balls> angles{};
    int k = 0;
    for (int i = first_ball; i < n; ++i)
      if (class_of[std::size_t(i)] == c) members[std::size_t(k)] = i, angles[std::size_t(k++)] = wrap_angle(s(2 + i));
    // Insertion sort (k <= 12; std::sort on a prefix of the array trips GCC 12's
    // -Warray-bounds with a false positive).
    for (int a = 1; a < k; ++a)
      for (int b = a; b > 0 && angles[std::size_t(b)] < angles[std::size_t(b - 1)]; --b)
        std::swap(angles[std::size_t(b)], angles[std::size_t(b - 1)]);
    for (int j = 0; j < k; ++j) out(2 + members[std::size_t(j)]) = angles[std::size_t(j)];
  }
  return out;
}

// The sign pattern of an aligned configuration, ball 1 taken '+' (equilibria.hpp).
unsigned pattern_of(const Coordinates<ld, any_balls>& s) {
  unsigned bits = 0;
  for (Eigen::Index i = 1; i + 2 < s.size(); ++i)
    if (std::abs(std::remainder(s(2 + i) - s(2), 2 * std::numbers::pi_v<ld>)) > std::numbers::pi_v<ld> / 2)
      bits |= 1u << unsigned(i);
  return bits;
}

}  // namespace abu::n_balls
