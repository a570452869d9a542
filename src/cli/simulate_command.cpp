// `stability-scan simulate SCENE`: a trajectory of model.md §3 at constant speed, or of §9
// during a run-up (--ramp, --speed-profile), from balls at rest (--balls), a given state
// (--from-state) or a perturbed equilibrium (--from-equilibrium, --perturb); CSV, charts
// and a summary (model.md §15).
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <charconv>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/dynamics/stick_slip.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/analysis/race_end.hpp"
#include "abu/analysis/equilibrium_start.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_simulation.hpp"
#include "abu/scan/scan.hpp"
#include "commands.hpp"
#include "simulate_options.hpp"

namespace abu::cli {

std::function<void(double)> simulate_progress(const SimulateOptions& o, double t_end) {
  if (o.quiet || !(o.progress || isatty(STDERR_FILENO))) return {};
  const auto t0 = std::chrono::steady_clock::now();
  return [t0, t_end, last = t0, every = std::chrono::milliseconds(o.progress && !isatty(STDERR_FILENO) ? 5000 : 200)](
             double t) mutable {
    const auto now = std::chrono::steady_clock::now();
    if (now - last < every) return;
    last = now;
    const double frac = t / t_end, el = std::chrono::duration<double>(now - t0).count();
    fmt::print(stderr, "\rsimulate: t = {:.4g} / {:.4g} s ({:5.1f} %), {:.0f} s elapsed, ETA {:.0f} s   ", t, t_end,
               100 * frac, el, frac > 0 ? el * (1 - frac) / frac : 0.0);
  };
}

namespace {

template <int N>
int run_simulation(const Scene& scene, const SimulateOptions& o, const SpeedProfile& speed) {
  ParamsT<double, N> p = params_of<N>(scene);
  const int n = ball_count(p);
  p.omega = speed.omega(0.0);
  State<double, N> x0;
  const int starts = int(!o.balls.empty()) + int(!o.from_state.empty()) + int(!o.from_equilibrium.empty());
  if (starts != 1)
    throw InputError("simulate", 0, "", "give exactly one start: --balls, --from-state or --from-equilibrium");
  if (o.perturb && o.from_equilibrium.empty())
    throw InputError("--perturb", 0, "", "--perturb goes with --from-equilibrium");
  SimulationOptions so = o.sim;
  const bool lugre = p.law == FrictionLaw::lugre;  // 3n + 4 states (model.md §12.7)
  if (!o.balls.empty()) x0 = start_at_rest(p, parse_real_list(o.balls, "--balls"));
  if (!o.from_state.empty()) {
    auto v = parse_real_list(o.from_state, "--from-state");
    if (lugre && int(v.size()) == 3 * n + 4) {  // the bristle states z_1..z_n last
      so.bristle_start.assign(v.end() - n, v.end());
      v.resize(std::size_t(2 * n + 4));
    }
    if (int(v.size()) != 2 * n + 4)
      throw InputError("--from-state", 0, "",
                       fmt::format("a state of {} balls has 2n + 4 = {} values (q1,q2,beta1..,dq1,dq2,dbeta1..){}, got {}",
                                   n, 2 * n + 4,
                                   lugre ? fmt::format(", or 3n + 4 = {} with the bristle states z1..z{} last", 3 * n + 4, n)
                                         : std::string(),
                                   v.size()));
    x0 = State<double, N>::Zero(2 * n + 4);
    for (int i = 0; i < 2 * n + 4; ++i) x0(i) = v[std::size_t(i)];
  }
  // An unround race (model.md §15.6): the balls run on their paths; the run's end is matched
  // against the equilibria of §11.4 at the final speed (§15.7).
  const RaceShape race = race_shape(scene);
  const bool unround = !race.round();
  if (unround) so.race = &race;
  // An anisotropic support (model.md §20): p carries its mean (k_bar, c_bar), the field adds
  // the force that turns with the spin angle.
  if (scene.support) so.support = &*scene.support;
  if (!o.from_equilibrium.empty()) {
    const double eps = o.perturb.value_or(1e-3);
    if (!(std::isfinite(eps) && eps >= 0 && eps <= 1))
      throw InputError("--perturb", 0, "", fmt::format("EPS must lie in [0, 1] (scaled units), got {}", eps));
    const EquilibriumChoice choice =
        parse_equilibrium_choice(o.from_equilibrium, "--from-equilibrium", unround, "--balls", "--from-state");
    // LuGre: the z = 0 equilibria are the frictionless model's (model.md §12.3); the start is
    // displaced along that model's rightmost mode, with z(0) = 0 (model.md §12.7).
    ParamsT<double, N> at = p;
    if (lugre) at.law = FrictionLaw::none;
    x0 = start_from_equilibrium(at, analyze(at), choice, eps, "--from-equilibrium");
  }
  so.method = *integration_method_from_string(o.method);
  // Validate before any work (nothing is written on bad input).
  if (!(std::isfinite(so.t_end) && so.t_end > 0))
    throw InputError("--t-end", 0, "", fmt::format("the end time must be > 0 s (got {})", so.t_end));
  if (!(so.every >= 0)) throw InputError("--every", 0, "", "the output interval must be > 0 s");
  namespace fs = std::filesystem;
  const fs::path dir(o.output);
  const fs::path csv_path = dir / "simulation.csv", png_path = dir / "simulation.png";

  so.interrupt = &stop_flag();  // set by the CLI's signal thread (cli.cpp)
  const bool show = !o.quiet && (o.progress || isatty(STDERR_FILENO));
  so.progress = simulate_progress(o, so.t_end);
  // Set-valued Coulomb friction: event-driven stick-slip (model.md §14.5), the rest as usual.
  std::optional<StickSlipResult<N>> stick_slip;
  SimulationResult<N> smooth;
  if (p.law == FrictionLaw::coulomb_set)
    stick_slip = simulate_stick_slip(p, speed, x0, so);
  else
    smooth = simulate(p, speed, x0, so);
  // On an unround race the run's end is matched against the race's states (model.md §15.7; on
  // an anisotropic support their periodic orbits at its spin angle, §20.8).
  if constexpr (N == any_balls)
    if (!stick_slip) judge_race_end(smooth, p, speed, race, so.support, so.settle_tolerance);
  const SimulationResult<N>& r = stick_slip ? stick_slip->run : smooth;
  if (show) fmt::print(stderr, "\r{:80}\r", "");

  const std::string header = provenance_header(command_line(), scene.file, p);
  {
    OutputTransaction out;
    out.stage(csv_path, stick_slip ? stick_slip_csv(*stick_slip, p, speed, header) : simulation_csv(r, p, speed, header));
    if (!o.summary.empty())
      out.stage(o.summary, stick_slip ? stick_slip_json(*stick_slip, p, speed, command_line(), scene.file)
                                      : simulation_json(r, p, speed, command_line(), scene.file));
    out.commit();
  }
  int code = r.status == SimulationStatus::completed ? exit_ok
             : r.status == SimulationStatus::interrupted ? interrupted_exit_code()
                                                          : exit_numerical;
  // Every ball stuck yet the arrangement outside the stick set (14.3): a numerical failure.
  const bool outside = stick_slip && stick_slip->end.all_stuck && !stick_slip->end.in_set;
  if (outside && code == exit_ok) code = exit_numerical;
  if (o.chart && r.samples.size() >= 2) {
    // The CSV is in place already: a failing chart loses nothing else.
    try {
      OutputTransaction chart;
      run_gnuplot(plots_dir() / "simulation.gp",
                  {{"csv", csv_path.string()},
                   {"png", chart.reserve(png_path).string()},
                   {"n", std::to_string(n)},
                   {"rel", [&] {
                      if (r.unround_race) return "0";  // no balanced set to measure from (§15.7)
                      std::vector<double> beta(static_cast<std::size_t>(n));
                      for (int i = 0; i < n; ++i) beta[std::size_t(i)] = r.x_end(2 + i);
                      return nearest_balanced_angles(p, beta) ? "1" : "0";
                    }()},
                   {"omega_n", fmt::format("{}", r.summary.omega_n)},
                   {"stick", stick_slip ? "1" : "0"},
                   {"title", fmt::format("{}: {} ({}), outcome {}", scene.file, speed.describe(), to_string(r.method),
                                         to_string(r.summary.outcome))}});
      chart.commit();
    } catch (const std::exception& e) {
      fmt::print(stderr, "stability-scan: warning: chart not drawn ({}); the CSV is complete\n", e.what());
      if (code == exit_ok) code = exit_chart_failed;
    }
  }
  if (!o.quiet) fmt::print(stderr, "{}", stick_slip ? stick_slip_text(*stick_slip, speed) : simulation_text(r, speed));
  if (outside)
    fmt::print(stderr,
               "stability-scan: numerical failure: every ball stuck at t = {:.9g} s but max |s_i| = {:.9g} > 1 + {:g}: "
               "the end point lies outside the stick set (model.md §14.7)\n",
               r.t_reached, stick_slip->end.max_abs_s, stick_set_tolerance);
  if (r.status == SimulationStatus::failed) fmt::print(stderr, "stability-scan: numerical failure: {}\n", r.reason);
  if (r.status == SimulationStatus::interrupted) fmt::print(stderr, "stability-scan: {}; kept what was computed\n", r.reason);
  if (!o.quiet)
    fmt::print(stderr, "wrote {}{}{}\n", csv_path.string(), o.summary.empty() ? "" : " and " + o.summary,
               o.chart && fs::exists(png_path) ? " and " + png_path.string() : "");
  return code;
}

// The scene's [simulate] keys where the command line gave none (flags override keys).
void apply_scene_settings(const Scene& scene, const CLI::App& sub, SimulateOptions& o) {
  if (!scene.simulate) return;
  const SimulateSettings& s = *scene.simulate;
  if (s.t_end && sub.count("--t-end") == 0) o.sim.t_end = *s.t_end;
  if (s.every && sub.count("--every") == 0) o.sim.every = *s.every;
  if (s.rtol && sub.count("--rtol") == 0) o.sim.rtol = *s.rtol;
  if (s.method && sub.count("--method") == 0) o.method = *s.method;
  // A start on the command line replaces the scene's start, whichever kind either is.
  if (o.balls.empty() && o.from_state.empty() && o.from_equilibrium.empty()) {
    auto list = [](const std::vector<double>& v) {
      std::string text;
      for (double x : v) text += (text.empty() ? "" : ",") + fmt::format("{}", x);
      return text;
    };
    o.balls = list(s.balls);
    o.from_state = list(s.from_state);
  }
}

}  // namespace

Action add_simulate_command(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* sub = app.add_subcommand(
      "simulate",
      "Trajectory of the rotor and balls (model.md §3 at constant speed, §9 during a run-up) by GSL odeiv2 with the "
      "analytic Jacobian: CSV, chart, outcome (balanced / aligned / periodic / not settled), settle time, stall "
      "(model.md §15).");
  add_scene_options(*sub, o->scene);
  sub->add_option("--t-end", o->sim.t_end, "End time [s]")->capture_default_str();
  auto* ramp = sub->add_option("--ramp", o->ramp,
                               "Run-up: OMEGA0:OMEGA1:ALPHA, linear from OMEGA0 to OMEGA1 [rad/s] at |ALPHA| [rad/s^2], "
                               "then held (model.md §9)")
                   ->type_name("W0:W1:ALPHA");
  auto* prof = sub->add_option("--speed-profile", o->profile_file,
                               "Speed profile FILE: lines `t, omega` [s, rad/s] from t = 0, piecewise linear, held after "
                               "the last")
                   ->type_name("FILE");
  ramp->excludes(prof);
  sub->add_option("--balls", o->balls, "Start: balls at rest in the rotor frame at these angles [rad], rotor at rest")
      ->type_name("B1,B2,...");
  sub->add_option("--from-state", o->from_state, "Start: the 2n + 4 values q1,q2,beta1..,dq1,dq2,dbeta1.. (model.md §2)")
      ->type_name("X1,X2,...");
  sub->add_option("--from-equilibrium", o->from_equilibrium,
                  "Start: an equilibrium at omega(0), balanced[:K] | together[:K] | opposite[:K] | aligned:PATTERN[:K], "
                  "displaced along its rightmost eigenmode by --perturb")
      ->type_name("F");
  sub->add_option("--perturb", o->perturb, "Displacement of --from-equilibrium (scaled: q / L, rad; default 1e-3)")
      ->type_name("EPS");
  sub->add_option("--method", o->method, "Integrator (auto: by the stiffness ratio, model.md §15.1)")
      ->check(CLI::IsMember({"auto", "bdf", "rk8pd", "rk4imp", "bsimp", "rkf45"}))
      ->capture_default_str();
  sub->add_option("--rtol", o->sim.rtol, "Tolerance per component in the model's scaling (model.md §15.1)")
      ->capture_default_str();
  sub->add_option("--every", o->sim.every, "Output interval [s] (default t_end / 2000)")->type_name("DT");
  sub->add_option("--max-steps", o->sim.max_steps, "Fail (exit 3, keeping the samples) after this many steps")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--settle-tol", o->sim.settle_tolerance, "Scaled distance for 'settled' (model.md §15.2)")
      ->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output directory: simulation.csv, simulation.png")->capture_default_str();
  sub->add_option("--summary", o->summary, "Also write the summary as JSON to FILE")->type_name("FILE");
  sub->add_flag("--no-chart", [o](std::int64_t) { o->chart = false; }, "Do not draw the chart");
  auto* progress = sub->add_flag("--progress", o->progress, "Progress on stderr even if not a terminal");
  auto* quiet = sub->add_flag("--quiet", o->quiet, "No progress and no summary on stderr");
  progress->excludes(quiet);
  return [o, sub]() -> int {
    Scene scene = load(o->scene);
    refuse_unmodelled(scene, "simulate", handles_of("simulate"));
    apply_scene_settings(scene, *sub, *o);
    check_output_directory(o->output);  // refused before any work
    if (!o->summary.empty()) {
      check_output_target(o->summary, "--summary");
      // The summary and the run's own files are three files: one written over another would
      // leave a chart where the JSON was said to be.
      namespace fs = std::filesystem;
      const fs::path summary = fs::weakly_canonical(o->summary);
      for (const char* own : {"simulation.csv", "simulation.png"})
        if (summary == fs::weakly_canonical(fs::path(o->output) / own))
          throw InputError("--summary", 0, o->summary,
                           fmt::format("is the run's own {} in -o {}: give the summary another name", own, o->output));
    }
    if (!(o->sim.settle_tolerance > 0 && o->sim.settle_tolerance < 1))
      throw InputError("--settle-tol", 0, "", "must lie in (0, 1)");
    // --units converts --set omega and --ramp; a profile file stays in rad/s (docs/views.md).
    const SpeedProfile speed = run_speed(o->scene, o->ramp, o->profile_file, scene);
    // LuGre's 3n + 4 states run in the bounded any-ball storage (model.md §12.7).
    // An unround race and an anisotropic support run in the any-ball storage too (model.md §15.6, §20).
    if (scene.shaft) return run_shaft_simulation(scene, *o, speed);  // model.md §18.16
    if (two_ball_storage(scene)) return run_simulation<2>(scene, *o, speed);
    return run_simulation<any_balls>(scene, *o, speed);
  };
}

}  // namespace abu::cli
