// Outputs of the stick-set analysis (model.md §14).
#include "abu/output/report_stick_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/core/errors.hpp"
#include "abu/output/format.hpp"
#include "abu/output/provenance.hpp"

namespace abu {

namespace {
std::string num(double v, std::string_view what) { return format_number(v, what); }
std::string list(const std::vector<double>& v, std::string_view what) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += fmt::format("{}{}", i ? ", " : "", num(v[i], what));
  return out + "]";
}
std::string ilist(const std::vector<int>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += fmt::format("{}{}", i ? ", " : "", v[i] + 1);
  return out + "]";
}
std::string angles(const std::vector<double>& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += fmt::format("{}{:.9f}", i ? ", " : "", v[i]);
  return out;
}
constexpr double two_pi = 2 * std::numbers::pi;
}  // namespace

std::string shaft_stick_lines(const ShaftStickFigures& f, const StickSet& s, std::string_view prefix) {
  std::string out = fmt::format(
      "{}the balls sit on a flexible shaft (model.md §18.17): they see a rigid rotor with the balancer node's dynamic "
      "stiffness K_eff + i C_eff = {:.9g} {} {:.9g} i N/m (18.8.1; the rotor's k, c and M listed are that "
      "equivalent rigid balancer's, (18.8.2))\n",
      prefix, f.dynamic_stiffness.real(), f.dynamic_stiffness.imag() < 0 ? '-' : '+', std::abs(f.dynamic_stiffness.imag()));
  out += fmt::format("{}largest deflection along the shaft: node {} deflects {:.6g} x the balancer node's (18.17.2): "
                     "{} m where V is attained, {:.9g} m where V_E is\n",
                     prefix, f.worst_node, f.deflection_ratio[std::size_t(f.worst_node)],
                     s.balanced_exists ? fmt::format("{:.9g}", f.worst_deflection) : std::string("not defined"),
                     f.worst_deflection_any);
  return out;
}

std::string shaft_stick_json(const ShaftStickFigures& f) {
  return fmt::format("{{\"dynamic_stiffness\": [{}, {}], \"deflection_ratio\": {}, \"worst_node\": {}, "
                     "\"worst_deflection\": {}, \"worst_deflection_any\": {}}}",
                     num(f.dynamic_stiffness.real(), "K_eff"), num(f.dynamic_stiffness.imag(), "C_eff"),
                     list(f.deflection_ratio, "ratio"), f.worst_node, num(f.worst_deflection, "deflection"),
                     num(f.worst_deflection_any, "deflection"));
}

