// A balanced sample of n >= 3 balls carried to other parameter values (docs/model.md §10.16):
// the free angles beta_3..beta_n held, balls 1 and 2 close W = U + sum m_i l_i e^{i beta_i} = 0
// (§13.5) by Newton from a nearby point of the same sample's branch, which keeps the sheet.
//
//   std::optional<abu::EquilibriumN> e = abu::balanced_sample_at(p, branch_point.position, member);
#pragma once

#include <optional>

#include "abu/equilibria/equilibria_n.hpp"

namespace abu {

/// The balanced state of `p` with the free angles of `near` (q = 0, rates 0), on_balanced_set;
/// nullopt if Newton does not reach |W| <= 1e-15 (U + sum m_i l_i) in 30 steps (the sample
/// left the set: balls 1 and 2 can no longer close the polygon, or they became collinear).
std::optional<EquilibriumN> balanced_sample_at(const ParamsN& p, const Coordinates<long double, any_balls>& near,
                                               int member);

}  // namespace abu
