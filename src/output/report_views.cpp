#include "abu/output/report_views.hpp"
#include "equilibrium_text.hpp"

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

using detail::pattern_of;
using detail::q_abs;
using detail::state_label;

namespace {

using cd_t = std::complex<double>;

std::string num(double v, std::string_view what) { return format_number(v, what); }

std::string quantity(double value, std::string_view unit, std::string_view what) {
  return fmt::format("{{\"value\": {}, \"unit\": {}}}", num(value, what), json_string(unit));
}

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
      quantity(ans.omega, "rad/s", "omega"), quantity(ans.omega_n, "rad/s", "omega_n"),
      num(ans.omega / ans.omega_n, "omega/omega_n"), quantity(ans.capacity, "kg m", "capacity"),
      quantity(ans.unbalance, "kg m", "U"), ans.capacity_exceeded, ans.balanced_exists, ans.balanced_stable,
      ans.best.has_value(), states,
      ans.best ? fmt::format("{{\"state\": {}, \"q_abs\": {}}}", json_string(*ans.best),
                             quantity(ans.best_q_abs, "m", "|q|"))
               : std::string("null"),
      quantity(ans.q0_balls_neutral, "m", "|q0|"), quantity(ans.q0_without_balls, "m", "|q0|"),
      ans.best ? num(ans.reduction, "reduction") : std::string("null"), json_string(statement));
}

