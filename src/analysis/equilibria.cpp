// `equilibria` on any scene (analysis/equilibria.hpp).
#include "abu/analysis/equilibria.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "abu/analysis/machine_parts.hpp"
#include "abu/core/widen_params.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/linear/unround_stick_set.hpp"

namespace abu {

namespace {

// A row must be an equilibrium: a point whose Newton polish left a residual above 1e-8
// (rounding level is 1e-16) is a numerical failure, exit 3, not a row.
template <class A>
void check_equilibria(const A& a, double omega) {
  for (const auto& e : a.equilibria.points())
    if (!e.converged && !(e.residual <= 1e-8))
      throw NumericalError(fmt::format("omega={}: the Newton polish of a {} point did not converge (residual {:.3g}): "
                                       "it is not an equilibrium",
                                       omega, to_string(e.family), e.residual));
}

LugreStates lugre_states(const Scene& scene, const EquilibriaOptions& o) {
  if (o.mode_shapes) throw InputError("--mode-shapes", 0, "", "not available for friction law 'lugre' yet (model.md §12)");
  LugreStates out{params_of<any_balls>(scene), {}};
  const ParamsN& p = out.params;
  const int n = p.n_balls();
  throw_if_stopped("equilibria (lugre)");
  out.rows = lugre_zero_bristle_rows(p, o.sampling);
  if (!o.stuck_balls.empty()) {
    if (int(o.stuck_balls.size()) != n)
      throw InputError("--at-balls", 0, "",
                       fmt::format("the scene has {} balls: give {} angles beta_1..beta_{} [rad] (got {})", n, n, n,
                                   o.stuck_balls.size()));
    out.rows.push_back({"stuck", "", 1, analyze_lugre_rest(p, lugre_configuration(p, o.stuck_balls), false)});
  }
  return out;
}

UnroundStates unround_states(const Scene& scene, const EquilibriaOptions& o, std::string& warnings) {
  if (o.mode_shapes) throw NotSupportedError("--mode-shapes on an unround race (model.md §11): not supported yet");
  UnroundStates out{params_of<any_balls>(scene), race_shape(scene), {}, {}};
  out.result = find_unround_equilibria(out.params, out.race);
  out.dry = dry_friction_verdict(out.params, o.stick, &out.race);  // dry friction as it is (§20.5)
  for (const auto& e : out.result.list)
    if (!(e.residual <= 1e-8))
      throw NumericalError(fmt::format("omega={}: an equilibrium of the unround race has residual {:.3g}: it is not "
                                       "an equilibrium",
                                       out.params.omega, e.residual));
  // An incomplete search is said on stderr as well as in the output's search line.
  if (!out.result.doubt.empty())
    warnings = fmt::format("warning: omega={}: unround race: {}\n", out.params.omega, out.result.doubt);
  return out;
}

AnisotropicStates anisotropic_states(const Scene& scene, const EquilibriaOptions& o) {
  if (o.mode_shapes)
    throw NotSupportedError("--mode-shapes on an anisotropic support (the modes are Floquet modes, model.md §10)");
  AnisotropicStates out{params_of<any_balls>(scene), *scene.support, {}, {}};
  out.floquet = analyze_floquet(out.params, out.support, o.sampling);
  // The other states: periodic orbits continued from the mean system's (model.md §10.14).
  // They cost seconds to minutes on stiff coulomb balls; the caller may leave them out.
  if (o.periodic_orbits) {
    out.orbits = analyze_forced_orbits(out.params, out.support, out.floquet.mean_equilibria);
    out.floquet.periodic_orbits_not_computed = 0;
  }
  return out;
}

// Every state a pi/omega-periodic orbit (model.md §20.4): the race's equilibria on the mean
// support, continued in the support's anisotropy.
UnroundAnisotropicStates unround_anisotropic_states(const Scene& scene, const EquilibriaOptions& o,
                                                    std::string& warnings) {
  if (o.mode_shapes) throw NotSupportedError("--mode-shapes on an anisotropic support (the modes are Floquet modes, model.md §10)");
  UnroundStates race = unround_states(scene, o, warnings);
  UnroundAnisotropicStates out{race.params, race.race, *scene.support, std::move(race.result), {}};  // (no stick set on a turning support)
  out.orbits = analyze_unround_orbits(out.params, out.support, out.race, out.mean);
  return out;
}

template <class States, class P>
States rigid_states(const P& p, const BalancedSampling& sampling) {
  States out;
  out.params = p;
  if constexpr (std::is_same_v<P, Params>) {
    out.analysis = analyze(p);
    out.dry = dry_friction_verdict(widen(p));
  } else {
    out.analysis = analyze(p, sampling);
    out.dry = dry_friction_verdict(p);
  }
  check_equilibria(out.analysis, p.omega);
  out.kappa = kappa_sensitivities(out.analysis, p);
  return out;
}

}  // namespace

template <class A, int N>
std::vector<KappaSensitivity<N>> kappa_sensitivities(const A& a, const ParamsT<double, N>& p) {
  std::vector<KappaSensitivity<N>> out;
  const auto points = a.equilibria.points();
  out.reserve(points.size());
  const auto pl = p.template cast<long double>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (p.law != FrictionLaw::coulomb && p.law != FrictionLaw::stribeck) {
      out.emplace_back();
      continue;
    }
    if constexpr (std::is_same_v<A, AnalysisN>) {  // a permutation image: its representative's (model.md §13.9)
      if (i < a.representative.size() && a.representative[i] < int(i)) {
        out.push_back(out[std::size_t(a.representative[i])]);
        continue;
      }
    }
    out.push_back(kappa_sensitivity(p, linearize(pl, at_rest<long double, N>(points[i].position)), a.spectra[i]));
  }
  return out;
}
template std::vector<KappaSensitivity<2>> kappa_sensitivities<Analysis, 2>(const Analysis&, const Params&);
template std::vector<KappaSensitivity<any_balls>> kappa_sensitivities<AnalysisN, any_balls>(const AnalysisN&,
                                                                                           const ParamsN&);

