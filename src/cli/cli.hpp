// The `stability-scan` command line: subcommands `equilibria`, `sweep` (and the ones
// later issues add). Exit codes: 0 done, 1 internal or I/O failure, 2 invalid input
// (nothing written), 3 numerical failure (reported with where and why), 130 interrupted.
#pragma once

#include <string>
#include <vector>

#include "abu/core/speed_units.hpp"
#include "abu/io/scene.hpp"

namespace abu::cli {

enum ExitCode : int {
  exit_ok = 0,
  exit_failure = 1,
  exit_bad_input = 2,
  exit_numerical = 3,
  exit_interrupted = 130,  ///< SIGINT/SIGTERM (map: the finished tiles are kept for --resume)
};

/// Runs the program; never throws.
int run(int argc, char** argv);

/// Options every scene-driven subcommand has.
struct SceneOptions {
  std::string scene;
  std::vector<std::string> overrides;  ///< --set NAME=VALUE, in order
  std::string units = "rad/s";          ///< --units: how omega is typed and displayed (docs/views.md)
  SpeedUnit speed_unit() const;
};

/// A value of omega typed in the command's --units, in rad/s.
double omega_input(const SceneOptions& options, double typed);

/// Loads the scene and applies the overrides (throws InputError).
Scene load(const SceneOptions& options);

/// The command line as typed, for provenance headers.
const std::string& command_line();

}  // namespace abu::cli
