// The search of a design study (docs/model.md §22.4): the box checked, the scene's own design,
// the grid, NLopt's COBYLA from the grid's best design per ball count, and the recommendation.
#include <fmt/format.h>
#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "abu/analysis/design_study.hpp"
#include "abu/analysis/machine_parts.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "design_search.hpp"

namespace abu {

namespace {

// Larger is better: the objective, or its negative.
double score(const DesignOptions& o, const DesignPoint& d) {
  return o.objective.larger_is_better() ? *d.objective : -*d.objective;
}

// a better than b: feasible first, then the score; equal scores (a probability of 1 at several
// designs) by the smaller 90th percentile residual, then the smaller ball mass.
bool better(const DesignOptions& o, const DesignPoint& a, const DesignPoint& b) {
  if (a.feasible != b.feasible) return a.feasible;
  if (!a.objective || !b.objective) return a.objective.has_value();
  if (score(o, a) != score(o, b)) return score(o, a) > score(o, b);
  if (a.outcomes && b.outcomes && a.outcomes->residual.count && b.outcomes->residual.count &&
      a.outcomes->residual.p90.value != b.outcomes->residual.p90.value)
    return a.outcomes->residual.p90.value < b.outcomes->residual.p90.value;
  return a.ball_mass < b.ball_mass;
}

// The box and the options, before any work (docs/model.md §22.5).
void check_study(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o) {
  if (o.variables.empty()) throw InputError("--vary", 0, "", "a design study needs at least one design variable");
  for (std::size_t i = 0; i < o.variables.size(); ++i) {
    const auto& v = o.variables[i];
    for (std::size_t j = 0; j < i; ++j)
      if (o.variables[j].name == v.name) throw InputError("--vary", 0, v.name, "is given twice");
    for (const auto& u : o.outcomes.uncertain)
      if (u.name == v.name)
        throw InputError("--vary", 0, v.name, "is also an --uncertain input: a quantity is designed or uncertain, not both");
    if (v.discrete() && !scene.ring)
      throw InputError("--vary", 0, "n", fmt::format("the ball count varies a [balls] ring; {} lists its balls one by "
                                                     "one (write them as [balls] count = ..., docs/cli.md)", scene.file));
    if (v.name == "alpha" && speed.points().size() != 2)
      throw InputError("--vary", 0, "alpha", "the run-up's acceleration varies a ramp (--ramp W0:W1:ALPHA)");
    if (v.name == "hold" && !(v.low >= 0)) throw InputError("--vary", 0, "hold", "the hold must be >= 0 s");
    if (v.name == "omega") throw InputError("--vary", 0, "omega", "the speed is the profile's: vary alpha or hold");
    if (!v.discrete() && v.name != "alpha" && v.name != "hold" && v.name != "unroundness" &&
        !parse_param(v.name, int(scene.balls.size())))
      throw InputError("--vary", 0, v.name,
                       "names no design variable (n, alpha, hold, unroundness or a --set name: m r l k c M_r mu ...)");
    if (v.name == "unroundness")
      for (double x : {v.low, v.high}) {
        Scene s = scene;
        set_study_input(s, v.name, x, "--vary");
      }
  }
  if (o.objective.kind == DesignObjective::Kind::maximize || o.objective.kind == DesignObjective::Kind::minimize)
    if (std::none_of(o.variables.begin(), o.variables.end(), [&](const auto& v) { return v.name == o.objective.variable; }))
      throw InputError("--objective", 0, o.objective.variable, "is not one of the --vary variables");
  for (const auto& c : o.constraints)
    if (c.kind == DesignConstraint::Kind::stable && route_of(scene) != Route::rigid)
      throw InputError("--constraint", 0, "stable",
                       "the balanced state's spectrum is that of a rigid rotor on an isotropic support, round race, "
                       "smooth law; this scene's stability is `equilibria`'s (Floquet, stick set)");
}

// Every combination of the variables' grid values, the first variable slowest.
std::vector<std::vector<double>> grid_designs(const DesignOptions& o) {
  std::vector<std::vector<double>> all{{}};
  for (const auto& v : o.variables) {
    std::vector<std::vector<double>> next;
    for (const auto& head : all)
      for (double x : v.grid()) {
        next.push_back(head);
        next.back().push_back(x);
      }
    all = std::move(next);
  }
  return all;
}

// The scene's own values of the variables (its design, the baseline).
std::vector<double> scene_values(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o) {
  std::vector<double> v;
  for (const auto& d : o.variables) {
    if (d.discrete()) v.push_back(double(scene.balls.size()));
    else if (d.name == "alpha") v.push_back(std::abs(speed.omega_dot(0.0)));
    else if (d.name == "hold") v.push_back(std::max(0.0, o.outcomes.sim.t_end - speed.end_of_change()));
    else if (d.name == "unroundness") v.push_back(1.0);  // the scene's own race
    else if (d.name == "f" && scene.balls.front().rolling_length == 0)  // mu given directly: f = mu r (model.md §1.1)
      v.push_back(scene.balls.front().mu * scene.balls.front().radius);
    else v.push_back(get(params_of<any_balls>(scene), *parse_param(d.name, int(scene.balls.size()))));
  }
  return v;
}

// u in [0, 1] -> the variable's value (log where its grid is).
double from_unit(const DesignVariable& v, double u) {
  u = std::clamp(u, 0.0, 1.0);
  return v.log ? v.low * std::pow(v.high / v.low, u) : v.low + u * (v.high - v.low);
}
double to_unit(const DesignVariable& v, double x) {
  if (v.high == v.low) return 0.0;
  return v.log ? std::log(x / v.low) / std::log(v.high / v.low) : (x - v.low) / (v.high - v.low);
}

// A constraint's value in units of its own scale, for the optimizer (stable: 1/s per rad/s of the range's low end).
double scaled(const DesignConstraint& c, double g, double u_max) {
  using K = DesignConstraint::Kind;
  switch (c.kind) {
    case K::stable: return g / c.low;
    case K::capacity: return g / u_max;
    case K::mass: return g / c.value;
    case K::stall: return g;
  }
  return g;
}

struct Search {
  const Scene& scene;
  const SpeedProfile& speed;
  const DesignOptions& o;
  DesignStudy& study;
  std::map<std::vector<double>, int> seen;
  double u_max = 0;
  int grid_size = 0;

