// `continue` on an unround race with an anisotropic support (docs/model.md §20.9): every
// periodic orbit `equilibria` finds at the scene's value (composed_orbits_at), each continued
// by pseudo-arclength in the parameter to the other end (dynamics/forced_branch.hpp), through
// its folds, with its fold (LP), branch (BP), flip (PD) and Neimark-Sacker (NS) points
// located; then every orbit at that other end that no branch reached (a pair born at a fold
// inside the interval) continued back. Each orbit at either end must end exactly one branch:
// a check that no run jumped to a neighbouring orbit.
//
//   abu::ComposedBranches b = abu::composed_branches(*scene.support, at, 1100, 1400);
//   if (!b.status.ok()) ... b.reason ...;   // the branches are kept in any case
#pragma once

#include <string>
#include <vector>

#include "abu/analysis/composed_sweep.hpp"
#include "abu/dynamics/forced_branch.hpp"

namespace abu {

struct ComposedBranch {
  double start_value = 0;  ///< the end it was started from (the scene's value or `to`)
  ForcedBranch branch;
};

struct ComposedBranches {
  double start = 0, end = 0;  ///< the scene's value and the other end (`to`)
  std::vector<ComposedBranch> branches;
  int orbits_at_start = 0, orbits_at_end = 0;  ///< usable orbits found at each end
  /// converged: every branch ran to the interval's ends (or closed), every orbit at each end
  /// ends one branch, and the race's equilibrium searches were complete; otherwise the first
  /// problem, where and why (the branches are kept).
  Status status;
  std::string reason;
};

/// The branches over [start, end] (either order; start != end). `at` gives the machine at a
/// value and must accept values a little beyond the ends (forced_orbits.hpp, MachineFamily).
/// Throws NumericalError where an equilibrium of the race has a residual above 1e-8 (as
/// composed_orbits_at).
ComposedBranches composed_branches(const AnisotropicSupport& support, const ComposedAt& at, double start, double end,
                                   const ForcedBranchOptions& options = {});

}  // namespace abu