std::string stick_set_table(const StickSet& s, const ParamsN& p, const ShaftStickFigures* shaft) {
  const double omega_n = std::sqrt(p.rotor.stiffness / p.total_mass());
  std::string out =
      shaft ? fmt::format("{} balls; omega = {} rad/s, friction coulomb-set (model.md §14)\n", s.n_balls, p.omega) +
                  shaft_stick_lines(*shaft, s, "")
            : fmt::format("{} balls; omega = {} rad/s = {:.4f} omega_n (omega_n = {:.6g} rad/s), friction coulomb-set "
                          "(model.md §14)\n",
                          s.n_balls, p.omega, p.omega / omega_n, omega_n);
  out += s.unround_race ? "stick set E on the unround race's paths: every arrangement where every ball can stick, "
                          "|Re(conj(p_i') (p_i + q))| / s_i' <= mu_i l_i (model.md (20.5))\n"
                        : "stick set E: every arrangement where every ball can stick, |q1 sin b_i - q2 cos b_i| <= mu_i l_i\n";
  if (s.sampled)
    out += fmt::format("method: grid of {} points per angle (resolution {:.4g} rad), flood fill on the torus\n",
                       s.grid_points_per_angle, s.resolution);
  else
    out += fmt::format("method: columns in beta1, interval ends to rounding, adaptive area, traced boundary ({} arcs); "
                       "finest column step {:.3g} rad\n",
                       s.boundary.size(), s.resolution);
  out += fmt::format("area {:.9g} rad^{} ({:.6g} of the torus){}; max over the torus of max_i |s_i| = {:.6g}\n", s.area,
                     s.n_balls, s.area_fraction, s.whole_torus ? ", the WHOLE torus: every arrangement sticks" : "",
                     s.max_abs_s);
  out += fmt::format("components {}\n", s.components.size());
  if (s.balanced_exists)
    out += fmt::format("worst residual vibration V (connected to {}) = {:.9g} m at beta = ({}) rad; {:.4g} x the "
                       "rotor without balls ({:.6g} m)\n",
                       s.unround_race ? "the " + s.anchor : std::string("balance"), s.worst_q_abs, angles(s.worst_beta), s.bare_rotor_q_abs > 0 ? s.worst_q_abs / s.bare_rotor_q_abs : 0.0,
                       s.bare_rotor_q_abs);
  else
    out += fmt::format("worst residual vibration V: not defined ({})\n", s.status.reason);
  out += fmt::format("worst over the whole set V_E = {:.9g} m at beta = ({}) rad\n", s.worst_q_abs_any,
                     angles(s.worst_beta_any));
  out += fmt::format("mean |q| over the set {:.9g} m\n", s.mean_q_abs);
  std::string spread;
  for (std::size_t i = 0; i < s.spread.size(); ++i)
    spread += fmt::format("{}{:.6f} rad ({:.3f} deg)", i ? ", " : "", s.spread[i], s.spread[i] * 180 / std::numbers::pi);
  out += fmt::format("spread of each ball over a component holding {}: {}\n",
                     s.unround_race ? "the " + s.anchor : std::string("a balanced point"), spread);
  for (std::size_t c = 0; c < s.components.size(); ++c) {
    const auto& comp = s.components[c];
    out += fmt::format("\ncomponent {}: area {:.9g} rad^{}, max |q| {:.9g} m at beta = ({}), mean |q| {:.6g} m{}\n",
                       c + 1, comp.area, s.n_balls, comp.q_abs_max, angles(comp.beta_at_max),
                       comp.area > 0 ? comp.q_abs_integral / comp.area : 0.0,
                       comp.balanced_points.empty() ? "" : ", holds " + (s.unround_race ? "the " + s.anchor : std::string("a balanced point")));
    for (int k : comp.seeds) {
      const auto& sd = s.seeds[std::size_t(k)];
      out += fmt::format("  {:<9} beta = ({}) rad, |q| = {:.6g} m\n", sd.family, angles(sd.beta), sd.q_abs);
    }
  }
  int outside = 0;
  for (const auto& sd : s.seeds) outside += sd.component < 0;
  if (outside) out += fmt::format("\n{} smooth equilibria not located in a resolved component\n", outside);
  return out;
}

std::string stick_set_csv(const StickSet& s, const std::string& header, const ShaftStickFigures* shaft) {
  std::string out = header;
  if (shaft) out += shaft_stick_lines(*shaft, s, "# ");
  out += fmt::format("# stick set (model.md §14): area {} rad^{}, components {}, V {} m, V_E {} m, mean |q| {} m{}\n",
                     num(s.area, "area"), s.n_balls, s.components.size(), num(s.worst_q_abs, "V"),
                     num(s.worst_q_abs_any, "V_E"), num(s.mean_q_abs, "mean"),
                     s.sampled ? fmt::format(", grid {} per angle", s.grid_points_per_angle) : std::string());
  out += "component,area,q_abs_max,balanced_points,smooth_equilibria,mean_q_abs";
  for (int i = 1; i <= s.n_balls; ++i) out += fmt::format(",beta{}_at_max", i);
  for (int i = 1; i <= s.n_balls; ++i) out += fmt::format(",spread{}", i);
  out += "\n";
  for (std::size_t c = 0; c < s.components.size(); ++c) {
    const auto& comp = s.components[c];
    out += fmt::format("{},{},{},{},{},{}", c + 1, num(comp.area, "area"), num(comp.q_abs_max, "q"),
                       comp.balanced_points.size(), comp.seeds.size(),
                       num(comp.area > 0 ? comp.q_abs_integral / comp.area : 0.0, "mean"));
    for (double b : comp.beta_at_max) out += fmt::format(",{}", num(b, "beta"));
    for (int i = 0; i < s.n_balls; ++i)
      out += fmt::format(",{}", comp.spread.empty() ? std::string() : num(comp.spread[std::size_t(i)], "spread"));
    out += "\n";
  }
  return out;
}

