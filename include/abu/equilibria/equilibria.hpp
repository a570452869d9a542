// All real equilibria of the two-ball balancer (model.md §5), from closed forms, each
// polished by Newton on the full static equations b(s, 0) = 0 in extended precision.
// (Any number of balls: equilibria_n.hpp, the same types with N = any_balls.)
//
//   balanced  q = 0, m1 l1 e^{i b1} + m2 l2 e^{i b2} = -U        (2 mirror points)
//   together  b1 = b2 = b, K U sin b + C U cos b + C (m1 l1 + m2 l2) = 0   (<= 2)
//   opposite  b2 = b1 + pi, K U sin b1 + C U cos b1 + C (m1 l1 - m2 l2) = 0 (<= 2)
//
// with K = k - omega^2 M, C = c omega and q from (K + iC) q = omega^2 (U + sum m l e^{ib}).
// The inputs are taken as the exact values of their doubles; the closed forms are
// evaluated in long double with the cancellation-free triangle formula for the
// balanced angles, so that equilibria 1e-9 from merging keep their small angles.
//
// Degenerate cases are reported as flags, never hidden:
//   U = 0                 the equilibria come in circles (rotational symmetry): one
//                         representative per circle is listed, `is_set` marks it;
//   U = m1 l1 + m2 l2     the two balanced points merge with a together point;
//   U = |m1 l1 - m2 l2|   the two balanced points merge with an opposite point;
//   K = C = 0             (c = 0 at omega = omega_n) no rotor equilibrium but the balanced;
//   a double root         the two together (or opposite) points coincide (a fold).
// "Equal" means equal within the rounding of the inputs (a few units of 2^-53).
//
//   auto set = abu::find_equilibria(p);
//   for (const auto& e : set.points()) fmt::print("{} {}\n", to_string(e.family), e.residual);
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "abu/core/status.hpp"
#include "abu/model/model.hpp"

namespace abu {

/// balanced: q = 0; the others have every ball on the line of q (model.md §13.2), named
/// together / opposite for two balls (patterns ++ and +-) and aligned for n >= 3.
enum class Family { balanced, together, opposite, aligned };
std::string_view to_string(Family family);

/// Degeneracies of an equilibrium set, as bit flags.
enum Degeneracy : unsigned {
  degeneracy_none = 0,
  unbalance_zero = 1u << 0,          ///< U = 0: circles of equilibria
  balanced_merges_together = 1u << 1,  ///< U = m1 l1 + m2 l2
  balanced_merges_opposite = 1u << 2,  ///< U = |m1 l1 - m2 l2| (unequal balls)
  no_rotor_equilibrium = 1u << 3,    ///< K = C = 0
  together_double_root = 1u << 4,    ///< fold of the together family
  opposite_double_root = 1u << 5,    ///< fold of the opposite family
  // n >= 3 balls (equilibria_n.hpp):
  aligned_double_root = 1u << 6,      ///< C^2 S^2 = U^2 (K^2 + C^2) for a pattern: a fold
  aligned_zero_resultant = 1u << 7,   ///< S = 0 for a pattern: the bare rotor's response
  balanced_collinear = 1u << 8,       ///< U = |S| for a pattern: the balanced set is singular there
  balanced_absent = 1u << 9,          ///< the polygon inequality fails: no balanced state
};

/// One equilibrium: s = (q1, q2, beta_1..beta_n) with beta in [0, 2 pi), ball speeds 0.
template <int N>
struct EquilibriumT {
  Family family = Family::balanced;
  /// Aligned families: bit i set when ball i + 1 lies opposite the line direction
  /// phi (sigma_{i+1} = -1); ball 1 is always + (model.md §13.2). 0 for balanced.
  unsigned pattern = 0;
  /// Which root of the family's closed form (1 or 2), stable in parameters; for a
  /// sample of the balanced set of n >= 3 balls, the sample's index (1-based).
  int member = 1;
  Coordinates<long double, N> position = Coordinates<long double, N>::Zero(N == any_balls ? 0 : N + 2);
  double residual = 0.0;  ///< max_i |b_i| / static_force_scale_i at the reported double state
  int newton_iterations = 0;
  bool converged = false;  ///< Newton reached the rounding level of long double
  /// The polish's outcome, with the reason if not converged (`converged` is status.ok()).
  Status status{Outcome::not_converged, "not polished"};
  bool is_set = false;     ///< representative of a circle of equilibria (U = 0)
  /// A point of the balanced set of n >= 3 balls (model.md §13.4): its tangent
  /// directions are structural zero eigenvalues, its stability the normal stability.
  bool on_balanced_set = false;
  /// Eigenvalues zero by construction: at an isolated but singular equilibrium (a circle
  /// representative, a merging point, a double root), whatever rounding makes of them;
  /// on the balanced set, the tangent directions (n - 2, twice that without friction).
  int structural_zeros = 0;

  bool singular() const { return structural_zeros > 0; }
  int n_balls() const { return int(position.size()) - 2; }
  Coordinates<double, N> position_si() const { return position.template cast<double>(); }
  State<long double, N> state() const { return at_rest<long double, N>(position); }
};
using Equilibrium = EquilibriumT<2>;
using EquilibriumN = EquilibriumT<any_balls>;

/// The equilibria of one parameter set, in the order balanced, together, opposite.
class EquilibriumSet {
 public:
  void add(const Equilibrium& e);
  std::span<const Equilibrium> points() const& { return {points_.data(), count_}; }
  std::span<Equilibrium> points() & { return {points_.data(), count_}; }
  // The span views storage inside the set: on a temporary it would dangle (a range-for over
  // find_equilibria(p).points() did, caught by ASan), so that use does not compile.
  std::span<const Equilibrium> points() const&& = delete;
  unsigned degeneracy = degeneracy_none;

 private:
  std::array<Equilibrium, 6> points_{};  // at most six on the torus (model.md §5)
  std::size_t count_ = 0;
};

/// The closed forms alone (model.md §5), in long double, not yet polished.
EquilibriumSet closed_form_equilibria(const Params& p);

/// Every real equilibrium of the two-ball model: closed forms polished by Newton. Never throws on degenerate physics;
/// an equilibrium whose polish does not converge is kept with converged = false.
EquilibriumSet find_equilibria(const Params& p);

/// Newton polish of a configuration on b(s, 0) = 0 in long double, q measured in the
/// displacement scale. Returns the polished equilibrium fields (residual, iterations,
/// converged); family/member are copied from `guess`. N = 2 and any_balls.
template <int N>
EquilibriumT<N> polish_equilibrium(const ParamsT<double, N>& p, const EquilibriumT<N>& guess);

/// Dimensionless static residual max_i |b_i(s, 0)| / scale_i (model.hpp).
template <int N>
double static_residual(const ParamsT<double, N>& p, const Coordinates<long double, N>& s);

/// One sentence per flag set in `degeneracy`, for CSV comments and the table.
std::vector<std::string> describe_degeneracy(unsigned degeneracy);

/// Wraps an angle to [0, 2 pi) such that its double rounding is also < 2 pi.
long double wrap_angle(long double beta);

}  // namespace abu
