// `stability-scan equilibria SCENE`: every state of one parameter point with its spectrum,
// as a table, CSV or JSON (analysis/equilibria.hpp computes, output/equilibria_report.hpp
// writes).
#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <vector>

#include "abu/analysis/equilibria.hpp"
#include "abu/output/equilibria_report.hpp"
#include "abu/output/files.hpp"
#include "cli.hpp"
#include "abu/core/resources.hpp"
#include "commands.hpp"
#include "shaft_commands.hpp"
#include "stick_options.hpp"

namespace abu::cli {

namespace {
struct EquilibriaOptions {
  SceneOptions scene;
  std::string format = "table";
  std::string output;
  abu::EquilibriaOptions analysis;
  bool chart = true;        // no chart to draw: --no-chart is accepted like everywhere
  std::string mode_shapes;  // --mode-shapes DIR
  std::string at_balls;     // --at-balls b1,..,bn: a LuGre stuck state [rad]
  std::string stick_dir;    // --stick-set DIR (coulomb-set scenes)
  StickSetOptions stick;
};
}  // namespace

Action add_equilibria_command(CLI::App& app) {
  auto options = std::make_shared<EquilibriaOptions>();
  CLI::App* sub = app.add_subcommand(
      "equilibria",
      "All real equilibria (model.md §5, §13: balanced, and every aligned ball pattern; for n >= 3 balls the "
      "balanced set by samples) with residuals, eigenvalues [1/s, rotating frame] sorted by real part, condition "
      "numbers and stability.");
  add_scene_options(*sub, options->scene);
  sub->add_option("--format", options->format, "Output format")
      ->check(CLI::IsMember({"table", "csv", "json"}))
      ->capture_default_str();
  sub->add_option("-o,--output", options->output, "Write to FILE (atomically) instead of standard output")
      ->type_name("FILE");
  sub->add_option("--set-samples", options->analysis.sampling.samples_per_sheet,
                  "Samples per sheet of the balanced set (n >= 3): G = max(2, round(S^(1/(n-2)))) values per free "
                  "angle")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--at-balls", options->at_balls,
                  "LuGre scenes (model.md §12): also analyse the stuck state with these ball angles "
                  "beta_1,..,beta_n [rad] (q from (5.4), z from (12.5)), both one-sided spectra")
      ->type_name("B1,..,BN");
  sub->add_flag("!--no-periodic-orbits", options->analysis.periodic_orbits,
                "Anisotropic support: do not compute the other states' pi/omega-periodic orbits (model.md §10.14; "
                "seconds to minutes with stiff coulomb balls); the balanced states' Floquet verdicts only");
  sub->add_flag("!--no-chart", options->chart,
                "Do not draw the --mode-shapes chart (its CSV is still written)");
  sub->add_option("--mode-shapes", options->mode_shapes,
                  "Also write DIR/modes.csv (every mode of every equilibrium: rotor and ball motion over one cycle) and "
                  "DIR/modes.png")
      ->type_name("DIR");
  sub->add_option("--stick-set", options->stick_dir,
                  "coulomb-set scenes: also write DIR/stick_set.csv, and for two balls DIR/stick_boundary.csv (the "
                  "traced boundary curves), DIR/stick_raster.dat and DIR/stick_set.png (model.md §14)")
      ->type_name("DIR");
  add_stick_resolution_options(*sub, options->stick);
  add_shaft_spectrum_options(*sub, options->analysis.shaft);
  return [options]() -> int {
    const Scene scene = load(options->scene);
    if (!options->output.empty()) check_output_target(options->output);  // refused before any work
    abu::EquilibriaOptions request = options->analysis;
    request.stick = stick_resolution(options->stick);
    request.mode_shapes = !options->mode_shapes.empty();
    if (!options->at_balls.empty()) request.stuck_balls = parse_real_list(options->at_balls, "--at-balls");
    request.output_bytes_per_state = equilibria_text_bytes_per_state(options->format);
    const EquilibriaEstimate estimate = equilibria_estimate(scene, request);
    if (!options->output.empty())
      require_disk(estimate.states * request.output_bytes_per_state,
                   std::filesystem::absolute(options->output).parent_path(), "-o", "the equilibria",
                   fmt::format("up to {:.0f} states as {}", estimate.states, options->format),
                   "use a smaller --set-samples or write elsewhere");
    if (estimate.memory > 1e8)
      fmt::print(stderr, "equilibria: up to {:.0f} states; memory: at most about {}\n", estimate.states,
                 gigabytes(estimate.memory));
    const EquilibriaReport report = analyze_equilibria(scene, request);
    const OutputContext context{command_line(), scene.file, options->scene.speed_unit()};
    OutputTransaction out;
    if (!options->mode_shapes.empty()) stage_mode_shapes(out, options->mode_shapes, report, context, options->chart);
    if (!options->stick_dir.empty()) stage_stick_set_files(out, options->stick_dir, report, context, options->chart);
    const std::string text = equilibria_text(report, options->format, context);
    fmt::print(stderr, "{}", equilibria_warnings(report));
    if (options->output.empty()) {
      out.commit();
      fmt::print("{}", text);
    } else {
      out.stage(options->output, text);
      out.commit();
    }
    return exit_ok;
  };
}

}  // namespace abu::cli
