// Dry friction as it is, next to a smooth coulomb or stribeck law (docs/model.md §14.10): the
// smooth laws regularize the stick (arctan in kappa); their verdict is that of creeping balls.
// The set-valued law with the same coefficients (stribeck: the breakaway level mu_s) says where
// the balls really stop, and the worst vibration they leave there.
//
//   abu::DryFrictionVerdict d = abu::dry_friction_verdict(p);   // p: a coulomb scene
//   if (d.set) ... d.set->worst_q_abs, d.set->area ...
#pragma once

#include <optional>
#include <string>

#include "abu/equilibria/shaft_stick_set.hpp"
#include "abu/equilibria/stick_set.hpp"

namespace abu {

struct DryFrictionVerdict {
  bool applies = false;         ///< the law is coulomb or stribeck
  std::string which;            ///< "the same mu_i" (coulomb) or "mu_i = mu_s" (stribeck)
  std::optional<StickSet> set;  ///< the stick set; absent where it is not defined
  std::string not_defined;      ///< why not (the set's NotSupportedError), when absent
  /// On a flexible shaft (model.md §18.17): the set of the rigid balancer the balls see through
  /// the shaft's receptance, and the shaft's figures of it.
  std::optional<ShaftStickFigures> shaft;
};

/// The stick set of coulomb-set friction with the smooth law's coefficients (no boundary
/// tracing: the verdict needs the area and the worst vibration only), on the race's paths when
/// `race` is unround (model.md §20.5). Empty (applies = false) for the other laws.
DryFrictionVerdict dry_friction_verdict(const ParamsN& smooth, const StickSetOptions& options = {},
                                        const RaceShape* race = nullptr);
/// The same for the balls of a flexible shaft (model.md §18.17): the set through the shaft's
/// receptance, not defined at an undamped critical speed.
DryFrictionVerdict dry_friction_verdict(const ShaftSystem& smooth, const StickSetOptions& options = {});

}  // namespace abu
