// Every equilibrium of the balancer on an unround race (model.md §11.4): for n = 2 or 3 balls
// all of them; for n >= 4 those a multistart Newton finds (not proven complete, and said so:
// model.md §11.11). Their spectra (§11.5) and stability are the linear layer's
// (linear/unround_spectrum.hpp: find_unround_equilibria).
//
// With s' = 0 the rotor equation gives q(beta) = omega^2 (U + sum m_i p_i(beta_i)) / (K + iC)
// and the ball conditions become n equations on the torus T^n,
//
//     g_i(beta) = Re( conj(p_i'(beta_i)) (q(beta) + p_i(beta_i)) ) / l_i^2 = 0.   (§11.4)
//
// Search (why it misses nothing, model.md §11.4): the torus is cut into boxes; a box is
// dropped only if some |g_i| at its centre exceeds a rigorous Lipschitz bound of g_i
// over the box (built from the harmonics' amplitudes and orders), so no zero is in a
// dropped box. The boxes that remain are halved down to a leaf width, and Newton (long
// double) starts at every leaf's centre (every zero lies within h sqrt(n) of one); a
// leaf whose Newton fails is counted as unresolved and reported. The zeros found are checked
// against Poincare-Hopf: their indices sign det(dg/dbeta) sum to chi(T^n) = 0.
//
//   abu::UnroundRoots r = abu::find_unround_roots(p, race);
//   for (const auto& e : r.list) ... e.amplitude ... e.index ...
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "abu/model/unround_race.hpp"

namespace abu {

/// The search's resolution. Defaults: 8 (k_max + 1) boxes per angle to start, leaves of
/// width 2 pi / 512 (n = 2) or 2 pi / 128 (n = 3), at most 4e6 leaf Newton starts.
struct UnroundSearch {
  int start_boxes = 0;             ///< per angle; 0: 8 (k_max + 1)
  int leaf_boxes = 0;              ///< per angle at the finest level; 0: 512 (n = 2), 128 (n = 3)
  long long max_leaves = 4000000;  ///< beyond this the search stops and says so
  /// n >= 4: quasi-random Newton starts (Halton) besides the round race's equilibria.
  int multistart = 4096;
};

/// An equilibrium of the race: a zero of the reduced ball conditions g(beta) = 0 (§11.4).
struct UnroundRoot {
  Coordinates<long double, any_balls> position;  ///< (q1, q2, beta_1..beta_n), beta in [0, 2 pi)
  double residual = 0;                    ///< max |b_i(s, 0)| / its natural size (§11.4)
  bool converged = false;
  int index = 0;        ///< sign det(dg/dbeta): +1 / -1, 0 if singular to rounding
  double amplitude = 0; ///< |q| [m], the residual whirl radius (fixed frame)
};

struct UnroundSearchReport {
  long long boxes_tested = 0;   ///< boxes whose exclusion test ran
  long long leaves = 0;         ///< boxes not excluded at the finest level (Newton starts)
  long long unresolved = 0;     ///< leaves whose Newton failed
  int index_sum = 0;            ///< sum of indices; 0 when the list is complete (Poincare-Hopf)
  bool budget_exhausted = false;
};

struct UnroundRoots {
  std::vector<UnroundRoot> list;  ///< sorted by |q|, then by beta
  UnroundSearchReport search;
  std::string doubt;  ///< empty when the search is complete, else what makes the list doubtful
};

using UnroundAngles = Eigen::Matrix<long double, Eigen::Dynamic, 1, 0, max_balls, 1>;
using UnroundAngleMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic, 0, max_balls, max_balls>;

/// The reduced ball conditions of §11.4 at angles beta: q(beta) (rotating frame [m]),
/// g(beta) (g_i scaled by 1/l_i^2) and dg/dbeta (whose determinant's sign is the index).
struct UnroundReduced {
  std::complex<long double> q;
  UnroundAngles g;
  UnroundAngleMatrix dg;
};
UnroundReduced unround_reduced(const LongParamsN& p, const RaceShape& race, const UnroundAngles& beta);

/// The equilibrium at angles beta that solve g = 0: position, |q|, index and residual of the
/// full static equations (§11.3). Shared by the search and, with its spectrum
/// (unround_spectrum.hpp), the continuation in the unroundness (§11.10).
UnroundRoot unround_root_at(const LongParamsN& p, const RaceShape& race, const UnroundAngles& beta);

/// The reduced residual g(beta) of §11.4 and q(beta). Exposed for tests.
Coordinates<long double, any_balls> unround_rotor_and_residual(const LongParamsN& p, const RaceShape& race,
                                                               const Eigen::Matrix<long double, Eigen::Dynamic, 1, 0, max_balls, 1>& beta,
                                                               Eigen::Matrix<long double, Eigen::Dynamic, 1, 0, max_balls, 1>& g);

/// Every equilibrium of an unround race (n = 2, 3: the complete box search). For n >= 4 the
/// equilibria Newton finds from the round race's equilibria and `search.multistart`
/// quasi-random starts, with `doubt` saying the list is not proven complete (§11.11).
/// Throws NumericalError for K = C = 0 (no q(beta)).
UnroundRoots find_unround_roots(const ParamsN& p, const RaceShape& race, const UnroundSearch& search = {});

}  // namespace abu