namespace {
template <int N>
std::string parameters_object(const ParamsT<double, N>& p) {
  std::string s = fmt::format(
      "{{\"M_r\": {}, \"k\": {}, \"c\": {}, \"U\": {}, \"omega\": {}, \"law\": {}", quantity(p.rotor.mass, "kg", "M_r"),
      quantity(p.rotor.stiffness, "N/m", "k"), quantity(p.rotor.damping, "N s/m", "c"),
      quantity(p.rotor.unbalance, "kg m", "U"), quantity(p.omega, "rad/s", "omega"), json_string(to_string(p.law)));
  if (p.law == FrictionLaw::coulomb || p.law == FrictionLaw::stribeck)
    s += fmt::format(", \"kappa\": {}", quantity(p.kappa, "s/rad", "kappa"));
  for (std::size_t i = 0; i < p.balls.size(); ++i) {
    const auto& b = p.balls[i];
    const auto n = i + 1;
    s += fmt::format(", \"m{}\": {}, \"l{}\": {}, \"r{}\": {}, \"j{}\": {}", n, quantity(b.mass, "kg", "m"), n,
                     quantity(b.race_radius, "m", "l"), n, quantity(b.radius, "m", "r"), n,
                     quantity(b.inertia_factor, "-", "j"));
    switch (p.law) {
      case FrictionLaw::none: break;
      case FrictionLaw::viscous: s += fmt::format(", \"d{}\": {}", n, quantity(b.d, "N s/m", "d")); break;
      case FrictionLaw::coulomb:
      case FrictionLaw::coulomb_set: s += fmt::format(", \"mu{}\": {}", n, quantity(b.mu, "-", "mu")); break;
      case FrictionLaw::stribeck:
        s += fmt::format(", \"mu_c{}\": {}, \"mu_s{}\": {}, \"v_s{}\": {}", n, quantity(b.mu_c, "-", "mu_c"), n,
                         quantity(b.mu_s, "-", "mu_s"), n, quantity(b.v_s, "rad/s", "v_s"));
        break;
      case FrictionLaw::lugre:
        s += fmt::format(", \"sigma0_{}\": {}, \"sigma1_{}\": {}, \"sigma2_{}\": {}", n,
                         quantity(b.sigma0, "1/rad", "sigma0"), n, quantity(b.sigma1, "s/rad", "sigma1"), n,
                         quantity(b.sigma2, "s/rad", "sigma2"));
        s += fmt::format(", \"mu_c{}\": {}, \"mu_s{}\": {}, \"v_s{}\": {}", n, quantity(b.mu_c, "-", "mu_c"), n,
                         quantity(b.mu_s, "-", "mu_s"), n, quantity(b.v_s, "rad/s", "v_s"));
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

template <int N>
CampbellSample sample_of(int step, const ParamsT<double, N>& p, const EquilibriumT<N>& e, const SpectrumT<N>& sp) {
  CampbellSample s;
  s.step = step;
  s.omega = p.omega;
  s.omega_n = natural_frequency(p);
  s.family = std::string(to_string(e.family));
  s.pattern = pattern_of(e);
  s.member = e.member;
  s.stable = sp.stability == Stability::stable;
  s.series = state_label(e);
  s.modes = mode_views(p, e.position, sp);
  return s;
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

std::vector<CampbellSample> campbell_samples(const SweepResult& s, const Params& base) {
  std::vector<CampbellSample> out;
  if (s.param.quantity != Quantity::omega) return out;
  // Ordered as the sweep CSV: by family, member, then value, so that a series is contiguous.
  for (auto family : {Family::balanced, Family::together, Family::opposite})
    for (int member = 1; member <= 2; ++member)
      for (std::size_t i = 0; i < s.points.size(); ++i) {
        Params p = base;
        p.omega = s.values[i];
        const auto points = s.points[i].equilibria.points();
        for (std::size_t k = 0; k < points.size(); ++k)
          if (points[k].family == family && points[k].member == member)
            out.push_back(sample_of(int(i), p, points[k], s.points[i].spectra[k]));
      }
  return out;
}

std::vector<CampbellSample> campbell_samples(const SweepResultN& s, const std::vector<ParamsN>& params) {
  std::vector<CampbellSample> out;
  if (s.name != "omega") return out;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const auto points = s.points[i].equilibria.points();
    for (std::size_t k = 0; k < points.size(); ++k) out.push_back(sample_of(int(i), params[i], points[k], s.points[i].spectra[k]));
  }
  // Contiguous series: stable sort by the series label keeps the values in order.
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.series < b.series; });
  return out;
}

std::vector<CampbellSample> campbell_samples(const ContinuationRun& run, const Params& base) {
  std::vector<CampbellSample> out;
  if (run.param.quantity != Quantity::omega) return out;
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    const auto& branch = run.branches[b];
    for (std::size_t j = 0; j < branch.points.size(); ++j) {
      const auto& pt = branch.points[j];
      Params p = base;
      p.omega = double(pt.parameter);
      Equilibrium e;
      e.family = pt.family;
      e.pattern = pt.family == Family::opposite ? 2u : 0u;  // ball 2 opposite: "+-" (two balls)
      e.member = int(b) + 1;
      e.position = pt.position;
      CampbellSample s = sample_of(int(j), p, e, pt.spectrum);
      s.series = fmt::format("branch {}", b + 1);
      out.push_back(std::move(s));
    }
  }
  return out;
}

namespace {
// The rotor forward-whirl mode of a sample with the largest rotor share, if any.
const ModeView* rotor_forward(const CampbellSample& s) {
  const ModeView* best = nullptr;
  for (const auto& m : s.modes)
    if (m.kind == ModeKind::rotor_forward && (!best || m.rotor_share > best->rotor_share)) best = &m;
  return best;
}
}  // namespace

std::vector<CriticalSpeed> critical_speeds(const std::vector<CampbellSample>& samples) {
  std::vector<CriticalSpeed> out;
  const CampbellSample* last = nullptr;  // last sample of the current series with a nonzero whirl - omega
  double last_g = 0, last_zeta = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    if (i > 0 && samples[i - 1].series != s.series) last = nullptr;
    const ModeView* m = rotor_forward(s);
    if (!m) continue;
    // whirl - omega = +-Im lambda (16.1.3): zero exactly at the 1X crossing.
    const double g = m->whirl_frequency - s.omega;
    if (g == 0) continue;
    if (last && (g > 0) != (last_g > 0)) {
      const double t = last_g / (last_g - g);
      CriticalSpeed c;
      c.series = s.series, c.family = s.family, c.pattern = s.pattern, c.member = s.member;
      c.omega = last->omega + t * (s.omega - last->omega);
      c.omega_n = last->omega_n + t * (s.omega_n - last->omega_n);
      c.bracket_from = last->omega, c.bracket_to = s.omega;
      c.damping_ratio = last_zeta + t * (m->damping_ratio - last_zeta);
      out.push_back(c);
    }
    last = &s, last_g = g, last_zeta = m->damping_ratio;
  }
  return out;
}

