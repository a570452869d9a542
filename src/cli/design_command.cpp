// `stability-scan design SCENE`: which balancer works (docs/model.md §22). Design variables on a
// grid, then NLopt from the grid's best; objectives and constraints from the outcome study and
// the linear analysis; the recommended design stated in words and in JSON, every design in a
// CSV, the Pareto front and the objective against the first variable charted.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "abu/analysis/design_study.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "abu/output/files.hpp"
#include "abu/output/format.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_design.hpp"
#include "cli.hpp"
#include "commands.hpp"
#include "outcome_flags.hpp"

namespace abu::cli {

namespace {

struct DesignCommand {
  SceneOptions scene;
  OutcomeFlags flags;
  std::vector<std::string> vary, constraints;
  std::string objective = "below", output = "out/design";
  DesignOptions study;
  bool grid_only = false, chart = true;
};

std::function<void(int, int, int)> progress_line(const OutcomeFlags& f) {
  if (f.quiet || !(f.progress || isatty(STDERR_FILENO))) return {};
  const auto t0 = std::chrono::steady_clock::now();
  return [t0](int designs, int grid, int runs) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fmt::print(stderr, "\rdesign: {} designs (grid {}), {} runs, {:.0f} s elapsed   ", designs, grid, runs, el);
  };
}

DesignOptions options_of(const DesignCommand& o, const CLI::App& sub, const Scene& scene, const SpeedProfile& speed) {
  DesignOptions d = o.study;
  d.outcomes = outcome_options(o.flags, sub, scene, speed);
  for (const auto& v : o.vary) d.variables.push_back(parse_design_variable(v));
  d.objective = parse_design_objective(o.objective);
  for (const auto& c : o.constraints) d.constraints.push_back(parse_design_constraint(c));
  d.optimize = !o.grid_only;
  d.progress = progress_line(o.flags);
  return d;
}

// The grid's size and what it holds, before any work: at most every design run, each keeping
// its summary; the CSV a row of ~1 kB per design.
void check_size(const DesignOptions& d, const std::string& output, int balls) {
  double designs = 1;
  for (const auto& v : d.variables) designs *= double(v.grid().size());
  designs += 1 + double(d.optimize ? d.max_evaluations : 0) * 12;  // the scene, the optimizer per ball count at most
  const double memory = outcome_memory_estimate(d.outcomes, std::max(balls, 12)) + designs * 4096.0;
  require_memory(memory, "--vary", "the design study", fmt::format("{:.0f} designs", designs), "take fewer levels");
  require_disk(designs * 2048.0, output, "--vary", "the design study's files", fmt::format("{:.0f} designs", designs),
               "take fewer levels");
}

int run(const DesignCommand& o, const CLI::App& sub) {
  const Scene scene = load(o.scene);
  check_output_directory(o.output);
  const SpeedProfile speed = speed_of(o.flags, o.scene, scene);
  const DesignOptions options = options_of(o, sub, scene, speed);
  check_size(options, o.output, int(scene.balls.size()));
  const DesignStudy study = run_design_study(scene, speed, options);
  if (options.progress) fmt::print(stderr, "\r{:80}\r", "");
  namespace fs = std::filesystem;
  const fs::path dir(o.output), csv = dir / "design.csv", json = dir / "design.json", png = dir / "design.png";
  {
    OutputTransaction out;
    out.stage(csv, design_csv(study, provenance_header(command_line(), scene.file, params_of<any_balls>(scene))));
    out.stage(json, design_json(study, command_line(), scene.file));
    out.commit();
  }
  int code = study.status.ok() ? exit_ok : exit_numerical;
  if (o.chart && study.best >= 0) {
    OutputTransaction chart;
    const auto& v = options.variables.front();
    if (run_gnuplot(plots_dir() / "design.gp",
                    {{"csv", csv.string()},
                     {"png", chart.reserve(png).string()},
                     {"variables", std::to_string(options.variables.size())},
                     {"constraints", std::to_string(options.constraints.size())},
                     {"xname", v.name},
                     {"xlog", v.log ? "1" : "0"},
                     {"objective", describe(options.objective)},
                     {"percent", options.objective.kind == DesignObjective::Kind::below ? "1" : "0"},
                     {"micron", options.objective.needs_runs() && options.objective.kind != DesignObjective::Kind::below ? "1" : "0"},
                     {"title", fmt::format("{}: {}, {} samples per design, final {:g} rad/s", escaped(scene.file),
                                           study.speed, options.outcomes.samples, study.omega_final)}}))
      chart.commit();
    else if (code == exit_ok)
      code = exit_chart_failed;
  }
  if (!o.flags.quiet) fmt::print(stderr, "{}", design_text(study));
  if (!o.flags.quiet)
    fmt::print(stderr, "wrote {}, {}{}\n", csv.string(), json.string(), fs::exists(png) && o.chart ? ", " + png.string() : "");
  return code;
}

}  // namespace

Action add_design_command(CLI::App& app) {
  auto o = std::make_shared<DesignCommand>();
  CLI::App* sub = app.add_subcommand(
      "design",
      "Which balancer works (model.md §22): design variables (ball count, any parameter, run-up rate, hold) on a grid, "
      "then NLopt from the grid's best; objectives from the outcome of run-ups over every start and the uncertain "
      "inputs, constraints from the linear analysis and the machine; the recommended design stated.");
  add_scene_options(*sub, o->scene);
  add_outcome_flags(*sub, o->flags, 64);
  sub->add_option("--vary", o->vary,
                  "A design variable NAME=LOW:HIGH[:LEVELS[:log]]: n (ball count of a [balls] ring), alpha (run-up "
                  "acceleration), hold (s after the change), or a --set name (repeatable)")
      ->type_name("NAME=LOW:HIGH[:K]")
      ->required();
  sub->add_option("--objective", o->objective,
                  "below (probability the residual stays below the limit), median, p90, worst (residual), max:NAME, "
                  "min:NAME")
      ->capture_default_str();
  sub->add_option("--constraint", o->constraints,
                  "stable=W_LO:W_HI (balanced state stable over the speeds), capacity=FACTOR, mass=KG, stall=FRACTION "
                  "(repeatable)")
      ->type_name("KIND=VALUE");
  sub->add_flag("--grid-only", o->grid_only, "The grid only, no optimizer");
  sub->add_option("--max-evaluations", o->study.max_evaluations, "Optimizer evaluations per ball count")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--xtol", o->study.xtol_rel, "Optimizer step tolerance on the variables scaled to [0, 1]")
      ->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output directory: design.csv, design.json, design.png")->capture_default_str();
  sub->add_flag("--no-chart", [o](std::int64_t) { o->chart = false; }, "Do not draw the chart");
  return [o, sub]() -> int { return run(*o, *sub); };
}

}  // namespace abu::cli
