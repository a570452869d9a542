// The scans of a scene with an anisotropic support (docs/model.md §10.11): the sweep's
// per-value Floquet multipliers and crossings. Called by the sweep command once it has
// checked its options; outputs as every command writes them (one transaction).
#pragma once

#include <string>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/core/params.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/analysis/floquet_sweep.hpp"
#include "abu/input/scene.hpp"
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

/// n >= 3 balls: the branches of the mean system's balanced samples (each with its free angles
/// held, the real system's balanced states, model.md §10.16), Floquet multipliers at every
/// point with the n - 2 unit ones deflated, and the crossings located between them; the
/// outputs of continue_anisotropic.
int continue_anisotropic_n(const Scene& scene, const SceneOptions& scene_options, ParamRef param, double to,
                           const ContinuationOptions& numerics, const BalancedSampling& sampling, bool chart,
                           const std::string& output_dir);

/// Appends one balanced branch point to `branch`: `e` (member, position) as a converged
/// balanced equilibrium at param = value, with its Floquet multipliers (model.md §10.13,
/// §10.16). A failure is a NumericalError naming the value, `what` ("branch", "sample") and
/// the member.
void append_balanced_floquet(FloquetSweep& branch, const ParamsN& base, const Scene& scene, ParamRef param,
                             double value, EquilibriumN e, const FloquetSweepOptions& options, const char* what);

/// The continuation options of a Floquet branch run: the step bound 0.005 unless --ds-max
/// was given (model.md §10.13).
ContinuationOptions floquet_branch_numerics(const ContinuationOptions& numerics);

/// The Floquet outputs of a sweep or branch run: `stem`_NAME.csv, floquet_crossings_NAME.csv,
/// (chart) `stem`_NAME.png, the crossings on stderr; for a sweep in omega also the Campbell
/// view (campbell_aniso.hpp). `what`: the chart title's second part. Returns the exit code.
int write_floquet_outputs(const Scene& scene, const SceneOptions& scene_options, const FloquetSweep& s,
                          const ParamsN& base, bool logarithmic, bool chart, const std::string& output_dir,
                          const std::string& stem, const std::string& what);

}  // namespace abu::cli
