// Trajectory CSV and summary JSON of a simulation (report_simulation.hpp, model.md §15).
#include "abu/output/report_simulation.hpp"

#include <fmt/format.h>

#include <functional>

#include <cmath>
#include <numbers>

#include "abu/output/format.hpp"
#include "abu/output/provenance.hpp"

namespace abu {

namespace {

std::string number_list(const std::vector<double>& v, std::string_view what) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format_number(v[i], what);
  return out + "]";
}

template <int N>
std::vector<double> end_angles(const SimulationResult<N>& r, int n) {
  std::vector<double> beta(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) beta[std::size_t(i)] = r.x_end(2 + i);
  return beta;
}

// What the run leaves against the two references (model.md §21.1), in µm.
std::string residual_line(const SimulationSummary& s) {
  std::string out = fmt::format("  residual |q| over the final window: {:.4g} µm", s.residual_q_abs * 1e6);
  if (s.bare_rotor_q_abs > 0)
    out += fmt::format(", {:.3g} times the bare rotor's {:.4g} µm (16.5.1)", s.residual_q_abs / s.bare_rotor_q_abs,
                       s.bare_rotor_q_abs * 1e6);
  if (s.balls_held_q_abs > 0)
    out += fmt::format(", {:.3g} times the {:.4g} µm with the balls held at their start",
                       s.residual_q_abs / s.balls_held_q_abs, s.balls_held_q_abs * 1e6);
  return out + "\n";
}

}  // namespace

std::string with_columns(std::string_view csv, std::string_view comment, std::string_view names,
                         const std::function<void(std::size_t row, std::string& out)>& row_values) {
  std::string out;
  out.reserve(csv.size() + csv.size() / 4 + comment.size());
  std::size_t row = 0, pos = 0;
  bool columns_seen = false;
  while (pos < csv.size()) {
    std::size_t end = csv.find('\n', pos);
    if (end == std::string_view::npos) end = csv.size();
    const std::string_view line = csv.substr(pos, end - pos);
    const bool data = !line.empty() && line[0] != '#';
    if (data && !columns_seen) out += comment;
    out += line;
    if (data) {
      if (!columns_seen) {
        out += names;
        columns_seen = true;
      } else {
        row_values(row++, out);
      }
    }
    out += '\n';
    pos = end + 1;
  }
  return out;
}

template <int N>
std::string simulation_csv(const SimulationResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                           std::string_view header) {
  const int n = ball_count(p), d = n + 2;
  // An unround race has no balanced set in general (model.md §11.4): no reference angles.
  const auto balanced = r.unround_race ? std::nullopt : nearest_balanced_angles(p, end_angles(r, n));
  std::string out(header);
  out += fmt::format("# speed: {}\n", speed.describe());
  out += fmt::format("# method: {} (stiffness ratio rho(J)/(omega_max + omega_n) = {:.4g}, rho = {:.4g} 1/s; model.md §15.1)\n",
                     to_string(r.method), r.stiffness_ratio, r.spectral_radius);
  out += fmt::format("# status: {}{}\n", to_string(r.status), r.reason.empty() ? "" : ": " + r.reason);
  if (r.start_below_resolution > 0)
    out += fmt::format("# start: {} component(s) below 1e-3 of their absolute tolerance, integrated as 0\n",
                       r.start_below_resolution);
  out += fmt::format("# steps {}, rejected {}, rhs evaluations {}, jacobian evaluations {}, restarts {}\n",
                     r.stats.steps, r.stats.rejected, r.stats.rhs_evaluations, r.stats.jacobian_evaluations,
                     r.stats.restarts);
  out += "# columns: t [s], omega [rad/s], q1 q2 [m] rotor centre in the rotating frame, beta_i [rad] from the\n"
         "# unbalance, continuous (not wrapped), dq [m/s], dbeta [rad/s], q_abs = |q| [m], x_fixed y_fixed [m] the\n"
         "# rotor centre in the fixed frame R(theta(t)) q (theta the spin angle), beta_rel_i [rad] = beta_i minus the\n"
         "# nearest balanced configuration's angle (to the end state), in [-pi, pi]; empty if no balanced state exists\n";
  if (r.bristle_count > 0)
    out += "# friction lugre: z_i [rad] the bristle deflection of ball i (model.md §12), integrated with the 2n + 4 states\n";
  if (balanced) {
    out += "# balanced reference angles:";
    for (double b : *balanced) {
      out += ' ';
      out += format_number(b, "balanced angle");
    }
    out += "\n";
  }
  out += "t,omega,q1,q2";
  for (int i = 1; i <= n; ++i) out += fmt::format(",beta{}", i);
  out += ",dq1,dq2";
  for (int i = 1; i <= n; ++i) out += fmt::format(",dbeta{}", i);
  out += ",q_abs,x_fixed,y_fixed";
  for (int i = 1; i <= n; ++i) out += fmt::format(",beta_rel{}", i);
  for (int i = 1; i <= r.bristle_count; ++i) out += fmt::format(",z{}", i);  // LuGre (model.md §12.7)
  out += "\n";
  out.reserve(out.size() + r.samples.size() * std::size_t(60 + 45 * n));
  for (std::size_t k = 0; k < r.samples.size(); ++k) {
    const auto& s = r.samples[k];
    out += format_number(s.t, "t");
    out += ',';
    out += format_number(s.omega, "omega");
    for (int i = 0; i < 2 * d; ++i) {
      out += ',';
      out += format_number(s.x(i), "state");
    }
    const double theta = speed.angle(s.t), c = std::cos(theta), sn = std::sin(theta);
    for (double v : {std::hypot(s.x(0), s.x(1)), c * s.x(0) - sn * s.x(1), sn * s.x(0) + c * s.x(1)}) {
      out += ',';
      out += format_number(v, "q_abs / fixed-frame position");
    }
    for (int i = 0; i < n; ++i) {
      out += ',';
      if (balanced) out += format_number(std::remainder(s.x(2 + i) - (*balanced)[std::size_t(i)], 2 * std::numbers::pi), "beta_rel");
    }
    for (int i = 0; i < r.bristle_count; ++i) {
      out += ',';
      out += format_number(r.bristle[k * std::size_t(r.bristle_count) + std::size_t(i)], "z");
    }
    out += '\n';
  }
  return out;
}

