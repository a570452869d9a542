// The answer of one parameter point, the parameters as JSON, each eigenvalue's mode and the
// mode tables, shapes and chart of report_views.hpp (docs/views.md, docs/model.md §16); the
// Campbell view is in report_campbell.cpp, the stability ranges in report_ranges.cpp.
#include "abu/output/report_views.hpp"
#include "equilibrium_text.hpp"
#include "json_quantity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <complex>
#include <numbers>
#include <cmath>
#include <map>
#include <type_traits>

#include "abu/output/format.hpp"

namespace abu {

using detail::json_quantity;
using detail::pattern_of;
using detail::q_abs;
using detail::state_label;

namespace {

using cd_t = std::complex<double>;

std::string num(double v, std::string_view what) { return format_number(v, what); }

// "900 rad/s" or "900 rad/s = 8594.37 rpm".
std::string speed_text(double omega, SpeedUnit unit) {
  if (unit == SpeedUnit::rad_per_s) return fmt::format("{:.6g} rad/s", omega);
  return fmt::format("{:.6g} rad/s = {:.6g} {}", omega, from_rad_per_s(omega, unit), to_string(unit));
}

template <class A, int N>
PointAnswer answer_of(const A& a, const ParamsT<double, N>& p) {
  PointAnswer ans;
  ans.omega = p.omega;
  ans.omega_n = natural_frequency(p);
  ans.capacity = ball_capacity_of(p);
  ans.unbalance = p.rotor.unbalance;
  ans.capacity_exceeded = ans.unbalance > ans.capacity;
  const auto points = a.equilibria.points();
  const EquilibriumT<N>* best = nullptr;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const bool balanced = e.family == Family::balanced || e.on_balanced_set;
    const bool stable = a.spectra[i].stability == Stability::stable;
    ans.balanced_exists = ans.balanced_exists || balanced;
    ans.balanced_stable = ans.balanced_stable || (balanced && stable);
    if (!stable) continue;
    ans.stable_states.push_back(state_label(e));
    if (!best || q_abs(e) < q_abs(*best)) best = &e;
  }
  // (16.5.1): the reference whirl without a balancing effect.
  ans.q0_balls_neutral = unbalanced_amplitude(p, p.total_mass());
  ans.q0_without_balls = unbalanced_amplitude(p, p.rotor.mass);
  if (best) {
    ans.best = state_label(*best);
    // A balanced state has q = 0 by construction (model.md §5): its rounding-level |q| is 0.
    ans.best_q_abs = best->family == Family::balanced || best->on_balanced_set ? 0.0 : q_abs(*best);
    ans.reduction = ans.q0_balls_neutral > 0 ? ans.best_q_abs / ans.q0_balls_neutral : 0.0;
  }
  return ans;
}

}  // namespace

PointAnswer point_answer(const Analysis& a, const Params& p) { return answer_of<Analysis, 2>(a, p); }
PointAnswer point_answer(const AnalysisN& a, const ParamsN& p) { return answer_of<AnalysisN, any_balls>(a, p); }

