// The files of a sweep on an unround race with an anisotropic support (docs/model.md §20.6,
// analysis/composed_sweep.hpp): one CSV row per orbit per value (lost tracks and orbits that
// did not converge included, their reasons as comment lines; no NaN, empty fields where a row
// has no number), the crossings of |rho| = 1 in the layout of the anisotropic support's
// floquet_crossings_NAME.csv (the first column the orbit's track), and the summary for stderr.
//
//   std::string csv = abu::composed_sweep_csv(s, "omega", header);
#pragma once

#include <string>

#include "abu/analysis/composed_sweep.hpp"

namespace abu {

/// NAME,track,equilibrium,status,stability,rho_abs_max,decay_rate,q_abs_max,q_abs_min,band,
/// steps_per_interval,mult_re1,mult_im1,... (modulus descending), x0_1..x0_(2n+4) (the orbit at
/// t = 0, SI, rotating frame: a reference's start).
std::string composed_sweep_csv(const ComposedSweep& s, const std::string& name, const std::string& header);
/// orbit,NAME,kind,direction,mult_re,mult_im,mult_abs,bracket_lower,bracket_upper; the sign
/// changes bisection could not follow as comment lines.
std::string composed_crossings_csv(const ComposedSweep& s, const std::string& name, const std::string& header);
/// For stderr: the crossings (as the anisotropic support's sweep prints them, "orbit" for
/// "balanced"), the lost tracks, the orbits that did not converge, the searches' doubts.
std::string composed_sweep_text(const ComposedSweep& s, const std::string& name);

}  // namespace abu
