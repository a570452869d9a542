// Sweep with an anisotropic support (docs/model.md §10.11): the glue between the sweep
// command's options and io's floquet_sweep.
#include "floquet_commands.hpp"

#include "campbell_aniso.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "abu/output/chart_labels.hpp"
#include "abu/analysis/floquet_sweep.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/core/errors.hpp"

namespace abu::cli {

namespace {
constexpr double kFloquetBranchStep = 0.005;  // scaled arclength: the interval is 1
}  // namespace

ContinuationOptions floquet_branch_numerics(const ContinuationOptions& numerics) {
  // A crossing is found where ln max|rho| changes sign between branch points, and the
  // engine's steps follow the branch's geometry, not the multipliers: with the default
  // step bound (0.2 of the interval) a window of instability a few % wide is stepped over.
  // Unless --ds-max is given, points at most 1/200 of the interval apart (§10.13).
  ContinuationOptions dense = numerics;
  if (dense.ds_max == ContinuationOptions{}.ds_max) dense.ds_max = kFloquetBranchStep;
  dense.ds = std::min(dense.ds, dense.ds_max);
  return dense;
}

int write_floquet_outputs(const Scene& scene, const SceneOptions& scene_options, const FloquetSweep& s,
                          const ParamsN& base, bool logarithmic, bool chart, const std::string& output_dir,
                          const std::string& stem, const std::string& what) {
  const std::string name = to_string(s.param);
  const std::string header = provenance_header(command_line(), scene.file, base);
  const std::filesystem::path dir(output_dir);
  const auto csv_path = dir / fmt::format("{}_{}.csv", stem, name);
  const auto crossings_path = dir / fmt::format("floquet_crossings_{}.csv", name);
  const auto png_path = dir / fmt::format("{}_{}.png", stem, name);
  OutputTransaction out;
  const auto staged_csv = out.stage(csv_path, floquet_sweep_csv(s, header));
  const auto staged_crossings = out.stage(crossings_path, floquet_crossings_csv(s, header));
  if (chart)
    run_gnuplot(plots_dir() / "sweep_floquet.gp",
                {{"csv", staged_csv.string()},
                 {"crossings", staged_crossings.string()},
                 {"png", out.reserve(png_path).string()},
                 {"param", name},
                 {"unit", std::string(unit(s.param.quantity))},
                 {"logx", logarithmic ? "1" : "0"},
                 {"has_crossings", s.crossings.empty() ? "0" : "1"},
                 {"title", fmt::format("{}: {} (anisotropic support: Floquet over pi/omega)", scene.file, what)},
                 {"subtitle", chart_subtitle(scene, scene_options.overrides,
                                              {{name, s.values.front(), s.values.back(), std::string(unit(s.param.quantity))}})}});
  // An omega sweep also gets the Campbell view of the Floquet modes (model.md §10.15).
  const auto campbell = stem == "sweep" ? stage_floquet_campbell(out, s, base, scene, scene_options, dir, header, chart)
                                        : std::vector<std::filesystem::path>{};
  out.commit();
  fmt::print(stderr, "{}", floquet_crossings_text(s));
  fmt::print(stderr, "wrote {} and {}{}\n", csv_path.string(), crossings_path.string(),
             chart ? fmt::format(" and {}", png_path.string()) : std::string());
  for (const auto& f : campbell) fmt::print(stderr, "wrote {}\n", f.string());
  return exit_ok;
}

int sweep_anisotropic(const Scene& scene, const SceneOptions& scene_options, ParamRef param,
                      const std::vector<double>& values, bool logarithmic, bool chart, const std::string& output_dir,
                      const BalancedSampling& sampling) {
  const ParamsN base = params_of<any_balls>(scene);
  const FloquetSweep s = floquet_sweep(base, *scene.support, param, values, sampling);
  return write_floquet_outputs(scene, scene_options, s, base, logarithmic, chart, output_dir, "sweep",
                               fmt::format("sweep of {}", to_string(param)));
}

void append_balanced_floquet(FloquetSweep& branch, const ParamsN& base, const Scene& scene, ParamRef param,
                             double value, EquilibriumN e, const FloquetSweepOptions& options, const char* what) {
  ParamsN p = base;
  set(p, param, value);
  e.family = Family::balanced;
  e.converged = true;
  FloquetAnalysis a;
  a.balanced.push_back(e);
  a.floquet.push_back(balanced_floquet(p, *scene.support, e, options.floquet));
  if (!a.floquet.back().status.ok())
    throw NumericalError(fmt::format("{}={}: Floquet multipliers of balanced {} {}: {}", to_string(param), value,
                                     what, e.member, a.floquet.back().status.reason));
  branch.values.push_back(value);
  branch.points.push_back(std::move(a));
}

int continue_anisotropic(const Scene& scene, const SceneOptions& scene_options, ParamRef param, double to,
                         const ContinuationOptions& numerics, bool chart, const std::string& output_dir) {
  // The balanced states are equilibria of the real system (model.md §10.3) and the mean
  // system's balanced branches are theirs: the one continuation engine traces them, and
  // the Floquet verdict is evaluated at every branch point (§10.13).
  const Params p2 = params_of<2>(scene);
  const ParamsN base = params_of<any_balls>(scene);
  StartSelection start;
  start.family = Family::balanced;
  const ContinuationRun run = continue_branches(p2, param, to, floquet_branch_numerics(numerics), start);
  FloquetSweepOptions options;
  FloquetSweep all;
  all.param = param;
  for (const Branch& b : run.branches) {
    FloquetSweep branch;
    branch.param = param;
    for (const BranchPoint& point : b.points) {
      if (point.family != Family::balanced) continue;
      EquilibriumN e;
      e.member = b.member;
      e.position = point.position;
      append_balanced_floquet(branch, base, scene, param, double(point.parameter), e, options, "branch");
    }
    locate_floquet_crossings(branch, base, *scene.support, {}, options);
    all.values.insert(all.values.end(), branch.values.begin(), branch.values.end());
    all.points.insert(all.points.end(), branch.points.begin(), branch.points.end());
    all.crossings.insert(all.crossings.end(), branch.crossings.begin(), branch.crossings.end());
  }
  fmt::print(stderr, "{} balanced branch(es), {} points (continuation of the mean system's balanced states)\n",
             run.branches.size(), all.values.size());
  return write_floquet_outputs(scene, scene_options, all, base, false, chart, output_dir, "floquet_branch",
                               fmt::format("balanced branches in {}", to_string(param)));
}

}  // namespace abu::cli
