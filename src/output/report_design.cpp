// The design study's files and its answer in words (docs/model.md §22).
#include "abu/output/report_design.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "abu/output/format.hpp"

namespace abu {

namespace {

bool residual_objective(const DesignObjective& o) {
  using K = DesignObjective::Kind;
  return o.kind == K::median || o.kind == K::p90 || o.kind == K::worst;
}

// The objective's value in words: "94.0 %", "2.31 µm", or the variable's value.
std::string objective_text(const DesignOptions& o, const DesignPoint& d) {
  if (!d.objective) return "not computed";
  if (o.objective.kind == DesignObjective::Kind::below) return fmt::format("{:.1f} %", 100 * *d.objective);
  if (residual_objective(o.objective)) return fmt::format("{:.4g} µm", *d.objective * 1e6);
  return fmt::format("{:.10g}", *d.objective);
}

std::string values_text(const DesignOptions& o, const DesignPoint& d) {
  std::string out;
  for (std::size_t i = 0; i < o.variables.size(); ++i)
    out += fmt::format("{}{} = {:.6g}", i ? ", " : "", o.variables[i].name, d.values[i]);
  return out;
}

// The run figures of a design in words (empty if not run).
std::string figures_text(const DesignPoint& d) {
  if (!d.outcomes || d.outcomes->runs == 0) return "";
  const OutcomeSummary& s = *d.outcomes;
  return fmt::format("balanced in {:.1f} % of runs, residual below the limit in {:.1f} % [{:.1f}, {:.1f}], median "
                     "residual {:.4g} µm, 90th percentile {:.4g} µm, worst {:.4g} µm, stalled {:.1f} %",
                     100 * s.balanced.value, 100 * s.below_limit.value, 100 * s.below_limit.low,
                     100 * s.below_limit.high, s.residual.median.value * 1e6, s.residual.p90.value * 1e6,
                     s.residual.worst.value * 1e6, 100 * s.stalled.value);
}

std::string json_values(const DesignPoint& d) {
  std::string out;
  for (double v : d.values) out += fmt::format("{}{}", out.empty() ? "" : ", ", format_number(v, "design value"));
  return "[" + out + "]";
}

std::string json_point(const DesignPoint& d) {
  std::string g;
  for (double x : d.constraints) g += fmt::format("{}{}", g.empty() ? "" : ", ", format_number(x, "constraint"));
  std::string runs = "null";
  if (d.outcomes && d.outcomes->runs > 0) {
    const OutcomeSummary& s = *d.outcomes;
    runs = fmt::format("{{\"runs\": {}, \"balanced\": {}, \"below_limit\": [{}, {}, {}], \"residual_median\": {}, "
                       "\"residual_p90\": {}, \"residual_worst\": {}, \"stalled\": {}}}",
                       s.runs, format_number(s.balanced.value), format_number(s.below_limit.value),
                       format_number(s.below_limit.low), format_number(s.below_limit.high),
                       format_number(s.residual.median.value), format_number(s.residual.p90.value),
                       format_number(s.residual.worst.value), format_number(s.stalled.value));
  }
  return fmt::format("{{\"origin\": {}, \"values\": {}, \"feasible\": {}, \"objective\": {}, \"constraints\": [{}], "
                     "\"ball_mass\": {}, \"capacity\": {}, \"outcomes\": {}, \"note\": {}}}",
                     json_string(d.origin), json_values(d), d.feasible ? "true" : "false",
                     json_number_or_null(d.objective, "objective"), g,
                     format_number(d.ball_mass), format_number(d.capacity), runs, json_string(d.note));
}

}  // namespace

std::string design_csv(const DesignStudy& s, std::string_view header) {
  const DesignOptions& o = s.options;
  std::string out(header);
  out += "design,origin";
  for (const auto& v : o.variables) out += fmt::format(",{}", v.name);
  out += ",feasible,objective";
  for (std::size_t i = 0; i < o.constraints.size(); ++i) out += fmt::format(",g{}", i + 1);
  out += ",ball_mass,capacity,runs,balanced,below_limit,below_low,below_high,residual_median,residual_p90,"
         "residual_worst,stalled,bare_rotor,pareto,recommended,note\n";
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const DesignPoint& d = s.points[k];
    out += fmt::format("{},{}", k, d.origin);
    for (double v : d.values) out += fmt::format(",{}", format_number(v, "design value"));
    out += fmt::format(",{},{}", d.feasible ? 1 : 0, d.objective ? format_number(*d.objective, "objective") : "");
    for (double g : d.constraints) out += fmt::format(",{}", format_number(g, "constraint"));
    out += fmt::format(",{},{}", format_number(d.ball_mass), format_number(d.capacity));
    if (d.outcomes && d.outcomes->runs > 0) {
      const OutcomeSummary& r = *d.outcomes;
      out += fmt::format(",{},{},{},{},{},{},{},{},{},{}", r.runs, format_number(r.balanced.value),
                         format_number(r.below_limit.value), format_number(r.below_limit.low),
                         format_number(r.below_limit.high), format_number(r.residual.median.value),
                         format_number(r.residual.p90.value), format_number(r.residual.worst.value),
                         format_number(r.stalled.value), format_number(r.bare_rotor_median));
    } else {
      out += ",0,,,,,,,,,";
    }
    const bool front = std::find(s.pareto.begin(), s.pareto.end(), int(k)) != s.pareto.end();
    std::string note = d.note;
    std::replace(note.begin(), note.end(), ',', ';');
    out += fmt::format(",{},{},{}\n", front ? 1 : 0, int(k) == s.best ? 1 : 0, note);
  }
  return out;
}

