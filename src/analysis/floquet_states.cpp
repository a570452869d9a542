// Floquet verdicts of the balanced states on an anisotropic support (floquet_states.hpp).
#include "abu/analysis/floquet_states.hpp"

#include <fmt/format.h>

#include "abu/core/errors.hpp"

namespace abu {

FloquetAnalysis analyze_floquet(const ParamsN& p, const AnisotropicSupport& support, const BalancedSampling& sampling,
                                const FloquetOptions& options, double cross_check_tolerance) {
  FloquetAnalysis a;
  a.mean_equilibria = find_equilibria(p, sampling);
  for (const EquilibriumN& e : a.mean_equilibria.points()) {
    if (e.family != Family::balanced) {
      ++a.periodic_orbits_not_computed;
      continue;
    }
    if (!e.converged && !(e.residual <= 1e-8))
      throw NumericalError(fmt::format("omega={}: the Newton polish of balanced state {} did not converge (residual "
                                       "{:.3g}): it is not an equilibrium",
                                       p.omega, e.member, e.residual));
    BalancedFloquet f = balanced_floquet(p, support, e, options);
    if (!f.status.ok())
      throw NumericalError(fmt::format("omega={}: Floquet multipliers of balanced state {}: {} (N = {})", p.omega,
                                       e.member, f.status.reason, f.harmonics));
    if (!(f.monodromy_deviation <= cross_check_tolerance))
      throw NumericalError(fmt::format("omega={}: Floquet multipliers of balanced state {}: Hill's method and the "
                                       "Magnus monodromy disagree by {:.3g} (relative), above {:.3g}",
                                       p.omega, e.member, f.monodromy_deviation, cross_check_tolerance));
    a.balanced.push_back(e);
    a.floquet.push_back(std::move(f));
  }
  return a;
}

ForcedOrbitAnalysis analyze_forced_orbits(const ParamsN& p, const AnisotropicSupport& support,
                                          const EquilibriumSetN& mean, const ForcedOrbitOptions& options) {
  ForcedOrbitAnalysis a;
  for (const EquilibriumN& e : mean.points()) {
    if (e.family == Family::balanced) continue;
    ++a.aligned;
    a.orbits.push_back(forced_orbit(p, support, e, options));
    if (a.orbits.back().status.ok()) ++a.converged;
  }
  return a;
}

ForcedOrbitAnalysis analyze_unround_orbits(const ParamsN& p, const AnisotropicSupport& support, const RaceShape& race,
                                           const UnroundResult& mean, const ForcedOrbitOptions& options) {
  ForcedOrbitAnalysis a;
  a.origin = OrbitOrigin::unround_equilibria;
  const int d = p.n_balls() + 2;
  for (std::size_t k = 0; k < mean.list.size(); ++k) {
    Coordinates<double, any_balls> s(d);
    for (int i = 0; i < d; ++i) s(i) = double(mean.list[k].position(i));
    ++a.aligned;
    a.orbits.push_back(forced_orbit(p, RigidMachine{&race, &support}, at_rest<double, any_balls>(s),
                                    fmt::format("unround equilibrium {}", k + 1), options));
    if (a.orbits.back().status.ok()) ++a.converged;
  }
  return a;
}

}  // namespace abu
