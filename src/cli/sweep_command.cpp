// `stability-scan sweep SCENE --param NAME --from A --to B --steps N [--log]`: the
// analysis on a plain grid of one parameter, as a long CSV and a gnuplot chart.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "cli.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "abu/core/suggest.hpp"
#include "abu/core/widen_params.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/input/ranges.hpp"
#include "abu/output/report_dry_along.hpp"
#include "abu/output/report_lugre.hpp"
#include "abu/output/report.hpp"
#include "abu/output/sweep_stream.hpp"
#include "abu/analysis/dry_friction.hpp"
#include "abu/analysis/equilibria.hpp"
#include "abu/scan/scan.hpp"
#include "commands.hpp"
#include "composed_commands.hpp"
#include "shaft_commands.hpp"
#include "stick_options.hpp"
#include "unround_commands.hpp"
#include "floquet_commands.hpp"
#include "views.hpp"

namespace abu::cli {

namespace {
struct SweepOptions {
  SceneOptions scene;
  std::string param;
  double from = 0, to = 0;
  int steps = 0;
  bool logarithmic = false;
  bool chart = true;
  std::string output_dir = "out";
  BalancedSampling sampling;
  StickSetOptions stick;  // coulomb-set scenes
  DryRows dry = DryRows::automatic;  // coulomb / stribeck: the rows' dry figures (model.md §14.10)
  ShaftSpectrumOptions shaft;  // a flexible shaft's Campbell diagram (model.md §18)
};
// The grid must stay inside the parameter's physical range; it is an interval, so the
// two ends decide. Checked before any work, with the scene's own rules.
constexpr int kMaxSteps = 1000000;

// The parameter of --param (not the ball count) and its grid's rules, checked.
ParamRef checked_param(const SweepOptions& o, int n_balls) {
  const auto ref = parse_param(o.param, n_balls);
  if (!ref)
    throw InputError("--param", 0, o.param,
                     unknown_name_rule("unknown parameter", closest_param(o.param, true), "known",
                                       fmt::format("{}, or n (a ring's ball count)", param_symbols_help())));
  if (o.steps < 1 || o.steps > kMaxSteps)
    throw InputError("--steps", 0, "steps", fmt::format("must be in [1, {}] (got {})", kMaxSteps, o.steps));
  if (o.logarithmic && !(o.from > 0 && o.to > 0))
    throw InputError("--log", 0, o.param, fmt::format("a log grid needs both ends > 0 (got {} .. {})", o.from, o.to));
  return *ref;
}

// The values of a sweep over any parameter, or the ball count of a ring scene (`--param n`:
// every integer from --from to --to), each value's scene checked against its rules.
struct SweepGrid {
  std::string name, unit;
  std::vector<double> values;
  std::vector<Scene> scenes;  // one per value
};
SweepGrid sweep_grid(const Scene& scene, const SweepOptions& o) {
  SweepGrid result;
  result.name = o.param;
  std::vector<Scene>& scenes = result.scenes;
  if (o.param == "n") {
    if (!scene.ring)
      throw InputError("--param", 0, "n", "the ball count is a study parameter only for a [balls] ring scene");
    if (o.from != std::floor(o.from) || o.to != std::floor(o.to))
      throw InputError("--from", 0, "n", fmt::format("a range of integers (got {} .. {})", o.from, o.to));
    result.unit = "-";
    const double step = o.to < o.from ? -1 : 1;  // a descending range runs downward
    for (double n = o.from; step * n <= step * o.to; n += step) {
      Scene s = scene;
      set_ball_count(s, int(n), "--param n");
      scenes.push_back(s);
      result.values.push_back(n);
    }
  } else {
    const auto ref = std::optional<ParamRef>(checked_param(o, int(scene.balls.size())));
    result.name = to_string(*ref);
    result.unit = std::string(unit(ref->quantity));
    for (double v : grid_values(o.from, o.to, o.steps, o.logarithmic)) {
      Scene s = scene;
      set_checked(s, *ref, v, "--from/--to");
      check_numerical_range(s, "--from/--to", fmt::format("at {}={}", o.param, v));
      scenes.push_back(s);
      result.values.push_back(v);
    }
  }
  return result;
}

// What a sweep other than the two-ball one holds, estimated before the work and refused
// beyond the machine (docs/robustness.md): with `streamed` (sweep_any_balls, output/
// sweep_stream.hpp) one value's analysis as `equilibria` holds it (the stick set's grid only
// with the rows' dry figures),
// and per value its kept text (4 kB) and, for omega, its Campbell samples (16 kB a state,
// measured 12.6 kB for 11 balls); otherwise (LuGre, coulomb-set) every value's analysis with
// ~2 kB of CSV a state. For --param n at the largest ball count.
void check_sweep_memory(const Scene& scene, const SweepOptions& o, bool streamed) {
  double values = double(o.steps) + 1;
  Scene largest = scene;
  if (o.param == "n") {
    values = std::abs(o.to - o.from) + 1;
    const double n = std::clamp(std::max(o.from, o.to), 2.0, double(max_balls));
    largest.balls.resize(std::size_t(n), scene.balls.back());
  }
  EquilibriaOptions request;
  request.sampling = o.sampling;
  request.stick = stick_resolution(o.stick);
  request.output_bytes_per_state = 2e3;
  const EquilibriaEstimate per_value = equilibria_estimate(largest, request);
  // the stick set's grid only where the rows may carry the dry figures (one set at a time)
  const bool dry = has_dry_verdict(scene.law) && o.dry != DryRows::off;
  const double analysis = per_value.memory - 60e6 - (dry ? 0.0 : per_value.grid);
  const double kept = 4e3 + (o.param == "omega" ? 16e3 * per_value.states : 0.0);
  const double memory = streamed ? 60e6 + analysis + values * kept : 60e6 + values * analysis;
  if (memory > 1e8) fmt::print(stderr, "sweep: memory: at most about {}\n", gigabytes(memory));
  require_memory(memory, "--steps", "the sweep",
                 fmt::format("{:.0f} values of up to {:.0f} states each, {}", values, per_value.states,
                             streamed ? "what each keeps (its Campbell samples for omega)" : "their analyses and text"),
                 "use fewer steps or a smaller --set-samples");
}

// A LuGre scene (model.md §12.8): per value the z = 0 equilibria with both one-sided
// spectra (what `equilibria` lists), one CSV; the ball count is not a LuGre parameter here.
int sweep_lugre(const Scene& scene, const SweepOptions& o) {
  if (o.param == "n")
    throw InputError("--param", 0, "n", "the ball count is not swept for friction law 'lugre' (model.md §12.8)");
  const SweepGrid grid = sweep_grid(scene, o);
  const std::string& name = grid.name;
  const std::vector<double>& values = grid.values;
  const std::vector<Scene>& scenes = grid.scenes;
  std::vector<std::vector<LugreRow>> rows;
  for (std::size_t i = 0; i < values.size(); ++i) {
    throw_if_stopped("sweep (lugre)");
    rows.push_back(lugre_zero_bristle_rows(params_of<any_balls>(scenes[i]), o.sampling));
    const std::string w = lugre_warnings(rows.back());
    if (!w.empty()) fmt::print(stderr, "at {}={}:\n{}", name, values[i], w);
  }
  const ParamsN first = params_of<any_balls>(scenes.front());
  const auto csv_path = std::filesystem::path(o.output_dir) / fmt::format("sweep_{}.csv", name);
  OutputTransaction out;
  out.stage(csv_path, lugre_sweep_csv(name, values, rows, first, provenance_header(command_line(), scene.file, first)));
  out.commit();
  std::size_t count = 0;
  for (const auto& r : rows) count += r.size();
  fmt::print(stderr, "wrote {} ({} states over {} values; no chart for friction law 'lugre' yet)\n", csv_path.string(),
             count, values.size());
  return exit_ok;
}

// Any ball count, and the ball count itself as the parameter (`--param n` on a [balls]
// ring scene: every integer from --from to --to, --steps ignored): the long CSV, a
// summary per value (capacity, balanced set, fraction stable, aligned equilibria, best
// stable |q|) and its chart.
int sweep_any_balls(const Scene& scene, const SweepOptions& o) {
  const SweepGrid grid = sweep_grid(scene, o);
  int n_max = 2;
  for (const auto& s : grid.scenes) n_max = std::max(n_max, int(s.balls.size()));
  // Each value's analysis is written and dropped as it comes (output/sweep_stream.hpp); with a
  // coulomb or stribeck law each row also carries what dry friction leaves there (model.md §14.10).
  std::vector<ParamsN> params;
  for (const auto& s : grid.scenes) params.push_back(params_of<any_balls>(s));
  const DryAlong dry = dry_figures_along(grid.values, params, {o.dry, stick_resolution(o.stick), 1});
  SweepStream stream(grid.name, grid.unit, grid.values.size(), n_max, grid.name == "omega",
                     dry.computed() ? dry.which : std::string());
  std::string warnings;  // after the dry verdict, which leads
  for (std::size_t i = 0; i < grid.scenes.size(); ++i) {
    throw_if_stopped("sweep");
    const AnalysisN analysis = analyze(params[i], o.sampling);
    warnings += analysis_warnings(analysis, fmt::format("{}={}", grid.name, grid.values[i]));
    stream.add(grid.values[i], analysis, params[i], dry.computed() ? dry.figures.at(grid.values[i]) : DryFigures{});
  }
  const ParamsN& first = params.front();
  const std::string header = provenance_header(command_line(), scene.file, first);
  const std::filesystem::path dir(o.output_dir);
  const auto [csv_path, summary_path, png_path] = sweep_paths(dir, grid.name);
  fmt::print(stderr, "{}{}", dry_along_lead(grid.name, grid.unit, dry, csv_path.string()), warnings);
  OutputTransaction out;
  stage_views(out,
              {dir, grid.name, grid.unit, grid.values.front(), grid.values.back(), stream.campbell(), stream.ranges(),
               header, fmt::format("{}: Campbell diagram (fixed frame)", scene.file), o.chart},
              first, scene, o.scene);
  const auto staged_summary = stream.stage(out, csv_path, summary_path, header).second;
  if (o.chart) {
    run_gnuplot(plots_dir() / "sweep_summary.gp",
                {{"csv", staged_summary.string()},
                 {"png", out.reserve(png_path).string()},
                 {"param", grid.name},
                 {"unit", grid.unit},
                 {"logx", o.logarithmic ? "1" : "0"},
                 {"title", fmt::format("{}: sweep of {}", scene.file, grid.name)},
                 {"subtitle", chart_subtitle(scene, o.scene.overrides,
                                              {{grid.name, grid.values.front(), grid.values.back(), grid.unit}})},
                 {"dry", dry.computed() ? "1" : "0"}});
  }
  out.commit();
  fmt::print(stderr, "wrote {} and {}{}\n", csv_path.string(), summary_path.string(),
             o.chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}
}  // namespace

Action add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub = app.add_subcommand(
      "sweep",
      "Equilibria and spectra on a plain grid of one parameter: CSV (one row per equilibrium per value) and a PNG "
      "chart of |q| and the spectral abscissa (stable solid, unstable dashed).");
  add_scene_options(*sub, o->scene);
  sub->add_option("--param", o->param,
                  fmt::format("Parameter to sweep: {}, or n (the ball count of a [balls] ring scene), or unroundness (every race amplitude times a factor, model.md §11.10)", param_symbols_help()))
      ->required();
  sub->add_option("--from", o->from, "First value (SI; omega in --units)")->required();
  sub->add_option("--to", o->to, "Last value (SI; omega in --units)")->required();
  sub->add_option("--steps", o->steps, "Number of intervals: N+1 values including both ends (not for --param n)");
  sub->add_flag("--log", o->logarithmic, "Space the values evenly in log");
  sub->add_flag("!--no-chart", o->chart, "Skip the PNG chart");
  sub->add_option("-o,--output-dir", o->output_dir, "Directory for sweep_NAME.csv and sweep_NAME.png")
      ->capture_default_str();
  sub->add_option("--set-samples", o->sampling.samples_per_sheet,
                  "Samples per sheet of the balanced set (n >= 3 balls), as for `equilibria`")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  add_stick_resolution_options(*sub, o->stick);
  add_dry_rows_option(*sub, o->dry);
  add_shaft_spectrum_options(*sub, o->shaft);
  return [o]() -> int {
    Scene scene = load(o->scene);
    if (unround_on_shaft(scene)) {  // the race's equilibria on the shaft per value (model.md §18.18)
      refuse_unmodelled(scene, "sweep", {.shaft_unround = true});
      check_output_directory(o->output_dir);
      if (o->param == "omega") o->from = omega_input(o->scene, o->from), o->to = omega_input(o->scene, o->to);
      return sweep_shaft_race(scene, o->scene,
                              {o->param, o->from, o->to, o->steps, o->logarithmic, o->chart, o->output_dir}, o->shaft);
    }
    if (scene.shaft && !set_valued_on_shaft(scene)) {  // the Campbell diagram over omega (model.md §16.1, §18)
      refuse_unmodelled(scene, "sweep", {.shaft = true});
      if (o->param != "omega")
        throw InputError("--param", 0, o->param,
                         "a flexible shaft ([shaft]) is swept over omega only so far (its Campbell diagram)");
      if (o->steps < 1 || o->steps > 100000)
        throw InputError("--steps", 0, "steps", fmt::format("must be in [1, 100000] (got {})", o->steps));
      if (o->logarithmic && !(o->from > 0 && o->to > 0))
        throw InputError("--log", 0, "omega", fmt::format("a log grid needs both ends > 0 (got {} .. {})", o->from, o->to));
      check_output_directory(o->output_dir);
      return shaft_campbell_sweep(scene, o->scene, omega_input(o->scene, o->from), omega_input(o->scene, o->to),
                                  o->steps, o->logarithmic, o->shaft, o->chart, o->output_dir);
    }
    if (unround_on_anisotropic_support(scene)) {  // every state a periodic orbit (model.md §20.6)
      refuse_unmodelled(scene, "sweep", {.unround_anisotropic = true});
      check_output_directory(o->output_dir);
      if (o->param == "omega") o->from = omega_input(o->scene, o->from), o->to = omega_input(o->scene, o->to);
      return sweep_composed(scene, o->scene, {o->param, o->from, o->to, o->steps, o->logarithmic, o->chart, o->output_dir});
    }
    const bool stick = scene.law == FrictionLaw::coulomb_set;  // the stick set per value (model.md §14, §20.5)
    // model.md §11.10; coulomb-set balls on an unround race take the stick-set path (§20.5)
    const bool unround = (!scene.race.round() || o->param == kUnroundnessParam) && !stick;
    refuse_unmodelled(scene, "sweep",
                      unround ? Handles{.unround = true}
                              : Handles{.lugre = true, .set_valued = true, .anisotropic = true,
                                        .unround_set_valued = true, .shaft_set_valued = true});
    check_output_directory(o->output_dir);  // refused before any work
    if (o->param == "omega") o->from = omega_input(o->scene, o->from), o->to = omega_input(o->scene, o->to);
    if (unround)
      return sweep_unround(scene, o->scene,
                           {o->param, o->from, o->to, o->steps, o->logarithmic, o->chart, o->output_dir});
    if (o->from > o->to)
      fmt::print(stderr, "stability-scan: note: --from {} > --to {}: the sweep runs downward (rows in decreasing {})\n",
                 o->from, o->to, o->param);
    if (scene.law == FrictionLaw::lugre || stick) check_sweep_memory(scene, *o, false);
    if (scene.law == FrictionLaw::lugre) return sweep_lugre(scene, *o);
    if (stick) {
      SweepGrid grid = sweep_grid(scene, *o);
      return sweep_stick_set(scene, {std::move(grid.name), std::move(grid.unit), std::move(grid.values),
                                     std::move(grid.scenes), o->logarithmic, o->chart, o->output_dir,
                                     stick_resolution(o->stick), o->scene.overrides});
    }
    const int n_balls = int(scene.balls.size());
    if (scene.support && o->param == "n")
      throw InputError("--param", 0, "n", "the ball count is not a sweep parameter with an anisotropic support");
    if (!scene.support && (o->param == "n" || n_balls != 2)) {
      check_sweep_memory(scene, *o, true);
      return sweep_any_balls(scene, *o);
    }
    const auto ref = std::optional<ParamRef>(checked_param(*o, n_balls));
    {
      Scene probe = scene;
      set_checked(probe, *ref, o->from, "--from");
      check_numerical_range(probe, "--from");
      set_checked(probe, *ref, o->to, "--to");
      check_numerical_range(probe, "--to");
    }
    const auto values = grid_values(o->from, o->to, o->steps, o->logarithmic);
    if (scene.support)  // Floquet multipliers per value and their crossings (model.md §10.11)
      return sweep_anisotropic(scene, o->scene, *ref, values, o->logarithmic, o->chart, o->output_dir, o->sampling);
    const Params base = params_of<2>(scene);
    require_memory(sweep_memory_estimate(values.size(), ref->quantity == Quantity::omega), "--steps", "the sweep",
                   fmt::format("{} values: what each keeps{}", values.size(),
                               ref->quantity == Quantity::omega ? " (its Campbell samples)" : ""),
                   "use fewer steps");
    // Each value's rows are written and its analysis dropped as it comes (output/sweep_stream.hpp).
    // With a coulomb or stribeck law each row also carries what dry friction leaves (model.md §14.10).
    const DryAlong dry = dry_figures_along(widen(base), *ref, values, {o->dry, stick_resolution(o->stick), 1});
    TwoBallSweepStream stream(*ref, values.size(), base, dry.computed() ? dry.which : std::string());
    Params p = base;
    std::string warnings;  // after the dry verdict, which leads
    for (const double v : values) {
      throw_if_stopped("sweep");
      set(p, *ref, v);
      const Analysis a = analyze(p);
      warnings += analysis_warnings(a, fmt::format("{}={}", o->param, v));
      stream.add(v, a, dry.computed() ? dry.figures.at(v) : DryFigures{});
    }

    const std::string name = to_string(*ref);
    const std::filesystem::path dir(o->output_dir);
    const auto csv_path = dir / fmt::format("sweep_{}.csv", name);
    const auto png_path = dir / fmt::format("sweep_{}.png", name);
    fmt::print(stderr, "{}{}", dry_along_lead(name, unit(ref->quantity), dry, csv_path.string()), warnings);
    OutputTransaction out;
    const auto staged_csv = stream.stage(out, csv_path, provenance_header(command_line(), scene.file, base));
    stage_views(out,
                {dir, name, std::string(unit(ref->quantity)), values.front(), values.back(), stream.campbell(),
                 stream.ranges(), provenance_header(command_line(), scene.file, base),
                 fmt::format("{}: Campbell diagram (fixed frame)", scene.file), o->chart},
                base, scene, o->scene);
    if (o->chart) {
      // gnuplot reads the staged CSV and writes the staged PNG; both move into place together.
      run_gnuplot(plots_dir() / "sweep.gp",
                  {{"csv", staged_csv.string()},
                   {"png", out.reserve(png_path).string()},
                   {"param", name},
                   {"unit", std::string(unit(ref->quantity))},
                   {"logx", o->logarithmic ? "1" : "0"},
                   {"title", fmt::format("{}: sweep of {}", scene.file, name)},
                   {"subtitle", chart_subtitle(scene, o->scene.overrides,
                                                {{name, values.front(), values.back(), std::string(unit(ref->quantity))}})},
                   {"omega_n", format_omega_n(scene)},
                   {"dry", dry.computed() ? "1" : "0"}});
    }
    out.commit();
    fmt::print(stderr, "wrote {} ({} rows){}\n", csv_path.string(), stream.rows(),
               o->chart ? fmt::format(" and {}", png_path.string()) : std::string());
    return exit_ok;
  };
}

}  // namespace abu::cli
