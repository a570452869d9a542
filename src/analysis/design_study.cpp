// Design studies (docs/model.md §22): the variables, objectives and constraints, a design's
// machine and its evaluation, the grid, and the recommendation.
#include "abu/analysis/design_study.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "abu/analysis/machine_parts.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "abu/input/option_values.hpp"
#include "abu/scan/scan.hpp"
#include "design_search.hpp"

namespace abu {

namespace {

std::vector<double> numbers(const std::string& text, const std::string& origin) {
  std::string list = text;
  std::replace(list.begin(), list.end(), ':', ',');
  return parse_real_list(list, origin);
}

// "NAME=REST" split; throws naming the expected form.
std::pair<std::string, std::string> assignment(const std::string& text, const std::string& origin,
                                               const std::string& form) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError(origin, 0, text, "expected " + form);
  return {text.substr(0, eq), text.substr(eq + 1)};
}

double ball_mass(const Scene& s) {
  double m = 0;
  for (const auto& b : s.balls) m += b.mass;
  return m;
}

double capacity(const Scene& s) {
  double c = 0;
  for (const auto& b : s.balls) c += b.mass * b.race_radius;
  return c;
}

// The unbalances the `stable` and `capacity` constraints hold for: five evenly over U's uncertain
// range (its ends included), else the scene's (docs/model.md §22.3).
std::vector<double> unbalances(const Scene& s, const OutcomeOptions& o) {
  for (const auto& u : o.uncertain)
    if (u.name == "U") return u.high > u.low ? grid_values(u.low, u.high, 4, false) : std::vector<double>{u.low};
  return {s.rotor.unbalance};
}

// The largest abscissa of the balanced states at one speed (+1e3 where none exists).
double balanced_abscissa_at(const Scene& scene, double omega) {
  double worst = -HUGE_VAL;
  bool any = false;
  if (scene.balls.size() == 2) {
    Params p = params_of<2>(scene);
    p.omega = omega;
    const Analysis a = analyze(p);
    const auto points = a.equilibria.points();
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].family == Family::balanced) any = true, worst = std::max(worst, a.spectra[i].abscissa);
  } else {
    ParamsN p = params_of<any_balls>(scene);
    p.omega = omega;
    const AnalysisN a = analyze(p);
    const auto points = a.equilibria.points();
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].on_balanced_set) any = true, worst = std::max(worst, a.spectra[i].abscissa);
  }
  return any ? worst : 1e3;
}

}  // namespace

std::vector<double> DesignVariable::grid() const {
  if (discrete()) {
    std::vector<double> v;
    for (int k = int(std::lround(low)); k <= int(std::lround(high)); ++k) v.push_back(k);
    return v;
  }
  return levels == 1 ? std::vector<double>{low} : grid_values(low, high, levels - 1, log);
}

DesignVariable parse_design_variable(const std::string& text, const std::string& origin) {
  const std::string form = "NAME=LOW:HIGH[:LEVELS[:log]], e.g. m=1e-5:5e-5:5 or n=2:4";
  auto [name, rest] = assignment(text, origin, form);
  DesignVariable v;
  v.name = name;
  if (rest.size() > 4 && rest.substr(rest.size() - 4) == ":log") {
    v.log = true;
    rest.resize(rest.size() - 4);
  }
  const auto x = numbers(rest, origin);
  if (x.size() < 2 || x.size() > 3) throw InputError(origin, 0, text, "expected " + form);
  v.low = x[0];
  v.high = x[1];
  if (x.size() == 3) {
    if (x[2] != std::floor(x[2]) || x[2] < 1 || x[2] > 1000)
      throw InputError(origin, 0, name, fmt::format("LEVELS must be an integer in 1..1000, got {}", x[2]));
    v.levels = int(x[2]);
  }
  if (!(v.low <= v.high)) throw InputError(origin, 0, name, fmt::format("an empty range: LOW {} > HIGH {}", v.low, v.high));
  if (v.low == v.high) v.levels = 1;
  if (v.log && !(v.low > 0)) throw InputError(origin, 0, name, "a log grid needs LOW > 0");
  if (v.discrete() && (v.low != std::floor(v.low) || v.high != std::floor(v.high) || v.low < kSceneMinBalls ||
                       v.high > kSceneMaxBalls))
    throw InputError(origin, 0, name, fmt::format("the ball count takes integers in {}..{}", kSceneMinBalls, kSceneMaxBalls));
  return v;
}

