// The commands on a flexible-shaft scene ([shaft], docs/model.md §18): `equilibria` (each
// equilibrium's state and its rightmost eigenvalues by ARPACK shift-invert, §19) and
// `sweep --param omega` (the Campbell diagram: the rightmost eigenvalues of the balanced
// state over speed, fixed-frame whirl frequencies forward and backward, §16.1), and `map`
// (the balanced state's stability over two parameters, §18.13).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "abu/analysis/shaft_states.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "cli.hpp"

namespace abu::cli {

void add_shaft_spectrum_options(CLI::App& sub, ShaftSpectrumOptions& o);

/// `sweep --param omega` on a shaft scene: DIR/campbell_shaft_omega.csv and its chart.
/// Returns the exit code.
int shaft_campbell_sweep(const Scene& scene, const SceneOptions& options, double from, double to, int steps,
                         bool logarithmic, const ShaftSpectrumOptions& spectrum, bool chart,
                         const std::string& output_dir);

struct UnroundGrid;
/// `sweep` of balls on an unround race on a shaft (model.md §18.18): sweep_NAME.csv (every
/// equilibrium per value), summary_NAME.csv and summary_NAME.png. Returns the exit code.
int sweep_shaft_race(const Scene& scene, const SceneOptions& options, const UnroundGrid& grid,
                     const ShaftSpectrumOptions& spectrum);

/// `map` on a shaft scene (shaft_map.cpp, model.md §18.13): the axes, as the rigid map's
/// NAME:FROM:TO:N[:log] (omega already in rad/s), and the run's options.
struct ShaftMapRequest {
  std::string x, y;
  std::string command_line;  ///< what determines the output (provenance)
  std::vector<std::string> overrides;
  ShaftSpectrumOptions spectrum;
  BalancedSampling sampling;
  int threads = 1;
  bool resume = false, fresh = false, progress = false, quiet = false, chart = true;
  std::string output_dir;
};
/// DIR/shaft_map_X_Y.csv and its chart. Returns the exit code.
int map_shaft(const Scene& scene, const ShaftMapRequest& request);
/// Balls on an unround race on the shaft (shaft_race_map.cpp, model.md §18.18): DIR/summary_X_Y.csv
/// and its chart; axes a scene parameter or `unroundness` (k, c, M_r refused; --set-samples unused).
int map_shaft_race(const Scene& scene, const ShaftMapRequest& request);

}  // namespace abu::cli
