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
#include "abu/core/resources.hpp"
#include "abu/output/files.hpp"
#include "abu/output/format.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_outcomes.hpp"
#include "cli.hpp"
#include "commands.hpp"
#include "outcome_flags.hpp"

namespace abu::cli {

namespace {

struct OutcomesCommand {
  SceneOptions scene;
  OutcomeFlags flags;
  std::string output = "out/outcomes";
  bool chart = true;
};

std::function<void(int, int)> progress_line(const OutcomeFlags& o) {
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
  const SpeedProfile speed = speed_of(o.flags, o.scene, scene);
  OutcomeOptions options = outcome_options(o.flags, sub, scene, speed);
  options.progress = progress_line(o.flags);
  // The CSV (a row of the start angles, the inputs and a dozen figures) and the JSON, before any run.
  const double row = 200.0 + 25.0 * double(scene.balls.size() + options.uncertain.size());
  require_disk(double(options.samples) * row + 1e5, o.output, "--samples", "the study's files",
               fmt::format("{} rows", options.samples), "take fewer --samples or write elsewhere");
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
  if (!o.flags.quiet) fmt::print(stderr, "{}", outcomes_text(study));
  if (!study.status.ok()) fmt::print(stderr, "stability-scan: {}; kept what was computed\n", study.status.reason.view());
  if (!o.flags.quiet)
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
  add_outcome_flags(*sub, o->flags, 256);
  sub->add_option("-o,--output", o->output, "Output directory: outcomes.csv, outcomes.json, outcomes.png")
      ->capture_default_str();
  sub->add_flag("--no-chart", [o](std::int64_t) { o->chart = false; }, "Do not draw the chart");
  return [o, sub]() -> int { return run(*o, *sub); };
}

}  // namespace abu::cli
