// Dry friction next to a smooth law (dry_friction.hpp, model.md §14.10).
#include "abu/analysis/dry_friction.hpp"

#include "abu/core/errors.hpp"
#include "abu/linear/unround_stick_set.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

DryFrictionVerdict dry_friction_verdict(const ParamsN& smooth, const StickSetOptions& options, const RaceShape* race) {
  DryFrictionVerdict out;
  if (smooth.law != FrictionLaw::coulomb && smooth.law != FrictionLaw::stribeck) return out;
  out.applies = true;
  ParamsN p = smooth;
  p.law = FrictionLaw::coulomb_set;
  if (smooth.law == FrictionLaw::stribeck)
    for (auto& b : p.balls) b.mu = b.mu_s;  // the breakaway level holds a ball at rest
  StickSetOptions o = options;
  o.trace = false;
  o.verdict_only = true;  // area, components, V, V_E: the same values, not the |q| integrals nor the spreads
  out.which = smooth.law == FrictionLaw::stribeck ? "mu_i = mu_s" : "the same mu_i";
  try {
    out.set = race ? stick_set(p, *race, o) : stick_set(p, o);
  } catch (const NotSupportedError& e) {
    out.not_defined = e.what();
  }
  return out;
}

}  // namespace abu