std::string answer_lines(const PointAnswer& ans, SpeedUnit unit, std::string_view prefix) {
  std::string out;
  out += fmt::format("{}speed: omega = {} = {:.6g} omega_n (omega_n = sqrt(k/(M_r + sum m_i)) = {})\n", prefix,
                     speed_text(ans.omega, unit), ans.omega / ans.omega_n, speed_text(ans.omega_n, unit));
  if (ans.capacity_exceeded) {
    out += fmt::format("{}capacity exceeded: no balanced state (U = {:.6g} kg m > sum m_i l_i = {:.6g} kg m)\n", prefix,
                       ans.unbalance, ans.capacity);
  } else {
    out += fmt::format("{}capacity: sum m_i l_i = {:.6g} kg m against U = {:.6g} kg m (U / capacity = {:.4g}); "
                       "balanced state {}\n",
                       prefix, ans.capacity, ans.unbalance, ans.capacity > 0 ? ans.unbalance / ans.capacity : 0.0,
                       ans.balanced_exists ? (ans.balanced_stable ? "exists and is stable" : "exists, unstable")
                                           : "does not exist (the balls cannot close the polygon, model.md §13.4)");
  }
  if (!ans.best) {
    out += fmt::format("{}no stable state at this speed\n", prefix);
  } else {
    std::string states;
    for (std::size_t i = 0; i < ans.stable_states.size(); ++i) states += (i ? ", " : "") + ans.stable_states[i];
    out += fmt::format("{}stable states: {}\n", prefix, states);
    out += fmt::format("{}best stable state: {}, |q| = {:.6g} m against |q0| = {:.6g} m (rotor whose balls cancel "
                       "each other, mass M; {:.6g} m without the balls, mass M_r): reduction |q|/|q0| = {:.6g}\n",
                       prefix, *ans.best, ans.best_q_abs, ans.q0_balls_neutral, ans.q0_without_balls, ans.reduction);
  }
  return out;
}

std::string answer_json(const PointAnswer& ans) {
  std::string states = "[";
  for (std::size_t i = 0; i < ans.stable_states.size(); ++i) states += (i ? ", " : "") + json_string(ans.stable_states[i]);
  states += "]";
  std::string statement = answer_lines(ans, SpeedUnit::rad_per_s, "");
  if (!statement.empty()) statement.pop_back();
  return fmt::format(
      "{{\"omega\": {}, \"omega_n\": {}, \"omega_over_omega_n\": {}, \"capacity\": {}, \"unbalance\": {}, "
      "\"capacity_exceeded\": {}, \"balanced_exists\": {}, \"balanced_stable\": {}, \"any_stable\": {}, "
      "\"stable_states\": {}, \"best\": {}, \"q0_balls_neutral\": {}, \"q0_without_balls\": {}, "
      "\"reduction_ratio\": {}, \"statement\": {}}}",
      json_quantity(ans.omega, "rad/s", "omega"), json_quantity(ans.omega_n, "rad/s", "omega_n"),
      num(ans.omega / ans.omega_n, "omega/omega_n"), json_quantity(ans.capacity, "kg m", "capacity"),
      json_quantity(ans.unbalance, "kg m", "U"), ans.capacity_exceeded, ans.balanced_exists, ans.balanced_stable,
      ans.best.has_value(), states,
      ans.best ? fmt::format("{{\"state\": {}, \"q_abs\": {}}}", json_string(*ans.best),
                             json_quantity(ans.best_q_abs, "m", "|q|"))
               : std::string("null"),
      json_quantity(ans.q0_balls_neutral, "m", "|q0|"), json_quantity(ans.q0_without_balls, "m", "|q0|"),
      ans.best ? num(ans.reduction, "reduction") : std::string("null"), json_string(statement));
}

