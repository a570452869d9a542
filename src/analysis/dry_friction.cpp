// Dry friction next to a smooth law (dry_friction.hpp, model.md §14.10).
#include "abu/analysis/dry_friction.hpp"

#include "abu/core/errors.hpp"
#include "abu/linear/unround_stick_set.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

namespace {
// The set-valued law of a smooth one: its mu_i (stribeck: the breakaway level mu_s, which holds
// a ball at rest), and the verdict's options.
ParamsN resting_balls(const ParamsN& smooth) {
  ParamsN p = smooth;
  p.law = FrictionLaw::coulomb_set;
  if (smooth.law == FrictionLaw::stribeck)
    for (auto& b : p.balls) b.mu = b.mu_s;
  return p;
}
StickSetOptions verdict_options(StickSetOptions o) {
  o.trace = false;
  o.verdict_only = true;  // area, components, V, V_E: the same values, not the |q| integrals nor the spreads
  return o;
}
bool has_resting_law(FrictionLaw law) { return law == FrictionLaw::coulomb || law == FrictionLaw::stribeck; }
std::string coefficients(FrictionLaw law) { return law == FrictionLaw::stribeck ? "mu_i = mu_s" : "the same mu_i"; }
}  // namespace

DryFrictionVerdict dry_friction_verdict(const ParamsN& smooth, const StickSetOptions& options, const RaceShape* race) {
  DryFrictionVerdict out;
  if (!has_resting_law(smooth.law)) return out;
  out.applies = true;
  out.which = coefficients(smooth.law);
  const ParamsN p = resting_balls(smooth);
  try {
    out.set = race ? stick_set(p, *race, verdict_options(options)) : stick_set(p, verdict_options(options));
  } catch (const NotSupportedError& e) {
    out.not_defined = e.what();
  }
  return out;
}

DryFrictionVerdict dry_friction_verdict(const ShaftSystem& smooth, const StickSetOptions& options) {
  DryFrictionVerdict out;
  if (!has_resting_law(smooth.balancer.law)) return out;
  out.applies = true;
  out.which = coefficients(smooth.balancer.law);
  ShaftSystem sys = smooth;
  sys.balancer = resting_balls(smooth.balancer);  // the receptance reads no law (§18.17)
  try {
    ShaftStickSet s = shaft_stick_set(sys, verdict_options(options));
    out.set = std::move(s.set);
    out.shaft = std::move(s.shaft);
  } catch (const NotSupportedError& e) {
    out.not_defined = e.what();
  }
  return out;
}

}  // namespace abu