std::string campbell_csv(const std::vector<CampbellSample>& samples, std::string_view header, SpeedUnit unit) {
  std::string out(header);
  const std::string u(to_string(unit));
  out += fmt::format(
      "# Campbell diagram (docs/views.md, docs/model.md §16): one row per mode (a conjugate pair of rotating-frame "
      "eigenvalues, or one real eigenvalue) per equilibrium per speed; structural zeros left out.\n"
      "# columns: omega [rad/s]; speed = omega in the display unit [{0}]; omega_n = sqrt(k/M) [rad/s] at this point; "
      "omega_over_omega_n; family, pattern, member (continuation: member = branch); stable = the equilibrium's "
      "verdict;\n"
      "#   mode = 1-based index of the mode in the sorted spectrum's pairs; label = rotor forward whirl | rotor "
      "backward whirl | ball mode | ball relative mode (by participation, model.md (16.3.1));\n"
      "#   re_rotating, im_rotating [1/s]: the rotating-frame eigenvalue lambda (Im >= 0); re_fixed [1/s], "
      "whirl_frequency [rad/s]: the fixed-frame eigenvalue carrying most of the motion, lambda + i omega or "
      "conj(lambda) + i omega (16.1.2);\n"
      "#   whirl_frequency > 0: forward whirl, < 0: backward; whirl_display = |whirl_frequency| in the display unit "
      "[{0}]; whirl = forward|backward;\n"
      "#   zeta = -re_fixed / |fixed eigenvalue|; log_decrement = -2 pi re_fixed / |whirl_frequency| (empty when "
      "the whirl frequency is 0);\n"
      "#   rotor_share = rotor translation's share of M|dq|^2 + sum j_i m_i l_i^2 |dbeta_i|^2; forward_share = "
      "the mass-weighted share of the motion at a positive fixed-frame frequency (§16.2); balls_together = the balls' share in common rotation (16.3.1)\n",
      u);
  for (const auto& c : critical_speeds(samples))
    out += fmt::format("# critical speed ({}: rotor forward whirl = 1X): omega = {:.9g} rad/s = {:.6g} {} = {:.6g} "
                       "omega_n, between {} and {} rad/s, zeta = {:.4g}\n",
                       c.series, c.omega, from_rad_per_s(c.omega, unit), u, c.omega / c.omega_n, c.bracket_from,
                       c.bracket_to, c.damping_ratio);
  out += "step,omega,speed,omega_n,omega_over_omega_n,family,pattern,member,stable,mode,label,re_rotating,im_rotating,"
         "re_fixed,whirl_frequency,whirl_display,whirl,zeta,log_decrement,rotor_share,forward_share,balls_together\n";
  for (const auto& s : samples) {
    for (std::size_t k = 0; k < s.modes.size(); ++k) {
      const auto& m = s.modes[k];
      if (m.kind == ModeKind::set_direction) continue;
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},", s.step, num(s.omega, "omega"),
                         num(from_rad_per_s(s.omega, unit), "speed"), num(s.omega_n, "omega_n"),
                         num(s.omega / s.omega_n, "omega/omega_n"), s.family, s.pattern, s.member, s.stable ? 1 : 0,
                         k + 1, to_string(m.kind));
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", num(m.rotating.real(), "eigenvalue"),
                         num(m.rotating.imag(), "eigenvalue"), num(m.fixed.real(), "eigenvalue"),
                         num(m.whirl_frequency, "whirl"), num(from_rad_per_s(std::abs(m.whirl_frequency), unit), "whirl"),
                         m.whirl_frequency >= 0 ? "forward" : "backward", num(m.damping_ratio, "zeta"),
                         m.has_log_decrement ? num(m.log_decrement, "log decrement") : std::string(),
                         num(m.rotor_share, "share"), num(m.forward_share, "share"), num(m.common_share, "share"));
    }
  }
  return out;
}

