// The Campbell view of an omega sweep on an anisotropic support (docs/model.md §10.15,
// docs/views.md): per speed and balanced state, every Floquet mode as a fixed-frame whirl
// (linear/floquet_modes.hpp), as CampbellSample rows for report_views' campbell_csv and
// critical_speeds, so that the CSV and the chart have the isotropic view's columns.
//
//   auto samples = abu::floquet_campbell_samples(sweep, base, *scene.support);   // omega sweeps only
//   std::string csv = abu::campbell_csv(samples, header + abu::floquet_campbell_note(), unit);
#pragma once

#include <string>
#include <vector>

#include "abu/analysis/floquet_sweep.hpp"
#include "abu/output/report_views.hpp"

namespace abu {

/// One sample per balanced state per value of `s` (empty if the parameter is not omega),
/// ordered by series (balanced state), then speed. `base` carries the mean support.
/// Throws NumericalError (the speed, the state, Hill's reason) where Hill's method fails.
std::vector<CampbellSample> floquet_campbell_samples(const FloquetSweep& s, const ParamsN& base,
                                                     const AnisotropicSupport& support);

/// The CSV header lines ("# ...") that say how the Floquet exponents became fixed-frame whirl
/// frequencies (written before campbell_csv's own column notes).
std::string floquet_campbell_note(const AnisotropicSupport& support, const ParamsN& base);

}  // namespace abu
