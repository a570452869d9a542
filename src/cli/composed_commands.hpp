// `sweep` and `map` on an unround race with an anisotropic support (docs/model.md §20.6, §20.7):
// the glue between the commands' options and analysis/composed_sweep, analysis/composed_map.
// Private to the CLI.
#pragma once

#include "abu/continuation/arclength.hpp"
#include "abu/input/scene.hpp"
#include "cli.hpp"
#include "unround_commands.hpp"

namespace abu::cli {

/// The sweep's parameters on this machine: omega and the other scene parameters that keep it
/// one (U, M_r, m, l, r, d, mu, kappa, ..., and `unroundness`, the race's amplitudes times a
/// factor); the ball count and the support's means k, c are refused (exit 2, naming what to use
/// instead) before any work. Writes sweep_NAME.csv, floquet_crossings_NAME.csv and (chart)
/// sweep_NAME.png; the crossings, lost tracks and failures on stderr. Returns the exit code.
int sweep_composed(const Scene& scene, const SceneOptions& options, const UnroundGrid& grid);

/// `continue` in one of the sweep's parameters from the scene's value (unroundness: 1) to `to`:
/// every orbit at either end continued by pseudo-arclength through its folds, with its LP, BP,
/// PD and NS points (analysis/composed_branches.hpp, model.md §20.9). Writes branch_NAME.csv,
/// special_NAME.csv and (chart) branch_NAME.png; the special points and doubts on stderr.
int continue_composed(const Scene& scene, const SceneOptions& options, const std::string& param, double to,
                      const ContinuationOptions& numerics, bool chart, const std::string& output_dir);

/// summary_X_Y.csv and summary_X_Y.png over two of the sweep's parameters (`unroundness:FROM:TO:N`
/// an axis too): per cell the orbits `equilibria` finds there counted by verdict, and the design
/// figure (analysis/composed_map.hpp). Threads, --resume and the same bytes as every map.
int map_composed(const Scene& scene, const SceneOptions& options, const UnroundMapRequest& request);

}  // namespace abu::cli