namespace {
// Maximal runs of consecutive values where `flag` holds; ends are grid brackets.
std::vector<Range> runs(const std::vector<double>& values, const std::vector<bool>& flag) {
  std::vector<Range> out;
  for (std::size_t i = 0; i < values.size();) {
    if (!flag[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < values.size() && flag[j + 1]) ++j;
    Range r;
    r.from = values[i], r.to = values[j];
    r.from_kind = i == 0 ? "interval" : "grid";
    r.to_kind = j + 1 == values.size() ? "interval" : "grid";
    if (i > 0) r.from_outside = values[i - 1];
    if (j + 1 < values.size()) r.to_outside = values[j + 1];
    out.push_back(r);
    i = j + 1;
  }
  return out;
}

template <class S>
StabilityRanges sweep_ranges(const S& s) {
  std::vector<bool> balanced(s.values.size()), some(s.values.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const auto points = s.points[i].equilibria.points();
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (s.points[i].spectra[k].stability != Stability::stable) continue;
      some[i] = true;
      if (points[k].family == Family::balanced || points[k].on_balanced_set) balanced[i] = true;
    }
  }
  std::vector<bool> none(some.size());
  for (std::size_t i = 0; i < some.size(); ++i) none[i] = !some[i];
  return {runs(s.values, balanced), runs(s.values, none), runs(s.values, some)};
}

// Union of intervals (from <= to), merged where they touch or overlap.
std::vector<Range> merged(std::vector<Range> v) {
  std::sort(v.begin(), v.end(), [](const Range& a, const Range& b) { return a.from < b.from; });
  std::vector<Range> out;
  for (const auto& r : v) {
    if (!out.empty() && r.from <= out.back().to) {
      if (r.to > out.back().to) {
        out.back().to = r.to, out.back().to_kind = r.to_kind, out.back().to_outside = r.to_outside;
      }
      continue;
    }
    out.push_back(r);
  }
  return out;
}

// The complement of sorted disjoint `stable` in [lo, hi]. A stable range's "grid" end
// lies between its value and its outer neighbour, which is the complement's first
// (last) value inside, with the stable value as its own outer neighbour.
std::vector<Range> complement(const std::vector<Range>& stable, double lo, double hi) {
  std::vector<Range> out;
  Range gap;
  gap.from = lo, gap.from_kind = "interval";
  for (const auto& r : stable) {
    if (r.from > gap.from || (r.from_kind == "grid" && r.from_outside)) {
      gap.to = r.from, gap.to_kind = r.from_kind, gap.to_outside = std::nullopt;
      if (r.from_kind == "grid" && r.from_outside) gap.to = *r.from_outside, gap.to_outside = r.from;
      if (gap.to > gap.from || (gap.to == gap.from && gap.from_kind == "grid")) out.push_back(gap);
    }
    gap = Range{};
    gap.from = r.to, gap.from_kind = r.to_kind;
    if (r.to_kind == "grid" && r.to_outside) gap.from = *r.to_outside, gap.from_outside = r.to;
  }
  if (gap.from < hi) {
    gap.to = hi, gap.to_kind = "interval";
    out.push_back(gap);
  }
  return out;
}

// Stable segments of one branch: consecutive stable points (of the family `balanced_only`
// asks for), their ends at a located special point between the bracketing points if there
// is one (model.md §13.7), else at the last stable point (a grid end).
void branch_segments(const Branch& b, bool balanced_only, double lo, double hi, std::vector<Range>& out) {
  const auto ok = [&](const BranchPoint& pt) {
    return pt.spectrum.stability == Stability::stable && (!balanced_only || pt.family == Family::balanced);
  };
  const auto located = [&](double a, double c) -> std::optional<double> {
    for (const auto& sp : b.specials) {
      const double x = double(sp.parameter);
      // Between the two points, or (a fold: the parameter turns back between them) the
      // special point bracketed by exactly these two points.
      const double f = double(sp.bracket_from), t = double(sp.bracket_to);
      const bool bracketed = (f == a && t == c) || (f == c && t == a);
      if (sp.converged && ((x >= std::min(a, c) && x <= std::max(a, c)) || bracketed) &&
          (sp.label == Label::HB || sp.label == Label::LP || sp.label == Label::BP))
        return x;
    }
    return std::nullopt;
  };
  const auto& pts = b.points;
  for (std::size_t i = 0; i < pts.size();) {
    if (!ok(pts[i])) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < pts.size() && ok(pts[j + 1])) ++j;
    struct End { double value; std::string kind; std::optional<double> outside; };
    const auto end_at = [&](std::size_t inside, bool first) -> End {
      const bool at_end = first ? inside == 0 : inside + 1 == pts.size();
      const double x = double(pts[inside].parameter);
      if (at_end) {
        const bool interval = x <= lo || x >= hi;
        return {x, interval ? "interval" : "branch_end", std::nullopt};
      }
      const double y = double(pts[first ? inside - 1 : inside + 1].parameter);
      if (const auto z = located(x, y)) return {*z, "located", std::nullopt};
      return {x, "grid", y};
    };
    const End a = end_at(i, true), c = end_at(j, false);
    Range r;
    if (a.value <= c.value) {
      r = {a.value, c.value, a.kind, c.kind, a.outside, c.outside};
    } else {
      r = {c.value, a.value, c.kind, a.kind, c.outside, a.outside};
    }
    out.push_back(r);
    i = j + 1;
  }
}
}  // namespace

