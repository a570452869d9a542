// The `stability-scan` command line: subcommands `equilibria`, `sweep` (and the ones
// later issues add). Exit codes (docs/robustness.md): 0 done, 1 internal or I/O failure,
// 2 invalid input (nothing written), 3 numerical failure (reported with where and why),
// 4 results written but a chart could not be drawn, 130 / 143 stopped by SIGINT / SIGTERM.
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

/// Loads the scene and applies the overrides (throws InputError).
Scene load(const SceneOptions& options);
/// A comma-separated list of finite reals ("2, 4.5,1e-3"; spaces around items allowed), as
/// --balls, --from-state, --fixed and --at-balls take it; otherwise InputError naming
/// `option`, exit 2.
std::vector<double> parse_real_list(const std::string& text, const std::string& option);

/// Commands built on the (2n + 4) vector field of the base model (sweep, continue, map,
/// simulate) refuse a scene that needs more (exit 2, naming what to use instead): LuGre
/// friction (model.md §12, InputError at the `law` key), an unround race (§11) or an
/// anisotropic support (§10) (NotSupportedError), `coulomb-set` friction (§14, not a vector
/// field; InputError at the `law` key) — except what `handles` says the command carries
/// itself: LuGre's bristle states (model.md §12.7), the event-driven stick-slip of
/// `coulomb-set` (§14.5), an unround race (its own path, unround_commands.hpp, §11.10).
struct Handles {
  bool lugre = false;       ///< the 3n + 4 LuGre state (§12.7, §12.8)
  bool set_valued = false;  ///< coulomb-set, event-driven stick-slip (§14.5–§14.8) or the stick set (§14.10)
  bool unround = false;     ///< an unround race (§11.10)
  bool anisotropic = false; ///< an anisotropic support, balanced states by Floquet (§10.11–§10.13)
  bool shaft = false;       ///< a flexible shaft ([shaft], model.md §18)
};
/// A scene that combines two of the extensions (anisotropic support, unround race, LuGre,
/// coulomb-set) is refused (NotSupportedError): each is modelled on its own so far. Every
/// command calls it (refuse_unmodelled does).
void refuse_combined_extensions(const Scene& scene);
void refuse_unmodelled(const Scene& scene, std::string_view command, Handles handles = {});

/// The exit code of a stop request: 128 + its signal (SIGINT 130, SIGTERM 143).
int interrupted_exit_code();

/// Set by `map` while it runs: what to say if the signal thread must end the process
/// ("the tiles are kept in DIR; rerun with --resume").
void set_interrupt_note(std::string note);

/// The command line as typed, for provenance headers.
const std::string& command_line();

}  // namespace abu::cli
