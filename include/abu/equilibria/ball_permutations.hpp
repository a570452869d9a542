// Equal balls make equilibria permutation images of each other (model.md §13.9): if balls
// i and j are equal in every parameter of the model, exchanging them maps an equilibrium
// to an equilibrium, and its linearization to P (lambda^2 A + lambda C + K) P^T with P the
// permutation matrix, so the two have one spectrum (eigenvectors permuted alike). An
// 11-ball ring has 2468 equilibria in 14 such classes: one representative per class is
// analysed, the others copy its spectrum.
//
// Matching is numerical, on the positions that find_equilibria computed for each
// equilibrium (every one keeps its own angles): q equal and, kind by kind, the balls'
// angles equal as multisets, both to 1e-13 (the polish reaches ~1e-18; two distinct
// equilibria that close would be a fold within 1e-26 of its parameter). A pair that the
// test misses is merely analysed twice.
//
//   abu::PermutationClasses classes;
//   abu::find_permutation_classes(abu::ball_kinds(p), set.points(), classes);
//   if (classes.images[k].representative != int(k)) ... copy, permuted by ball_of ...
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "abu/equilibria/equilibria.hpp"

namespace abu {

/// The balls grouped by equality: kind[i] is the smallest index j whose ball equals ball i
/// in every parameter the model uses (mass, race radius, radius, inertia factor and every
/// friction coefficient).
struct BallKinds {
  int n = 0;
  std::array<std::int8_t, max_balls> kind{};
  bool any_equal = false;  ///< some two balls are of one kind
  bool all_equal = false;  ///< every ball is of one kind
};
BallKinds ball_kinds(const ParamsN& p);

/// Equilibrium k of a list as the image of its class's representative: ball i of k sits
/// where ball ball_of[i] of the representative sits.
struct PermutationImage {
  int representative = 0;  ///< index in the list; k itself for a representative
  std::array<std::int8_t, max_balls> ball_of{};
};

/// The classes of a list of equilibria. The storage is kept from call to call (a map
/// cell per call allocates nothing once it has grown to the largest list).
struct PermutationClasses {
  std::vector<PermutationImage> images;  ///< one per equilibrium, in list order
  int representatives = 0;               ///< how many classes
  std::vector<int> scratch;              ///< the representatives' indices (internal)
};

/// `image` (of some representative) as the image of another member `member` of the same
/// class, whose index is `member_index`: ball i of the image sits where ball ball_of[i] of
/// that member sits.
PermutationImage relative_to(const PermutationImage& image, const PermutationImage& member, int member_index,
                             int n_balls);

/// Fills `out` for `points`: each equilibrium's representative is the first in list order
/// of which it is a permutation image (same family, both polished, the same structural
/// zeros). Without two equal balls every equilibrium is its own representative.
void find_permutation_classes(const BallKinds& kinds, std::span<const EquilibriumN> points,
                              PermutationClasses& out);

}  // namespace abu
