// `stability-scan outcomes SCENE`: the outcome of the machine in operation (docs/model.md §21):
// runs through the speed profile from sampled starts and uncertain inputs, their figures (CSV),
// the statistics with their intervals (JSON), the answer on stderr and a chart of the
// residual's distribution against the bare rotor.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "abu/analysis/outcomes.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/output/files.hpp"
#include "abu/output/format.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_outcomes.hpp"
#include "cli.hpp"
#include "commands.hpp"

namespace abu::cli {

namespace {

struct OutcomesCommand {
  SceneOptions scene;
  std::string ramp, profile_file, design = "sobol", method = "auto", output = "out/outcomes";
  std::vector<std::string> uncertain;
  OutcomeOptions study;
  bool chart = true, progress = false, quiet = false;
};

// The run's speed: --ramp, --speed-profile, the scene's [simulate] run-up, else its constant speed.
SpeedProfile speed_of(const OutcomesCommand& o, const Scene& scene) {
  if (o.scene.speed_unit() != SpeedUnit::rad_per_s && (!o.ramp.empty() || !o.profile_file.empty()))
    throw InputError(!o.ramp.empty() ? "--ramp" : "--speed-profile", 0, "units",
                     "a speed profile is given in rad/s; --units applies to --set omega only (drop --units)");
  if (!o.ramp.empty()) return SpeedProfile::parse_ramp(o.ramp);
  if (!o.profile_file.empty()) return SpeedProfile::load(o.profile_file);
  if (scene.simulate && scene.simulate->speed) return *scene.simulate->speed;
  return SpeedProfile::constant(scene.omega, scene.file, "speed.omega");
}

// The scene's [simulate] keys where no flag is given; the end time defaults to the profile's
// change plus two seconds of hold.
OutcomeOptions options_of(const OutcomesCommand& o, const CLI::App& sub, const Scene& scene, const SpeedProfile& speed) {
  OutcomeOptions s = o.study;
  if (scene.simulate) {
    const SimulateSettings& k = *scene.simulate;
    if (k.t_end && sub.count("--t-end") == 0) s.sim.t_end = *k.t_end;
    if (k.every && sub.count("--every") == 0) s.sim.every = *k.every;
    if (k.rtol && sub.count("--rtol") == 0) s.sim.rtol = *k.rtol;
  }
  if (sub.count("--t-end") == 0 && !(scene.simulate && scene.simulate->t_end)) s.sim.t_end = speed.end_of_change() + 2.0;
  s.sim.method = *integration_method_from_string(scene.simulate && scene.simulate->method && sub.count("--method") == 0
                                                     ? *scene.simulate->method
                                                     : o.method);
  s.design = *sample_design_from_string(o.design);
  for (const auto& u : o.uncertain) s.uncertain.push_back(parse_uncertain(u));
  s.interrupt = &stop_flag();
  return s;
}

std::function<void(int, int)> progress_line(const OutcomesCommand& o) {
  if (o.quiet || !(o.progress || isatty(STDERR_FILENO))) return {};
  const auto t0 = std::chrono::steady_clock::now();
  return [t0](int done, int total) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fmt::print(stderr, "\routcomes: {} / {} runs, {:.0f} s elapsed, ETA {:.0f} s   ", done, total, el,
               el * (total - done) / done);
  };
}

int run(const OutcomesCommand& o, const CLI::App& sub) {
  const Scene scene = load(o.scene);
  check_output_directory(o.output);
  const SpeedProfile speed = speed_of(o, scene);
  OutcomeOptions options = options_of(o, sub, scene, speed);
  options.progress = progress_line(o);
  const OutcomeStudy study = analyze_outcomes(scene, speed, options);
  if (options.progress) fmt::print(stderr, "\r{:80}\r", "");
  namespace fs = std::filesystem;
  const fs::path dir(o.output), csv = dir / "outcomes.csv", json = dir / "outcomes.json", png = dir / "outcomes.png";
  {
    OutputTransaction out;
    out.stage(csv, outcomes_csv(study, provenance_header(command_line(), scene.file, params_of<any_balls>(scene))));
    out.stage(json, outcomes_json(study, command_line(), scene.file));
    out.commit();
  }
  int code = study.status.outcome == Outcome::converged      ? exit_ok
             : study.status.outcome == Outcome::not_converged ? interrupted_exit_code()
                                                             : exit_numerical;
  if (o.chart && study.summary.runs > 0) {
    OutputTransaction chart;
    if (run_gnuplot(plots_dir() / "outcomes.gp",
                    {{"csv", csv.string()},
                     {"png", chart.reserve(png).string()},
                     {"columns", std::to_string(study.balls + int(study.options.uncertain.size()))},
                     {"runs", std::to_string(study.summary.runs + study.summary.failed)},
                     {"bare", fmt::format("{}", study.summary.bare_rotor_median * 1e6)},
                     {"title", fmt::format("{}: {} balls, {}, final {:g} rad/s, {} runs", escaped(scene.file),
                                           study.balls, study.speed, study.omega_final, study.summary.runs)}}))
      chart.commit();
    else if (code == exit_ok)
      code = exit_chart_failed;
  }
  if (!o.quiet) fmt::print(stderr, "{}", outcomes_text(study));
  if (!study.status.ok()) fmt::print(stderr, "stability-scan: {}; kept what was computed\n", study.status.reason.view());
  if (!o.quiet)
    fmt::print(stderr, "wrote {}, {}{}\n", csv.string(), json.string(), fs::exists(png) && o.chart ? ", " + png.string() : "");
  return code;
}

}  // namespace

