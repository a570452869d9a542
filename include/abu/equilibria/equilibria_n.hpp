// All real equilibria of the balancer with any number of balls, 2 <= n <= max_balls
// (model.md §13), each polished by Newton in extended precision.
//
//  aligned   q != 0, every ball on the line of q: e^{i beta_i} = sigma_i e^{i phi}. For
//            each sign pattern sigma (sigma_1 = +1, 2^(n-1) patterns), S = sum sigma_i m_i l_i
//            and K U sin phi + C U cos phi + C S = 0 (up to two roots), then
//            q = omega^2 (U + S e^{i phi}) / (K + iC): at most 2^n isolated equilibria
//            (§13.2). For two balls the patterns ++ and +- are the together and opposite
//            families of equilibria.hpp, and keep those names.
//  balanced  q = 0, sum m_i l_i e^{i beta_i} = -U: for n >= 3 a manifold of dimension n - 2
//            (§13.4), nonempty iff max(U, m_i l_i) <= (U + sum m_j l_j) / 2 (the lengths
//            close a polygon). It is reported by deterministic samples: the free angles
//            beta_3..beta_n on a grid of G values each, 2 pi k / G (k = 0..G-1), closed by
//            balls 1 and 2 (the triangle with sides m1 l1, m2 l2, |R|,
//            R = U + sum_{j>=3} m_j l_j e^{i beta_j}), on both sheets (ball 1 on either
//            side of -R); grid points where balls 1 and 2 cannot close the polygon are
//            skipped. Each sample is polished onto the set by Newton on W = 0 in
//            (beta_1, beta_2). Its spectrum has n - 2 structural zeros along the set
//            (2 (n - 2) without friction); its stability is the normal stability
//            (spectrum.hpp, compute_normal_spectrum).
//
// Degenerate cases are flags (equilibria.hpp, Degeneracy), never hidden: S = 0 patterns,
// double roots (U^2 (K^2 + C^2) = C^2 S^2), collinear points of the set (U = |S|),
// K = C = 0, U = 0.
//
//   abu::EquilibriumSetN set = abu::find_equilibria(p);          // p: abu::ParamsN
//   for (const auto& e : set.points()) ... abu::pattern_string(e.pattern, p.n_balls()) ...
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "abu/equilibria/equilibria.hpp"

namespace abu {

/// How the balanced set is sampled. G = max(2, round(samples_per_sheet^(1/(n-2))))
/// values per free angle, so a sheet has G^(n-2) grid points: for the default 64, G = 64
/// (n = 3), 8 (4), 4 (5), 3 (6), and 2 from n = 7 on (2^(n-2) points, 1024 at n = 12).
/// Default 64 per sheet (the CLI's --set-samples): enough to see stability vary along
/// the set at n = 3 (64 angles 0.1 rad apart) while n = 12 stays at the floor G = 2,
/// 1024 grid points per sheet; options_violation() gives the range.
struct BalancedSampling {
  int samples_per_sheet = 64;  ///< S, default 64; 1 .. 100000
};
/// The rule broken by the options, if any.
std::optional<std::string> options_violation(const BalancedSampling& s);

/// What the samples say about the balanced set as a whole.
struct BalancedSetSummary {
  bool exists = false;   ///< the polygon inequality holds
  int dimension = 0;     ///< n - 2
  int grid = 0;          ///< G, values per free angle
  int grid_points = 0;   ///< 2 G^(n-2): both sheets
  int samples = 0;       ///< grid points where balls 1 and 2 close the polygon
};

/// The equilibria of one parameter set: balanced samples (by index), then the aligned
/// ones by pattern and member.
struct EquilibriumSetN {
  std::vector<EquilibriumN> list;
  unsigned degeneracy = degeneracy_none;
  BalancedSetSummary balanced_set;

  std::span<const EquilibriumN> points() const& { return list; }
  std::span<EquilibriumN> points() & { return list; }
  std::span<const EquilibriumN> points() const&& = delete;  // would dangle (see EquilibriumSet)
};

/// Every real equilibrium: the aligned ones complete, the balanced set sampled. Never
/// throws on degenerate physics; an equilibrium whose polish does not converge is kept
/// with converged = false.
EquilibriumSetN find_equilibria(const ParamsN& p, const BalancedSampling& sampling = {});
/// The same into `set`, reusing its storage (a map cell per call: no allocation once
/// the list has grown to the largest count, model.md §13.3).
void find_equilibria(const ParamsN& p, const BalancedSampling& sampling, EquilibriumSetN& set);

/// The balanced set exists (the polygon inequality, within input rounding).
bool balanced_set_exists(const ParamsN& p);

/// G, the values per free angle of the balanced set's grid for n balls: max(2, round(S^(1/(n-2))))
/// (1 for two balls, whose set is two points).
int balanced_grid_size(int n, const BalancedSampling& sampling);
/// 2 G^(n-2), the grid points of both sheets: an upper bound on the balanced samples listed.
double balanced_grid_points(int n, const BalancedSampling& sampling);

/// An orthonormal basis of the balanced set's tangent space at s (q = 0), in
/// configuration space: the null space of the 2 x n matrix [m_j l_j cos beta_j;
/// m_j l_j sin beta_j] (model.md §13.4), embedded with zero rotor rows. n - 2 columns
/// (n - 1 at a collinear point).
TangentBasis balanced_tangent_basis(const ParamsN& p, const Coordinates<long double, any_balls>& s);

/// "+-+" for a pattern of n balls.
std::string pattern_string(unsigned pattern, int n_balls);

}  // namespace abu
