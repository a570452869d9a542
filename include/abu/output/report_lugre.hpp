// `equilibria` of a LuGre scene (model.md §12): the z = 0 equilibria (those of §5 / §13)
// and any stuck state asked for (--at-balls), each with both one-sided normal spectra,
// the n zero eigenvalues along the family, the cross-check of the two routes (§12.5) and
// the verdict (stable only if both sides are; non-smooth where they disagree). Table, CSV
// and JSON carry the same numbers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "abu/analysis/lugre_states.hpp"
#include "abu/core/params.hpp"

namespace abu {

/// `sweep` of a LuGre scene (model.md §12.8): the columns of lugre_equilibria_csv after a
/// first column named `param` with the value; one block of rows per value.
std::string lugre_sweep_csv(std::string_view param, const std::vector<double>& values,
                            const std::vector<std::vector<LugreRow>>& rows, const ParamsN& p, const std::string& header);

/// CSV: one line per state and side (side "both" at z = 0, where the sides coincide).
/// Columns family,pattern,member,side,q1,q2,beta1..n,z1..n,load1..n,reachable,
/// rotor_residual,spectral_abscissa,side_stable,stable,non_smooth,verdict,n_zero,
/// route_deviation,re1,im1,..,re(3n+4),im(3n+4): the 2n + 4 normal eigenvalues sorted by
/// real part, then the n zeros as 0,0. `header` is written first (# lines).
std::string lugre_equilibria_csv(const std::vector<LugreRow>& rows, const ParamsN& p, const std::string& header);
std::string lugre_equilibria_json(const std::vector<LugreRow>& rows, const ParamsN& p, std::string_view command_line,
                                  std::string_view scene_file);
std::string lugre_equilibria_table(const std::vector<LugreRow>& rows, const ParamsN& p);
/// Warnings for stderr: routes that disagree, unreachable stuck states, unconverged spectra.
std::string lugre_warnings(const std::vector<LugreRow>& rows);

}  // namespace abu
