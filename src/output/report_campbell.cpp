// The Campbell view (docs/views.md, docs/model.md §16; declared in report_views.hpp): the
// modes of every equilibrium along an omega sweep or continuation, their critical speeds
// (rotor forward whirl = 1X) and the Campbell CSV.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abu/output/format.hpp"
#include "abu/output/report_views.hpp"
#include "equilibrium_text.hpp"

namespace abu {

using detail::pattern_of;
using detail::state_label;

namespace {

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

CampbellSample campbell_sample(int step, const Params& p, const Equilibrium& e, const Spectrum& sp) {
  return sample_of(step, p, e, sp);
}

void append_campbell_samples(std::vector<CampbellSample>& out, int step, const ParamsN& p, const AnalysisN& a) {
  const auto points = a.equilibria.points();
  for (std::size_t k = 0; k < points.size(); ++k) out.push_back(sample_of(step, p, points[k], a.spectra[k]));
}

void sort_campbell_series(std::vector<CampbellSample>& samples) {
  // Contiguous series: stable sort by the series label keeps the values in order.
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.series < b.series; });
}

std::vector<CampbellSample> campbell_samples(const SweepResultN& s, const std::vector<ParamsN>& params) {
  std::vector<CampbellSample> out;
  if (s.name != "omega") return out;
  for (std::size_t i = 0; i < s.points.size(); ++i) append_campbell_samples(out, int(i), params[i], s.points[i]);
  sort_campbell_series(out);
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
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},", s.step, format_number(s.omega, "omega"),
                         format_number(from_rad_per_s(s.omega, unit), "speed"), format_number(s.omega_n, "omega_n"),
                         format_number(s.omega / s.omega_n, "omega/omega_n"), s.family, s.pattern, s.member,
                         s.stable ? 1 : 0, k + 1, to_string(m.kind));
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", format_number(m.rotating.real(), "eigenvalue"),
                         format_number(m.rotating.imag(), "eigenvalue"), format_number(m.fixed.real(), "eigenvalue"),
                         format_number(m.whirl_frequency, "whirl"),
                         format_number(from_rad_per_s(std::abs(m.whirl_frequency), unit), "whirl"),
                         m.whirl_frequency >= 0 ? "forward" : "backward", format_number(m.damping_ratio, "zeta"),
                         m.has_log_decrement ? format_number(m.log_decrement, "log decrement") : std::string(),
                         format_number(m.rotor_share, "share"), format_number(m.forward_share, "share"),
                         format_number(m.common_share, "share"));
    }
  }
  return out;
}

}  // namespace abu
