// The parts of a scene's machine (machine_parts.hpp).
#include "abu/analysis/machine_parts.hpp"

#include <fmt/format.h>

#include "abu/core/errors.hpp"

namespace abu {

std::string_view to_string(Route route) {
  switch (route) {
    case Route::rigid: return "rigid";
    case Route::lugre: return "lugre";
    case Route::set_valued: return "set_valued";
    case Route::unround: return "unround";
    case Route::anisotropic: return "anisotropic";
    case Route::shaft: return "shaft";
  }
  return "?";
}

Route route_of(const Scene& scene) {
  refuse_combined_extensions(scene);
  if (scene.shaft) return Route::shaft;
  if (!scene.race.round()) return Route::unround;
  if (scene.support) return Route::anisotropic;
  if (scene.law == FrictionLaw::coulomb_set) return Route::set_valued;
  if (scene.law == FrictionLaw::lugre) return Route::lugre;
  return Route::rigid;
}

namespace {
void refuse_unround(const Scene& scene, std::string_view command) {
  if (!scene.race.round())
    throw NotSupportedError(fmt::format("`{}` on an unround race ([race] in {}, model.md §11): only `equilibria`, "
                                        "`sweep` and `continue --param unroundness` analyse it so far",
                                        command, scene.file));
}

void refuse_anisotropic(const Scene& scene, std::string_view command) {
  if (scene.support)
    throw NotSupportedError(fmt::format(
        "{}: {} has an anisotropic support (stiffness_x, ... in [rotor], docs/model.md §10); only `equilibria`, "
        "`sweep`, `map` and `continue` handle it so far (the balanced states' Floquet multipliers)",
        command, scene.file));
}

void refuse_lugre(const Scene& scene, std::string_view command) {
  if (scene.law != FrictionLaw::lugre) return;
  throw InputError(scene.file, scene.law_line, "friction.law",
                   fmt::format("friction law 'lugre' is not supported by '{}' yet (model.md §12: a 3n + 4 state whose "
                               "equilibria form a family); use 'equilibria' (its z = 0 equilibria, and stuck states "
                               "with --at-balls)",
                               command));
}

void refuse_set_valued(const Scene& scene, std::string_view command) {
  if (scene.law != FrictionLaw::coulomb_set) return;
  throw InputError(scene.file, scene.law_line, "friction.law",
                   fmt::format("friction law 'coulomb-set' is set-valued, not a vector field: `{}` needs one; "
                               "`equilibria` computes its stick set and `simulate` and `basin` its stick-slip dynamics "
                               "(model.md §14); use 'coulomb' with a large kappa here",
                               command));
}
}  // namespace

void refuse_combined_extensions(const Scene& scene) {
  // The extensions are modelled one at a time (model.md §10-§12, §14): a scene that combines
  // them is refused rather than analysed with one of them silently dropped.
  const int extensions = int(scene.support.has_value()) + int(!scene.race.round()) +
                         int(scene.law == FrictionLaw::lugre) + int(scene.law == FrictionLaw::coulomb_set) +
                         int(scene.shaft != nullptr);
  if (extensions > 1)
    throw NotSupportedError(fmt::format("{} combines two of an anisotropic support, an unround race, LuGre and "
                                        "coulomb-set friction{}; each is analysed only on its own so far "
                                        "(model.md §10-§12, §14{})",
                                        scene.file, scene.shaft ? ", a flexible shaft" : "",
                                        scene.shaft ? ", §18" : ""));
}

void refuse_unmodelled(const Scene& scene, std::string_view command, Handles handles) {
  refuse_combined_extensions(scene);
  if (!handles.lugre) refuse_lugre(scene, command);
  if (!handles.unround) refuse_unround(scene, command);
  if (!handles.anisotropic) refuse_anisotropic(scene, command);
  if (!handles.set_valued) refuse_set_valued(scene, command);
  if (!handles.shaft && scene.shaft)
    throw NotSupportedError(fmt::format("`{}` on a flexible shaft ([shaft] in {}, model.md §18): only `equilibria`, "
                                        "`sweep --param omega` (its Campbell diagram) and `map` analyse it so far",
                                        command, scene.file));
}

}  // namespace abu
