// Registration of the subcommands (private to the CLI). Each add_* function declares a
// subcommand's options on `app` and returns the action to run if it was selected.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace abu::cli {

using Action = std::function<int()>;

Action add_equilibria_command(CLI::App& app);
Action add_sweep_command(CLI::App& app);
Action add_continue_command(CLI::App& app);
Action add_map_command(CLI::App& app);
Action add_simulate_command(CLI::App& app);
Action add_basin_command(CLI::App& app);
Action add_outcomes_command(CLI::App& app);
Action add_design_command(CLI::App& app);

/// Adds SCENE and --set to a subcommand.
struct SceneOptions;
void add_scene_options(CLI::App& sub, SceneOptions& options);

/// CLI::Range for tolerances: the bounds in %g ("must be in [1e-15, 0.01]"), where CLI11's
/// own message prints them with six fixed decimals ("0.000000 to 0.010000").
CLI::Validator tolerance_range(double lo, double hi);

}  // namespace abu::cli
