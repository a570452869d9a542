// The composed machine's parameter and the machine along it (composed_parameter.hpp).
#include "abu/analysis/composed_parameter.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "abu/analysis/machine_parts.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/suggest.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/ranges.hpp"

namespace abu {

namespace {
[[noreturn]] void refuse_composed_param(const Scene& scene, const std::string& key, const std::string& param,
                                        const std::string& why) {
  throw InputError(key, 0, param,
                   fmt::format("{} has an unround race on an anisotropic support (model.md §20): {}", scene.file, why));
}
}  // namespace

ComposedParam composed_param(const Scene& scene, const std::string& param, const std::string& key) {
  if (param == "n")
    refuse_composed_param(scene, key, param,
                          "the ball count is not swept here (each ball has its own path); sweep each count's scene "
                          "separately");
  ComposedParam out;
  if (param == kUnroundnessParam) return out;
  out.ref = parse_param(param, int(scene.balls.size()));
  if (!out.ref)
    throw InputError(key, 0, param,
                     unknown_name_rule("unknown parameter", closest_param(param, true), "known",
                                       fmt::format("{}, or {} (the race's amplitudes times a factor)",
                                                   param_symbols_help(), kUnroundnessParam)));
  if (out.ref->quantity == Quantity::stiffness || out.ref->quantity == Quantity::damping)
    refuse_composed_param(scene, key, param,
                          "k and c are the anisotropic support's means (stiffness_x, ... in [rotor]), not one "
                          "parameter; edit the support's keys in the scene, or sweep omega, U, the balls' "
                          "parameters or unroundness");
  out.name = to_string(*out.ref);
  out.unit_name = std::string(unit(out.ref->quantity));
  return out;
}

void check_composed_value(const Scene& scene, const ComposedParam& c, double v, const std::string& origin) {
  if (!c.ref) {
    if (!(v >= 0)) throw InputError(origin, 0, kUnroundnessParam, fmt::format("the unroundness factor is >= 0 (got {})", v));
    checked_scaled_race(scene, race_shape(scene), v, origin);
    return;
  }
  Scene s = scene;
  set_checked(s, *c.ref, v, origin);
  check_numerical_range(s, origin, fmt::format("at {}={}", c.name, v));
}

ComposedAt composed_machine_at(const Scene& scene, const ComposedParam& c, const std::string& origin) {
  const RaceShape race = race_shape(scene);
  return [scene, ref = c.ref, race, origin](double v) {
    if (!ref) return ComposedMachineAt{params_of<any_balls>(scene), checked_scaled_race(scene, race, v, origin)};
    Scene s = scene;
    set_checked(s, *ref, v, origin);
    return ComposedMachineAt{params_of<any_balls>(s), race_shape(s)};
  };
}

ComposedAt composed_family(const Scene& scene, const ComposedParam& c, double lo, double hi) {
  const RaceShape race = race_shape(scene);
  if (!c.ref) return [scene, race](double v) { return ComposedMachineAt{params_of<any_balls>(scene), scaled_race(race, v)}; };
  return [scene, ref = *c.ref, lo, hi](double v) {
    Scene s = scene;
    set_checked(s, ref, std::clamp(v, lo, hi), "continuation");
    ParamsN p = params_of<any_balls>(s);
    set(p, ref, v);
    return ComposedMachineAt{std::move(p), race_shape(s)};
  };
}

double composed_start(const Scene& scene, const ComposedParam& c) {
  return c.ref ? get(params_of<any_balls>(scene), *c.ref) : 1.0;
}

ComposedBranches continue_composed(const Scene& scene, const ComposedParam& c, double to,
                                   const ForcedBranchOptions& options, const std::string& to_key) {
  if (!unround_on_anisotropic_support(scene))
    throw InputError(scene.file, 0, "", "continue_composed: the scene is not an unround race on an anisotropic support "
                                        "(model.md §20)");
  const double from = composed_start(scene, c);
  if (!(to != from)) throw InputError(to_key, 0, c.name, fmt::format("must differ from the start value {}", from));
  check_composed_value(scene, c, to, to_key);
  ForcedBranchOptions o = options;  // steps of at most 0.05 of the interval (forced_branch.hpp)
  o.continuation.ds_max = std::min(o.continuation.ds_max, 0.05);
  o.continuation.ds = std::min(o.continuation.ds, o.continuation.ds_max);
  return composed_branches(*scene.support, composed_family(scene, c, std::min(from, to), std::max(from, to)), from, to,
                           o);
}

}  // namespace abu
