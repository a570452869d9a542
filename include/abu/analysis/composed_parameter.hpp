// The parameter of a sweep or a continuation on an unround race with an anisotropic support
// (docs/model.md §20.6, §20.9), and the machine along it: one place for the CLI's `sweep` and
// `continue` and the Python module's abu.continue_orbits, so that they take and refuse the
// same parameters with the same messages.
//
//   const abu::ComposedParam c = abu::composed_param(scene, "omega", "--param");
//   abu::ComposedBranches b = abu::continue_composed(scene, c, 1400, {}, "--to");
#pragma once

#include <optional>
#include <string>

#include "abu/analysis/composed_branches.hpp"
#include "abu/analysis/composed_sweep.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/scene.hpp"

namespace abu {

/// A scene symbol (ref), or the unroundness factor (no ref); its name and unit.
struct ComposedParam {
  std::optional<ParamRef> ref;
  std::string name = kUnroundnessParam, unit_name = "-";
};

/// `param` on this machine: any scene symbol but the support's means k, c, and `unroundness`;
/// the ball count refused too (each ball has its own path). InputError at `key`.
ComposedParam composed_param(const Scene& scene, const std::string& param, const std::string& key);

/// The scene at value v of c checked by the scene's rules (InputError naming `origin`).
void check_composed_value(const Scene& scene, const ComposedParam& c, double v, const std::string& origin);

/// The machine at a value, every value checked by the scene's rules (a sweep's grid values and
/// bisection points lie between checked ends). `origin` names the values in a refusal.
ComposedAt composed_machine_at(const Scene& scene, const ComposedParam& c, const std::string& origin);

/// The machine along a continuation over [lo, hi]: the parameter set exactly, also a little
/// beyond the ends (MachineFamily); the scene's rules and the race re-read at the value clamped
/// into [lo, hi] (its paths follow l and r); the unroundness factor unchecked (a negative factor
/// turns each harmonic by half its period).
ComposedAt composed_family(const Scene& scene, const ComposedParam& c, double lo, double hi);

/// The scene's value of c (1 for the unroundness factor).
double composed_start(const Scene& scene, const ComposedParam& c);

/// `continue` on this machine (model.md §20.9): from the scene's value to `to` (checked: it
/// differs from the start and keeps the scene's rules; InputError at `to_key`).
ComposedBranches continue_composed(const Scene& scene, const ComposedParam& c, double to,
                                   const ForcedBranchOptions& options, const std::string& to_key);

}  // namespace abu
