// The resolution options of the stick set of coulomb-set friction (model.md §14.3), the
// same for `equilibria`, `sweep` and `map`: --stick-columns (two balls) and --stick-grid
// (n >= 3). A map cell and `equilibria` with the same values compute the same numbers.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "abu/analysis/dry_friction.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/input/scene.hpp"

namespace abu::cli {

/// Adds --stick-columns C (two balls: C beta_1 columns and 2 C beta_2 samples per column)
/// and --stick-grid B (n >= 3: at most B grid points) with `options`' values as defaults.
void add_stick_resolution_options(CLI::App& sub, StickSetOptions& options);

/// Adds --dry auto|on|off: whether the rows of a coulomb / stribeck sweep or continuation carry
/// the dry figures (analysis/dry_friction.hpp, model.md §14.10).
void add_dry_rows_option(CLI::App& sub, DryRows& rows);

/// `options` with the samples per column following the columns (2 C), as parsed.
StickSetOptions stick_resolution(StickSetOptions options);

/// A sweep of a coulomb-set scene (sweep_stick_set.cpp): the values of the parameter and
/// each value's scene, as `sweep` checked them.
struct StickSweepInput {
  std::string name, unit;  ///< the swept parameter
  std::vector<double> values;
  std::vector<Scene> scenes;  ///< one per value
  bool logarithmic = false, chart = true;
  std::string output_dir;
  StickSetOptions stick;  ///< the resolution (stick_resolution applied)
  std::vector<std::string> overrides;  ///< --set, for the chart's subtitle
};

/// The stick set of every value: OUT/sweep_stick_NAME.csv (stick_sweep_csv) and its chart
/// OUT/sweep_stick_NAME.png (plots/stick_set_sweep.gp), written together. Each value is
/// `equilibria`'s computation at its parameters (the boundary curves left out).
int sweep_stick_set(const Scene& scene, const StickSweepInput& in);

}  // namespace abu::cli
