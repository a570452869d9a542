#include "abu/equilibria/ball_permutations.hpp"

#include <cmath>
#include <numbers>

namespace abu {

namespace {

using ld = long double;
constexpr ld kTwoPi = 2 * std::numbers::pi_v<ld>;
// Positions of images agree to the polish's ~1e-18; 1e-13 leaves room for a few roundings
// of the closed forms without letting two distinct equilibria meet (header).
constexpr ld kTolerance = 1e-13L;

bool same_ball(const BallT<double>& a, const BallT<double>& b) {
  return a.mass == b.mass && a.race_radius == b.race_radius && a.radius == b.radius &&
         a.inertia_factor == b.inertia_factor && a.mu == b.mu && a.d == b.d && a.mu_c == b.mu_c &&
         a.mu_s == b.mu_s && a.v_s == b.v_s && a.sigma0 == b.sigma0 && a.sigma1 == b.sigma1 &&
         a.sigma2 == b.sigma2;
}

ld circular_distance(ld a, ld b) {
  const ld d = std::abs(a - b);
  return std::min(d, std::abs(kTwoPi - d));
}

// Could the two be images at all (the attributes a permutation keeps)?
bool comparable(const EquilibriumN& a, const EquilibriumN& b) {
  return a.family == b.family && a.converged && b.converged && a.on_balanced_set == b.on_balanced_set &&
         a.is_set == b.is_set && a.structural_zeros == b.structural_zeros && a.position.size() == b.position.size();
}

// A permutation within kinds taking the representative's angles to the image's, if one
// exists within the tolerance (greedy: the angles of one kind closer than the tolerance
// are interchangeable for the spectrum anyway).
bool match(const BallKinds& kinds, const EquilibriumN& image, const EquilibriumN& rep, PermutationImage& out) {
  const ld q_scale = std::max(std::hypot(rep.position(0), rep.position(1)), ld(0));
  const ld q_tol = kTolerance * q_scale;
  if (std::abs(image.position(0) - rep.position(0)) > q_tol || std::abs(image.position(1) - rep.position(1)) > q_tol)
    return false;
  std::array<bool, max_balls> used{};
  for (int i = 0; i < kinds.n; ++i) {
    int found = -1;
    for (int j = 0; j < kinds.n && found < 0; ++j)
      if (!used[std::size_t(j)] && kinds.kind[std::size_t(j)] == kinds.kind[std::size_t(i)] &&
          circular_distance(image.position(2 + i), rep.position(2 + j)) <= kTolerance)
        found = j;
    if (found < 0) return false;
    used[std::size_t(found)] = true;
    out.ball_of[std::size_t(i)] = std::int8_t(found);
  }
  return true;
}

}  // namespace

BallKinds ball_kinds(const ParamsN& p) {
  BallKinds k;
  k.n = p.n_balls();
  k.all_equal = true;
  for (int i = 0; i < k.n; ++i) {
    k.kind[std::size_t(i)] = std::int8_t(i);
    for (int j = 0; j < i; ++j)
      if (same_ball(p.balls[std::size_t(j)], p.balls[std::size_t(i)])) {
        k.kind[std::size_t(i)] = std::int8_t(j);
        break;
      }
    k.any_equal = k.any_equal || k.kind[std::size_t(i)] != i;
    k.all_equal = k.all_equal && k.kind[std::size_t(i)] == 0;
  }
  return k;
}

PermutationImage relative_to(const PermutationImage& image, const PermutationImage& member, int member_index,
                             int n_balls) {
  // The representative's ball b sits where the member's ball `where[b]` does.
  std::array<std::int8_t, max_balls> where{};
  for (int i = 0; i < n_balls; ++i) where[std::size_t(member.ball_of[std::size_t(i)])] = std::int8_t(i);
  PermutationImage out;
  out.representative = member_index;
  for (int i = 0; i < n_balls; ++i) out.ball_of[std::size_t(i)] = where[std::size_t(image.ball_of[std::size_t(i)])];
  return out;
}

void find_permutation_classes(const BallKinds& kinds, std::span<const EquilibriumN> points, PermutationClasses& out) {
  out.images.resize(points.size());
  out.scratch.clear();
  PermutationImage identity;
  for (int i = 0; i < kinds.n; ++i) identity.ball_of[std::size_t(i)] = std::int8_t(i);
  for (std::size_t k = 0; k < points.size(); ++k) {
    PermutationImage& image = out.images[k];
    image = identity;
    image.representative = int(k);
    if (!kinds.any_equal) continue;  // (every one its own class)
    for (const int r : out.scratch) {
      PermutationImage candidate = identity;
      if (!comparable(points[k], points[std::size_t(r)]) ||
          !match(kinds, points[k], points[std::size_t(r)], candidate))
        continue;
      image = candidate;
      image.representative = r;
      break;
    }
    if (image.representative == int(k)) out.scratch.push_back(int(k));
  }
  out.representatives = kinds.any_equal ? int(out.scratch.size()) : int(points.size());
}

}  // namespace abu
