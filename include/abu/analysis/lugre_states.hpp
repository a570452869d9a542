// The states of a LuGre scene (docs/model.md §12): the z = 0 equilibria of §5 / §13 and any
// stuck state asked for, each with both one-sided normal spectra (linear/lugre_spectrum.hpp).
#pragma once

#include <string>
#include <vector>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/lugre_spectrum.hpp"

namespace abu {

/// One state of the report: where it came from and its analysis.
struct LugreRow {
  std::string family;   ///< balanced, together, opposite, aligned (z = 0), or stuck (--at-balls)
  std::string pattern;  ///< aligned sign pattern ("+-+"), else empty
  int member = 1;
  LugreRest rest;
};

/// The z = 0 equilibria of a LuGre scene (model.md §12.3: those of §5 / §13, found with the
/// friction left out, which does not move them) with both one-sided spectra each. Throws
/// NumericalError for a state whose Newton polish did not converge.
std::vector<LugreRow> lugre_zero_bristle_rows(const ParamsN& p, const BalancedSampling& sampling);

}  // namespace abu