std::vector<Range> grid_ranges(const std::vector<double>& values, const std::vector<bool>& flag) {
  return runs(values, flag);
}

StabilityRanges stability_ranges(const SweepResult& s) { return sweep_ranges(s); }
StabilityRanges stability_ranges(const SweepResultN& s) { return sweep_ranges(s); }

StabilityRanges stability_ranges(const ContinuationRun& run) {
  const double lo = std::min(run.from, run.to), hi = std::max(run.from, run.to);
  std::vector<Range> balanced, some;
  for (const auto& b : run.branches) {
    branch_segments(b, true, lo, hi, balanced);
    branch_segments(b, false, lo, hi, some);
  }
  StabilityRanges r;
  r.balanced_stable = merged(balanced);
  r.some_stable = merged(some);
  r.nothing_stable = complement(r.some_stable, lo, hi);
  return r;
}

namespace {
std::string range_text(const Range& r, std::string_view param, std::string_view param_unit, SpeedUnit unit,
                       double omega_n) {
  const auto end = [](double x, const std::string& kind, const std::optional<double>& outside) {
    std::string s = fmt::format("{:.9g}", x);
    if (kind == "grid" && outside) s += fmt::format(" (grid: next value {:.9g})", *outside);
    if (kind == "located") s += " (located)";
    return s;
  };
  std::string s = fmt::format("{} .. {} {}", end(r.from, r.from_kind, r.from_outside), end(r.to, r.to_kind, r.to_outside),
                              param_unit);
  if (param == "omega" && unit != SpeedUnit::rad_per_s)
    s += fmt::format(" = {:.6g} .. {:.6g} {}", from_rad_per_s(r.from, unit), from_rad_per_s(r.to, unit), to_string(unit));
  if (param == "omega" && omega_n > 0) s += fmt::format(" ({:.4g} .. {:.4g} omega_n)", r.from / omega_n, r.to / omega_n);
  return s;
}

// omega_n > 0 (an omega range): the ends also as multiples of omega_n.
std::string ranges_json(const std::vector<Range>& v, double omega_n = 0) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& r = v[i];
    s += fmt::format("{}{{\"from\": {}, \"to\": {}, \"from_end\": \"{}\", \"to_end\": \"{}\", \"from_outside\": {}, "
                     "\"to_outside\": {}}}",
                     i ? ", " : "", num(r.from, "range"), num(r.to, "range"), r.from_kind, r.to_kind,
                     r.from_outside ? num(*r.from_outside, "range") : std::string("null"),
                     r.to_outside ? num(*r.to_outside, "range") : std::string("null"));
    if (omega_n > 0)
      s.insert(s.size() - 1, fmt::format(", \"from_over_omega_n\": {}, \"to_over_omega_n\": {}",
                                         num(r.from / omega_n, "ratio"), num(r.to / omega_n, "ratio")));
  }
  return s + "]";
}
}  // namespace