Action add_outcomes_command(CLI::App& app) {
  auto o = std::make_shared<OutcomesCommand>();
  CLI::App* sub = app.add_subcommand(
      "outcomes",
      "The outcome of the machine in operation (model.md §21): runs through the speed profile from rest, every ball's "
      "start angle and each uncertain input sampled; residual |q| against the bare rotor, peak, stalls, balls stuck "
      "away from balance, settle time: median, 90th percentile and worst with confidence intervals.");
  add_scene_options(*sub, o->scene);
  auto* ramp = sub->add_option("--ramp", o->ramp, "Run-up OMEGA0:OMEGA1:ALPHA [rad/s, rad/s^2], then held (as simulate; "
                                                  "default: the scene's [simulate] run-up, else its constant speed)")
                   ->type_name("W0:W1:ALPHA");
  auto* prof = sub->add_option("--speed-profile", o->profile_file, "Speed profile FILE (as simulate)")->type_name("FILE");
  ramp->excludes(prof);
  sub->add_option("--t-end", o->study.sim.t_end, "End of each run [s] (default: the profile's change + 2 s)");
  sub->add_option("--samples", o->study.samples, "Runs: points of the design")->capture_default_str();
  sub->add_option("--seed", o->study.seed, "Seed of the points (the same seed, the same study)")->capture_default_str();
  sub->add_option("--design", o->design, "Points: sobol (shifted Sobol sequence) or random (independent)")
      ->check(CLI::IsMember({"sobol", "random"}))
      ->capture_default_str();
  sub->add_option("--uncertain", o->uncertain,
                  "An input known within a range, uniform: NAME=LOW:HIGH with NAME a --set name (repeatable)")
      ->type_name("NAME=LOW:HIGH");
  sub->add_option("--limit", o->study.residual_limit,
                  "Residual |q| that counts as good enough [m] (default 0: each run's bare rotor)");
  sub->add_option("--confidence", o->study.confidence, "Level of every interval")->capture_default_str();
  sub->add_option("--every", o->study.sim.every, "Sample interval [s] (default t_end / 2000)")->type_name("DT");
  sub->add_option("--rtol", o->study.sim.rtol, "Integration tolerance (model.md §15.1)")->capture_default_str();
  sub->add_option("--method", o->method, "Integrator (auto: by the stiffness ratio, model.md §15.1)")
      ->check(CLI::IsMember({"auto", "bdf", "rk8pd", "rk4imp", "bsimp", "rkf45"}))
      ->capture_default_str();
  o->study.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  sub->add_option("--threads", o->study.threads, "Worker threads (the output does not depend on it)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output directory: outcomes.csv, outcomes.json, outcomes.png")
      ->capture_default_str();
  sub->add_flag("--no-chart", [o](std::int64_t) { o->chart = false; }, "Do not draw the chart");
  auto* progress = sub->add_flag("--progress", o->progress, "Progress on stderr even if not a terminal");
  auto* quiet = sub->add_flag("--quiet", o->quiet, "No progress and no summary on stderr");
  progress->excludes(quiet);
  return [o, sub]() -> int { return run(*o, *sub); };
}

}  // namespace abu::cli