namespace {
template <int N>
std::string parameters_object(const ParamsT<double, N>& p) {
  std::string s = fmt::format(
      "{{\"M_r\": {}, \"k\": {}, \"c\": {}, \"U\": {}, \"omega\": {}, \"law\": {}",
      json_quantity(p.rotor.mass, "kg", "M_r"), json_quantity(p.rotor.stiffness, "N/m", "k"),
      json_quantity(p.rotor.damping, "N s/m", "c"), json_quantity(p.rotor.unbalance, "kg m", "U"),
      json_quantity(p.omega, "rad/s", "omega"), json_string(to_string(p.law)));
  if (p.law == FrictionLaw::coulomb || p.law == FrictionLaw::stribeck)
    s += fmt::format(", \"kappa\": {}", json_quantity(p.kappa, "s/rad", "kappa"));
  for (std::size_t i = 0; i < p.balls.size(); ++i) {
    const auto& b = p.balls[i];
    const auto n = i + 1;
    s += fmt::format(", \"m{}\": {}, \"l{}\": {}, \"r{}\": {}, \"j{}\": {}", n, json_quantity(b.mass, "kg", "m"), n,
                     json_quantity(b.race_radius, "m", "l"), n, json_quantity(b.radius, "m", "r"), n,
                     json_quantity(b.inertia_factor, "-", "j"));
    switch (p.law) {
      case FrictionLaw::none: break;
      case FrictionLaw::viscous: s += fmt::format(", \"d{}\": {}", n, json_quantity(b.d, "N s/m", "d")); break;
      case FrictionLaw::coulomb:
      case FrictionLaw::coulomb_set: s += fmt::format(", \"mu{}\": {}", n, json_quantity(b.mu, "-", "mu")); break;
      case FrictionLaw::stribeck:
        s += fmt::format(", \"mu_c{}\": {}, \"mu_s{}\": {}, \"v_s{}\": {}", n, json_quantity(b.mu_c, "-", "mu_c"), n,
                         json_quantity(b.mu_s, "-", "mu_s"), n, json_quantity(b.v_s, "rad/s", "v_s"));
        break;
      case FrictionLaw::lugre:
        s += fmt::format(", \"sigma0_{}\": {}, \"sigma1_{}\": {}, \"sigma2_{}\": {}", n,
                         json_quantity(b.sigma0, "1/rad", "sigma0"), n, json_quantity(b.sigma1, "s/rad", "sigma1"), n,
                         json_quantity(b.sigma2, "s/rad", "sigma2"));
        s += fmt::format(", \"mu_c{}\": {}, \"mu_s{}\": {}, \"v_s{}\": {}", n, json_quantity(b.mu_c, "-", "mu_c"), n,
                         json_quantity(b.mu_s, "-", "mu_s"), n, json_quantity(b.v_s, "rad/s", "v_s"));
        break;
    }
  }
  return s + "}";
}
}  // namespace

std::string parameters_json(const Params& p) { return parameters_object(p); }
std::string parameters_json(const ParamsN& p) { return parameters_object(p); }

template <int N>
std::string eigen_view_json(const ParamsT<double, N>& p, const SpectrumT<N>& sp, int k,
                            const std::vector<ModeView>& modes, const std::vector<int>& mode_of) {
  (void)p;
  const int mi = mode_of[std::size_t(k)];
  if (mi < 0) return ", \"frame\": \"rotating\"";
  const ModeView& m = modes[std::size_t(mi)];
  const auto lambda = sp.eigenvalues[std::size_t(k)];
  // x = (v, lambda v), v of unit norm with its largest component real and positive.
  auto v = sp.vectors[std::size_t(k)];
  std::string vector = "[";
  const double norm = v.norm();
  if (norm > 0) {
    Eigen::Index largest = 0;
    v.cwiseAbs().maxCoeff(&largest);
    const std::complex<double> phase = std::abs(v(largest)) > 0 ? std::conj(v(largest)) / std::abs(v(largest)) : 1.0;
    v = (v * phase / norm).eval();
    if (sp.structural[std::size_t(k)] || lambda == 0.0) v(largest) = std::abs(v(largest));
    for (int half = 0; half < 2; ++half)
      for (Eigen::Index c = 0; c < v.size(); ++c) {
        const std::complex<double> z = half == 0 ? v(c) : lambda * v(c);
        vector += fmt::format("{}[{}, {}]", half + c == 0 ? "" : ", ", num(z.real(), "eigenvector"),
                              num(z.imag(), "eigenvector"));
      }
  }
  vector += "]";
  const bool whirl_none = m.kind == ModeKind::set_direction;
  return fmt::format(
      ", \"frame\": \"rotating\", \"mode\": {}, \"mode_label\": {}, \"fixed_frame\": {{\"re\": {}, \"im\": {}, "
      "\"whirl\": {}, \"whirl_frequency\": {}, \"damping_ratio\": {}, \"log_decrement\": {}}}, "
      "\"participation\": {{\"rotor\": {}, \"forward\": {}, \"balls_together\": {}}},\n       \"vector\": {}",
      mi + 1, json_string(to_string(m.kind)), num(m.fixed.real(), "fixed-frame eigenvalue"),
      num(m.fixed.imag(), "fixed-frame eigenvalue"),
      whirl_none ? "null" : (m.whirl_frequency >= 0 ? "\"forward\"" : "\"backward\""),
      num(m.whirl_frequency, "whirl frequency"), num(m.damping_ratio, "damping ratio"),
      m.has_log_decrement ? num(m.log_decrement, "log decrement") : std::string("null"),
      num(m.rotor_share, "rotor share"), num(m.forward_share, "forward share"), num(m.common_share, "common share"),
      vector);
}
template std::string eigen_view_json<2>(const Params&, const Spectrum&, int, const std::vector<ModeView>&,
                                        const std::vector<int>&);