template <int N>
std::string simulation_json(const SimulationResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                            std::string_view command_line, std::string_view scene_file) {
  const auto& s = r.summary;
  std::vector<int> stalled = s.stalled_balls;
  std::string balls = "[";
  for (std::size_t i = 0; i < stalled.size(); ++i) balls += (i ? ", " : "") + std::to_string(stalled[i]);
  balls += "]";
  std::string out = "{\n";
  out += fmt::format("  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n", ABU_VERSION,
                     json_string(command_line), json_string(scene_file));
  out += fmt::format("  \"parameters\": {},\n  \"balls\": {},\n  \"speed\": {},\n", json_string(describe_parameters(p)),
                     ball_count(p), json_string(speed.describe()));
  out += fmt::format("  \"status\": {},\n  \"reason\": {},\n", json_string(to_string(r.status)), json_string(r.reason));
  out += fmt::format("  \"outcome\": {},\n  \"pattern\": {},\n  \"note\": {},\n", json_string(to_string(s.outcome)),
                     json_string(s.pattern), json_string(s.note));
  if (s.unround_member > 0)  // model.md §15.7
    out += fmt::format("  \"unround_equilibrium\": {{\"member\": {}, \"q_abs\": {}, \"distance\": {}}},\n",
                       s.unround_member, format_number(s.unround_q_abs, "unround q_abs"),
                       format_number(s.unround_distance, "unround distance"));
  if (s.orbit_member > 0)  // model.md §20.8
    out += fmt::format("  \"periodic_orbit\": {{\"member\": {}, \"q_abs_max\": {}, \"distance\": {}}},\n",
                       s.orbit_member, format_number(s.orbit_q_abs_max, "orbit q_abs_max"),
                       format_number(s.orbit_distance, "orbit distance"));
  out += fmt::format("  \"t_end\": {},\n  \"state_end\": {},\n", format_number(s.t_end, "t_end"),
                     number_list(s.state_end, "state_end"));
  if (r.bristle_count > 0) out += fmt::format("  \"bristle_end\": {},\n", number_list(r.bristle_end, "bristle_end"));
  out += fmt::format("  \"max_q_abs\": {},\n  \"t_max_q_abs\": {},\n", format_number(s.max_q_abs, "max_q_abs"),
                     format_number(s.t_max_q_abs, "t_max_q_abs"));
  out += fmt::format("  \"max_q_abs_run_up\": {},\n", json_number_or_null(s.max_q_abs_run_up, "max_q_abs_run_up"));
  out += fmt::format("  \"residual_q_abs\": {},\n  \"bare_rotor_q_abs\": {},\n  \"balls_held_q_abs\": {},\n",
                     format_number(s.residual_q_abs, "residual"),
                     s.bare_rotor_q_abs > 0 ? format_number(s.bare_rotor_q_abs, "bare rotor") : "null",
                     s.balls_held_q_abs > 0 ? format_number(s.balls_held_q_abs, "balls held") : "null");
  out += fmt::format("  \"settle_time\": {},\n", json_number_or_null(s.settle_time, "settle_time"));
  out += fmt::format("  \"stalled\": {},\n  \"stalled_balls\": {},\n", s.stalled ? "true" : "false", balls);
  out += fmt::format("  \"ball_speed_fixed\": {},\n  \"omega_mean_window\": {},\n  \"window_from\": {},\n",
                     number_list(s.ball_speed_fixed, "ball speed"), format_number(s.omega_mean_window, "omega"),
                     format_number(s.window_from, "window"));
  out += fmt::format("  \"omega_n\": {},\n  \"t_omega_n\": {},\n", format_number(s.omega_n, "omega_n"),
                     number_list(s.t_omega_n, "t_omega_n"));
  out += fmt::format("  \"method\": {},\n  \"stiffness_ratio\": {},\n  \"spectral_radius\": {},\n",
                     json_string(to_string(r.method)), format_number(r.stiffness_ratio, "stiffness"),
                     format_number(r.spectral_radius, "spectral radius"));
  out += fmt::format("  \"displacement_scale\": {},\n", format_number(r.displacement_scale, "L"));
  out += fmt::format("  \"start_below_resolution\": {},\n", r.start_below_resolution);
  out += fmt::format("  \"memory_estimate\": {},\n", format_number(r.memory_estimate, "memory estimate"));
  out += fmt::format(
      "  \"stats\": {{\"steps\": {}, \"rejected\": {}, \"rhs_evaluations\": {}, \"jacobian_evaluations\": {}, "
      "\"restarts\": {}, \"wall_seconds\": {}}},\n",
      r.stats.steps, r.stats.rejected, r.stats.rhs_evaluations, r.stats.jacobian_evaluations, r.stats.restarts,
      format_number(r.stats.wall_seconds, "wall"));
  out += fmt::format("  \"units\": {}\n}}\n",
                     json_string("t [s], q [m], beta [rad], omega and ball speeds [rad/s] (fixed frame for ball_speed_fixed), "
                            "state order (q1, q2, beta_1..beta_n, dq1, dq2, dbeta_1..dbeta_n), model.md §2"));
  return out;
}

