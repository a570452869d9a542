// The balanced set's stability boundary in one parameter: the envelope of its samples'
// Hopf points (model.md §13.7, branches_n.hpp BalancedEnvelope). Internal header.
#pragma once

#include <vector>

#include "abu/continuation/branches_n.hpp"

namespace abu::n_balls {

/// The interval [from, to] cut at every located HB and LP of any balanced-sample branch
/// (and at the ends of each), each piece with the samples (weighted 1 + images) stable
/// throughout.
BalancedEnvelope envelope_of(const std::vector<BranchN>& branches, long double from, long double to);

}  // namespace abu::n_balls
