// The attractors of a basin for any machine the basin integrates (model.md §15.5): the scan's
// targets (stable equilibria by their spectra, certified regions for two balls) or, on an
// anisotropic support, the balanced states whose Floquet multipliers say stable (§10.5, §10.6).
//
//   std::vector<abu::BasinTarget> targets = abu::machine_basin_targets(job);
#pragma once

#include <vector>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/scan/basin.hpp"

namespace abu {

/// basin_targets(job), or on an anisotropic support (job.support; job.params_n carrying its
/// mean) the balanced states at the final speed judged by analyze_floquet: each stable one a
/// target (two balls: the mirror states; n >= 3: the balanced set when every sample is stable),
/// found by the settle radius test (no certified region: the linearization is periodic). The
/// aligned states are pi/omega-periodic orbits there, not targets: a cell that ends on one is
/// judged at t_end by §15.2 (`periodic`). Throws NumericalError where Hill's method fails.
std::vector<BasinTarget> machine_basin_targets(const BasinJob& job, const BalancedSampling& sampling = {});

}  // namespace abu
