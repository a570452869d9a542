// The `stability-scan` command line: subcommands `equilibria`, `sweep` (and the ones
// later issues add). Exit codes (docs/robustness.md): 0 done, 1 internal or I/O failure,
// 2 invalid input (nothing written), 3 numerical failure (reported with where and why),
// 4 results written but a chart could not be drawn, 130 / 143 stopped by SIGINT / SIGTERM.
#pragma once

#include <string>
#include <vector>

#include "abu/core/speed_units.hpp"
#include "abu/analysis/machine_parts.hpp"
#include "abu/input/option_values.hpp"
#include "abu/input/scene.hpp"

namespace abu::cli {

enum ExitCode : int {
  exit_ok = 0,
  exit_failure = 1,
  exit_bad_input = 2,
  exit_numerical = 3,
  exit_chart_failed = 4,   ///< every CSV written, a chart not drawn (cause on stderr)
  exit_interrupted = 130,  ///< 128 + the signal: SIGINT 130, SIGTERM 143 (map: the finished tiles are kept)
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
/// A run's speed (simulate, basin, outcomes, design): --ramp OMEGA0:OMEGA1:ALPHA in the command's
/// --units (rpm: rpm, rpm, rpm/s), else --speed-profile FILE (rad/s: refused with other --units),
/// else the scene's [simulate] run-up, else its constant [speed].
SpeedProfile run_speed(const SceneOptions& options, const std::string& ramp, const std::string& profile_file,
                       const Scene& scene);

/// Loads the scene and applies the overrides (throws InputError).
Scene load(const SceneOptions& options);
// parse_real_list: abu/input/option_values.hpp



/// The exit code of a stop request: 128 + its signal (SIGINT 130, SIGTERM 143).
int interrupted_exit_code();

/// Set by `map` while it runs: what to say if the signal thread must end the process
/// ("the tiles are kept in DIR; rerun with --resume").
void set_interrupt_note(std::string note);

/// The command line as typed, for provenance headers.
const std::string& command_line();

}  // namespace abu::cli
