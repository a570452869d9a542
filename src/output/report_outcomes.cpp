// The study's files and its answer in words (docs/model.md §21).
#include "abu/output/report_outcomes.hpp"

#include <fmt/format.h>

#include "abu/output/format.hpp"

namespace abu {

namespace {

std::string opt(const std::optional<double>& v, std::string_view what) {
  return v ? format_number(*v, what) : std::string();
}

std::string json_quantile(const QuantileEstimate& q, std::string_view what) {
  return fmt::format("{{\"p\": {}, \"value\": {}, \"low\": {}, \"high\": {}}}", q.probability,
                     format_number(q.value, what), json_number_or_null(q.low, what), json_number_or_null(q.high, what));
}

std::string json_figure(const FigureStatistics& f, std::string_view what) {
  if (f.count == 0) return "{\"runs\": 0}";
  return fmt::format("{{\"runs\": {}, \"median\": {}, \"p90\": {}, \"worst\": {}}}", f.count,
                     json_quantile(f.median, what), json_quantile(f.p90, what), format_number(f.worst.value, what));
}

std::string json_proportion(const ProportionEstimate& p) {
  return fmt::format("{{\"runs\": {}, \"events\": {}, \"value\": {}, \"low\": {}, \"high\": {}}}", p.count, p.events,
                     format_number(p.value), format_number(p.low), format_number(p.high));
}

std::string figure_line(std::string_view what, const FigureStatistics& f, double scale, std::string_view unit) {
  if (f.count == 0) return fmt::format("  {}: no run has it\n", what);
  return fmt::format("  {}: median {}, 90th percentile {}, worst {:.4g}{} (of {} runs)\n", what,
                     interval_text(f.median, scale, unit), interval_text(f.p90, scale, unit), f.worst.value * scale,
                     unit, f.count);
}

std::string percent(const ProportionEstimate& p) {
  return fmt::format("{:.1f} % [{:.1f}, {:.1f}]", 100 * p.value, 100 * p.low, 100 * p.high);
}

}  // namespace

std::string interval_text(const QuantileEstimate& q, double scale, std::string_view unit) {
  const auto side = [&](const std::optional<double>& v) { return v ? fmt::format("{:.4g}", *v * scale) : std::string("-"); };
  return fmt::format("{:.4g}{} [{}, {}]", q.value * scale, unit, side(q.low), side(q.high));
}

std::string outcomes_csv(const OutcomeStudy& s, std::string_view header) {
  std::string out(header);
  out += "sample";
  for (int i = 1; i <= s.balls; ++i) out += fmt::format(",beta{}_0", i);
  for (const auto& u : s.options.uncertain) {
    out += ',';
    out += u.name;
  }
  out += ",outcome,residual_q,bare_rotor_q,balls_fixed_q,ratio_bare,ratio_fixed,peak_q,peak_q_run_up,stalled,"
         "settle_time,stuck_off_balance,steps\n";
  for (const auto& x : s.samples) {
    if (!x.done) continue;
    out += std::to_string(x.index);
    for (double b : x.beta0) out += fmt::format(",{}", format_number(b, "beta0"));
    for (double v : x.inputs) out += fmt::format(",{}", format_number(v, "uncertain input"));
    const bool ok = x.outcome != "failed";
    out += fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{}\n", x.outcome, ok ? format_number(x.residual, "residual") : "",
                       format_number(x.bare_rotor, "bare rotor"), format_number(x.balls_fixed, "balls fixed"),
                       ok && x.bare_rotor > 0 ? format_number(x.residual / x.bare_rotor, "ratio") : "",
                       ok && x.balls_fixed > 0 ? format_number(x.residual / x.balls_fixed, "ratio") : "",
                       ok ? format_number(x.peak, "peak") : "", ok ? opt(x.peak_run_up, "peak") : "",
                       ok ? (x.stalled ? "1" : "0") : "", ok ? opt(x.settle_time, "settle time") : "",
                       ok ? (x.stuck_off_balance ? "1" : "0") : "", x.steps);
  }
  return out;
}