EquilibriaEstimate equilibria_estimate(const Scene& scene, const EquilibriaOptions& o) {
  const int n = int(scene.balls.size());
  const double balanced = n >= 3 ? balanced_grid_points(n, o.sampling) : 2.0;
  const double aligned = std::ldexp(1.0, n);  // 2^(n-1) patterns, two roots each (model.md (13.3))
  const bool dry = scene.law == FrictionLaw::coulomb || scene.law == FrictionLaw::stribeck ||
                   scene.law == FrictionLaw::coulomb_set;
  // The stick set's grid (n >= 3): G = max(floor(B^(1/n)), 4) per angle, a label and |q| a point.
  const double G = std::max(std::floor(std::pow(double(o.stick.grid_budget), 1.0 / n) + 1e-9), 4.0);
  const double grid = dry && n >= 3 ? 16 * std::pow(G, n) : 0.0;
  const double states = balanced * (10e3 + o.output_bytes_per_state) + aligned * 2 * (12e3 + o.output_bytes_per_state);
  return {balanced + aligned, 60e6 + states + grid, grid};
}

EquilibriaReport analyze_equilibria(const Scene& scene, const EquilibriaOptions& o) {
  const EquilibriaEstimate estimate = equilibria_estimate(scene, o);
  require_memory(estimate.memory, "--set-samples", "the equilibria",
                 fmt::format("up to {:.0f} states of {} balls with their spectra and text", estimate.states,
                             scene.balls.size()),
                 "use a smaller --set-samples (or --stick-grid)");
  EquilibriaReport r;
  const Route route = route_of(scene);
  if (!o.stuck_balls.empty() && route != Route::lugre)
    throw InputError("--at-balls", 0, "",
                     fmt::format("a stuck state is an equilibrium only with friction law 'lugre' (model.md §12.3); "
                                 "this scene's law is '{}'",
                                 to_string(scene.law)));
  switch (route) {
    case Route::shaft: {  // its equilibria and rightmost eigenvalues (model.md §18)
      if (o.mode_shapes) throw NotSupportedError("--mode-shapes on a flexible shaft ([shaft], model.md §18)");
      if (!scene.race.round()) {  // the race's equilibria on the shaft (model.md §18.18)
        ShaftStates st = analyze_shaft_race_states(shaft_system_of(scene), race_shape(scene), o.shaft);
        if (scene.law == FrictionLaw::coulomb || scene.law == FrictionLaw::stribeck) {
          st.dry.applies = true;
          st.dry.which = scene.law == FrictionLaw::stribeck ? "mu_i = mu_s" : "the same mu_i";
          st.dry.not_defined =
              "not computed on an unround race on a shaft: V is anchored at the race's least-|q| stable equilibrium "
              "(model.md §20.5), whose stability here is the shaft's";
        }
        r.warnings = st.warnings;
        r.states = std::move(st);
        break;
      }
      ShaftStates st = analyze_shaft_states(shaft_system_of(scene), o.sampling, o.shaft);
      st.dry = dry_friction_verdict(st.system, o.stick);  // coulomb / stribeck: where the balls really stop
      r.warnings = st.warnings;
      r.states = std::move(st);
      break;
    }
    case Route::unround: r.states = unround_states(scene, o, r.warnings); break;
    case Route::anisotropic: r.states = anisotropic_states(scene, o); break;
    case Route::unround_anisotropic: r.states = unround_anisotropic_states(scene, o, r.warnings); break;
    case Route::set_valued: {  // on the race's paths if unround (§20.5), through the shaft on a shaft (§18.17)
      SceneStickSet s = scene_stick_set(scene, o.stick);
      r.states = StickSetStates{std::move(s.params), std::move(s.set), std::move(s.shaft)};
      break;
    }
    case Route::lugre: r.states = lugre_states(scene, o); break;
    case Route::rigid:
      if (scene.balls.size() == 2)
        r.states = rigid_states<RigidStates2>(params_of<2>(scene), o.sampling);
      else
        r.states = rigid_states<RigidStatesN>(params_of<any_balls>(scene), o.sampling);
      break;
  }
  return r;
}

}  // namespace abu
