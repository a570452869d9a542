#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <exception>
#include <string>

#include "cli.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/params.hpp"
#include "commands.hpp"

namespace abu::cli {

namespace {
std::string g_command_line;
}

const std::string& command_line() { return g_command_line; }

SpeedUnit SceneOptions::speed_unit() const { return speed_unit_from_string(units).value_or(SpeedUnit::rad_per_s); }

double omega_input(const SceneOptions& options, double typed) { return to_rad_per_s(typed, options.speed_unit()); }

namespace {
// `--set omega=V` in the command's --units: rewritten to rad/s before the scene's rules
// check it (a value that is not a number is left for apply_override to report).
std::string in_si(const SceneOptions& options, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (options.speed_unit() == SpeedUnit::rad_per_s || eq == std::string::npos) return assignment;
  std::string name = assignment.substr(0, eq);
  name.erase(0, name.find_first_not_of(" \t"));
  name.erase(name.find_last_not_of(" \t") + 1);
  if (name != "omega") return assignment;
  std::string text = assignment.substr(eq + 1);
  text.erase(0, text.find_first_not_of(" \t"));
  text.erase(text.find_last_not_of(" \t") + 1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(v)) return assignment;
  return fmt::format("omega={}", omega_input(options, v));
}
}  // namespace

Scene load(const SceneOptions& options) {
  Scene scene = load_scene(options.scene);
  for (const auto& assignment : options.overrides) apply_override(scene, in_si(options, assignment));
  return scene;
}

void add_scene_options(CLI::App& sub, SceneOptions& options) {
  sub.add_option("scene", options.scene, "Scene file (TOML, SI units), e.g. data/scenes/default.toml")->required();
  sub.add_option("--set", options.overrides,
                 fmt::format("Override a parameter, NAME=VALUE (repeatable). Names: {}", param_symbols_help()))
      ->type_name("NAME=VALUE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub.add_option("--units", options.units,
                 "Unit of the speed omega as typed (--set omega=, --from/--to of omega) and displayed: rad/s, rpm or "
                 "hz; CSV columns named omega and JSON values stay in rad/s")
      ->check(CLI::IsMember({"rad/s", "rpm", "hz", "Hz"}))
      ->capture_default_str();
}

int run(int argc, char** argv) {
  for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + std::string(argv[i]);

  CLI::App app{"stability-scan: linear stability of the automatic ball balancer (model: docs model.md)"};
  app.name("stability-scan");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("stability-scan ") + ABU_VERSION);
  std::vector<std::pair<CLI::App*, Action>> commands;
  for (auto add : {add_equilibria_command, add_sweep_command, add_continue_command, add_map_command,
                    add_simulate_command}) {
    Action a = add(app);
    commands.emplace_back(app.get_subcommands({}).back(), a);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "stability-scan: {}\nRun with --help for usage.\n", e.what());
    return exit_bad_input;
  }
  try {
    for (auto& [sub, action] : commands)
      if (sub->parsed()) return action();
    return exit_bad_input;
  } catch (const InputError& e) {
    fmt::print(stderr, "stability-scan: error: {}\n", e.what());
    return exit_bad_input;
  } catch (const NotSupportedError& e) {
    fmt::print(stderr, "stability-scan: not supported yet: {}\n", e.what());
    return exit_bad_input;
  } catch (const NumericalError& e) {
    fmt::print(stderr, "stability-scan: numerical failure: {}\n", e.what());
    return exit_numerical;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stability-scan: failed: {}\n", e.what());
    return exit_failure;
  }
}

}  // namespace abu::cli
