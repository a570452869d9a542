// Equilibria of a flexible shaft whose balls roll on an unround race (docs/model.md §18.18).
//
// At rest the balls load the shaft only at the balancer node, with omega^2 (U + sum m_i p_i(beta_i))
// (the path points of §11.1), and the node answers by its receptance h (18.8.1). The ball
// conditions of §11.4 read only the node's q, so the equilibria are those of the unround race on
// the equivalent rigid balancer (18.8.2) — the box search of §11.4, complete for n = 2, 3 — and the
// shaft's deflection follows from one sparse solve, then Newton on the full static equations
// (18.18.1) polishes it (status, residual).
//
//   abu::ShaftRaceEquilibria set = abu::find_shaft_race_equilibria(sys, race);
//   for (const auto& e : set.list) ... e.position (s = (u, beta)), e.residual, e.member ...
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/equilibria/unround_equilibria.hpp"
#include "abu/model/shaft_race.hpp"

namespace abu {

struct ShaftRaceEquilibria {
  /// Sorted as the race's equilibria on the equivalent rigid balancer (by |q|); each with
  /// on_unround_race set and member = its 1-based place in that list.
  std::vector<ShaftEquilibrium> list;
  std::optional<std::complex<double>> dynamic_stiffness;  ///< K_eff + i C_eff (18.8.1); nullopt: singular
  UnroundSearchReport search;  ///< the box search of §11.4 on the equivalent balancer
  std::string doubt;           ///< empty when the list is complete (§11.4, §11.11)
  Status status{};             ///< the worst polish; numerical_issue at an undamped critical speed
};

ShaftRaceEquilibria find_shaft_race_equilibria(const ShaftSystem& sys, const RaceShape& race,
                                               const UnroundSearch& search = {});

}  // namespace abu