template <int N>
std::string simulation_text(const SimulationResult<N>& r, const SpeedProfile& speed) {
  const auto& s = r.summary;
  std::string out;
  out += fmt::format("simulate: {} to t = {:.6g} s ({}), method {} (stiffness ratio {:.3g})\n", to_string(r.status),
                     s.t_end, speed.describe(), to_string(r.method), r.stiffness_ratio);
  if (r.memory_estimate > 1e8)
    out += fmt::format("  memory: at most about {:.3g} GB held for the samples and the CSV text (estimated before "
                       "the run)\n",
                       r.memory_estimate / 1e9);
  if (r.start_below_resolution > 0)
    out += fmt::format("  start: {} component(s) below 1e-3 of their absolute tolerance (rtol times their scale, "
                       "model.md §15.1), integrated as 0\n",
                       r.start_below_resolution);
  out += fmt::format("  outcome: {}{} — {}\n", to_string(s.outcome), s.pattern.empty() ? "" : " " + s.pattern, s.note);
  out += residual_line(s);
  if (s.settle_time) out += fmt::format("  settle time: {:.6g} s\n", *s.settle_time);
  out += fmt::format("  largest |q|: {:.6g} m at t = {:.6g} s\n", s.max_q_abs, s.t_max_q_abs);
  for (double t : s.t_omega_n) out += fmt::format("  passes omega_n = {:.6g} rad/s at t = {:.6g} s\n", s.omega_n, t);
  out += fmt::format("  stalled: {}", s.stalled ? "yes, balls" : "no");
  for (int b : s.stalled_balls) out += fmt::format(" {}", b);
  out += "\n";
  out += fmt::format("  steps {} (rejected {}), rhs evaluations {}, jacobian evaluations {}, {:.3g} s\n", r.stats.steps,
                     r.stats.rejected, r.stats.rhs_evaluations, r.stats.jacobian_evaluations, r.stats.wall_seconds);
  return out;
}


template <int N>
std::string stick_slip_csv(const StickSlipResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                           std::string_view header) {
  const int n = ball_count(p);
  std::string base = simulation_csv(r.run, p, speed, header);
  // No stiffness probe here: the phases are not stiff (model.md §14.6).
  if (const std::size_t at = base.find("# method: "); at != std::string::npos)
    base.replace(at, base.find('\n', at) - at,
                 fmt::format("# method: {} between switches, event-driven stick-slip (model.md §14.6); switches: {} "
                             "slip->stick, {} stick->slip, {} reversals",
                             to_string(r.run.method), r.sticks, r.slips, r.reversals));
  return with_columns(
      base,
      "# stick_i: 1 while ball i sticks to the race (beta_i' = 0, |F_i| <= mu_i N_i), 0 while it slips "
      "(set-valued Coulomb friction, model.md §14.5)\n",
      [&] {
        std::string names;
        for (int i = 1; i <= n; ++i) names += fmt::format(",stick{}", i);
        return names;
      }(),
      [&](std::size_t row, std::string& out) {
        const std::uint32_t m = row < r.stuck_mask.size() ? r.stuck_mask[row] : 0u;
        for (int i = 0; i < n; ++i) out += (m >> i) & 1u ? ",1" : ",0";
      });
}

