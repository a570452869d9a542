// A simulation's start at a chosen equilibrium: the text `FAMILY[:K]` or
// `aligned:PATTERN[:K]` (the CLI's --from-equilibrium, the Python module's
// from_equilibrium), and the state displaced from that equilibrium along its rightmost
// non-structural eigenmode (model.md §15: how a perturbed start is made).
//
//   abu::EquilibriumChoice c = abu::parse_equilibrium_choice("aligned:+-+:2", "--from-equilibrium");
//   abu::State<double, 2> x0 = abu::start_from_equilibrium(p, abu::analyze(p), c, 1e-3, "--from-equilibrium");
#pragma once

#include <string>

#include "abu/model/model.hpp"
#include "abu/scan/scan.hpp"

namespace abu {

/// Which equilibrium: family "balanced", "together", "opposite" (two balls) or "aligned"
/// with its sign pattern (`+-+`), and the member K (1-based, default 1).
struct EquilibriumChoice {
  std::string family, pattern;
  int member = 1;
};

/// Parses FAMILY[:K] | aligned:PATTERN[:K]. Throws InputError naming `option` and the
/// expected form. On an unround race (`unround_race`) there is no such start yet: throws
/// NotSupportedError naming `option` and the starts to use instead (`balls_option`,
/// `state_option`).
EquilibriumChoice parse_equilibrium_choice(const std::string& text, const std::string& option);
EquilibriumChoice parse_equilibrium_choice(const std::string& text, const std::string& option, bool unround_race,
                                           const std::string& balls_option, const std::string& state_option);

/// The chosen equilibrium of `analysis` (at p) displaced by eps (scaled: q / L, rad) along
/// the real part of its rightmost non-structural eigenmode. Throws InputError naming
/// `option` and listing the equilibria there if there is no such one; NumericalError if it
/// has no usable eigenvector.
State<double, 2> start_from_equilibrium(const Params& p, const Analysis& analysis, const EquilibriumChoice& choice,
                                        double eps, const std::string& option);
State<double, any_balls> start_from_equilibrium(const ParamsN& p, const AnalysisN& analysis,
                                                const EquilibriumChoice& choice, double eps, const std::string& option);

}  // namespace abu
