// The stick set of a coulomb-set scene, whatever its rotor (scene_stick_set.hpp).
#include "abu/analysis/scene_stick_set.hpp"

#include <stdexcept>

#include "abu/core/errors.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/shaft_scene.hpp"
#include "abu/linear/unround_stick_set.hpp"

namespace abu {

namespace {
ShaftSystem scene_shaft_for_stuck_balls(const Scene& scene, const ParamsN& p) {
  try {
    return stuck_balls_shaft(shaft_spec_of(scene), p);
  } catch (const std::invalid_argument& e) {
    throw InputError(scene.file, 0, "shaft", e.what());  // a rule the scene reader missed (shaft_system_of's)
  }
}
}  // namespace

void check_scene_stick_set_defined(const Scene& scene) {
  const ParamsN p = params_of<any_balls>(scene);
  if (scene.shaft) {
    check_shaft_stick_set_defined(scene_shaft_for_stuck_balls(scene, p));
  } else {
    check_stick_set_defined(p);
  }
}

SceneStickSet scene_stick_set(const Scene& scene, const StickSetOptions& options) {
  const ParamsN p = params_of<any_balls>(scene);
  if (scene.shaft) {  // through the shaft (model.md §18.17)
    ShaftStickSet s = shaft_stick_set(scene_shaft_for_stuck_balls(scene, p), options);
    return {std::move(s.equivalent), std::move(s.set), std::move(s.shaft)};
  }
  return {p, stick_set(p, race_shape(scene), options), std::nullopt};  // on the race's paths if unround (§20.5)
}

}  // namespace abu
