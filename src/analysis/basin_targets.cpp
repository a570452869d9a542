// The attractors of a basin (basin_targets.hpp).
#include "abu/analysis/basin_targets.hpp"

#include "abu/analysis/floquet_states.hpp"

namespace abu {

std::vector<BasinTarget> machine_basin_targets(const BasinJob& job, const BalancedSampling& sampling) {
  if (!job.support) return basin_targets(job);
  ParamsN p = job.params_n;
  p.omega = job.final_omega();
  const FloquetAnalysis a = analyze_floquet(p, *job.support, sampling);
  std::vector<bool> stable;
  for (const auto& f : a.floquet) stable.push_back(f.verdict == Stability::stable);
  return balanced_targets(a.balanced, stable,
                          "an anisotropic support: the linearization is pi/omega-periodic (model.md §10.6), no "
                          "Lyapunov region of §15.8 yet; the balanced states judged by their Floquet multipliers, "
                          "reached by the settle radius test");
}

}  // namespace abu