std::string design_json(const DesignStudy& s, std::string_view command_line, std::string_view scene_file) {
  const DesignOptions& o = s.options;
  std::string vars, cons, points, front;
  for (const auto& v : o.variables)
    vars += fmt::format("{}{{\"name\": {}, \"low\": {}, \"high\": {}, \"levels\": {}, \"log\": {}}}",
                        vars.empty() ? "" : ", ", json_string(v.name), format_number(v.low), format_number(v.high),
                        v.levels, v.log ? "true" : "false");
  for (const auto& c : o.constraints) cons += fmt::format("{}{}", cons.empty() ? "" : ", ", json_string(describe(c)));
  for (const auto& d : s.points) points += fmt::format("{}\n    {}", points.empty() ? "" : ",", json_point(d));
  for (int k : s.pareto) front += fmt::format("{}{}", front.empty() ? "" : ", ", k);
  return fmt::format("{{\n  \"command\": {},\n  \"scene\": {},\n  \"status\": {},\n  \"reason\": {},\n  \"speed\": {},\n"
                     "  \"objective\": {},\n  \"variables\": [{}],\n  \"constraints\": [{}],\n  \"samples\": {},\n"
                     "  \"seed\": {},\n  \"runs\": {},\n  \"recommended\": {},\n  \"baseline\": {},\n  \"binding\": {},\n"
                     "  \"pareto\": [{}],\n  \"designs\": [{}\n  ]\n}}\n",
                     json_string(command_line), json_string(scene_file), json_string(to_string(s.status.outcome)),
                     json_string(s.status.reason.view()), json_string(s.speed), json_string(describe(o.objective)), vars,
                     cons, o.outcomes.samples, o.outcomes.seed, s.runs, s.best, s.baseline, json_string(s.binding), front,
                     points);
}

std::string design_text(const DesignStudy& s) {
  const DesignOptions& o = s.options;
  std::string out = fmt::format("design: {} designs evaluated ({} machine runs), objective: {}; {}\n", s.points.size(),
                                s.runs, describe(o.objective), s.speed);
  if (s.best < 0) return out + "  no design could be evaluated\n";
  const DesignPoint& b = s.points[std::size_t(s.best)];
  const DesignPoint& base = s.points[std::size_t(s.baseline)];
  out += fmt::format("  recommended{}: {} ({} design): {} = {}\n", b.feasible ? "" : " (meets NOT every constraint)",
                     values_text(o, b), b.origin, o.objective.needs_runs() ? "objective" : describe(o.objective),
                     objective_text(o, b));
  if (const auto f = figures_text(b); !f.empty()) out += "    " + f + "\n";
  out += fmt::format("    total ball mass {:.4g} kg, capacity {:.4g} kg m; binding constraint: {}\n", b.ball_mass,
                     b.capacity, s.binding);
  out += fmt::format("  the scene's own design: {}: {}{}\n", values_text(o, base), objective_text(o, base),
                     base.feasible ? "" : fmt::format(" (infeasible: {})", base.note.empty() ? "a constraint fails" : base.note));
  if (b.objective && base.objective) {
    const double gain = *b.objective - *base.objective;
    if (o.objective.kind == DesignObjective::Kind::below)
      out += fmt::format("  better by {:+.1f} percentage points\n", 100 * gain);
    else if (residual_objective(o.objective) && *b.objective > 0)
      out += fmt::format("  the residual {:.3g} times smaller\n", *base.objective / *b.objective);
  }
  out += fmt::format("  Pareto front (objective against total ball mass): {} designs\n", s.pareto.size());
  for (int k : s.pareto) {
    const DesignPoint& d = s.points[std::size_t(k)];
    out += fmt::format("    {}: {} at {:.4g} kg\n", values_text(o, d), objective_text(o, d), d.ball_mass);
  }
  if (!s.status.ok()) out += fmt::format("  {}\n", s.status.reason.view());
  return out;
}

}  // namespace abu