std::string stick_set_json_object(const StickSet& s) {
  // On an unround race (model.md §20.5) V is anchored at the race's least-|q| stable
  // equilibrium: "balanced_exists" and "balanced_points" then mean that anchor.
  const std::string race = s.unround_race ? fmt::format("\"unround_race\": true, \"anchor\": {}, ", json_string(s.anchor))
                                          : std::string();
  std::string out = fmt::format(
      "{{\"area\": {}, \"area_fraction\": {}, \"whole_torus\": {}, \"components\": {}, \"sampled\": {}, "
      "\"resolution\": {}, \"grid_points_per_angle\": {}, \"max_abs_s\": {}, \"balanced_exists\": {}, "
      "\"worst_q_abs\": {}, \"worst_beta\": {}, \"worst_q_abs_any\": {}, \"worst_beta_any\": {}, \"mean_q_abs\": {}, "
      "\"spread\": {}, \"bare_rotor_q_abs\": {}, \"status\": {}, \"boundary_arcs\": {}, \"component_list\": [",
      num(s.area, "area"), num(s.area_fraction, "fraction"), s.whole_torus, s.components.size(), s.sampled,
      num(s.resolution, "resolution"), s.grid_points_per_angle, num(s.max_abs_s, "s"), s.balanced_exists,
      num(s.worst_q_abs, "V"), list(s.worst_beta, "beta"), num(s.worst_q_abs_any, "V_E"), list(s.worst_beta_any, "beta"),
      num(s.mean_q_abs, "mean"), list(s.spread, "spread"), num(s.bare_rotor_q_abs, "bare"),
      json_string(s.status.ok() ? "ok" : s.status.reason), s.boundary.size());
  out.insert(1, race);  // inside the object
  for (std::size_t c = 0; c < s.components.size(); ++c) {
    const auto& comp = s.components[c];
    out += fmt::format("{}{{\"area\": {}, \"q_abs_max\": {}, \"beta_at_max\": {}, \"mean_q_abs\": {}, "
                       "\"balanced_points\": {}, \"smooth_equilibria\": {}, \"spread\": {}}}",
                       c ? ", " : "", num(comp.area, "area"), num(comp.q_abs_max, "q"), list(comp.beta_at_max, "beta"),
                       num(comp.area > 0 ? comp.q_abs_integral / comp.area : 0.0, "mean"), ilist(comp.balanced_points),
                       ilist(comp.seeds), list(comp.spread, "spread"));
  }
  out += "], \"smooth_equilibria\": [";
  for (std::size_t k = 0; k < s.seeds.size(); ++k) {
    const auto& sd = s.seeds[k];
    out += fmt::format("{}{{\"family\": {}, \"beta\": {}, \"q_abs\": {}, \"component\": {}}}", k ? ", " : "",
                       json_string(sd.family), list(sd.beta, "beta"), num(sd.q_abs, "q"),
                       sd.component < 0 ? std::string("null") : std::to_string(sd.component + 1));
  }
  return out + "]}";
}

std::string stick_set_json(const StickSet& s, std::string_view command_line, std::string_view scene_file,
                           const ParamsN& p, const ShaftStickFigures* shaft) {
  return fmt::format(
      "{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n  \"parameters\": {},\n  "
      "\"balls\": {},\n  \"units\": {},\n  \"frame\": \"rotating\",\n  \"stick_set\": {}{}\n}}\n",
      ABU_VERSION, json_string(command_line), json_string(scene_file), json_string(describe_parameters(p)), p.n_balls(),
      json_string("area [rad^n], q [m], beta and spread [rad]; q is the rotor displacement in the rotating frame (a whirl of "
           "radius |q| in the fixed frame)"),
      stick_set_json_object(s), shaft ? ",\n  \"shaft\": " + shaft_stick_json(*shaft) : std::string());
}

std::string stick_boundary_csv(const StickSet& s, const std::string& header) {
  std::string out = fmt::format("{}arc,ball,sign,beta1,beta2\n", header);
  for (std::size_t a = 0; a < s.boundary.size(); ++a) {
    const auto& arc = s.boundary[a];
    for (std::size_t k = 0; k < arc.points.size(); ++k) {
      if (k > 0 && (std::fabs(arc.points[k][0] - arc.points[k - 1][0]) > 3.0 ||
                    std::fabs(arc.points[k][1] - arc.points[k - 1][1]) > 3.0))
        out += "\n";  // a wrap by 2 pi: break the line
      out += fmt::format("{},{},{},{},{}\n", a + 1, arc.ball + 1, arc.sign, num(arc.points[k][0], "beta"),
                         num(arc.points[k][1], "beta"));
    }
    out += "\n";
  }
  return out;
}

