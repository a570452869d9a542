// Output of `equilibria` for an unround race (model.md §11): a table, CSV or JSON with
// every equilibrium of §11.4, its Poincare-Hopf index, spectrum (rotating frame, 1/s) and
// stability, the search's completeness record, the first-order parameter Lambda_k of
// §11.6 and the design figure: the residual whirl |q| of the best stable state.
#pragma once

#include <string>
#include <string_view>

#include "abu/continuation/unround_branches.hpp"
#include "abu/linear/unround_spectrum.hpp"

namespace abu {

// unround_lambda and kFirstOrderLambda (§11.6): model/unround_race.hpp.

std::string unround_table(const UnroundResult& r, const ParamsN& p, const RaceShape& race, std::string_view scene);
/// `header`: the provenance comment lines (output/provenance.hpp).
std::string unround_csv(const UnroundResult& r, const ParamsN& p, const RaceShape& race, const std::string& header);
std::string unround_json(const UnroundResult& r, const ParamsN& p, const RaceShape& race, std::string_view command_line,
                         std::string_view scene);

/// A sweep on an unround race (model.md §11.10): per value of the parameter, every
/// equilibrium of the complete search, the race's Lambda and the design figure.
struct UnroundSweep {
  std::string name, unit;  ///< the parameter ("unroundness": the factor e on every amplitude)
  std::vector<double> values;
  std::vector<double> lambdas;        ///< Lambda of §11.6 per value
  std::vector<double> bare_whirls;    ///< omega^2 U / |K + iC| per value [m]
  std::vector<UnroundResult> points;  ///< per value
};
/// One row per equilibrium per value (columns named in the header line).
std::string unround_sweep_csv(const UnroundSweep& s, const std::string& header);
/// One row per value: equilibria, stable ones, best stable |q|, Lambda, first-order flag,
/// whether the search was complete.
std::string unround_sweep_summary_csv(const UnroundSweep& s, const std::string& header);

/// The branches of continue_unround: one row per point (branch, factor, q, beta, index,
/// abscissa, stable) and one per special point (LP, HB, BP).
std::string unround_branch_csv(const UnroundBranches& b, const std::string& header);
std::string unround_special_csv(const UnroundBranches& b, const std::string& header);

}  // namespace abu
