// A branch's special points as points of the branch: so that a table or a chart of the
// branch changes stability exactly where the special point was located, and not somewhere
// between the two grid points that bracket it (a continuation step can be a tenth of the
// interval: the HB of the default scene at 249.934 rad/s lies between points at 186 and
// 342 rad/s).
//
// Each located (converged) LP, BP and HB of a branch becomes a BranchPoint labelled with
// it, at its located parameter and state, with its spectrum computed there and matched to
// the tracked modes of the branch; it is inserted between the two points that bracket it.
// Where the stability (or n_unstable) differs on the two sides, the point is inserted
// twice: first carrying the stability and n_unstable of the point before it, then those
// of the point after it, so that the stability flips exactly at the located parameter.
// (At the point itself the critical eigenvalue is on the imaginary axis: it is neither.)
// Either side of a Hopf point (two balls), three more points of the branch at 30, 10 and
// 2 % of the way to the bracketing point, each with its own spectrum, so that the
// spectral abscissa is drawn as the curve it is into the crossing.
//
//   abu::ContinuationRun run = abu::continue_branches(p, param, to, options);
//   abu::insert_special_rows(p, run);   // for output; the located points stay in specials
//   branch_csv(abu::with_special_rows(p, run), header);   // the same, on a copy
#pragma once

#include "abu/continuation/branches_n.hpp"
#include "abu/continuation/continuation.hpp"

namespace abu {

/// Inserts the located special points of every branch of `run` (continued from `p`)
/// into its points, as described above. Specials that were not located (converged =
/// false) get no row.
void insert_special_rows(const Params& p, ContinuationRun& run);
/// A copy of `run` with the rows inserted (the run itself, e.g. for the two-parameter
/// curves that start from its special points, stays as traced).
ContinuationRun with_special_rows(const Params& p, ContinuationRun run);

/// The same for n >= 3 balls: the full spectrum at an aligned branch's special point, the
/// normal one (structural zeros flagged) at a balanced sample's (branches_n.hpp).
void insert_special_rows(const ParamsN& p, ContinuationRunN& run);
ContinuationRunN with_special_rows(const ParamsN& p, ContinuationRunN run);

}  // namespace abu
