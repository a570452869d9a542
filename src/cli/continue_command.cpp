// `stability-scan continue SCENE --param NAME --to VALUE`: pseudo-arclength continuation
// of equilibrium branches with special points located; with --param2/--to2 the fold and
// Hopf points found are continued in two parameters (stability boundaries).
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <sstream>

#include "cli.hpp"
#include "composed_commands.hpp"
#include "abu/continuation/boundaries.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/continuation/special_rows.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "abu/core/suggest.hpp"
#include "abu/dynamics/periodic_orbits.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/format.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_dry_along.hpp"
#include "abu/input/ranges.hpp"
#include "abu/output/report.hpp"
#include "commands.hpp"
#include "unround_commands.hpp"
#include "floquet_commands.hpp"
#include "stick_options.hpp"
#include "views.hpp"

namespace abu::cli {

namespace {
struct ContinueOptions {
  SceneOptions scene;
  std::string param, param2;
  double to = 0, to2 = 0;
  std::string family;
  std::string state;
  bool all = false;
  ContinuationOptions numerics;
  BalancedSampling sampling;  // n >= 3 balls
  bool chart = true;
  std::string output_dir = "out";
  bool cycles = false;  // follow the periodic orbits of every Hopf point (model.md §17)
  CycleOptions cycle;
  DryRows dry = DryRows::automatic;  // coulomb / stribeck: the dry figures on every row (model.md §14.10)
};

// The dry figures of every row's value (coulomb / stribeck, as --dry asks), the values shared
// among --threads.
template <class P, class Run>
DryAlong rows_dry_figures(const P& p, const Run& rows, const ContinueOptions& o) {
  return dry_figures_along(p, rows, {.rows = o.dry, .stick = {}, .threads = o.numerics.threads});  // 0: one per core
}

// What a continuation's charts vary: the parameter over the run (x axis), the second one from
// the scene's value to --to2 (y axis).
template <class Run>
ChartAxis along(ParamRef param, const Run& run) {
  return {to_string(param), run.from, run.to, std::string(unit(param.quantity))};
}
template <class P>
ChartAxis across(const P& p, ParamRef param2, double to2) {
  return {to_string(param2), double(get(p, param2)), to2, std::string(unit(param2.quantity)), "y axis"};
}

// True if setting `a` changes a value `b` also sets (m and m1, or m2 and m2): two axes or
// continuation parameters that overlap are one parameter, refused (docs/robustness.md).
bool params_overlap(ParamRef a, ParamRef b) {
  return a.quantity == b.quantity && (a.ball < 0 || b.ball < 0 || a.ball == b.ball);
}

// "q1,q2,beta1,beta2" -> a configuration, or an InputError naming the rule.
Coordinates<long double, 2> parse_state(const std::string& text) {
  Coordinates<long double, 2> s;
  std::stringstream in(text);
  std::string cell;
  int n = 0;
  while (std::getline(in, cell, ',')) {
    double v = 0;
    const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
    if (ec != std::errc() || ptr != cell.data() + cell.size() || !std::isfinite(v) || n >= 4)
      throw InputError("--from-state", 0, text, "expected four finite numbers q1,q2,beta1,beta2 (SI)");
    s(n++) = v;
  }
  if (n != 4) throw InputError("--from-state", 0, text, "expected four finite numbers q1,q2,beta1,beta2 (SI)");
  return s;
}

// The end value must move the parameter away from the scene's value.
template <class P>
void check_moves(const P& p, ParamRef ref, double to, const std::string& to_option, const std::string& symbol) {
  if (to == get(p, ref))
    throw InputError(to_option, 0, symbol, fmt::format("must differ from the start value {}", get(p, ref)));
}

// The two-parameter curves' CSV and chart staged in `out`, their failures warned about.
template <class BoundaryRunT>
void stage_boundaries(OutputTransaction& out, const BoundaryRunT& boundaries, const std::filesystem::path& dir,
                      const std::string& header, bool chart, const char* script, const std::string& title,
                      const std::string& subtitle) {
  const std::string name = to_string(boundaries.param), name2 = to_string(boundaries.param2);
  const auto curves = out.stage(dir / fmt::format("boundary_{}_{}.csv", name, name2), boundary_csv(boundaries, header));
  if (chart)
    run_gnuplot(plots_dir() / script,
                {{"curves", curves.string()},
                 {"png", out.reserve(dir / fmt::format("boundary_{}_{}.png", name, name2)).string()},
                 {"param", name},
                 {"unit", std::string(unit(boundaries.param.quantity))},
                 {"param2", name2},
                 {"unit2", std::string(unit(boundaries.param2.quantity))},
                 {"title", title},
                 {"subtitle", subtitle}});
  for (std::size_t c = 0; c < boundaries.curves.size(); ++c)
    for (int end = 0; end < 2; ++end)
      if (boundaries.curves[c].stop[std::size_t(end)] == StopReason::step_underflow)
        fmt::print(stderr, "warning: curve {}: {}\n", c + 1, boundaries.curves[c].stop_detail[std::size_t(end)]);
  fmt::print(stderr, "{} boundary curves -> {}\n", boundaries.curves.size(), dir.string());
}

// The cycle branches of every Hopf point of `run` (mirror images, the same parameter
// on the other balanced branch, skipped), model.md §17.
std::vector<CycleBranch> follow_cycles(const Params& p, const ContinuationRun& run, const CycleOptions& o) {
  std::vector<CycleBranch> out;
  std::vector<long double> done;
  for (const auto& b : run.branches)
    for (const auto& s : b.specials) {
      if (s.label != Label::HB || !s.converged) continue;
      const bool seen = std::any_of(done.begin(), done.end(), [&](long double d) {
        return std::abs(d - s.parameter) <= 1e-9L * std::max(std::abs(d), 1e-300L);
      });
      if (seen) continue;
      done.push_back(s.parameter);
      fmt::print(stderr, "cycles from the Hopf point at {} = {:.10g} ...\n", to_string(run.param), double(s.parameter));
      out.push_back(continue_cycles(p, run.param, s, run.from, run.to, o));
    }
  return out;
}

// cycles_NAME.csv: one row per orbit, columns by name (docs/guide.md, model.md §17).
std::string cycles_csv(const std::vector<CycleBranch>& cycles, const ParamRef& param, const std::string& header) {
  const std::string name = to_string(param);
  std::string s = header;
  s += fmt::format(
      "# periodic orbits (limit cycles) born at the Hopf points, by multiple shooting (docs/model.md §17), rotating frame\n"
      "# columns: cycle (1-based, one per Hopf point), point, {} [{}], period [s], amplitude = max |q| over the orbit [m]\n"
      "#   (|q| is the fixed-frame whirl radius), stable (1: every nontrivial Floquet multiplier inside the unit circle),\n"
      "#   trivial_distance = |mu - 1| of the flow direction's multiplier (0 exactly; its size is the orbit's accuracy),\n"
      "#   beta<i>_min, beta<i>_max [rad] the range of ball i's angle over the orbit,\n"
      "#   mult_re<k>, mult_im<k>, mult_logmod<k>: the 8 Floquet multipliers by modulus, descending (ln|mu|: moduli\n"
      "#   below 1e-308 show as 0 in mult_re/mult_im; -1e308: exactly 0),\n"
      "#   q1_0 .. dbeta2_0: the state at the orbit's phase origin (SI, model.md (2.2)): a start for `simulate --from-state`\n",
      name, unit(param.quantity));
  for (std::size_t c = 0; c < cycles.size(); ++c) {
    const CycleBranch& b = cycles[c];
    s += fmt::format("# cycle {}: Hopf point {} = {} (omega_H = {} rad/s, l1 = {}, dRe(lambda)/d{} = {}); {} orbits",
                     c + 1, name, b.hopf_parameter, b.hopf_frequency, b.lyapunov, name, b.real_part_slope,
                     b.orbits.size());
    s += b.reason.empty() ? std::string("; ended at the end of the interval\n") : "; ended: " + escaped(b.reason) + "\n";
    if (b.stiff && !b.orbits.empty())  // model.md §17.11-§17.13
      s += fmt::format("# cycle {}: stiff route: {} shooting intervals of {} fixed Radau IIA steps (the period and the two "
                       "resolved multipliers changed by {:.2g} at the last doubling); {} multipliers per orbit from the "
                       "frozen spectra along it (ln|mu| only: their moduli underflow), Liouville's check at most {:.2g}\n",
                       c + 1, b.intervals, b.steps_per_interval, b.discretization_change,
                       b.orbits.front().unresolved_multipliers,
                       std::max_element(b.orbits.begin(), b.orbits.end(), [](const CycleOrbit& x, const CycleOrbit& y) {
                         return x.liouville_error < y.liouville_error;
                       })->liouville_error);
    const auto incomplete = std::count_if(b.orbits.begin(), b.orbits.end(), [](const CycleOrbit& o) {
      return o.multipliers.size() != 8 || o.ball_min.size() != 2;
    });
    if (incomplete > 0)
      s += fmt::format("# cycle {}: {} orbits not written: their multipliers or their samples could not be computed\n",
                       c + 1, incomplete);
    for (const CycleSpecial& sp : b.specials)
      s += fmt::format("# cycle {}: {} at {} = {}, period {} s, amplitude {} m ({})\n", c + 1, sp.label, name, sp.parameter,
                       sp.period, sp.amplitude, sp.note);
  }
  s += fmt::format("cycle,point,{},period,amplitude,stable,trivial_distance,beta1_min,beta1_max,beta2_min,beta2_max", name);
  for (int k = 1; k <= 8; ++k) s += fmt::format(",mult_re{0},mult_im{0},mult_logmod{0}", k);
  s += ",q1_0,q2_0,beta1_0,beta2_0,dq1_0,dq2_0,dbeta1_0,dbeta2_0\n";
  for (std::size_t c = 0; c < cycles.size(); ++c)
    for (std::size_t i = 0; i < cycles[c].orbits.size(); ++i) {
      const CycleOrbit& o = cycles[c].orbits[i];
      if (o.multipliers.size() != 8 || o.ball_min.size() != 2) continue;  // no partial rows (counted above)
      s += fmt::format("{},{},{},{},{},{},{},{},{},{},{}", c + 1, i, o.parameter, o.period, o.amplitude, o.stable() ? 1 : 0,
                       o.trivial_distance, o.ball_min[0], o.ball_max[0], o.ball_min[1], o.ball_max[1]);
      for (std::size_t k = 0; k < 8; ++k) {
        const double lm = std::isfinite(o.log_moduli[k]) ? o.log_moduli[k] : -1e308;
        s += fmt::format(",{},{},{}", o.multipliers[k].real(), o.multipliers[k].imag(), lm);
      }
      for (double v : o.state0) s += fmt::format(",{}", v);
      s += "\n";
    }
  return s;
}

// cycle_special_NAME.csv: the LPC, PD and NS points of the cycle branches.
std::string cycle_specials_csv(const std::vector<CycleBranch>& cycles, const ParamRef& param, const std::string& header) {
  std::string s = header;
  s += "# special points of the cycle branches: LPC fold of cycles, PD period doubling, NS Neimark-Sacker (docs/model.md §17.5);\n"
       "#   the orbit where the test function is zero; located = 1: on the branch (Brent's method to ~1e-8 of the step,\n"
       "#   each value at an orbit corrected onto the branch), 0: interpolated between the two converged orbits around it\n";
  s += fmt::format("cycle,label,{},period,amplitude,located\n", to_string(param));
  for (std::size_t c = 0; c < cycles.size(); ++c)
    for (const CycleSpecial& sp : cycles[c].specials)
      s += fmt::format("{},{},{},{},{},{}\n", c + 1, sp.label, sp.parameter, sp.period, sp.amplitude, sp.located ? 1 : 0);
  return s;
}

// Exit 3 for a cycle branch that did not reach the end of its interval for a numerical
// reason (the first orbit, the corrector at the minimum step, out of steps).
int cycles_exit(const std::vector<CycleBranch>& cycles) {
  int code = exit_ok;
  for (std::size_t c = 0; c < cycles.size(); ++c) {
    const CycleBranch& b = cycles[c];
    const bool failed = b.orbits.empty() || b.end == arclength::End::step_underflow ||
                        b.end == arclength::End::max_steps || b.end == arclength::End::edge_not_reached;
    fmt::print(stderr, "cycle {}: {} orbits, {} LPC/PD/NS{}\n", c + 1, b.orbits.size(), b.specials.size(),
               b.reason.empty() ? std::string() : "; " + escaped(b.reason));
    if (failed) {
      fmt::print(stderr, "stability-scan: numerical failure: cycle {} (Hopf point at {}): {}\n", c + 1, b.hopf_parameter,
                 escaped(b.reason));
      code = exit_numerical;
    }
  }
  return code;
}

// The run's one-line account (`what`: "N branches" and more), and its exit code: a
// branch that ended in an MX (step underflow or out of steps) is a numerical failure.
template <class RunT>
int finish(const RunT& run, const std::string& what, const std::filesystem::path& dir) {
  std::size_t points = 0, specials_count = 0;
  for (const auto& b : run.branches) points += b.points.size(), specials_count += b.specials.size();
  fmt::print(stderr, "{}, {} points, {} special points -> {}\n", what, points, specials_count, dir.string());
  // A branch that ended in failure (an MX row: the corrector failed at the minimum step, or
  // the steps ran out) is a numerical failure, exit 3 (docs/robustness.md); the files are written.
  int code = exit_ok;
  for (std::size_t i = 0; i < run.branches.size(); ++i)
    for (int end = 0; end < 2; ++end) {
      const StopReason stop = run.branches[i].stop[std::size_t(end)];
      if (stop != StopReason::step_underflow && stop != StopReason::max_steps) continue;
      fmt::print(stderr, "stability-scan: numerical failure: branch {} ended in failure (MX): {}\n", i + 1,
                 escaped(run.branches[i].stop_detail[std::size_t(end)]));
      code = exit_numerical;
    }
  return code;
}

// Three or more balls (branches_n.hpp): every aligned branch and every balanced sample
// (free angles held), LP/BP/HB located, the balanced set's Hopf envelope.
int continue_any_balls(const Scene& scene, const ContinueOptions& o) {
  const int n_balls = int(scene.balls.size());
  const ParamRef param = checked_param(scene, "--param", o.param, "--to", o.to);
  if (const auto rule = options_violation(o.numerics)) throw InputError("options", 0, "", *rule);
  if (!o.family.empty() || !o.state.empty())
    throw NotSupportedError(fmt::format("--from-equilibrium / --from-state with {} balls (every aligned equilibrium "
                                        "and balanced sample is continued)", n_balls));
  const ParamsN p = params_of<any_balls>(scene);
  check_moves(p, param, o.to, "--to", o.param);
  std::optional<ParamRef> ref2;
  if (!o.param2.empty()) {
    ref2 = checked_param(scene, "--param2", o.param2, "--to2", o.to2);
    if (params_overlap(*ref2, param)) throw InputError("--param2", 0, o.param2, "must differ from --param (it sets the same value)");
    check_moves(p, *ref2, o.to2, "--to2", o.param2);
  }
  const ContinuationRunN run = continue_branches(p, param, o.to, o.numerics, o.sampling);
  // What the traced branches hold (each was bounded before it was traced, arclength.hpp; the
  // bound times the branch count is far above what they hold: 13.4 GB against 48 MB on 3 balls).
  double held = 0;
  std::size_t points = 0;
  for (const BranchN& b : run.branches)
    held += double(b.points.capacity()) * double(sizeof(BranchPointN)), points += b.points.size();
  if (held > 1e8)
    fmt::print(stderr, "memory: the branches hold about {} ({} branches, {} points)\n", gigabytes(held),
               run.branches.size(), points);
  const std::string name = to_string(param);
  const std::filesystem::path dir(o.output_dir);
  // With a coulomb or stribeck law every row also carries what dry friction leaves (model.md §14.10).
  const ContinuationRunN rows = with_special_rows(p, run);
  const DryAlong dry = rows_dry_figures(p, rows, o);
  fmt::print(stderr, "{}{}",
             dry_along_lead(name, unit(param.quantity), dry, (dir / fmt::format("branch_{}.csv", name)).string()),
             continuation_warnings(run));
  const std::string header = provenance_header(command_line(), scene.file, p);
  OutputTransaction out;
  const auto branches = out.stage(dir / fmt::format("branch_{}.csv", name),
                                  branch_csv(rows, header, dry.computed() ? &dry.figures : nullptr, dry.which));
  const auto specials = out.stage(dir / fmt::format("special_{}.csv", name), special_points_csv(run, header));
  const auto envelope = out.stage(dir / fmt::format("envelope_{}.csv", name), envelope_csv(run, header));
  if (o.chart)
    run_gnuplot(plots_dir() / "bifurcation_n.gp",
                {{"branches", branches.string()},
                 {"specials", specials.string()},
                 {"envelope", envelope.string()},
                 {"png", out.reserve(dir / fmt::format("bifurcation_{}.png", name)).string()},
                 {"param", name},
                 {"unit", std::string(unit(param.quantity))},
                 {"title", fmt::format("{}: {} balls, continuation in {}", scene.file, n_balls, name)},
                 {"subtitle", chart_subtitle(scene, o.scene.overrides, {along(param, run)})},
                 {"omega_n", format_omega_n(scene)}});
  if (ref2)
    stage_boundaries(out, continue_boundaries(p, run, *ref2, o.to2, o.numerics), dir, header, o.chart, "boundary_n.gp",
                     fmt::format("{}: {} balls, stability boundaries in ({}, {})", scene.file, n_balls, name,
                                 to_string(*ref2)),
                     chart_subtitle(scene, o.scene.overrides, {along(param, run), across(p, *ref2, o.to2)}));
  out.commit();
  return finish(run, fmt::format("{} branches ({} balanced samples)", run.branches.size(), run.envelope.samples), dir);
}
}  // namespace

Action add_continue_command(CLI::App& app) {
  auto o = std::make_shared<ContinueOptions>();
  CLI::App* sub = app.add_subcommand(
      "continue",
      "Pseudo-arclength continuation of equilibrium branches in one parameter, eigenvalues tracked, folds (LP), "
      "branch points (BP) and Hopf points (HB, with the first Lyapunov coefficient) located; with --param2 the "
      "fold and Hopf points are continued in two parameters.");
  add_scene_options(*sub, o->scene);
  sub->add_option("--param", o->param, fmt::format("Continuation parameter: {}, or unroundness (an unround race's amplitudes times a factor, from 0 to --to; model.md §11.10)", param_symbols_help()))->required();
  sub->add_option("--to", o->to, "End value of the parameter (it starts at the scene's value; omega in --units)")
      ->required();
  auto* fam = sub->add_option("--from-equilibrium", o->family, "Start only from this family's equilibria")
                  ->check(CLI::IsMember({"balanced", "together", "opposite"}));
  auto* all = sub->add_flag("--all", o->all, "Start from every equilibrium (the default)");
  auto* state = sub->add_option("--from-state", o->state, "Start from this configuration q1,q2,beta1,beta2 (SI)");
  fam->excludes(all)->excludes(state);
  all->excludes(state);
  sub->add_option("--param2", o->param2, "Second parameter: continue the fold and Hopf points in (param, param2)");
  sub->add_option("--to2", o->to2, "End value of the second parameter");
  sub->add_option("--ds", o->numerics.ds, "First step (scaled arclength: the interval is 1)")->capture_default_str();
  sub->add_option("--ds-min", o->numerics.ds_min, "Minimum step")->capture_default_str();
  sub->add_option("--ds-max", o->numerics.ds_max, "Maximum step")->capture_default_str();
  sub->add_option("--max-steps", o->numerics.max_steps, "Steps per branch and direction")->capture_default_str();
  add_dry_rows_option(*sub, o->dry);
  sub->add_option("--threads", o->numerics.threads,
                  "Branches traced at once (two balls, or the periodic orbits of an unround race on an anisotropic support), and the dry figures of the rows (0: one per core; the output does not depend on it; on a busy "
                  "machine more threads cost more CPU time: a branch that turns out to be one already traced is "
                  "traced anyway)")
      ->capture_default_str();
  sub->add_option("--set-samples", o->sampling.samples_per_sheet,
                  "n >= 3 balls: samples of the balanced set per sheet, each continued as a branch (docs/model.md §13.5)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_flag("!--no-chart", o->chart, "Skip the PNG chart");
  sub->add_option("-o,--output-dir", o->output_dir, "Directory for branch_NAME.csv, special_NAME.csv and the chart")
      ->capture_default_str();
  sub->add_flag("--cycles", o->cycles,
                "Also follow the periodic orbits born at every Hopf point (two balls): cycles_NAME.csv with periods, "
                "amplitudes and Floquet multipliers, cycle_special_NAME.csv (LPC, PD, NS), cycles_NAME.png "
                "(docs/model.md §17)");
  sub->add_option("--cycle-steps", o->cycle.continuation.max_steps, "Continuation steps per cycle branch")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--cycle-rtol", o->cycle.rtol,
                  "Integrator tolerance of the cycles' flows and transition matrices (scaled state)")
      ->check(tolerance_range(1e-15, 1e-3))
      ->capture_default_str();
  sub->add_option("--cycle-intervals", o->cycle.intervals, "Shooting intervals of the first orbit (then chosen along the branch so that each carries the same growth of its transition matrix, docs/model.md §17.9)")
      ->check(CLI::Range(4, 10000))
      ->capture_default_str();
  sub->add_option("--cycle-newton-rtol", o->cycle.newton_rtol,
                  "Tolerance of the variational equations for the chord corrector's Newton matrix where it is "
                  "integrated: the first two orbits and retried steps, elsewhere it is extrapolated from the orbits "
                  "accepted (its contraction rate only; never tighter than --cycle-rtol; docs/model.md §17.7-17.8)")
      ->check(tolerance_range(1e-15, 1e-2))
      ->capture_default_str();
  sub->add_option("--cycle-floquet-rtol", o->cycle.floquet_rtol,
                  "Tolerance of the transition matrices at a converged orbit (its Floquet multipliers, about 10 times "
                  "this relative; never tighter than --cycle-rtol; docs/model.md §17.8)")
      ->check(tolerance_range(1e-15, 1e-2))
      ->capture_default_str();
  return [o]() -> int {
    Scene scene = load(o->scene);
    if (unround_on_anisotropic_support(scene)) {  // branches of periodic orbits (model.md §20.9)
      refuse_unmodelled(scene, "continue", {.unround_anisotropic = true});
      if (!o->param2.empty() || o->cycles || !o->family.empty() || !o->state.empty())
        throw InputError(!o->param2.empty() ? "--param2" : o->cycles ? "--cycles" : !o->family.empty() ? "--family" : "--from-state",
                         0, "",
                         "an unround race on an anisotropic support: every periodic orbit is continued in one parameter "
                         "(model.md §20.9); --param2, --cycles, --family and --from-state do not apply");
      if (const auto rule = options_violation(o->numerics)) throw InputError("options", 0, "", *rule);
      check_output_directory(o->output_dir);
      if (o->param == "omega") o->to = omega_input(o->scene, o->to);
      return continue_composed(scene, o->scene, o->param, o->to, o->numerics, o->chart, o->output_dir);
    }
    if (o->param == kUnroundnessParam) {  // model.md §11.10
      refuse_unmodelled(scene, "continue", {.unround = true});
      if (!o->param2.empty() || o->cycles || !o->family.empty() || !o->state.empty())
        throw InputError("--param unroundness", 0, kUnroundnessParam,
                         "traces every branch in one parameter: --param2, --cycles, --from-equilibrium and "
                         "--from-state do not apply");
      if (const auto rule = options_violation(o->numerics)) throw InputError("options", 0, "", *rule);
      check_output_directory(o->output_dir);
      return continue_unroundness(scene, o->scene, o->to, o->numerics, o->chart, o->output_dir);
    }
    refuse_unmodelled(scene, "continue", {.lugre = true, .anisotropic = true});
    if (scene.law == FrictionLaw::lugre) {  // model.md §12.8: n >= 3 balls, one parameter
      const char* rule = scene.balls.size() == 2 ? "two balls are not continued yet (the n-ball engine needs n >= 3)"
                         : !o->param2.empty()    ? "--param2 (two-parameter boundaries) is not available for it yet"
                         : o->cycles             ? "--cycles is not available for it (the field is not smooth at rest)"
                                                 : nullptr;
      if (rule)
        throw InputError(scene.file, scene.law_line, "friction.law",
                         fmt::format("friction law 'lugre' in 'continue': {} (model.md §12.8)", rule));
    }
    check_output_directory(o->output_dir);  // refused before any work
    if (o->param == "omega") o->to = omega_input(o->scene, o->to);
    if (o->param2 == "omega") o->to2 = omega_input(o->scene, o->to2);
    if (o->cycles && scene.balls.size() != 2)
      throw InputError("--cycles", 0, "", fmt::format("periodic orbits are followed for two balls only (the scene has {})",
                                                      scene.balls.size()));
    if (scene.support && scene.balls.size() != 2) {  // balanced samples with Floquet multipliers (model.md §10.16)
      if (o->cycles || !o->param2.empty() || !o->state.empty() || !o->family.empty())
        throw InputError(o->cycles ? "--cycles" : !o->param2.empty() ? "--param2" : !o->state.empty() ? "--from-state"
                                                                                                      : "--family",
                         0, "", "with an anisotropic support only the balanced samples are continued (model.md §10.16)");
      const ParamRef param = checked_param(scene, "--param", o->param, "--to", o->to);
      if (const auto rule = options_violation(o->numerics)) throw InputError("options", 0, "", *rule);
      check_moves(params_of<any_balls>(scene), param, o->to, "--to", o->param);
      return continue_anisotropic_n(scene, o->scene, param, o->to, o->numerics, o->sampling, o->chart, o->output_dir);
    }
    if (scene.balls.size() != 2) return continue_any_balls(scene, *o);
    const ParamRef param = checked_param(scene, "--param", o->param, "--to", o->to);
    if (const auto rule = options_violation(o->numerics)) throw InputError("options", 0, "", *rule);
    const Params p = params_of<2>(scene);
    check_moves(p, param, o->to, "--to", o->param);
    if (scene.support) {  // balanced branches with Floquet multipliers (model.md §10.13)
      if (o->cycles || !o->param2.empty() || !o->state.empty() || (!o->family.empty() && o->family != "balanced"))
        throw InputError(o->cycles ? "--cycles" : !o->param2.empty() ? "--param2" : !o->state.empty() ? "--from-state"
                                                                                                      : "--family",
                         0, "", "with an anisotropic support only the balanced branches are continued (model.md §10.13)");
      return continue_anisotropic(scene, o->scene, param, o->to, o->numerics, o->chart, o->output_dir);
    }
    StartSelection start;
    if (!o->family.empty()) start.family = o->family == "balanced" ? Family::balanced
                                           : o->family == "together" ? Family::together
                                                                     : Family::opposite;
    if (!o->state.empty()) start.state = parse_state(o->state);
    std::optional<ParamRef> ref2;
    if (!o->param2.empty()) {
      ref2 = checked_param(scene, "--param2", o->param2, "--to2", o->to2, /*radius_allowed=*/true);
      if (params_overlap(*ref2, param)) throw InputError("--param2", 0, o->param2, "must differ from --param (it sets the same value)");
      check_moves(p, *ref2, o->to2, "--to2", o->param2);
    }

    const double cycle_memory = o->cycles ? cycle_branch_memory_estimate(o->cycle) : 0.0;
    if (o->cycles)  // before any work: the branches found are never lost to the cycles' memory
      require_memory(cycle_memory, "--cycle-intervals", "a cycle branch",
                     fmt::format("{} orbits, up to {} shooting intervals", o->cycle.continuation.max_steps,
                                 std::max(o->cycle.intervals, o->cycle.max_intervals)),
                     "use fewer --cycle-intervals or --cycle-steps");
    const ContinuationRun run = continue_branches(p, param, o->to, o->numerics, start);
    if (run.memory_estimate + cycle_memory > 1e8)
      fmt::print(stderr, "memory: at most about {} (the branches{})\n", gigabytes(run.memory_estimate + cycle_memory),
                 o->cycles ? " and one cycle branch at a time" : "");
    const std::string name = to_string(param);
    const std::filesystem::path dir(o->output_dir);
    // With a coulomb or stribeck law every row also carries what dry friction leaves (model.md §14.10).
    const ContinuationRun rows = with_special_rows(p, run);
    const DryAlong dry = rows_dry_figures(p, rows, *o);
    fmt::print(stderr, "{}{}",
               dry_along_lead(name, unit(param.quantity), dry, (dir / fmt::format("branch_{}.csv", name)).string()),
               continuation_warnings(run));
    const std::string header = provenance_header(command_line(), scene.file, p);
    OutputTransaction out;
    const auto branches = out.stage(dir / fmt::format("branch_{}.csv", name),
                                    branch_csv(rows, header, dry.computed() ? &dry.figures : nullptr, dry.which));
    const auto specials = out.stage(dir / fmt::format("special_{}.csv", name), special_points_csv(run, header));
    stage_views(out,
                {dir, name, std::string(unit(param.quantity)), run.from, run.to, campbell_samples(run, p),
                 stability_ranges(run), header, fmt::format("{}: Campbell diagram along the branches (fixed frame)",
                                                            scene.file),
                 o->chart},
                p, scene, o->scene);
    if (o->chart)
      run_gnuplot(plots_dir() / "bifurcation.gp",
                  {{"branches", branches.string()},
                   {"specials", specials.string()},
                   {"png", out.reserve(dir / fmt::format("bifurcation_{}.png", name)).string()},
                   {"param", name},
                   {"unit", std::string(unit(param.quantity))},
                   {"title", fmt::format("{}: continuation in {}", scene.file, name)},
                   {"subtitle", chart_subtitle(scene, o->scene.overrides, {along(param, run)})},
                   {"omega_n", format_omega_n(scene)}});
    if (ref2)
      stage_boundaries(out, continue_boundaries(p, run, *ref2, o->to2, o->numerics), dir, header, o->chart,
                       "boundary.gp",
                       fmt::format("{}: stability boundaries in ({}, {})", scene.file, name, to_string(*ref2)),
                       chart_subtitle(scene, o->scene.overrides, {along(param, run), across(p, *ref2, o->to2)}));
    int cycle_code = exit_ok;
    if (o->cycles) {
      const std::vector<CycleBranch> cycles = follow_cycles(p, run, o->cycle);
      const auto cycles_file = out.stage(dir / fmt::format("cycles_{}.csv", name), cycles_csv(cycles, param, header));
      const auto cycle_specials =
          out.stage(dir / fmt::format("cycle_special_{}.csv", name), cycle_specials_csv(cycles, param, header));
      if (o->chart)
        run_gnuplot(plots_dir() / "cycles.gp",
                    {{"branches", branches.string()},
                     {"cycles", cycles_file.string()},
                     {"specials", cycle_specials.string()},
                     {"png", out.reserve(dir / fmt::format("cycles_{}.png", name)).string()},
                     {"param", name},
                     {"unit", std::string(unit(param.quantity))},
                     {"title", fmt::format("{}: equilibria and periodic orbits in {}", scene.file, name)},
                     {"subtitle", chart_subtitle(scene, o->scene.overrides, {along(param, run)})}});
      cycle_code = cycles_exit(cycles);
    }
    out.commit();
    const int code = finish(run, fmt::format("{} branches", run.branches.size()), dir);
    return code != exit_ok ? code : cycle_code;
  };
}

}  // namespace abu::cli