DesignObjective parse_design_objective(const std::string& text, const std::string& origin) {
  DesignObjective o;
  using K = DesignObjective::Kind;
  if (text == "below") o.kind = K::below;
  else if (text == "median") o.kind = K::median;
  else if (text == "p90") o.kind = K::p90;
  else if (text == "worst") o.kind = K::worst;
  else if (text.rfind("max:", 0) == 0 && text.size() > 4) o.kind = K::maximize, o.variable = text.substr(4);
  else if (text.rfind("min:", 0) == 0 && text.size() > 4) o.kind = K::minimize, o.variable = text.substr(4);
  else
    throw InputError(origin, 0, text,
                     "expected below (the probability that the residual stays below the limit), median, p90, worst "
                     "(of the residual), max:NAME or min:NAME (a design variable)");
  return o;
}

std::string describe(const DesignObjective& o) {
  using K = DesignObjective::Kind;
  switch (o.kind) {
    case K::below: return "the probability that the residual stays below the limit";
    case K::median: return "the median residual";
    case K::p90: return "the 90th percentile residual";
    case K::worst: return "the worst residual";
    case K::maximize: return "the largest " + o.variable;
    case K::minimize: return "the smallest " + o.variable;
  }
  return "";
}

DesignConstraint parse_design_constraint(const std::string& text, const std::string& origin) {
  const std::string form = "stable=W_LO:W_HI, capacity=FACTOR, mass=KG or stall=FRACTION";
  const auto [name, rest] = assignment(text, origin, form);
  const auto x = numbers(rest, origin);
  DesignConstraint c;
  using K = DesignConstraint::Kind;
  if (name == "stable" && x.size() == 2) {
    c.kind = K::stable, c.low = x[0], c.high = x[1];
    if (!(c.low > 0 && c.low < c.high)) throw InputError(origin, 0, name, "the speed range needs 0 < W_LO < W_HI [rad/s]");
  } else if (name == "capacity" && x.size() == 1) {
    c.kind = K::capacity, c.value = x[0];
    if (!(c.value > 0)) throw InputError(origin, 0, name, "the capacity factor must be > 0");
  } else if (name == "mass" && x.size() == 1) {
    c.kind = K::mass, c.value = x[0];
    if (!(c.value > 0)) throw InputError(origin, 0, name, "the total ball mass limit must be > 0 kg");
  } else if (name == "stall" && x.size() == 1) {
    c.kind = K::stall, c.value = x[0];
    if (!(c.value >= 0 && c.value < 1)) throw InputError(origin, 0, name, "the stall fraction must lie in [0, 1)");
  } else {
    throw InputError(origin, 0, text, "expected " + form);
  }
  return c;
}

std::string describe(const DesignConstraint& c) {
  using K = DesignConstraint::Kind;
  switch (c.kind) {
    case K::stable: return fmt::format("a stable balanced state over {:g}..{:g} rad/s", c.low, c.high);
    case K::capacity: return fmt::format("capacity >= {:g} x the largest unbalance", c.value);
    case K::mass: return fmt::format("total ball mass <= {:g} kg", c.value);
    case K::stall: return fmt::format("stalled runs <= {:g} %", 100 * c.value);
  }
  return "";
}

DesignedMachine designed_machine(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o,
                                 const std::vector<double>& values) {
  DesignedMachine m{scene, speed, o.outcomes.sim.t_end};
  double hold = -1;
  for (std::size_t i = 0; i < o.variables.size(); ++i)  // the count first: the others then set every ball
    if (o.variables[i].discrete()) set_ball_count(m.scene, int(std::lround(values[i])), "--vary");
  for (std::size_t i = 0; i < o.variables.size(); ++i) {
    const auto& v = o.variables[i];
    if (v.discrete()) continue;
    if (v.name == "hold") {
      hold = values[i];
    } else if (v.name == "alpha") {
      const auto& p = speed.points();
      m.speed = SpeedProfile::ramp(p.front().omega, p.back().omega, values[i], "--vary");
    } else {
      set_study_input(m.scene, v.name, values[i], "--vary");
    }
  }
  if (hold >= 0) m.t_end = m.speed.end_of_change() + hold;
  return m;
}

