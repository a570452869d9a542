// `sweep` and `continue` on an unround race (model.md §11.10): the glue between the
// command line and the complete search (§11.4) / the branches in the unroundness factor.
// Private to the CLI.
#pragma once

#include <string>

#include "abu/continuation/arclength.hpp"
#include "cli.hpp"

namespace abu::cli {

/// The continuation / sweep parameter that scales every race amplitude (§11.10).
inline const std::string kUnroundnessParam = "unroundness";

struct UnroundGrid {
  std::string param;  ///< "unroundness" or a parameter symbol (omega, U, ...)
  double from = 0, to = 0;
  int steps = 0;
  bool logarithmic = false;
  bool chart = true;
  std::string output_dir;
};

/// sweep_NAME.csv (every equilibrium per value), summary_NAME.csv and summary_NAME.png.
int sweep_unround(const Scene& scene, const SceneOptions& options, const UnroundGrid& grid);
/// branch_unroundness.csv, special_unroundness.csv and branch_unroundness.png.
int continue_unroundness(const Scene& scene, const SceneOptions& options, double to, const ContinuationOptions& numerics,
                         bool chart, const std::string& output_dir);

}  // namespace abu::cli
