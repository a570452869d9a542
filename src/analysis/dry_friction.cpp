// Dry friction next to a smooth law (dry_friction.hpp, model.md §14.10).
#include "abu/analysis/dry_friction.hpp"

#include <algorithm>

#include "abu/core/errors.hpp"
#include "abu/core/parallel.hpp"
#include "abu/core/widen_params.hpp"
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
}  // namespace

bool has_dry_verdict(FrictionLaw law) { return law == FrictionLaw::coulomb || law == FrictionLaw::stribeck; }
std::string dry_coefficients(FrictionLaw law) {
  if (!has_dry_verdict(law)) return {};
  return law == FrictionLaw::stribeck ? "mu_i = mu_s" : "the same mu_i";
}

DryFigures dry_figures(const DryFrictionVerdict& d) {
  DryFigures f;
  if (!d.set) return f;
  const StickSet& s = *d.set;
  f.defined = true;
  f.balanced_exists = s.balanced_exists;
  f.worst_q_abs = s.worst_q_abs;
  f.whole_set_q_abs = s.worst_q_abs_any;
  f.bare_rotor_q_abs = s.bare_rotor_q_abs;
  f.area_fraction = s.area_fraction;
  return f;
}

DryAlong dry_figures_along(std::span<const double> values, std::span<const ParamsN> params,
                           const DryRequest& request) {
  DryAlong out;
  if (params.empty() || !has_dry_verdict(params.front().law) || request.rows == DryRows::off) return out;
  out.which = dry_coefficients(params.front().law);
  // each distinct value once, in ascending order
  std::vector<std::size_t> order(values.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  order.erase(std::unique(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] == values[b]; }),
              order.end());
  out.values = order.size();
  for (const std::size_t k : order) out.scans += !whole_torus_by_bound(resting_balls(params[k]));
  out.scan_limit = params.front().n_balls() == 2 ? kDryAutomaticScans : kDryAutomaticScansN;
  if (request.rows == DryRows::automatic && out.scans > out.scan_limit) return out;
  std::vector<DryFigures> figures(order.size());
  // each value's set alone: the same figures on any number of threads
  for_each_index(int(order.size()), request.threads, [&](int j) {
    figures[std::size_t(j)] = dry_figures(dry_friction_verdict(params[order[std::size_t(j)]], request.stick));
    return true;
  });
  for (std::size_t j = 0; j < order.size(); ++j) out.figures.emplace(values[order[j]], figures[j]);
  return out;
}

DryAlong dry_figures_along(const ParamsN& smooth, ParamRef param, std::span<const double> values,
                           const DryRequest& request) {
  std::vector<ParamsN> params(values.size(), smooth);
  for (std::size_t k = 0; k < values.size(); ++k) set(params[k], param, values[k]);
  return dry_figures_along(values, params, request);
}

namespace {
template <class Run>
std::vector<double> row_values(const Run& run) {
  std::vector<double> values;
  for (const auto& branch : run.branches)
    for (const auto& pt : branch.points) values.push_back(double(pt.parameter));
  return values;
}
}  // namespace

DryAlong dry_figures_along(const Params& smooth, const ContinuationRun& run, const DryRequest& request) {
  return dry_figures_along(widen(smooth), run.param, row_values(run), request);
}
DryAlong dry_figures_along(const ParamsN& smooth, const ContinuationRunN& run, const DryRequest& request) {
  return dry_figures_along(smooth, run.param, row_values(run), request);
}

DryFrictionVerdict dry_friction_verdict(const ParamsN& smooth, const StickSetOptions& options, const RaceShape* race) {
  DryFrictionVerdict out;
  if (!has_dry_verdict(smooth.law)) return out;
  out.applies = true;
  out.which = dry_coefficients(smooth.law);
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
  if (!has_dry_verdict(smooth.balancer.law)) return out;
  out.applies = true;
  out.which = dry_coefficients(smooth.balancer.law);
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
