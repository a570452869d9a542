// The states of an anisotropic support: the balanced states judged by their Floquet multipliers
// (docs/model.md §10.5, §10.6: Hill's method, cross-checked by a Magnus monodromy), and the other
// states as pi/omega-periodic orbits continued from the mean system's aligned equilibria (§10.14).
#pragma once

#include <vector>

#include "abu/dynamics/forced_orbits.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/balanced_floquet.hpp"
#include "abu/linear/unround_spectrum.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu {

struct FloquetAnalysis {
  EquilibriumSetN mean_equilibria;          ///< of the mean system (k_bar, c_bar)
  std::vector<EquilibriumN> balanced;       ///< its balanced states (exact equilibria, §10.5)
  std::vector<BalancedFloquet> floquet;     ///< one per balanced state
  int periodic_orbits_not_computed = 0;     ///< the mean system's other equilibria
};

/// `p` must carry the mean support. Throws NumericalError (where and why) if Hill's method
/// does not converge or Hill and Magnus disagree beyond `cross_check_tolerance` (1e-6).
FloquetAnalysis analyze_floquet(const ParamsN& p, const AnisotropicSupport& support, const BalancedSampling& sampling,
                                const FloquetOptions& options = {}, double cross_check_tolerance = 1e-6);

/// Where the periodic orbits start (at delta = 0): the mean system's aligned equilibria
/// (model.md §10.14), or the equilibria of an unround race on the mean support (§20.4).
enum class OrbitOrigin { aligned_equilibria, unround_equilibria };

struct ForcedOrbitAnalysis {
  OrbitOrigin origin = OrbitOrigin::aligned_equilibria;
  int aligned = 0;                  ///< the starting equilibria (aligned ones of the mean system, or the unround race's)
  int converged = 0;                ///< orbits found (status converged) among them
  std::vector<ForcedOrbit> orbits;  ///< one per aligned equilibrium, in the mean system's order
};

/// `p` must carry the mean support; `mean` its equilibria (find_equilibria).
ForcedOrbitAnalysis analyze_forced_orbits(const ParamsN& p, const AnisotropicSupport& support,
                                          const EquilibriumSetN& mean, const ForcedOrbitOptions& options = {});

/// An unround race on an anisotropic support (model.md §20.4): every equilibrium of the race on
/// the mean support (`mean`, find_unround_equilibria with p) continued to a pi/omega-periodic
/// orbit of the scene. `p` must carry the mean support.
ForcedOrbitAnalysis analyze_unround_orbits(const ParamsN& p, const AnisotropicSupport& support, const RaceShape& race,
                                           const UnroundResult& mean, const ForcedOrbitOptions& options = {});

}  // namespace abu
