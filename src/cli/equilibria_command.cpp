// `stability-scan equilibria SCENE`: every equilibrium of one parameter point with its
// spectrum, as a table, CSV or JSON.
#include <fmt/format.h>

#include <cstdio>

#include "cli.hpp"
#include "abu/io/io.hpp"
#include "abu/io/report.hpp"
#include "abu/scan/scan.hpp"
#include "commands.hpp"

namespace abu::cli {

namespace {
struct EquilibriaOptions {
  SceneOptions scene;
  std::string format = "table";
  std::string output;
};
}  // namespace

Action add_equilibria_command(CLI::App& app) {
  auto options = std::make_shared<EquilibriaOptions>();
  CLI::App* sub = app.add_subcommand(
      "equilibria",
      "All real equilibria of the two-ball balancer (model.md §5) with residuals, eigenvalues [1/s] sorted by "
      "real part, condition numbers and stability.");
  add_scene_options(*sub, options->scene);
  sub->add_option("--format", options->format, "Output format")
      ->check(CLI::IsMember({"table", "csv", "json"}))
      ->capture_default_str();
  sub->add_option("-o,--output", options->output, "Write to FILE (atomically) instead of standard output")
      ->type_name("FILE");
  return [options]() -> int {
    const Scene scene = load(options->scene);
    const Params p = params_of<2>(scene);
    const Analysis a = analyze(p);
    std::string text;
    if (options->format == "csv") {
      text = equilibria_csv(a, provenance_header(command_line(), scene.file, p));
    } else if (options->format == "json") {
      text = equilibria_json(a, command_line(), scene.file, p);
    } else {
      text = equilibria_table(a, p);
    }
    fmt::print(stderr, "{}", analysis_warnings(a, fmt::format("omega={}", p.omega)));
    if (options->output.empty()) {
      fmt::print("{}", text);
    } else {
      OutputTransaction out;
      out.stage(options->output, text);
      out.commit();
    }
    return exit_ok;
  };
}

}  // namespace abu::cli