template std::string eigen_view_json<any_balls>(const ParamsN&, const SpectrumN&, int, const std::vector<ModeView>&,
                                                const std::vector<int>&);

namespace {
template <class A, int N>
std::string shapes_csv(const A& a, const ParamsT<double, N>& p, std::string_view header) {
  std::string out(header);
  out += "# mode shapes (docs/views.md): one cycle Re(v e^{i theta}) of each mode, rotating frame (a1 toward the "
         "unbalance), in units of the race radius l_1;\n"
         "#   body = rotor (centre, drawn at the origin) or ball<i> (centre, drawn at its place x0, y0 = l_i e^{i beta_i} / l_1); "
         "displacements scaled so that the largest of a mode is 0.25; whirl_frequency [rad/s, fixed frame, signed: "
         "> 0 forward], zeta fixed frame (docs/model.md §16)\n";
  out += "equilibrium,family,pattern,member,mode,label,whirl_frequency,zeta,body,theta,x0,y0,x,y\n";
  const auto points = a.equilibria.points();
  const double l1 = p.balls[0].race_radius;
  constexpr int kSteps = 48;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const auto& sp = a.spectra[i];
    const auto modes = mode_views(p, e.position, sp);
    for (std::size_t k = 0; k < modes.size(); ++k) {
      const auto& m = modes[k];
      if (m.kind == ModeKind::set_direction) continue;
      const auto& v = sp.vectors[std::size_t(m.index)];
      const int n = e.n_balls();
      // Complex displacement amplitudes (x, y) per body, rotating frame [m].
      std::vector<std::array<cd_t, 2>> amp;
      amp.push_back({v(0), v(1)});
      for (int b = 0; b < n; ++b) {
        const double beta = double(e.position(2 + b)), l = p.balls[std::size_t(b)].race_radius;
        amp.push_back({v(0) - l * std::sin(beta) * v(2 + b), v(1) + l * std::cos(beta) * v(2 + b)});
      }
      double largest = 0;
      for (const auto& d : amp) largest = std::max(largest, std::sqrt(std::norm(d[0]) + std::norm(d[1])));
      const double scale = largest > 0 ? 0.25 / largest : 0;
      for (int body = 0; body <= n; ++body) {
        double cx = 0, cy = 0;
        if (body > 0) {
          const double beta = double(e.position(1 + body)), l = p.balls[std::size_t(body - 1)].race_radius;
          cx = l / l1 * std::cos(beta), cy = l / l1 * std::sin(beta);
        }
        const std::string name = body == 0 ? std::string("rotor") : fmt::format("ball{}", body);
        for (int j = 0; j <= kSteps; ++j) {
          const double theta = 2 * std::numbers::pi * j / kSteps;
          const cd_t phase = std::polar(1.0, theta);
          const double x = cx + scale * (amp[std::size_t(body)][0] * phase).real();
          const double y = cy + scale * (amp[std::size_t(body)][1] * phase).real();
          out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", i + 1, to_string(e.family),
                             pattern_of(e), e.member, k + 1, to_string(m.kind), num(m.whirl_frequency, "whirl"),
                             num(m.damping_ratio, "zeta"), name, num(theta, "theta"), num(cx, "x0"), num(cy, "y0"),
                             num(x, "x"), num(y, "y"));
        }
      }
    }
  }
  return out;
}