std::string outcomes_json(const OutcomeStudy& s, std::string_view command_line, std::string_view scene_file) {
  const OutcomeSummary& m = s.summary;
  std::string inputs;
  for (const auto& u : s.options.uncertain)
    inputs += fmt::format("{}{{\"name\": {}, \"low\": {}, \"high\": {}}}", inputs.empty() ? "" : ", ",
                          json_string(u.name), format_number(u.low), format_number(u.high));
  return fmt::format(
      "{{\n  \"command\": {},\n  \"scene\": {},\n  \"status\": {},\n  \"reason\": {},\n  \"balls\": {},\n"
      "  \"speed\": {},\n  \"omega_final\": {},\n  \"t_end\": {},\n  \"design\": {{\"kind\": {}, \"seed\": {}, "
      "\"samples\": {}}},\n  \"uncertain\": [{}],\n  \"confidence\": {},\n  \"runs\": {},\n  \"failed\": {},\n"
      "  \"residual_limit\": {},\n  \"bare_rotor_median\": {},\n  \"residual_q\": {},\n  \"ratio_bare\": {},\n"
      "  \"ratio_fixed\": {},\n  \"peak_q\": {},\n  \"settle_time\": {},\n  \"balanced\": {},\n  \"below_limit\": {},\n"
      "  \"stalled\": {},\n  \"stuck_off_balance\": {},\n  \"not_settled\": {}\n}}\n",
      json_string(command_line), json_string(scene_file), json_string(to_string(s.status.outcome)),
      json_string(s.status.reason.view()), s.balls, json_string(s.speed), format_number(s.omega_final),
      format_number(s.options.sim.t_end), json_string(to_string(s.options.design)), s.options.seed, s.options.samples,
      inputs, format_number(s.options.confidence), m.runs, m.failed, format_number(s.options.residual_limit),
      format_number(m.bare_rotor_median), json_figure(m.residual, "residual"), json_figure(m.ratio_bare, "ratio"),
      json_figure(m.ratio_fixed, "ratio"), json_figure(m.peak, "peak"), json_figure(m.settle_time, "settle time"),
      json_proportion(m.balanced), json_proportion(m.below_limit), json_proportion(m.stalled),
      json_proportion(m.stuck_off_balance), json_proportion(m.not_settled));
}

std::string outcomes_text(const OutcomeStudy& s) {
  const OutcomeSummary& m = s.summary;
  std::string inputs;
  for (const auto& u : s.options.uncertain) inputs += fmt::format("; {} in [{:g}, {:g}]", u.name, u.low, u.high);
  std::string out = fmt::format(
      "outcomes: {} runs of {} balls, {} to t = {:g} s (final speed {:g} rad/s); starts at rest, every ball's angle "
      "drawn ({}, seed {}){}; intervals at {:g} %\n",
      m.runs, s.balls, s.speed, s.options.sim.t_end, s.omega_final, to_string(s.options.design), s.options.seed, inputs,
      100 * s.options.confidence);
  if (m.runs == 0) return out + "  no run finished\n";
  const std::string limit = s.options.residual_limit > 0 ? fmt::format("{:.4g} µm", s.options.residual_limit * 1e6)
                                                         : std::string("the bare rotor's");
  out += fmt::format("  verdict: balanced in {} of runs; the residual stays below {} in {}; the median run leaves "
                     "{:.4g} µm, {:.3g} times the bare rotor's {:.4g} µm\n",
                     percent(m.balanced), limit, percent(m.below_limit), m.residual.median.value * 1e6,
                     m.ratio_bare.count ? m.ratio_bare.median.value : 0.0, m.bare_rotor_median * 1e6);
  out += figure_line("residual |q| at the end", m.residual, 1e6, " µm");
  out += figure_line("against the bare rotor (16.5.1)", m.ratio_bare, 1, "x");
  out += figure_line("against the balls held at their start", m.ratio_fixed, 1, "x");
  out += figure_line("peak |q| on the way", m.peak, 1e6, " µm");
  out += fmt::format("  ended: balanced {}, stuck away from balance {}, stalled {}, not settled {}\n",
                     percent(m.balanced), percent(m.stuck_off_balance), percent(m.stalled), percent(m.not_settled));
  out += figure_line("settle time (settled runs)", m.settle_time, 1, " s");
  if (m.failed > 0) out += fmt::format("  {} runs failed numerically (listed in the CSV as failed)\n", m.failed);
  return out;
}

}  // namespace abu