std::string stick_sweep_csv(std::string_view name, std::string_view unit, const std::vector<double>& values,
                            const std::vector<StickSet>& sets, const std::string& header,
                            const std::vector<ShaftStickFigures>* shaft) {
  int n_max = 0;
  for (const auto& s : sets) n_max = std::max(n_max, s.n_balls);
  std::string out = header;
  out += fmt::format(
      "# sweep of {0} [{1}], friction coulomb-set: per value the stick set E (model.md §14) as `equilibria` computes it\n"
      "# columns: {0} [{1}]; area [rad^n] of E, area_fraction = area / (2 pi)^n; whole_torus = 1 if every arrangement "
      "sticks; components = connected components of E;\n"
      "#   balanced_exists = 1 if a component holds a balanced point; worst_q_abs [m] = V, max |q| over the components "
      "holding a balanced point (empty if none); worst_q_abs_any [m] = V_E, max |q| over E;\n"
      "#   mean_q_abs [m] = mean |q| over E; bare_rotor_q_abs [m] = omega^2 U / |K + iC|, the rotor without balls; "
      "worst_over_bare = V / bare_rotor_q_abs;\n"
      "#   spread_i [rad] = the largest angular spread of ball i over a balanced component (empty if none); |q| is in "
      "the rotating frame, the whirl radius in the fixed frame\n",
      name, unit);
  if (shaft)
    out += "# flexible shaft (model.md §18.17): q is the balancer node's; K_eff, C_eff [N/m] its dynamic stiffness "
           "(18.8.1); worst_node = the node deflecting most per unit q, (18.17.2); worst_deflection [m] = its deflection "
           "where V is attained (empty if no balanced state), worst_deflection_any [m] where V_E is\n";
  out += fmt::format("{},area,area_fraction,whole_torus,components,balanced_exists,worst_q_abs,worst_q_abs_any,"
                     "mean_q_abs,bare_rotor_q_abs,worst_over_bare",
                     name);
  for (int i = 1; i <= n_max; ++i) out += fmt::format(",spread{}", i);
  if (shaft) out += ",K_eff,C_eff,worst_node,worst_deflection,worst_deflection_any";
  out += "\n";
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const StickSet& s = sets[k];
    const bool v = s.balanced_exists;
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}", num(values[k], name), num(s.area, "area"),
                       num(s.area_fraction, "area fraction"), int(s.whole_torus), s.components.size(), int(v),
                       v ? num(s.worst_q_abs, "V") : std::string(), num(s.worst_q_abs_any, "V_E"),
                       num(s.mean_q_abs, "mean |q|"), num(s.bare_rotor_q_abs, "bare rotor |q|"),
                       v && s.bare_rotor_q_abs > 0 ? num(s.worst_q_abs / s.bare_rotor_q_abs, "V / bare") : std::string());
    for (int i = 0; i < n_max; ++i) {
      out += ',';
      if (v && i < s.n_balls) out += num(s.spread[std::size_t(i)], "spread");
    }
    if (shaft) {
      const ShaftStickFigures& f = (*shaft)[k];
      out += fmt::format(",{},{},{},{},{}", num(f.dynamic_stiffness.real(), "K_eff"), num(f.dynamic_stiffness.imag(), "C_eff"),
                         f.worst_node, v ? num(f.worst_deflection, "deflection") : std::string(),
                         num(f.worst_deflection_any, "deflection"));
    }
    out += "\n";
  }
  return out;
}

std::string dry_first(const DryFrictionVerdict& d, const std::string& smooth, std::string_view prefix) {
  if (!d.applies) return smooth;
  return dry_friction_lines(d, prefix) +
         fmt::format("{}the smooth law's verdict (model.md §4, §14.10), as if the balls crept where dry balls "
                     "stick:\n",
                     prefix) +
         smooth;
}

