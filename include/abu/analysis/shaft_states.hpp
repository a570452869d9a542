// The states of a flexible shaft (docs/model.md §18.8) with their rightmost eigenvalues
// (ARPACK shift-invert on the pencil (18.7.3), §19) and the verdict those cover.
//
// Per equilibrium: the k eigenvalues of largest real part in the band |Im lambda| <= band,
// with the rectangle of the complex plane the search has covered. An eigenvalue found with
// Re > 0 makes the state unstable whatever the coverage; "stable" means every eigenvalue in
// the covered rectangle is listed and all have Re < 0 (eigenvalues above the band are not
// excluded, and the verdict text says so).
//
//   abu::ShaftSystem sys = abu::shaft_system_of(scene);
//   abu::ShaftStates st = abu::analyze_shaft_states(sys, {}, {});
//   for (const auto& s : st.states) ... s.verdict, s.spectrum.eigenpairs ...
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "abu/analysis/dry_friction.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/sparse_spectrum.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// How many rightmost eigenvalues, in which band (the --eigenvalues and --band options).
struct ShaftSpectrumOptions {
  int eigenvalues = 10;  ///< k rightmost asked for per equilibrium
  double band = 0.0;     ///< |Im lambda| <= band [1/s, rotating frame]; 0: 10 omega
};
/// The band searched at speed omega: `band`, or 10 omega when it is 0.
double shaft_band(const ShaftSpectrumOptions& o, double omega);

/// One equilibrium of the shaft with its rightmost eigenvalues and their verdict.
struct ShaftState {
  ShaftEquilibrium eq;
  SparseSpectrum spectrum;
  double q_abs = 0.0;           ///< |q| at the balancer node [m]
  double max_deflection = 0.0;  ///< max_k |u_k| over the nodes [m]
  int max_node = 0;
  double rightmost = -std::numeric_limits<double>::infinity();  ///< max Re of the non-structural eigenvalues
  std::vector<char> structural;  ///< per eigenpair: one of the equilibrium's structural zeros
  std::string verdict;           ///< stable / unstable / undetermined
  std::string verdict_text;      ///< the sentence that says what the verdict covers
  int merged = 0;                ///< copies of one eigenvalue from overlapping shifts, dropped
};

/// Every equilibrium of one speed with its spectrum; `warnings` holds what the caller should
/// say (an ARPACK shortfall, an unpolished equilibrium), one line each.
struct ShaftStates {
  ShaftSystem system;
  ShaftSpectrumOptions spectrum;
  std::vector<ShaftState> states;
  std::string warnings;
  DryFrictionVerdict dry;  ///< coulomb / stribeck: the stick set of the same mu through the shaft (§18.17)
  std::optional<RaceShape> race;  ///< an unround race (model.md §18.18): the states are its equilibria
  bool race_complete = true;      ///< the race's box search (§11.4) proved its list complete
};

/// The shaft system of a [shaft] scene. Throws InputError (file, key "shaft") for a rule the
/// scene reader missed.
ShaftSystem shaft_system_of(const Scene& scene);

/// One equilibrium analysed; `vectors` keeps the eigenvectors (Campbell views).
ShaftState analyze_shaft_state(const ShaftSystem& sys, const ShaftEquilibrium& e, const ShaftSpectrumOptions& o,
                               bool vectors, const RaceShape* race = nullptr);

/// Every equilibrium of the system (find_shaft_equilibria) analysed. Throws NumericalError
/// where ARPACK found no eigenvalue of an equilibrium.
ShaftStates analyze_shaft_states(const ShaftSystem& sys, const BalancedSampling& sampling,
                                 const ShaftSpectrumOptions& o);

/// Every equilibrium of the balls on an unround race (find_shaft_race_equilibria, model.md
/// §18.18) analysed. Throws NumericalError where ARPACK found no eigenvalue of an equilibrium.
ShaftStates analyze_shaft_race_states(const ShaftSystem& sys, const RaceShape& race, const ShaftSpectrumOptions& o);

/// The forward share f+ of a mode (model.md (16.2.1)) over the shaft's nodes (translations and
/// tilts, weighted by the diagonal of A) and the balls (absolute displacement
/// dq + l_i (-sin beta_i, cos beta_i) dbeta_i, mass m_i). `s` the configuration, `v` the mode's
/// configuration part.
double shaft_forward_share(const ShaftSystem& sys, const Eigen::SparseMatrix<double>& mass, const Eigen::VectorXd& s,
                           const Eigen::VectorXcd& v);

}  // namespace abu