std::string ranges_text(const StabilityRanges& r, std::string_view param, std::string_view param_unit, SpeedUnit unit,
                        double omega_n) {
  std::string out;
  const auto list = [&](std::string_view what, const std::vector<Range>& v) {
    if (v.empty()) {
      out += fmt::format("{}: nowhere in the range\n", what);
      return;
    }
    for (const auto& x : v) out += fmt::format("{}: {} = {}\n", what, param, range_text(x, param, param_unit, unit, omega_n));
  };
  list("balanced state stable", r.balanced_stable);
  list("no stable state", r.nothing_stable);
  return out;
}

template <int N>
std::string summary_json(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p,
                         std::string_view param, std::string_view param_unit, double from, double to,
                         const StabilityRanges& r, const std::vector<CriticalSpeed>& critical, SpeedUnit unit) {
  std::string out = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                                ABU_VERSION, json_string(command_line), json_string(scene_file));
  out += fmt::format("  \"parameters\": {},\n", parameters_json(p));
  out += fmt::format("  \"swept\": {{\"name\": {}, \"unit\": {}, \"from\": {}, \"to\": {}}},\n", json_string(param),
                     json_string(param_unit), num(from, "from"), num(to, "to"));
  out += fmt::format("  \"display_unit\": {},\n", json_string(to_string(unit)));
  out += fmt::format("  \"omega_n\": {},\n  \"capacity\": {},\n  \"unbalance\": {},\n  \"capacity_exceeded\": {},\n",
                     quantity(natural_frequency(p), "rad/s", "omega_n"), quantity(ball_capacity_of(p), "kg m", "capacity"),
                     quantity(p.rotor.unbalance, "kg m", "U"), p.rotor.unbalance > ball_capacity_of(p));
  out += fmt::format("  \"ranges_note\": {},\n",
                     json_string("ranges of the swept parameter, in its unit; an end is 'located' (a special point of "
                                 "the continuation), 'grid' (the true end lies between the value and *_outside), "
                                 "'interval' (the end of the computed interval) or 'branch_end' (a branch stopped)"));
  out += fmt::format("  \"balanced_stable\": {},\n  \"nothing_stable\": {},\n  \"some_stable\": {},\n",
                     ranges_json(r.balanced_stable, param == "omega" ? natural_frequency(p) : 0),
                     ranges_json(r.nothing_stable, param == "omega" ? natural_frequency(p) : 0),
                     ranges_json(r.some_stable, param == "omega" ? natural_frequency(p) : 0));
  out += "  \"critical_speeds\": [";
  for (std::size_t i = 0; i < critical.size(); ++i) {
    const auto& c = critical[i];
    out += fmt::format("{}{{\"equilibrium\": {}, \"omega\": {}, \"speed\": {}, \"omega_over_omega_n\": {}, "
                       "\"bracket\": [{}, {}], \"damping_ratio\": {}}}",
                       i ? ",\n    " : "\n    ", json_string(c.series), quantity(c.omega, "rad/s", "omega"),
                       quantity(from_rad_per_s(c.omega, unit), to_string(unit), "speed"),
                       num(c.omega / c.omega_n, "ratio"), num(c.bracket_from, "bracket"), num(c.bracket_to, "bracket"),
                       num(c.damping_ratio, "zeta"));
  }
  out += critical.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}