  // The design at `values`, evaluated once (runs too when `run`).
  int at(const std::vector<double>& values, const std::string& origin, bool run) {
    if (const auto it = seen.find(values); it != seen.end()) return it->second;
    return add(machine_figures(scene, speed, o, values, origin), run);
  }

  // A design whose machine figures `d` holds, kept once (its runs too when `run`).
  int add(DesignPoint d, bool run) {
    if (const auto it = seen.find(d.values); it != seen.end()) return it->second;
    const std::vector<double> values = d.values;
    if (run && needs_runs(o)) {
      run_design(scene, speed, o, d);
      study.runs += o.outcomes.samples;
    }
    study.points.push_back(std::move(d));
    if (o.progress) o.progress(int(study.points.size()), grid_size, study.runs);
    return seen[values] = int(study.points.size()) - 1;
  }
};

struct OptimizerCall {
  Search* search;
  std::vector<double> fixed;       // the discrete values (NaN where continuous)
  std::vector<int> continuous;     // variable indices
  std::vector<double> values(const std::vector<double>& u) const {
    std::vector<double> v = fixed;
    for (std::size_t k = 0; k < continuous.size(); ++k)
      v[std::size_t(continuous[k])] = from_unit(search->o.variables[std::size_t(continuous[k])], u[k]);
    return v;
  }
  const DesignPoint& point(const std::vector<double>& u) {
    throw_if_stopped("design study");
    return search->study.points[std::size_t(search->at(values(u), "optimizer", true))];
  }
};

double optimizer_objective(const std::vector<double>& u, std::vector<double>&, void* data) {
  auto* call = static_cast<OptimizerCall*>(data);
  const DesignPoint& d = call->point(u);
  if (!d.objective) return 1e3;  // no run finished: as bad as it gets
  return call->search->o.objective.larger_is_better() ? -*d.objective : *d.objective;
}

struct ConstraintCall {
  OptimizerCall* call;
  std::size_t index;
};
double optimizer_constraint(const std::vector<double>& u, std::vector<double>&, void* data) {
  auto* c = static_cast<ConstraintCall*>(data);
  const DesignPoint& d = c->call->point(u);
  const auto& k = c->call->search->o.constraints[c->index];
  return scaled(k, d.constraints[c->index], c->call->search->u_max);
}

// COBYLA over the continuous variables from the best design of one discrete combination.
void optimize_from(Search& s, int start) {
  OptimizerCall call{&s, s.study.points[std::size_t(start)].values, {}};
  for (std::size_t i = 0; i < s.o.variables.size(); ++i)
    if (!s.o.variables[i].discrete() && s.o.variables[i].high > s.o.variables[i].low) call.continuous.push_back(int(i));
  if (call.continuous.empty()) return;
  nlopt::opt opt(nlopt::LN_COBYLA, unsigned(call.continuous.size()));
  std::vector<double> u0, step;
  for (int i : call.continuous) {
    const auto& v = s.o.variables[std::size_t(i)];
    u0.push_back(to_unit(v, call.fixed[std::size_t(i)]));
    step.push_back(0.5 / std::max(1, v.levels - 1));  // half a grid spacing
  }
  opt.set_lower_bounds(std::vector<double>(u0.size(), 0.0));
  opt.set_upper_bounds(std::vector<double>(u0.size(), 1.0));
  opt.set_initial_step(step);
  opt.set_min_objective(optimizer_objective, &call);
  std::vector<ConstraintCall> constraints;
  for (std::size_t i = 0; i < s.o.constraints.size(); ++i) constraints.push_back({&call, i});
  for (auto& c : constraints) opt.add_inequality_constraint(optimizer_constraint, &c, 0.0);
  opt.set_xtol_abs(s.o.xtol_rel);
  opt.set_maxeval(s.o.max_evaluations);
  double f = 0;
  try {
    opt.optimize(u0, f);
  } catch (const nlopt::roundoff_limited&) {
    // the step reached rounding: the points found so far stand
  } catch (const std::invalid_argument&) {
  }
}

// The constraint that keeps the best design from a better one: at the nearest evaluated design
// with a better objective that fails, the constraint it fails by the most (scaled).
std::string binding_constraint(const DesignStudy& st, const DesignOptions& o, double u_max) {
  const DesignPoint& b = st.points[std::size_t(st.best)];
  double nearest = HUGE_VAL;
  std::string name = "none: no design with a better objective was found infeasible";
  for (const auto& d : st.points) {
    if (d.feasible || !d.objective || !b.objective) continue;
    if (!(score(o, d) > score(o, b))) continue;
    double dist = 0;
    for (std::size_t i = 0; i < o.variables.size(); ++i) {
      const double du = to_unit(o.variables[i], d.values[i]) - to_unit(o.variables[i], b.values[i]);
      dist += du * du;
    }
    if (dist >= nearest) continue;
    std::size_t worst = 0;
    for (std::size_t i = 1; i < o.constraints.size(); ++i)
      if (scaled(o.constraints[i], d.constraints[i], u_max) > scaled(o.constraints[worst], d.constraints[worst], u_max))
        worst = i;
    if (o.constraints.empty()) continue;
    nearest = dist;
    name = describe(o.constraints[worst]);
  }
  return name;
}

// Feasible designs no other feasible design beats in both the objective and the ball mass.
std::vector<int> pareto_front(const DesignStudy& st, const DesignOptions& o) {
  std::vector<int> front;
  for (std::size_t i = 0; i < st.points.size(); ++i) {
    const auto& a = st.points[i];
    if (!a.feasible) continue;
    bool dominated = false;
    for (const auto& b : st.points)
      if (b.feasible && score(o, b) >= score(o, a) && b.ball_mass <= a.ball_mass &&
          (score(o, b) > score(o, a) || b.ball_mass < a.ball_mass))
        dominated = true;
    if (!dominated) front.push_back(int(i));
  }
  std::sort(front.begin(), front.end(),
            [&](int x, int y) { return st.points[std::size_t(x)].ball_mass < st.points[std::size_t(y)].ball_mass; });
  return front;
}

}  // namespace

DesignStudy run_design_study(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o) {
  if (scene.shaft)
    throw NotSupportedError("design: a flexible shaft is not studied yet; `sweep`, `map` and `basin` answer it");
  check_study(scene, speed, o);
  DesignStudy st;
  st.options = o;
  st.options.outcomes.progress = nullptr;
  st.options.progress = nullptr;
  st.speed = speed.describe();
  st.omega_final = speed.omega(o.outcomes.sim.t_end);
  Search s{scene, speed, o, st, {}, 0};
  s.u_max = scene.rotor.unbalance;
  for (const auto& u : o.outcomes.uncertain)
    if (u.name == "U") s.u_max = u.high;
  // The grid's machine figures first (no runs): constraints no grid design meets are refused
  // before any run, naming the one that comes closest.
  const auto grid = grid_designs(o);
  s.grid_size = int(grid.size());
  std::vector<DesignPoint> figures;
  for (const auto& v : grid) figures.push_back(machine_figures(scene, speed, o, v, "grid"));
  for (std::size_t c = 0; c < o.constraints.size(); ++c) {
    if (o.constraints[c].needs_runs()) continue;
    double least = HUGE_VAL;
    for (const auto& d : figures) least = std::min(least, d.constraints[c]);
    if (least > 0)
      throw InputError("--constraint", 0, describe(o.constraints[c]),
                       fmt::format("no design of the box meets it (the closest misses by {:.4g}): widen --vary or relax "
                                   "the constraint", least));
  }
  s.at(scene_values(scene, speed, o), "scene", true);
  st.baseline = 0;
  for (auto& d : figures) {  // the figures above, not computed again
    throw_if_stopped("design study");
    const bool met = d.note.empty();
    s.add(std::move(d), met);
  }
  if (o.optimize) {
    // From the best grid design of each discrete combination.
    std::map<std::vector<double>, int> best_of;
    for (std::size_t i = 1; i < st.points.size(); ++i) {
      std::vector<double> key;
      for (std::size_t k = 0; k < o.variables.size(); ++k)
        if (o.variables[k].discrete()) key.push_back(st.points[i].values[k]);
      const auto it = best_of.find(key);
      if (it == best_of.end() || better(o, st.points[i], st.points[std::size_t(it->second)])) best_of[key] = int(i);
    }
    for (const auto& [key, start] : best_of) optimize_from(s, start);
  }
  for (std::size_t i = 0; i < st.points.size(); ++i)
    if (st.best < 0 || better(o, st.points[i], st.points[std::size_t(st.best)])) st.best = int(i);
  if (st.best >= 0 && !st.points[std::size_t(st.best)].feasible) {
    st.status.merge(Outcome::not_converged, "no design met every constraint; the least bad is listed as best");
    st.binding = "none";
  } else if (st.best >= 0) {
    st.binding = binding_constraint(st, o, s.u_max);
  }
  st.pareto = pareto_front(st, o);
  return st;
}

}  // namespace abu
