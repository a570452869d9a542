#include "views.hpp"

#include "abu/output/gnuplot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>
#include <cstdio>

namespace abu::cli {

template <int N>
std::vector<std::filesystem::path> stage_views(OutputTransaction& out, const ViewsInput& in, const ParamsT<double, N>& p,
                                               const Scene& scene, const SceneOptions& options) {
  const SpeedUnit unit = options.speed_unit();
  std::vector<std::filesystem::path> files;
  const std::vector<CriticalSpeed> critical = critical_speeds(in.samples);
  if (!in.samples.empty()) {
    const auto csv_path = in.dir / fmt::format("campbell_{}.csv", in.param);
    const auto staged = out.stage(csv_path, campbell_csv(in.samples, in.header, unit));
    files.push_back(csv_path);
    if (in.chart) {
      const auto png_path = in.dir / fmt::format("campbell_{}.png", in.param);
      std::string marks;
      for (const auto& c : critical)
        if (c.family == "balanced" || critical.size() == 1) marks += fmt::format("{} ", from_rad_per_s(c.omega, unit));
      // The chart shows one family: the balanced state where it exists (the design state).
      std::string family = "balanced";
      bool has_balanced = false;
      for (const auto& s : in.samples) has_balanced = has_balanced || s.family == "balanced";
      if (!has_balanced) family = in.samples.front().family;
      if (!has_balanced) {
        marks.clear();
        for (const auto& c : critical)
          if (c.family == family) marks += fmt::format("{} ", from_rad_per_s(c.omega, unit));
      }
      {  // one mark per distinct speed (mirror members and branches share theirs)
        std::vector<std::string> seen;
        std::string unique;
        for (std::size_t pos = 0; pos < marks.size();) {
          const auto end = marks.find(' ', pos);
          const std::string w = marks.substr(pos, end - pos);
          const std::string key = fmt::format("{:.6g}", std::stod(w));
          if (std::find(seen.begin(), seen.end(), key) == seen.end()) seen.push_back(key), unique += w + " ";
          pos = end + 1;
        }
        marks = unique;
      }
      run_gnuplot(plots_dir() / "campbell.gp",
                  {{"csv", staged.string()},
                   {"png", out.reserve(png_path).string()},
                   {"unit", std::string(to_string(unit))},
                   {"family", family},
                   {"critical", marks},
                   {"omega_n", fmt::format("{}", from_rad_per_s(natural_frequency(p), unit))},
                   {"title", in.title}});
      files.push_back(png_path);
    }
  }
  const auto json_path = in.dir / fmt::format("summary_{}.json", in.param);
  out.stage(json_path, summary_json(command_line(), scene.file, p, in.param, in.param_unit, in.from, in.to, in.ranges,
                                    critical, unit));
  files.push_back(json_path);
  fmt::print(stderr, "{}", ranges_text(in.ranges, in.param, in.param_unit, unit, natural_frequency(p)));
  // One line per family (and pattern): its equilibria's crossings share a speed up to the
  // ball arrangement (mirror members, branches, samples of one balanced set): min .. max.
  for (std::size_t i = 0; i < critical.size();) {
    const auto& c = critical[i];
    double lo = c.omega, hi = c.omega;
    std::size_t j = i + 1;
    for (; j < critical.size() && critical[j].family == c.family && critical[j].pattern == c.pattern; ++j)
      lo = std::min(lo, critical[j].omega), hi = std::max(hi, critical[j].omega);
    const auto speed = [&](double w) {
      return unit == SpeedUnit::rad_per_s ? fmt::format("{:.9g} rad/s", w)
                                          : fmt::format("{:.9g} rad/s = {:.6g} {}", w, from_rad_per_s(w, unit), to_string(unit));
    };
    const std::string who = j - i > 1 ? fmt::format("{}{}{}, {} equilibria", c.family, c.pattern.empty() ? "" : " ",
                                                    c.pattern, j - i)
                                      : c.series;
    fmt::print(stderr, "critical speed ({}: rotor forward whirl crosses 1X): omega = {}{} = {:.6g} omega_n\n", who,
               speed(lo), speed(hi) != speed(lo) ? fmt::format(" .. {}", speed(hi)) : std::string(), lo / c.omega_n);
    i = j;
  }
  return files;
}

std::string omega_axis_input(const SceneOptions& options, const std::string& axis) {
  if (options.speed_unit() == SpeedUnit::rad_per_s || axis.rfind("omega:", 0) != 0) return axis;
  std::vector<std::string> parts;
  for (std::size_t pos = 0;;) {
    const auto end = axis.find(':', pos);
    parts.push_back(axis.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
    if (end == std::string::npos) break;
    pos = end + 1;
  }
  if (parts.size() < 3) return axis;
  for (std::size_t k : {std::size_t(1), std::size_t(2)}) {
    double v = 0;
    const auto& t = parts[k];
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || ptr != t.data() + t.size()) return axis;
    parts[k] = fmt::format("{}", omega_input(options, v));
  }
  std::string out;
  for (std::size_t k = 0; k < parts.size(); ++k) out += (k ? ":" : "") + parts[k];
  return out;
}

void write_map_ranges(const std::filesystem::path& dir, const std::string& x, const std::string& y,
                      const MapVerdicts& verdicts, const Scene& scene, const SceneOptions& options,
                      const std::string& command, bool quiet) {
  if (x != "omega" && y != "omega") return;
  const MapRangesOutput r = map_ranges(verdicts, x, y, command, scene.file, params_of<any_balls>(scene),
                                       options.speed_unit(), 10);
  if (r.json.empty()) return;
  OutputTransaction out;
  out.stage(dir / fmt::format("summary_{}_{}.json", x, y), r.json);
  out.commit();
  if (!quiet) fmt::print(stderr, "{}", r.text);
}

template std::vector<std::filesystem::path> stage_views<2>(OutputTransaction&, const ViewsInput&, const Params&,
                                                           const Scene&, const SceneOptions&);
template std::vector<std::filesystem::path> stage_views<any_balls>(OutputTransaction&, const ViewsInput&,
                                                                   const ParamsN&, const Scene&, const SceneOptions&);

}  // namespace abu::cli
