#include "campbell_aniso.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "abu/output/chart_labels.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/report_campbell_aniso.hpp"

namespace abu::cli {

std::vector<std::filesystem::path> stage_floquet_campbell(OutputTransaction& out, const FloquetSweep& s,
                                                          const ParamsN& base, const Scene& scene,
                                                          const SceneOptions& options, const std::filesystem::path& dir,
                                                          const std::string& header, bool chart) {
  std::vector<std::filesystem::path> files;
  if (s.param.quantity != Quantity::omega || !scene.support) return files;
  const std::vector<CampbellSample> samples = floquet_campbell_samples(s, base, *scene.support);
  if (samples.empty()) return files;  // no balanced state at any speed
  const SpeedUnit unit = options.speed_unit();
  // Critical speeds (model.md §10.15): where a rotor mode's line |Omega| crosses 1X. The
  // isotropic rule (a rotor *forward* mode, §16.6) finds none here when the rotor modes are
  // nearly linear whirls labelled by a near-tie; the rotor modes of a sample, ordered by
  // |Omega|, are matched in that order between neighbouring speeds of a series.
  std::vector<CriticalSpeed> critical;
  auto rotor_lines = [](const CampbellSample& c) {
    std::vector<std::pair<double, double>> lines;  // |Omega|, zeta
    for (const ModeView& m : c.modes)
      if (m.rotor_share >= 0.5) lines.push_back({std::abs(m.whirl_frequency), m.damping_ratio});
    std::sort(lines.begin(), lines.end());
    return lines;
  };
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const CampbellSample &a = samples[i - 1], &b = samples[i];
    if (a.series != b.series) continue;
    const auto la = rotor_lines(a), lb = rotor_lines(b);
    if (la.size() != lb.size()) continue;
    for (std::size_t k = 0; k < la.size(); ++k) {
      const double ga = la[k].first - a.omega, gb = lb[k].first - b.omega;
      if (ga == 0 || gb == 0 || (ga > 0) == (gb > 0)) continue;
      const double t = ga / (ga - gb);
      CriticalSpeed c;
      c.series = b.series, c.family = b.family, c.pattern = b.pattern, c.member = b.member;
      c.omega = a.omega + t * (b.omega - a.omega);
      c.omega_n = a.omega_n + t * (b.omega_n - a.omega_n);
      c.bracket_from = a.omega, c.bracket_to = b.omega;
      c.damping_ratio = la[k].second + t * (lb[k].second - la[k].second);
      critical.push_back(c);
    }
  }
  std::string note = floquet_campbell_note(*scene.support, base);
  for (const auto& c : critical)
    note += fmt::format("# critical speed ({}: a rotor mode's |whirl_frequency| = 1X): omega = {:.9g} rad/s = {:.6g} {} "
                        "= {:.6g} omega_n, between {} and {} rad/s, zeta = {:.4g}\n",
                        c.series, c.omega, from_rad_per_s(c.omega, unit), to_string(unit), c.omega / c.omega_n,
                        c.bracket_from, c.bracket_to, c.damping_ratio);
  const auto csv_path = dir / "campbell_omega.csv";
  const auto staged = out.stage(csv_path, campbell_csv(samples, header + note, unit));
  files.push_back(csv_path);
  if (chart) {
    std::string marks;
    std::vector<std::string> seen;  // one mark per distinct speed (mirror members share theirs)
    for (const auto& c : critical) {
      const std::string key = fmt::format("{:.6g}", c.omega);
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
      seen.push_back(key);
      marks += fmt::format("{} ", from_rad_per_s(c.omega, unit));
    }
    const auto png_path = dir / "campbell_omega.png";
    run_gnuplot(plots_dir() / "campbell.gp",
                {{"csv", staged.string()},
                 {"png", out.reserve(png_path).string()},
                 {"unit", std::string(to_string(unit))},
                 {"family", "balanced"},
                 {"critical", marks},
                 {"omega_n", fmt::format("{}", from_rad_per_s(natural_frequency(base), unit))},
                 {"title", fmt::format("{}: Campbell diagram, anisotropic support (Floquet modes)", scene.file)}});
    files.push_back(png_path);
  }
  for (const auto& c : critical)
    fmt::print(stderr, "critical speed ({}: a rotor mode's whirl crosses 1X): omega = {:.9g} rad/s = {:.6g} omega_n\n",
               c.series, c.omega, c.omega / c.omega_n);
  return files;
}

}  // namespace abu::cli
