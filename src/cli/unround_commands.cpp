// `sweep` and `continue` on an unround race (unround_commands.hpp, model.md §11.10).
#include "unround_commands.hpp"
#include "tiled_run.hpp"

#include <fmt/format.h>

#include <sstream>

#include "abu/continuation/unround_branches.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/suggest.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/ranges.hpp"
#include "abu/output/report_unround.hpp"
#include "abu/analysis/map_setup.hpp"
#include "abu/scan/scan.hpp"
#include "abu/scan/unround_map.hpp"

namespace abu::cli {

namespace {
constexpr int kMaxUnroundSteps = 100000;
}  // namespace

namespace {
void require_unround(const Scene& scene, const std::string& option) {
  if (scene.race.round())
    throw InputError(option, 0, kUnroundnessParam,
                     fmt::format("{} has no unround race to scale ([race] unroundness, model.md §11.1)", scene.file));
}
}  // namespace

SweepPaths sweep_paths(const std::filesystem::path& dir, const std::string& name) {
  return {dir / fmt::format("sweep_{}.csv", name), dir / fmt::format("summary_{}.csv", name),
          dir / fmt::format("summary_{}.png", name)};
}

UnroundValues unround_values(const Scene& scene, const UnroundGrid& g) {
  if (g.steps < 1 || g.steps > kMaxUnroundSteps)
    throw InputError("--steps", 0, "steps", fmt::format("must be in [1, {}] (got {})", kMaxUnroundSteps, g.steps));
  if (g.logarithmic && !(g.from > 0 && g.to > 0))
    throw InputError("--log", 0, g.param, fmt::format("a log grid needs both ends > 0 (got {} .. {})", g.from, g.to));
  UnroundValues out;
  out.values = grid_values(g.from, g.to, g.steps, g.logarithmic);
  if (g.param == kUnroundnessParam) {
    require_unround(scene, "--param");
    if (!(g.from >= 0 && g.to >= 0))
      throw InputError("--from/--to", 0, kUnroundnessParam,
                       fmt::format("the unroundness factor is >= 0 (got {} .. {})", g.from, g.to));
    out.name = kUnroundnessParam;
    out.unit = std::string(1, '-');  // a factor (move-assigned: GCC 12's -Wrestrict misfires on "-")
    const RaceShape race = race_shape(scene);
    for (double v : out.values) {
      out.scenes.push_back(scene);
      out.races.push_back(checked_scaled_race(scene, race, v, "--from/--to"));
    }
    return out;
  }
  const auto ref = parse_param(g.param, int(scene.balls.size()));
  if (!ref)
    throw InputError("--param", 0, g.param,
                     unknown_name_rule("unknown parameter", closest_param(g.param, true), "known",
                                       fmt::format("{}, or {} (the race's amplitudes times a factor)",
                                                   param_symbols_help(), kUnroundnessParam)));
  out.name = to_string(*ref);
  out.unit = std::string(unit(ref->quantity));
  for (double v : out.values) {
    Scene s = scene;
    set_checked(s, *ref, v, "--from/--to");
    check_numerical_range(s, "--from/--to", fmt::format("at {}={}", g.param, v));
    out.races.push_back(race_shape(s));  // surface harmonics follow l and r; the rules are re-checked
    out.scenes.push_back(std::move(s));
  }
  return out;
}

int sweep_unround(const Scene& scene, const SceneOptions& options, const UnroundGrid& g) {
  UnroundValues grid = unround_values(scene, g);
  const std::vector<double>& values = grid.values;
  const std::vector<Scene>& scenes = grid.scenes;
  const std::vector<RaceShape>& races = grid.races;
  UnroundSweep sweep;
  sweep.name = grid.name;
  sweep.unit = grid.unit;
  for (std::size_t i = 0; i < values.size(); ++i) {
    throw_if_stopped("sweep: unround race");
    const ParamsN p = params_of<any_balls>(scenes[i]);
    UnroundResult r = find_unround_equilibria(p, races[i]);
    for (const auto& e : r.list)
      if (!(e.residual < 1e-8))
        throw NumericalError(fmt::format("{}={}: an equilibrium of the unround race has residual {:.3g}", sweep.name,
                                         values[i], e.residual));
    if (!r.doubt.empty()) fmt::print(stderr, "warning: {}={}: unround race: {}\n", sweep.name, values[i], r.doubt);
    sweep.values.push_back(values[i]);
    sweep.lambdas.push_back(unround_lambda(p, races[i]));
    const double dyn = std::hypot(p.rotor.stiffness - p.omega * p.omega * p.total_mass(), p.rotor.damping * p.omega);
    sweep.bare_whirls.push_back(p.omega * p.omega * p.rotor.unbalance / dyn);
    sweep.points.push_back(std::move(r));
  }
  const ParamsN first = params_of<any_balls>(scenes.front());
  const std::string header = provenance_header(command_line(), scene.file, first);
  const auto [csv_path, summary_path, png_path] = sweep_paths(g.output_dir, sweep.name);
  OutputTransaction out;
  const auto staged_all = out.stage(csv_path, unround_sweep_csv(sweep, header));
  const auto staged_summary = out.stage(summary_path, unround_sweep_summary_csv(sweep, header));
  if (g.chart)
    run_gnuplot(plots_dir() / "unround_sweep.gp",
                {{"csv", staged_all.string()},
                 {"summary", staged_summary.string()},
                 {"png", out.reserve(png_path).string()},
                 {"param", sweep.name},
                 {"unit", sweep.unit},
                 {"logx", g.logarithmic ? "1" : "0"},
                 {"title", fmt::format("{}: unround race, sweep of {}", scene.file, sweep.name)},
                 {"subtitle", chart_subtitle(scene, options.overrides,
                                              {{sweep.name, sweep.values.front(), sweep.values.back(), sweep.unit}})}});
  out.commit();
  fmt::print(stderr, "wrote {} and {}{}\n", csv_path.string(), summary_path.string(),
             g.chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}

int continue_unroundness(const Scene& scene, const SceneOptions& options, double to, const ContinuationOptions& numerics,
                         bool chart, const std::string& output_dir) {
  require_unround(scene, "--param");
  if (!(to > 0)) throw InputError("--to", 0, kUnroundnessParam, fmt::format("the factor's end must be > 0 (got {})", to));
  const RaceShape race = race_shape(scene);
  checked_scaled_race(scene, race, to, "--to");
  const ParamsN p = params_of<any_balls>(scene);
  const UnroundBranches b = continue_unround(p, race, to, numerics);
  if (!b.doubt.empty()) fmt::print(stderr, "warning: unround race continuation: {}\n", b.doubt);
  const std::string header = provenance_header(command_line(), scene.file, p);
  const std::filesystem::path dir(output_dir);
  const auto branch_path = dir / "branch_unroundness.csv";
  const auto special_path = dir / "special_unroundness.csv";
  const auto png_path = dir / "branch_unroundness.png";
  OutputTransaction out;
  const auto staged_branches = out.stage(branch_path, unround_branch_csv(b, header));
  const auto staged_specials = out.stage(special_path, unround_special_csv(b, header));
  if (chart)
    run_gnuplot(plots_dir() / "unround_branches.gp",
                {{"branches", staged_branches.string()},
                 {"specials", staged_specials.string()},
                 {"png", out.reserve(png_path).string()},
                 {"title", fmt::format("{}: unround race, continuation in the unroundness factor", scene.file)},
                 {"subtitle", chart_subtitle(scene, options.overrides, {{"unroundness", 0.0, to, "-"}})}});
  out.commit();
  std::size_t points = 0, specials = 0;
  for (const auto& br : b.branches) points += br.points.size(), specials += br.specials.size();
  fmt::print(stderr, "wrote {} ({} branches, {} points) and {} ({} special points){}\n", branch_path.string(),
             b.branches.size(), points, special_path.string(), specials,
             chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}

UnroundAxis unround_axis(const std::string& spec, const Scene& scene, const RaceShape& race, const std::string& origin) {
  UnroundAxis a;
  if (spec.rfind(kUnroundnessParam + ":", 0) != 0) {
    a.axis = parse_axis(spec, scene, origin);
    if (a.axis.ball_count) throw InputError(origin, 0, spec, "the ball count is not an axis of an unround race map");
    a.name = a.axis.name();
    a.unit = std::string(unit(a.axis.param.quantity));
    return a;
  }
  // unroundness:FROM:TO:N[:log], checked like the other axes (N in [1, 100000]).
  std::vector<std::string> f;
  std::stringstream in(spec);
  for (std::string x; std::getline(in, x, ':');) f.push_back(x);
  const auto bad = [&](const std::string& rule) { return InputError(origin, 0, spec, rule); };
  if (f.size() != 4 && !(f.size() == 5 && f[4] == "log")) throw bad("expected unroundness:FROM:TO:N[:log]");
  const std::vector<double> ends = parse_real_list(f[1] + "," + f[2], origin);
  int count = 0;
  try {
    std::size_t used = 0;
    count = std::stoi(f[3], &used);
    if (used != f[3].size()) count = 0;
  } catch (const std::exception&) {
    count = 0;
  }
  if (count < 1 || count > kMaxUnroundSteps) throw bad(fmt::format("N must be an integer in [1, {}]", kMaxUnroundSteps));
  a.axis.from = ends[0];
  a.axis.to = ends[1];
  a.axis.count = count;
  a.axis.logarithmic = f.size() == 5;
  if (!(a.axis.from >= 0 && a.axis.to >= 0)) throw bad("the unroundness factor is >= 0");
  if (a.axis.logarithmic && !(a.axis.from > 0 && a.axis.to > 0)) throw bad("a log axis needs both ends > 0");
  for (double v : {a.axis.from, a.axis.to}) checked_scaled_race(scene, race, v, origin);
  a.factor = true;
  a.name = kUnroundnessParam;
  a.unit = std::string(1, '-');
  return a;
}

UnroundMapAxes unround_map_axes(const std::string& x_spec, const std::string& y_spec, const Scene& scene,
                                const RaceShape& race) {
  UnroundMapAxes a{unround_axis(x_spec, scene, race, "--x"), unround_axis(y_spec, scene, race, "--y"), {}, {}};
  if (a.x.name == a.y.name) throw InputError("--y", 0, y_spec, "the two axes are one parameter");
  if (long(a.x.axis.count) * long(a.y.axis.count) > kMaxCells)
    throw InputError("--y", 0, y_spec, fmt::format("the map would have {} x {} cells; at most {} are allowed",
                                                   a.x.axis.count, a.y.axis.count, kMaxCells));
  for (int i = 0; i < a.x.axis.count; ++i) a.xs.push_back(a.x.axis.value(i));
  for (int i = 0; i < a.y.axis.count; ++i) a.ys.push_back(a.y.axis.value(i));
  return a;
}

UnroundCell unround_cell(const Scene& scene, const UnroundAxis& x, double xv, const UnroundAxis& y, double yv) {
  UnroundCell cell{scene, 1.0};
  for (const auto& [a, v] : {std::pair{&x, xv}, std::pair{&y, yv}}) {
    if (a->factor)
      cell.factor = v;
    else
      set_checked(cell.scene, a->axis.param, v, "--x/--y");
  }
  return cell;
}

int map_unround(const Scene& scene, const SceneOptions& options, const UnroundMapRequest& request) {
  require_unround(scene, request.x.rfind(kUnroundnessParam, 0) == 0 ? "--x" : "--y");
  const RaceShape race = race_shape(scene);
  const UnroundMapAxes axes = unround_map_axes(request.x, request.y, scene, race);
  const UnroundAxis &x = axes.x, &y = axes.y;
  UnroundMapJob job;
  job.x_name = x.name, job.y_name = y.name, job.x_unit = x.unit, job.y_unit = y.unit;
  job.xs = axes.xs, job.ys = axes.ys;
  job.cell_input = [&scene, &x, &y, &job](int ix, int iy) {
    const UnroundCell c = unround_cell(scene, x, job.xs[std::size_t(ix)], y, job.ys[std::size_t(iy)]);
    return std::pair{params_of<any_balls>(c.scene), scaled_race(race_shape(c.scene), c.factor)};
  };
  job.provenance = provenance_header(request.command_line, scene.file, params_of<any_balls>(scene));
  SummaryMapRun run{request.output_dir, "summary", "unround_map", x.name, y.name, int(job.xs.size()),
                    unround_map_manifest(job), unround_map_header(job),
                    {request.resume, request.fresh, request.progress, request.quiet, request.threads}, request.chart,
                    "unround_map.gp", axes_chart_variables(x.name, x.unit, x.axis.logarithmic, y.name, y.unit,
                                                           y.axis.logarithmic),
                    "equilibria"};
  run.chart_variables.insert(run.chart_variables.end(),
                             {{"title", fmt::format("{}: unround race map", scene.file)},
                              {"subtitle", chart_subtitle(scene, options.overrides, {{x.name, x.axis.from, x.axis.to, x.unit}, {y.name, y.axis.from, y.axis.to, y.unit, "y axis"}})}});
  return run_summary_map(run, [&job](const auto& missing, const auto& run_options, const auto& sink) {
    return compute_unround_map_tiles(job, missing, run_options, sink);
  });
}

}  // namespace abu::cli