std::string dry_friction_lines(const DryFrictionVerdict& d, std::string_view prefix) {
  if (!d.applies) return {};
  std::string out = fmt::format("{}dry friction as it is (coulomb-set with {}, model.md {}): ", prefix, d.which,
                                d.set && d.set->unround_race ? "§20.5, on the race's paths"
                                : d.shaft                    ? "§18.17, through the shaft's receptance"
                                                             : "§14");
  if (!d.set) return out + fmt::format("not defined: {}\n", d.not_defined);
  const StickSet& s = *d.set;
  std::string set = fmt::format("the stick set has area {:.6g} rad^{} ({:.4g} of the torus{}), {} component{}",
                                s.area, s.n_balls, s.area_fraction, s.whole_torus ? ": every arrangement sticks" : "",
                                s.components.size(), s.components.size() == 1 ? "" : "s");
  if (s.point_components > 0)
    set += fmt::format(" ({} of them a smooth equilibrium alone: its part of the set, whose width shrinks with mu, is "
                       "narrower than the scan's resolution)",
                       s.point_components);
  if (s.balanced_exists)
    out += fmt::format("the balls stick inside the set, residual vibration at most V = {:.6g} m ({:.3g} x the rotor "
                       "without balls, {:.6g} m; V_E = {:.6g} m over the whole set); {}\n",
                       s.worst_q_abs, s.bare_rotor_q_abs > 0 ? s.worst_q_abs / s.bare_rotor_q_abs : 0.0,
                       s.bare_rotor_q_abs, s.worst_q_abs_any, set);
  else
    out += fmt::format("no balanced point in the stick set ({}); a stuck state leaves at most V_E = {:.6g} m; {}\n",
                       s.status.reason, s.worst_q_abs_any, set);
  if (d.shaft)
    out += fmt::format("{}  along the shaft: node {} deflects {:.4g} x the balancer node, {} m where V is attained, "
                       "{:.6g} m where V_E is\n",
                       prefix, d.shaft->worst_node, d.shaft->deflection_ratio[std::size_t(d.shaft->worst_node)],
                       s.balanced_exists ? fmt::format("{:.6g}", d.shaft->worst_deflection) : std::string("not defined"),
                       d.shaft->worst_deflection_any);
  out += fmt::format("{}  the smooth law's stability is that of its arctan regularization: its creep modes "
                     "(lambda ~ 1/kappa) are the balls creeping through this set, not settling\n",
                     prefix);
  return out;
}

std::string dry_friction_json(const DryFrictionVerdict& d) {
  if (!d.applies) return {};
  std::string out = fmt::format("  \"dry_friction\": {{\"law\": \"coulomb-set\", \"coefficients\": {}, \"model\": "
                                "\"model.md {}\", ",
                                json_string(d.which),
                                d.set && d.set->unround_race ? "§20.5" : d.shaft ? "§18.17" : "§14");
  if (!d.set) return out + fmt::format("\"defined\": false, \"not_defined\": {}}},\n", json_string(d.not_defined));
  const StickSet& s = *d.set;
  out += fmt::format("\"defined\": true, \"area\": {}, \"area_unit\": \"rad^{}\", \"area_fraction\": {}, "
                     "\"whole_torus\": {}, \"components\": {}, \"balanced_in_set\": {}, ",
                     num(s.area, "area"), s.n_balls, num(s.area_fraction, "area fraction"), s.whole_torus,
                     s.components.size(), s.balanced_exists);
  if (d.shaft) out += fmt::format("\"shaft\": {}, ", shaft_stick_json(*d.shaft));
  out += fmt::format("\"worst_q_abs\": {}, \"worst_q_abs_any\": {}, \"bare_rotor_q_abs\": {}, \"status\": {}}},\n",
                     s.balanced_exists ? num(s.worst_q_abs, "V") : std::string("null"), num(s.worst_q_abs_any, "V_E"),
                     num(s.bare_rotor_q_abs, "bare rotor |q|"),
                     s.balanced_exists ? std::string("null") : json_string(std::string(s.status.reason)));
  return out;
}

std::string stick_raster_dat(const ParamsN& p, int cells) {
  std::string out;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const std::vector<double> b{two_pi * (i + 0.5) / cells, two_pi * (j + 0.5) / cells};
      const StickPoint sp = stick_point(p, b);
      bool in = true;
      for (double v : sp.s) in = in && std::fabs(v) <= 1.0;
      out += fmt::format("{:.6f},{:.6f},{}\n", b[0], b[1], in ? 1 : 0);
    }
    out += "\n";
  }
  return out;
}

}  // namespace abu