template <int N>
std::string stick_slip_json(const StickSlipResult<N>& r, const ParamsT<double, N>& p, const SpeedProfile& speed,
                            std::string_view command_line, std::string_view scene_file) {
  std::string out = simulation_json(r.run, p, speed, command_line, scene_file);
  const auto& e = r.end;
  std::string stuck = "[";
  for (std::size_t i = 0; i < e.stuck.size(); ++i) stuck += (i ? ", " : "") + std::string(e.stuck[i] ? "true" : "false");
  stuck += "]";
  const std::string block = fmt::format(
      "  \"stick_slip\": {{\"stuck\": {}, \"all_stuck\": {}, \"beta_end\": {}, \"s_end\": {}, \"max_abs_s\": {}, "
      "\"in_stick_set\": {}, \"set_tolerance\": {}, \"q_abs_end\": {}, \"q_abs_static\": {}, \"sticks\": {}, "
      "\"slips\": {}, \"reversals\": {}}},\n",
      stuck, e.all_stuck ? "true" : "false", number_list(e.beta, "beta_end"), number_list(e.s, "s_end"),
      format_number(e.max_abs_s, "max_abs_s"), e.in_set ? "true" : "false",
      format_number(stick_set_tolerance, "tolerance"), format_number(e.q_abs, "q_abs"),
      format_number(e.q_abs_static, "q_abs_static"), r.sticks, r.slips, r.reversals);
  const std::size_t at = out.rfind("  \"units\"");
  out.insert(at == std::string::npos ? out.size() : at, block);
  return out;
}

template <int N>
std::string stick_slip_text(const StickSlipResult<N>& r, const SpeedProfile& speed) {
  std::string out = simulation_text(r.run, speed);
  if (const std::size_t at = out.find(" (stiffness ratio"); at != std::string::npos)
    out.replace(at, out.find('\n', at) - at, " between switches (event-driven stick-slip, model.md §14.6)");
  const auto& e = r.end;
  out += "  balls at the end:";
  for (std::size_t i = 0; i < e.stuck.size(); ++i)
    out += fmt::format(" {} {} at {:.6f} rad (s = {:+.4f});", i + 1, e.stuck[i] ? "stuck" : "slipping", e.beta[i], e.s[i]);
  out += "\n";
  out += fmt::format("  stick set (model.md §14.2): max |s_i| = {:.6g}, {}; |q| = {:.6g} m (static {:.6g} m)\n",
                     e.max_abs_s,
                     e.in_set ? "inside" : e.all_stuck ? "OUTSIDE" : "not every ball stuck", e.q_abs, e.q_abs_static);
  out += fmt::format("  switches: {} slip->stick, {} stick->slip, {} reversals\n", r.sticks, r.slips, r.reversals);
  return out;
}

template std::string simulation_csv<2>(const SimulationResult<2>&, const ParamsT<double, 2>&, const SpeedProfile&,
                                       std::string_view);
template std::string simulation_csv<any_balls>(const SimulationResult<any_balls>&, const ParamsT<double, any_balls>&,
                                               const SpeedProfile&, std::string_view);
template std::string simulation_json<2>(const SimulationResult<2>&, const ParamsT<double, 2>&, const SpeedProfile&,
                                        std::string_view, std::string_view);
template std::string simulation_json<any_balls>(const SimulationResult<any_balls>&, const ParamsT<double, any_balls>&,
                                                const SpeedProfile&, std::string_view, std::string_view);
template std::string simulation_text<2>(const SimulationResult<2>&, const SpeedProfile&);
template std::string simulation_text<any_balls>(const SimulationResult<any_balls>&, const SpeedProfile&);
template std::string stick_slip_csv<2>(const StickSlipResult<2>&, const ParamsT<double, 2>&, const SpeedProfile&,
                                       std::string_view);
template std::string stick_slip_csv<any_balls>(const StickSlipResult<any_balls>&, const ParamsT<double, any_balls>&,
                                               const SpeedProfile&, std::string_view);
template std::string stick_slip_json<2>(const StickSlipResult<2>&, const ParamsT<double, 2>&, const SpeedProfile&,
                                        std::string_view, std::string_view);
template std::string stick_slip_json<any_balls>(const StickSlipResult<any_balls>&, const ParamsT<double, any_balls>&,
                                                const SpeedProfile&, std::string_view, std::string_view);
template std::string stick_slip_text<2>(const StickSlipResult<2>&, const SpeedProfile&);
template std::string stick_slip_text<any_balls>(const StickSlipResult<any_balls>&, const SpeedProfile&);

}  // namespace abu