template <int N>
MapRangesOutput map_ranges(const MapVerdicts& v, std::string_view x, std::string_view y,
                           std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p,
                           SpeedUnit unit, int max_lines) {
  MapRangesOutput result;
  if ((x != "omega" && y != "omega") || v.cells.empty() || v.cells.size() != v.x.size() * v.y.size()) return result;
  const std::string_view other = x == "omega" ? y : x;
  const bool omega_is_x = x == "omega";
  const std::vector<double>& omegas = omega_is_x ? v.x : v.y;
  const std::vector<double>& others = omega_is_x ? v.y : v.x;
  // omega ascending, whichever way the axis runs
  std::vector<std::size_t> order(omegas.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return omegas[a] < omegas[b]; });
  std::vector<double> omega(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) omega[k] = omegas[order[k]];
  std::vector<bool> balanced(order.size()), none(order.size());
  std::string json_rows;
  int lines = 0;
  for (std::size_t r = 0; r < others.size(); ++r) {
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t cell = omega_is_x ? order[k] * v.y.size() + r : r * v.y.size() + order[k];
      balanced[k] = (v.cells[cell] & MapVerdicts::balanced_stable) != 0;
      none[k] = (v.cells[cell] & MapVerdicts::some_stable) == 0;
    }
    StabilityRanges ranges;
    ranges.balanced_stable = runs(omega, balanced);
    ranges.nothing_stable = runs(omega, none);
    json_rows += fmt::format("{}{{{}: {}, \"balanced_stable\": {}, \"nothing_stable\": {}}}", r ? ",\n    " : "\n    ",
                             json_string(other), num(others[r], "axis"),
                             ranges_json(ranges.balanced_stable, natural_frequency(p)),
                             ranges_json(ranges.nothing_stable, natural_frequency(p)));
    if (lines < max_lines) {
      result.text += fmt::format("at {} = {:.6g}:\n", other, others[r]);
      const std::string block = ranges_text(ranges, "omega", "rad/s", unit, natural_frequency(p));
      for (std::size_t b = 0; b < block.size();) {
        const auto e = block.find('\n', b);
        result.text += "  " + block.substr(b, e - b + 1);
        b = e == std::string::npos ? block.size() : e + 1;
      }
      ++lines;
    }
  }
  if (int(others.size()) > max_lines)
    result.text += fmt::format("... {} more values of {} in the summary JSON\n", int(others.size()) - max_lines, other);
  result.json = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                            ABU_VERSION, json_string(command_line), json_string(scene_file));
  result.json += fmt::format("  \"parameters\": {},\n  \"omega_n\": {},\n  \"capacity\": {},\n  \"unbalance\": {},\n",
                             parameters_json(p), quantity(natural_frequency(p), "rad/s", "omega_n"),
                             quantity(ball_capacity_of(p), "kg m", "capacity"),
                             quantity(p.rotor.unbalance, "kg m", "U"));
  result.json += fmt::format("  \"speed_axis\": \"omega\",\n  \"speed_unit\": \"rad/s\",\n  \"other_axis\": {},\n", json_string(other));
  result.json += fmt::format("  \"ranges_note\": {},\n  \"rows\": [{}\n  ]\n}}\n",
                             json_string("per value of the other axis, the omega ranges on the map's grid where a "
                                         "balanced state is stable and where nothing is; an end is 'grid' (the true "
                                         "end lies between the value and *_outside) or 'interval'"),
                             json_rows);
  return result;
}
template MapRangesOutput map_ranges<2>(const MapVerdicts&, std::string_view, std::string_view, std::string_view,
                                       std::string_view, const Params&, SpeedUnit, int);
template MapRangesOutput map_ranges<any_balls>(const MapVerdicts&, std::string_view, std::string_view,
                                               std::string_view, std::string_view, const ParamsN&, SpeedUnit, int);

template std::string summary_json<2>(std::string_view, std::string_view, const Params&, std::string_view,
                                     std::string_view, double, double, const StabilityRanges&,
                                     const std::vector<CriticalSpeed>&, SpeedUnit);
template std::string summary_json<any_balls>(std::string_view, std::string_view, const ParamsN&, std::string_view,
                                             std::string_view, double, double, const StabilityRanges&,
                                             const std::vector<CriticalSpeed>&, SpeedUnit);

}  // namespace abu
