// Equilibrium branches of the unround race in its unroundness (model.md §11.10), traced
// by the project's one pseudo-arclength engine (arclength.hpp).
//
// The parameter is the factor e that multiplies every amplitude of the scene's race
// (scaled_race: e = 1 is the scene, e = 0 the round race). The branch is the zero set of
// the reduced ball conditions g(beta; e) = 0 of §11.4 in the n + 1 unknowns (beta, e / e_max);
// q follows from beta (§11.4). Along it: the index sign det(dg/dbeta), whose change is a
// fold (LP) in e or a branch point (BP), and the spectrum of §11.5, whose abscissa's sign
// change is a change of stability (at a fold, or a Hopf point HB when a complex pair crosses). Both are located
// by bisection on the secant between two branch points, each trial point corrected onto
// the branch.
//
// Starts: for n = 2 every equilibrium of the round race (e = 0, the complete search of
// §11.4 with zero amplitudes: the round model's aligned and balanced states), and every
// equilibrium of the complete search at the scene's race (e = 1, if inside) and at the end
// e_max that lies on no branch traced already (a pair born at a fold inside the interval
// is found this way from the end). Missed: an isola, a closed branch that lives only
// strictly between these starts. For n = 3 the round race's balanced states form a circle
// (degenerate at e = 0), so there are no starts at e = 0; the branches end on e = 0 at the
// isolated points of the circle that survive.
//
//   abu::UnroundBranches b = abu::continue_unround(p, race, 2.0);   // e in [0, 2]
//   for (const auto& br : b.branches) for (const auto& pt : br.points) ... pt.factor ...
#pragma once

#include <string>
#include <vector>

#include "abu/continuation/arclength.hpp"
#include "abu/linear/unround_spectrum.hpp"

namespace abu {

struct UnroundBranchPoint {
  double factor = 0;          ///< e: every race amplitude times e
  UnroundEquilibrium state;   ///< position, |q| [m], index, spectrum [1/s] (rotating frame)
};

/// A located special point: det dg/dbeta = 0 where the branch turns back in e (LP, a fold)
/// or goes on through (BP, a branch point: a pitchfork of mirror states), or a change of
/// stability elsewhere (HB when a complex pair crosses, ST a real eigenvalue).
struct UnroundSpecialPoint {
  std::string kind;  ///< "LP", "BP", "HB" or "ST"
  UnroundBranchPoint point;
};

struct UnroundBranch {
  std::vector<UnroundBranchPoint> points;  ///< in arclength order
  std::vector<UnroundSpecialPoint> specials;
  double start_factor = 0;                 ///< 0 or 1: where it was started
  std::string end_forward, end_backward;   ///< how each run ended (arclength::End)
};

struct UnroundBranches {
  std::vector<UnroundBranch> branches;
  double factor_max = 1;
  std::string doubt;  ///< non-empty if a start search was not complete or a run failed
};

/// Every branch in e over [0, factor_max] (factor_max > 0) from the starts above.
/// For n >= 4 the starts come from the multistart of find_unround_equilibria (not proven
/// complete: `doubt` says so). Throws NumericalError for K = C = 0.
UnroundBranches continue_unround(const ParamsN& p, const RaceShape& race, double factor_max,
                                 const ContinuationOptions& options = {});

}  // namespace abu
