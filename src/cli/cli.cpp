#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <string_view>

#include "cli.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/params.hpp"
#include "abu/core/suggest.hpp"
#include "abu/io/plausibility.hpp"
#include "commands.hpp"

namespace abu::cli {

namespace {
std::string g_command_line;
}

const std::string& command_line() { return g_command_line; }

Scene load(const SceneOptions& options) {
  Scene scene = load_scene(options.scene);
  for (const auto& assignment : options.overrides) apply_override(scene, assignment);
  for (const auto& w : implausible_values(scene)) fmt::print(stderr, "stability-scan: warning: {}\n", w);
  return scene;
}

void add_scene_options(CLI::App& sub, SceneOptions& options) {
  sub.add_option("scene", options.scene, "Scene file (TOML, SI units), e.g. data/scenes/default.toml")->required();
  sub.add_option("--set", options.overrides,
                 fmt::format("Override a parameter, NAME=VALUE (repeatable). Names: {}", param_symbols_help()))
      ->type_name("NAME=VALUE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
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
  // An unknown word where the subcommand goes is named (CLI11 would say only that a
  // subcommand is required), with the nearest subcommand.
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string_view> names;
    for (const auto* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    const std::string_view word = argv[1];
    if (std::find(names.begin(), names.end(), word) == names.end()) {
      std::string list;
      for (auto n : names) list += fmt::format("{}{}", list.empty() ? "" : ", ", n);
      fmt::print(stderr, "stability-scan: unknown subcommand '{}'{} (subcommands: {})\nRun with --help for usage.\n",
                 word, did_you_mean(word, names), list);
      return exit_bad_input;
    }
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
