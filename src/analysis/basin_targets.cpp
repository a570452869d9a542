// The attractors of a basin (basin_targets.hpp).
#include "abu/analysis/basin_targets.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

#include "abu/analysis/composed_sweep.hpp"
#include "abu/analysis/floquet_states.hpp"
#include "abu/analysis/shaft_states.hpp"
#include "abu/core/errors.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/model/model.hpp"

namespace abu {

namespace {

constexpr int kPhases = 128;  // (pi/128)^2 / 8 = 7.5e-5 of the orbit's variation (model.md §20.8)

// The orbit's states over its period, or the reason they could not be taken.
std::optional<BasinOrbit> sample_orbit(const ParamsN& p, const RaceShape& race, const AnisotropicSupport& support,
                                       const ForcedOrbit& orbit, std::string& why) {
  const int dim = 2 * (p.n_balls() + 2);
  State<double, any_balls> x0(dim);
  for (int k = 0; k < dim; ++k) x0(k) = orbit.state0[std::size_t(k)];
  const double period = M_PI / p.omega;
  SimulationOptions o;
  o.t_end = period;
  o.every = period / kPhases;
  o.rtol = 1e-11;
  o.record = true;
  o.race = &race;
  o.support = &support;
  const SimulationResult<any_balls> r = simulate(p, SpeedProfile::constant(p.omega), x0, o);
  if (r.status != SimulationStatus::completed) {
    why = "sampling its period failed: " + r.reason;
    return std::nullopt;
  }
  if (int(r.samples.size()) < kPhases + 1) {
    why = fmt::format("{} samples over its period, expected {}", r.samples.size(), kPhases + 1);
    return std::nullopt;
  }
  BasinOrbit b;
  b.omega = p.omega;
  b.dim = dim;
  b.states.reserve(std::size_t(kPhases) * std::size_t(dim));
  for (int k = 0; k < kPhases; ++k)
    for (int m = 0; m < dim; ++m) b.states.push_back(r.samples[std::size_t(k)].x(m));
  // One period on, the spin angle is pi: the state must be the first row's again.
  const double gap = b.distance(r.x_end.data(), M_PI, displacement_scale(p));
  if (!(gap <= 1e-7)) {
    why = fmt::format("one period from its state at theta = 0 ends {:.3g} away (scaled), more than 1e-7", gap);
    return std::nullopt;
  }
  return b;
}

// The unround race's stable orbits on the anisotropic support at the final speed (§20.8).
BasinAttractors composed_targets(const BasinJob& job) {
  ParamsN p = job.params_n;
  p.omega = job.final_omega();
  ComposedStates states = composed_states(p, job.race, *job.support);
  BasinAttractors out;
  out.unresolved = std::move(states.unresolved);
  for (SampledOrbit& s : states.orbits) {
    if (s.verdict != Stability::stable) continue;
    BasinTarget t;
    t.label = "orbit";
    t.member = s.member;
    t.orbit = std::move(s.orbit);
    t.region.reason = "a periodic orbit (model.md §20.8): no Lyapunov region of §15.8; its Floquet multipliers "
                      "judge it, the settle radius test against its state at the run's spin angle reaches it";
    out.targets.push_back(std::move(t));
  }
  return out;
}

// A shaft's equilibrium seen at the balancer node: (q, beta) of model.md (2.2).
EquilibriumN balancer_view_of(const ShaftSystem& sys, const ShaftEquilibrium& e) {
  EquilibriumN v;
  v.family = e.family;
  v.pattern = e.pattern;
  v.member = e.member;
  v.on_balanced_set = e.on_balanced_set;
  const Eigen::VectorXd x = e.state();
  v.position = balancer_view(sys, x.data()).head(sys.n_balls() + 2).cast<long double>();
  return v;
}

// A flexible shaft's stable equilibria at the final speed (model.md §18.21), each by its
// spectrum as `equilibria` judges it; on a race, the race's equilibria on the shaft.
BasinAttractors shaft_targets(const BasinJob& job) {
  ShaftSystem sys = *job.shaft;
  sys.balancer.omega = job.final_omega();
  BasinAttractors out;
  if (has_anisotropic_bearings(sys.spec)) {
    static const std::string no_floquet =
        "anisotropic bearings on a flexible shaft: the balanced states' Floquet multipliers are not computed there "
        "(model.md §18.19), so no state is an attractor of the settle test; every cell is judged at t_end (§15.2)";
    out.unresolved.push_back(no_floquet);
    return out;
  }
  const bool race = !job.race.round();
  const ShaftStates st = race ? analyze_shaft_race_states(sys, job.race, {}) : analyze_shaft_states(sys, {}, {});
  const std::string why = "a flexible shaft: no Lyapunov region of §15.8 for it yet; the settle radius test on the "
                          "balancer node and the balls (model.md §18.21)";
  std::vector<EquilibriumN> views;
  std::vector<bool> stable;
  int set_samples = 0, set_without_verdict = 0;
  std::string set_reason;
  for (const ShaftState& s : st.states) {
    const bool decided = s.verdict == "stable" || s.verdict == "unstable";
    if (s.eq.on_balanced_set) {  // one line for the set (model.md §13.5): its samples' verdicts
      ++set_samples;
      if (!decided && set_without_verdict++ == 0) set_reason = s.verdict_text;
    } else if (!decided) {
      out.unresolved.push_back(fmt::format("equilibrium {} ({}): {}", s.eq.member, s.verdict, s.verdict_text));
    }
    if (!race) {
      views.push_back(balancer_view_of(sys, s.eq));
      stable.push_back(s.verdict == "stable");
      continue;
    }
    if (s.verdict != "stable") continue;
    BasinTarget t;
    t.label = "equilibrium";
    t.member = s.eq.member;
    const auto pos = balancer_view_of(sys, s.eq).position_si();
    t.position.assign(pos.data(), pos.data() + pos.size());
    t.region.reason = why;
    out.targets.push_back(std::move(t));
  }
  if (set_without_verdict > 0)
    out.unresolved.push_back(fmt::format("the balanced set: {} of its {} samples have no verdict (the first: {})",
                                         set_without_verdict, set_samples, set_reason));
  if (!race) out.targets = balanced_targets(views, stable, why);
  return out;
}

}  // namespace

ComposedStates composed_states(const ParamsN& p, const RaceShape& race, const AnisotropicSupport& support) {
  const ComposedSweepPoint at = composed_orbits_at(support, {p, race}, p.omega);
  ComposedStates out;
  if (!at.search_doubt.empty()) out.unresolved.push_back("the race's equilibrium search: " + at.search_doubt);
  for (const ComposedOrbitRow& row : at.rows) {
    const ForcedOrbit& o = row.orbit;
    std::string why = o.reason.empty() ? "no multipliers" : o.reason;
    std::optional<BasinOrbit> sampled;
    if (composed_orbit_usable(o)) sampled = sample_orbit(p, race, support, o, why);
    if (!sampled) {
      out.unresolved.push_back(fmt::format("orbit {} ({}): {}", row.equilibrium, o.kind, why));
      continue;
    }
    out.orbits.push_back({row.equilibrium, o.verdict, o.q_abs_max, std::make_shared<const BasinOrbit>(*sampled)});
  }
  return out;
}

void classify_composed_end(SimulationSummary& s, const ParamsN& p, const ComposedStates& states, double theta_end,
                           double tolerance) {
  if (s.outcome != SimulationOutcome::periodic && s.outcome != SimulationOutcome::not_settled) return;
  if (s.state_end.empty()) return;
  const double L = displacement_scale(p);
  const SampledOrbit* best = nullptr;
  double best_d = HUGE_VAL;
  for (const SampledOrbit& o : states.orbits) {
    const double d = o.orbit->distance(s.state_end.data(), theta_end, L);
    if (d < best_d) best_d = d, best = &o;
  }
  if (!best || !(best_d <= tolerance)) return;
  s.outcome = SimulationOutcome::orbit;
  s.pattern.clear();
  s.orbit_member = best->member;
  s.orbit_q_abs_max = best->q_abs_max;
  s.orbit_distance = best_d;
  s.note = fmt::format("on orbit {} (the unround race's equilibrium {} continued on the anisotropic support, model.md "
                       "§20.4, §20.8), {}: largest whirl |q| over its period {:.6g} m, scaled distance {:.3g} at the "
                       "end's spin angle",
                       best->member, best->member, to_string(best->verdict), best->q_abs_max, best_d);
}

BasinAttractors machine_basin_targets(const BasinJob& job, const BalancedSampling& sampling) {
  if (job.shaft) return shaft_targets(job);
  if (!job.support) return {basin_targets(job), {}};
  if (!job.race.round()) return composed_targets(job);
  ParamsN p = job.params_n;
  p.omega = job.final_omega();
  const FloquetAnalysis a = analyze_floquet(p, *job.support, sampling);
  std::vector<bool> stable;
  for (const auto& f : a.floquet) stable.push_back(f.verdict == Stability::stable);
  return {balanced_targets(a.balanced, stable,
                           "an anisotropic support: the linearization is pi/omega-periodic (model.md §10.6), no "
                           "Lyapunov region of §15.8 yet; the balanced states judged by their Floquet multipliers, "
                           "reached by the settle radius test"),
          {}};
}

}  // namespace abu
