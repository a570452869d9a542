// The z = 0 equilibria of a LuGre scene with their one-sided spectra (lugre_states.hpp).
#include "abu/analysis/lugre_states.hpp"

#include <fmt/format.h>

#include "abu/core/errors.hpp"

namespace abu {

std::vector<LugreRow> lugre_zero_bristle_rows(const ParamsN& p, const BalancedSampling& sampling) {
  const int n = p.n_balls();
  ParamsN free = p;
  free.law = FrictionLaw::none;
  const EquilibriumSetN set = find_equilibria(free, sampling);
  std::vector<LugreRow> rows;
  for (const auto& e : set.points()) {
    if (!e.converged && !(e.residual <= 1e-8))
      throw NumericalError(fmt::format("omega={}: the Newton polish of a {} point did not converge (residual {:.3g}): "
                                       "it is not an equilibrium",
                                       p.omega, to_string(e.family), e.residual));
    rows.push_back({std::string(to_string(e.family)),
                    e.family == Family::balanced ? std::string() : pattern_string(e.pattern, n), e.member,
                    analyze_lugre_rest(p, e.position, true)});
  }
  return rows;
}

}  // namespace abu