template <class A, int N>
ModeChart chart_of(const A& a, const ParamsT<double, N>& p) {
  ModeChart c;
  const auto points = a.equilibria.points();
  double best = -1;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (a.spectra[i].stability == Stability::stable && (best < 0 || q_abs(points[i]) < best))
      best = q_abs(points[i]), c.equilibrium = int(i);
  if (points.empty()) return c;
  const auto& e = points[std::size_t(c.equilibrium)];
  c.label = fmt::format("{}{}", state_label(e), best < 0 ? " (nothing is stable: the first equilibrium)" : " (the best stable state)");
  const auto modes = mode_views(p, e.position, a.spectra[std::size_t(c.equilibrium)]);
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const auto& m = modes[k];
    if (m.kind == ModeKind::set_direction) continue;
    c.titles.push_back(fmt::format("mode {}: {}, {:.4g} rad/s {}, zeta {:.3g}", k + 1, to_string(m.kind),
                                   std::abs(m.whirl_frequency), m.whirl_frequency >= 0 ? "fw" : "bw", m.damping_ratio));
  }
  return c;
}
}  // namespace

namespace {
template <class A, int N>
std::string modes_block(const A& a, const ParamsT<double, N>& p, SpeedUnit unit) {
  std::string out = fmt::format(
      "\nmodes in the fixed frame (docs/model.md §16): Omega = fixed-frame whirl frequency, > 0 forward, < 0 "
      "backward; zeta, delta = damping ratio, log decrement; rotor = rotor translation's share\n");
  out += fmt::format("{:<13} {:>4} {:<22} {:>16} {:>12} {:>12} {:>12} {:>8}\n", "equilibrium", "mode", "label",
                     "Omega [rad/s]", unit == SpeedUnit::rad_per_s ? std::string() : fmt::format("[{}]", to_string(unit)),
                     "zeta", "delta", "rotor");
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto modes = mode_views(p, points[i].position, a.spectra[i]);
    for (std::size_t k = 0; k < modes.size(); ++k) {
      const auto& m = modes[k];
      if (m.kind == ModeKind::set_direction) continue;
      out += fmt::format("{:<13} {:>4} {:<22} {:>16.9g} {:>12} {:>12.4g} {:>12} {:>8.3g}\n", state_label(points[i]), k + 1,
                         to_string(m.kind), m.whirl_frequency,
                         unit == SpeedUnit::rad_per_s ? std::string()
                                                      : fmt::format("{:.6g}", from_rad_per_s(m.whirl_frequency, unit)),
                         m.damping_ratio, m.has_log_decrement ? fmt::format("{:.4g}", m.log_decrement) : "-",
                         m.rotor_share);
    }
  }
  return out;
}
}  // namespace

std::string modes_table(const Analysis& a, const Params& p, SpeedUnit unit) { return modes_block<Analysis, 2>(a, p, unit); }
std::string modes_table(const AnalysisN& a, const ParamsN& p, SpeedUnit unit) {
  return modes_block<AnalysisN, any_balls>(a, p, unit);
}

std::string mode_shapes_csv(const Analysis& a, const Params& p, std::string_view header) {
  return shapes_csv<Analysis, 2>(a, p, header);
}
std::string mode_shapes_csv(const AnalysisN& a, const ParamsN& p, std::string_view header) {
  return shapes_csv<AnalysisN, any_balls>(a, p, header);
}
ModeChart mode_chart(const Analysis& a, const Params& p) { return chart_of<Analysis, 2>(a, p); }
ModeChart mode_chart(const AnalysisN& a, const ParamsN& p) { return chart_of<AnalysisN, any_balls>(a, p); }

}  // namespace abu