double balanced_abscissa_over(const Scene& scene, double low, double high, const std::vector<double>& us,
                              int speed_points) {
  const std::vector<double> speeds = grid_values(low, high, std::max(2, speed_points) - 1, true);
  double worst = -HUGE_VAL;
  for (double U : us) {
    Scene s = scene;
    s.rotor.unbalance = U;
    std::vector<double> a(speeds.size());
    for (std::size_t k = 0; k < speeds.size(); ++k) a[k] = balanced_abscissa_at(s, speeds[k]);
    const std::size_t top = std::size_t(std::max_element(a.begin(), a.end()) - a.begin());
    worst = std::max(worst, a[top]);
    // A largest value inside the range: GSL's Brent minimizer of -abscissa between its neighbours.
    if (top == 0 || top + 1 == speeds.size() || a[top] >= 1e3 || !(a[top] > a[top - 1] && a[top] > a[top + 1])) continue;
    struct Ctx { const Scene* s; } ctx{&s};
    gsl_function f{[](double w, void* c) { return -balanced_abscissa_at(*static_cast<Ctx*>(c)->s, w); }, &ctx};
    const std::unique_ptr<gsl_min_fminimizer, decltype(&gsl_min_fminimizer_free)> m(
        gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent), &gsl_min_fminimizer_free);
    if (gsl_min_fminimizer_set_with_values(m.get(), &f, speeds[top], -a[top], speeds[top - 1], -a[top - 1],
                                           speeds[top + 1], -a[top + 1]) != GSL_SUCCESS)
      continue;
    for (int it = 0; it < 60; ++it) {
      if (gsl_min_fminimizer_iterate(m.get()) != GSL_SUCCESS) break;
      if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m.get()), gsl_min_fminimizer_x_upper(m.get()), 0, 1e-10) ==
          GSL_SUCCESS)
        break;
    }
    worst = std::max(worst, -gsl_min_fminimizer_f_minimum(m.get()));
  }
  return worst;
}

// The design's machine: the scene's own as it is (its values are only reported), else the values applied.
DesignedMachine machine_of(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o, const DesignPoint& d) {
  if (d.origin == "scene") return {scene, speed, o.outcomes.sim.t_end};
  return designed_machine(scene, speed, o, d.values);
}

DesignPoint machine_figures(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o,
                            const std::vector<double>& values, const std::string& origin) {
  DesignPoint d;
  d.values = values;
  d.origin = origin;
  const DesignedMachine m = machine_of(scene, speed, o, d);
  d.ball_mass = ball_mass(m.scene);
  d.capacity = capacity(m.scene);
  const auto us = unbalances(m.scene, o.outcomes);
  const double u_max = *std::max_element(us.begin(), us.end());
  using K = DesignConstraint::Kind;
  for (const auto& c : o.constraints) {
    double g = 0;
    if (c.kind == K::stable) g = balanced_abscissa_over(m.scene, c.low, c.high, us, o.speed_points);
    if (c.kind == K::capacity) g = c.value * u_max - d.capacity;
    if (c.kind == K::mass) g = d.ball_mass - c.value;
    d.constraints.push_back(g);
    if (!c.needs_runs() && g > 0 && d.note.empty()) d.note = describe(c) + " is not met";
  }
  for (std::size_t i = 0; i < o.variables.size(); ++i)
    if (!o.objective.needs_runs() && o.variables[i].name == o.objective.variable) d.objective = values[i];
  d.feasible = d.objective.has_value() && d.note.empty() &&
               std::all_of(d.constraints.begin(), d.constraints.end(), [](double g) { return g <= 0; });
  return d;
}

bool needs_runs(const DesignOptions& o) {
  return o.objective.needs_runs() ||
         std::any_of(o.constraints.begin(), o.constraints.end(), [](const auto& c) { return c.needs_runs(); });
}

void run_design(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o, DesignPoint& d) {
  const DesignedMachine m = machine_of(scene, speed, o, d);
  OutcomeOptions oo = o.outcomes;
  oo.sim.t_end = m.t_end;
  oo.progress = nullptr;
  const OutcomeStudy study = analyze_outcomes(m.scene, m.speed, oo);
  if (study.status.outcome == Outcome::not_converged) throw Interrupted(stop_signal(), "design study");
  d.outcomes = study.summary;
  const OutcomeSummary& s = study.summary;
  for (std::size_t i = 0; i < o.constraints.size(); ++i)
    if (o.constraints[i].kind == DesignConstraint::Kind::stall) d.constraints[i] = s.stalled.value - o.constraints[i].value;
  using O = DesignObjective::Kind;
  if (s.runs > 0) {
    if (o.objective.kind == O::below) d.objective = s.below_limit.value;
    if (o.objective.kind == O::median) d.objective = s.residual.median.value;
    if (o.objective.kind == O::p90) d.objective = s.residual.p90.value;
    if (o.objective.kind == O::worst) d.objective = s.residual.worst.value;
  }
  if (!study.status.ok()) d.note = std::string(study.status.reason.view());
  d.feasible = d.objective.has_value() && d.note.empty() &&
               std::all_of(d.constraints.begin(), d.constraints.end(), [](double g) { return g <= 0; });
}

}  // namespace abu
