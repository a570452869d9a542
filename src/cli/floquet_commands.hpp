// The scans of a scene with an anisotropic support (docs/model.md §10.11): the sweep's
// per-value Floquet multipliers and crossings. Called by the sweep command once it has
// checked its options; outputs as every command writes them (one transaction).
#pragma once

#include <string>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/core/params.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/io/scene.hpp"
#include "cli.hpp"

namespace abu::cli {

/// sweep_NAME.csv (balanced states' multipliers per value), floquet_crossings_NAME.csv and
/// (chart) sweep_NAME.png; the crossings also on stderr. Returns the exit code.
int sweep_anisotropic(const Scene& scene, const SceneOptions& scene_options, ParamRef param,
                      const std::vector<double>& values, bool logarithmic, bool chart, const std::string& output_dir,
                      const BalancedSampling& sampling);

/// Two balls: the balanced branches of the mean system (the real system's balanced states,
/// model.md §10.3) by the continuation engine, Floquet multipliers at every branch point and
/// the crossings of the unit circle located between them (§10.13): floquet_branch_NAME.csv,
/// floquet_crossings_NAME.csv, (chart) floquet_branch_NAME.png.
int continue_anisotropic(const Scene& scene, const SceneOptions& scene_options, ParamRef param, double to,
                         const ContinuationOptions& numerics, bool chart, const std::string& output_dir);

}  // namespace abu::cli
