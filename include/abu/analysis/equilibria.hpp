// `equilibria`: every state of one parameter point of a scene, whatever parts the machine has.
// The one place that decides, for this question, how each kind of machine is answered:
//
//   rigid rotor, isotropic support, smooth law   every equilibrium with its refined spectrum
//                                                (two balls: the closed forms, model.md §5;
//                                                n balls: §13), the creep modes (6.11) and, for
//                                                coulomb / stribeck, the dry-friction verdict (§14.10)
//   LuGre friction                               the z = 0 equilibria and a stuck state, both
//                                                one-sided spectra (§12)
//   coulomb-set friction                         the stick set (§14; on a shaft its equivalent
//                                                rigid balancer's, §18.17)
//   unround race                                 every equilibrium by the box search (§11.4)
//   anisotropic support                          the balanced states' Floquet verdicts and the
//                                                other states' periodic orbits (§10)
//   unround race on an anisotropic support       every state a periodic orbit, continued from the
//                                                race's equilibria on the mean support (§20.4)
//   flexible shaft                               the states with their rightmost eigenvalues (§18)
//
//   abu::EquilibriaReport r = abu::analyze_equilibria(scene, {});
//   std::string text = abu::equilibria_text(r, "table", context);   // output/equilibria_report.hpp
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "abu/analysis/dry_friction.hpp"
#include "abu/analysis/floquet_states.hpp"
#include "abu/analysis/lugre_states.hpp"
#include "abu/analysis/shaft_states.hpp"
#include "abu/analysis/scene_stick_set.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/kappa_sensitivity.hpp"
#include "abu/linear/unround_spectrum.hpp"
#include "abu/model/unround_race.hpp"
#include "abu/scan/scan.hpp"

namespace abu {

/// What `equilibria` computes beyond the defaults (the options of the command).
struct EquilibriaOptions {
  BalancedSampling sampling;          ///< n >= 3 balls: samples of the balanced set
  StickSetOptions stick;              ///< coulomb-set scenes: the stick set's resolution
  bool periodic_orbits = true;        ///< anisotropic support: the other states' orbits (§10.14)
  ShaftSpectrumOptions shaft;         ///< flexible shaft: how many rightmost eigenvalues, which band
  std::vector<double> stuck_balls;    ///< LuGre: also the stuck state at these angles [rad] (empty: none)
  bool mode_shapes = false;           ///< the caller will draw mode shapes (refused where there are none)
  /// What the caller will hold per state besides the analysis [bytes] (the CLI: its text),
  /// counted in the memory estimate that refuses, before any work, what this machine cannot hold.
  double output_bytes_per_state = 0;
};

/// What analyze_equilibria will list and hold, upper bounds: for n >= 3 balls the balanced
/// set's grid points (2 G^(n-2), equilibria_n.hpp) at 10 kB each plus the caller's
/// output_bytes_per_state, up to 2^n aligned states (model.md (13.3)) at 24 kB plus twice that,
/// the dry-friction or coulomb-set grid (max(floor(B^(1/n)), 4)^n points) at 16 bytes a point,
/// and 60 MB. Measured against the whole process (/usr/bin/time, 3 to 12 equal and unequal
/// balls, table and JSON text): 4 to 8 kB per balanced state; twelve coulomb balls 271 MB,
/// 201 MB of it the 4^12-point grid.
struct EquilibriaEstimate {
  double states = 0;  ///< balanced grid points + aligned bound
  double memory = 0;  ///< [bytes], grid included
  double grid = 0;    ///< of which the stick set's grid (a sweep does not build it)
};
EquilibriaEstimate equilibria_estimate(const Scene& scene, const EquilibriaOptions& options);

/// A rigid rotor on an isotropic support with a smooth law: two balls (the fixed-size path).
struct RigidStates2 {
  Params params;
  Analysis analysis;
  std::vector<KappaSensitivity<2>> kappa;  ///< per equilibrium; undefined for laws without kappa
  DryFrictionVerdict dry;                  ///< coulomb / stribeck: the stick set of the same mu
};
/// The same for any number of balls.
struct RigidStatesN {
  ParamsN params;
  AnalysisN analysis;
  std::vector<KappaSensitivity<any_balls>> kappa;
  DryFrictionVerdict dry;
};
struct LugreStates {
  ParamsN params;
  std::vector<LugreRow> rows;
};
struct StickSetStates {
  ParamsN params;  ///< on a shaft: the equivalent rigid balancer's (model.md (18.8.2))
  StickSet set;
  std::optional<ShaftStickFigures> shaft;  ///< on a flexible shaft (model.md §18.17)
};
struct UnroundStates {
  ParamsN params;
  RaceShape race;
  UnroundResult result;
  DryFrictionVerdict dry;  ///< coulomb / stribeck: the stick set of the same mu on the race's paths (§20.5)
};
struct AnisotropicStates {
  ParamsN params;  ///< with the mean support (k_bar, c_bar)
  AnisotropicSupport support;
  FloquetAnalysis floquet;
  std::optional<ForcedOrbitAnalysis> orbits;  ///< when asked for (EquilibriaOptions::periodic_orbits)
};

/// An unround race on an anisotropic support (model.md §20.4): no state is an equilibrium
/// (the race leaves q != 0, the support turns under it); each equilibrium of the race on the
/// mean support continues to a pi/omega-periodic orbit.
struct UnroundAnisotropicStates {
  ParamsN params;  ///< with the mean support (k_bar, c_bar)
  RaceShape race;
  AnisotropicSupport support;
  UnroundResult mean;          ///< the race's equilibria on the mean support (§11.4)
  ForcedOrbitAnalysis orbits;  ///< one per equilibrium of `mean`
};

struct EquilibriaReport {
  std::variant<RigidStates2, RigidStatesN, LugreStates, StickSetStates, UnroundStates, AnisotropicStates, ShaftStates,
               UnroundAnisotropicStates>
      states;
  std::string warnings;  ///< for the user (stderr), one line each
};

/// Every state of the scene at its parameters. Throws InputError / NotSupportedError for an
/// option the scene cannot take (exit 2), NumericalError where a state could not be computed
/// (a polish that did not converge: not an equilibrium; exit 3).
EquilibriaReport analyze_equilibria(const Scene& scene, const EquilibriaOptions& options = {});

/// The kappa sensitivity of every eigenvalue of every equilibrium (model.md (6.11)); undefined
/// entries for laws without kappa.
template <class A, int N>
std::vector<KappaSensitivity<N>> kappa_sensitivities(const A& analysis, const ParamsT<double, N>& p);

}  // namespace abu
