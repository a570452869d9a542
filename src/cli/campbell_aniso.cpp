#include "campbell_aniso.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "abu/io/chart_labels.hpp"
#include "abu/io/report_campbell_aniso.hpp"

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
  const auto csv_path = dir / "campbell_omega.csv";
  const auto staged = out.stage(csv_path, campbell_csv(samples, header + floquet_campbell_note(*scene.support, base), unit));
  files.push_back(csv_path);
  const std::vector<CriticalSpeed> critical = critical_speeds(samples);
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
    fmt::print(stderr, "critical speed ({}: rotor forward whirl crosses 1X): omega = {:.9g} rad/s = {:.6g} omega_n\n",
               c.series, c.omega, c.omega / c.omega_n);
  return files;
}

}  // namespace abu::cli
