// The stick set of a coulomb-set scene, whatever its rotor (docs/model.md §14): on a flexible
// shaft its equivalent rigid balancer's with the shaft's figures (§18.17), on an unround race on
// the race's paths (§20.5), else §14's. The one place that chooses among them.
//
//   abu::SceneStickSet s = abu::scene_stick_set(scene, {});
//   if (s.shaft) ... s.shaft->worst_deflection ...
#pragma once

#include <optional>

#include "abu/equilibria/shaft_stick_set.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/input/scene.hpp"

namespace abu {

struct SceneStickSet {
  ParamsN params;  ///< those the set was computed with (on a shaft: the equivalent rigid balancer's)
  StickSet set;
  std::optional<ShaftStickFigures> shaft;
};
SceneStickSet scene_stick_set(const Scene& scene, const StickSetOptions& options = {});

/// Throws what scene_stick_set would throw for `scene` before it computes anything
/// (NotSupportedError: mu_i <= 0, K = C = 0, a shaft at an undamped critical speed).
void check_scene_stick_set_defined(const Scene& scene);

}  // namespace abu
