// The parts of a scene's machine (machine_parts.hpp).
#include "abu/analysis/machine_parts.hpp"

#include <fmt/format.h>

#include <vector>

#include "abu/core/errors.hpp"
#include "abu/model/shaft.hpp"

namespace abu {

std::string_view to_string(Route route) {
  switch (route) {
    case Route::rigid: return "rigid";
    case Route::lugre: return "lugre";
    case Route::set_valued: return "set_valued";
    case Route::unround: return "unround";
    case Route::anisotropic: return "anisotropic";
    case Route::shaft: return "shaft";
    case Route::unround_anisotropic: return "unround_anisotropic";
  }
  return "?";
}

namespace {
// Anisotropic bearings (model.md §18.19) are modelled with a round race and a smooth law only:
// with another part they are refused by every command rather than replaced by their mean.
void refuse_anisotropic_bearings_combined(const Scene& scene) {
  if (!scene.shaft || !has_anisotropic_bearings(*scene.shaft) || anisotropic_bearings_on_shaft(scene)) return;
  throw NotSupportedError(fmt::format("{} has anisotropic bearings on a flexible shaft (model.md §18.19) together with "
                                      "{}: that combination is not modelled; anisotropic bearings run with a round "
                                      "race and a smooth friction law (none, viscous, coulomb, stribeck)",
                                      scene.file, !scene.race.round() ? "an unround race" : "a LuGre or coulomb-set law"));
}
}  // namespace

Route route_of(const Scene& scene) {
  refuse_anisotropic_bearings_combined(scene);
  if (unround_on_anisotropic_support(scene)) return Route::unround_anisotropic;  // model.md §20
  if (set_valued_on_unround_race(scene)) return Route::set_valued;               // on the race's paths, §20.5
  if (set_valued_on_shaft(scene)) return Route::set_valued;                      // the equivalent rigid balancer's, §18.17
  if (unround_on_shaft(scene)) return Route::shaft;                              // the race's equilibria on it, §18.18
  refuse_combined_extensions(scene);
  if (scene.shaft) return Route::shaft;
  if (!scene.race.round()) return Route::unround;
  if (scene.support) return Route::anisotropic;
  if (scene.law == FrictionLaw::coulomb_set) return Route::set_valued;
  if (scene.law == FrictionLaw::lugre) return Route::lugre;
  return Route::rigid;
}

namespace {
struct CommandParts {
  std::string_view command;
  Handles handles;
};
// Which command answers which part (docs/cli.md). sweep and continue take an unround race along
// its own parameters; simulate and basin a LuGre or set-valued law by their own integrators.
constexpr CommandParts kCommandParts[] = {
    {"equilibria",
     {.lugre = true, .set_valued = true, .unround = true, .anisotropic = true, .shaft = true, .unround_anisotropic = true,
      .unround_set_valued = true, .shaft_set_valued = true, .shaft_unround = true}},
    {"sweep",
     {.lugre = true, .set_valued = true, .unround = true, .anisotropic = true, .shaft = true, .unround_anisotropic = true,
      .unround_set_valued = true, .shaft_set_valued = true, .shaft_unround = true}},
    {"continue", {.lugre = true, .unround = true, .anisotropic = true, .unround_anisotropic = true}},
    {"map",
     {.lugre = true, .set_valued = true, .unround = true, .anisotropic = true, .shaft = true, .unround_anisotropic = true,
      .unround_set_valued = true, .shaft_set_valued = true, .shaft_unround = true}},
    {"simulate",
     {.lugre = true, .set_valued = true, .unround = true, .anisotropic = true, .shaft = true, .unround_anisotropic = true,
      .shaft_unround = true, .shaft_anisotropic = true}},
    {"basin",
     {.lugre = true, .set_valued = true, .unround = true, .anisotropic = true, .shaft = true, .unround_anisotropic = true,
      .shaft_unround = true, .shaft_anisotropic = true}},
    {"outcomes", {.lugre = true, .set_valued = true, .unround = true, .anisotropic = true, .unround_anisotropic = true}},
};
}  // namespace

Handles handles_of(std::string_view command) {
  for (const auto& c : kCommandParts)
    if (c.command == command) return c.handles;
  return {};
}

std::string commands_handling(bool Handles::*part) {
  std::vector<std::string_view> names;
  for (const auto& c : kCommandParts)
    if (c.handles.*part) names.push_back(c.command);
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += fmt::format("{}`{}`", i == 0 ? "" : i + 1 == names.size() ? " and " : ", ", names[i]);
  return out;
}

namespace {
// "`a` analyses" or "`a` and `b` analyse": the commands that handle a part with the verb agreeing.
std::string only_commands(bool Handles::*part, std::string_view verb) {
  int count = 0;
  for (const auto& c : kCommandParts) count += c.handles.*part ? 1 : 0;
  return fmt::format("{} {}{}", commands_handling(part), verb, count == 1 ? "s" : "");
}

void refuse_unround(const Scene& scene, std::string_view command) {
  if (!scene.race.round())
    throw NotSupportedError(fmt::format("`{}` on an unround race ([race] in {}, model.md §11): only {} analyse it so far",
                                        command, scene.file, commands_handling(&Handles::unround)));
}

void refuse_anisotropic(const Scene& scene, std::string_view command) {
  if (scene.support)
    throw NotSupportedError(fmt::format(
        "{}: {} has an anisotropic support (stiffness_x, ... in [rotor], docs/model.md §10); only {} handle it so "
        "far (the balanced states' Floquet multipliers)",
        command, scene.file, commands_handling(&Handles::anisotropic)));
}

void refuse_lugre(const Scene& scene, std::string_view command) {
  if (scene.law != FrictionLaw::lugre) return;
  throw InputError(scene.file, scene.law_line, "friction.law",
                   fmt::format("friction law 'lugre' is not supported by '{}' yet (model.md §12: a 3n + 4 state whose "
                               "equilibria form a family); use {} ('equilibria': its z = 0 equilibria, and stuck "
                               "states with --at-balls)",
                               command, commands_handling(&Handles::lugre)));
}

void refuse_set_valued(const Scene& scene, std::string_view command) {
  if (scene.law != FrictionLaw::coulomb_set) return;
  throw InputError(scene.file, scene.law_line, "friction.law",
                   fmt::format("friction law 'coulomb-set' is set-valued, not a vector field: `{}` needs one; "
                               "{} handle it (the stick set, the stick-slip dynamics: model.md §14); use 'coulomb' "
                               "with a large kappa here",
                               command, commands_handling(&Handles::set_valued)));
}
}  // namespace

bool unround_on_anisotropic_support(const Scene& scene) {
  return scene.support && !scene.race.round() && !scene.shaft && scene.law != FrictionLaw::lugre &&
         scene.law != FrictionLaw::coulomb_set;
}

bool set_valued_on_unround_race(const Scene& scene) {
  return scene.law == FrictionLaw::coulomb_set && !scene.race.round() && !scene.support && !scene.shaft;
}

bool unround_on_shaft(const Scene& scene) {
  return scene.shaft && !scene.race.round() && !scene.support && scene.law != FrictionLaw::lugre &&
         scene.law != FrictionLaw::coulomb_set;
}

bool anisotropic_bearings_on_shaft(const Scene& scene) {
  return scene.shaft && has_anisotropic_bearings(*scene.shaft) && scene.race.round() && !scene.support &&
         scene.law != FrictionLaw::lugre && scene.law != FrictionLaw::coulomb_set;
}

bool set_valued_on_shaft(const Scene& scene) {
  return scene.law == FrictionLaw::coulomb_set && scene.shaft && scene.race.round() && !scene.support;
}

namespace {
// The combinations of two parts some command answers as one, each with what names it in a refusal.
struct Combination {
  bool (*present)(const Scene&);
  bool Handles::*handled;
  std::string_view parts, section, answer;
};
constexpr Combination kCombinations[] = {
    {anisotropic_bearings_on_shaft, &Handles::shaft_anisotropic, "anisotropic bearings on a flexible shaft", "§18.19",
     " (the whole shaft with its pi/omega-periodic bearing forces)"},
    {unround_on_anisotropic_support, &Handles::unround_anisotropic, "an unround race on an anisotropic support",
     "§20", ""},
    {set_valued_on_unround_race, &Handles::unround_set_valued, "coulomb-set balls on an unround race", "§20.5",
     " (the stick set on the race's paths)"},
    {set_valued_on_shaft, &Handles::shaft_set_valued, "coulomb-set balls on a flexible shaft", "§18.17",
     " (the stick set of the rigid balancer the balls see through the shaft)"},
    {unround_on_shaft, &Handles::shaft_unround, "an unround race on a flexible shaft", "§18.18",
     " (the race's equilibria on the shaft with their rightmost eigenvalues)"},
};
}  // namespace

void refuse_combined_extensions(const Scene& scene, Handles handles) {
  refuse_anisotropic_bearings_combined(scene);
  // The extensions are modelled one at a time (model.md §10-§12, §14) except an unround race
  // on an anisotropic support (§20): a scene that combines them otherwise is refused rather
  // than analysed with one of them silently dropped.
  for (const Combination& c : kCombinations) {
    if (!c.present(scene)) continue;
    if (handles.*c.handled) return;
    throw NotSupportedError(fmt::format("{} has {} (model.md {}): only {} that combination so far{}", scene.file,
                                        c.parts, c.section, only_commands(c.handled, "analyse"), c.answer));
  }
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
  refuse_combined_extensions(scene, handles);
  // A combination the command answers as one (model.md §20) needs no single-part handling.
  if (handles.unround_set_valued && set_valued_on_unround_race(scene)) handles.unround = handles.set_valued = true;
  if (handles.unround_anisotropic && unround_on_anisotropic_support(scene)) handles.unround = handles.anisotropic = true;
  if (handles.shaft_set_valued && set_valued_on_shaft(scene)) handles.shaft = handles.set_valued = true;
  if (handles.shaft_unround && unround_on_shaft(scene)) handles.shaft = handles.unround = true;
  if (handles.shaft_anisotropic && anisotropic_bearings_on_shaft(scene)) handles.shaft = true;
  if (!handles.lugre) refuse_lugre(scene, command);
  if (!handles.unround) refuse_unround(scene, command);
  if (!handles.anisotropic) refuse_anisotropic(scene, command);
  if (!handles.set_valued) refuse_set_valued(scene, command);
  if (!handles.shaft && scene.shaft)
    throw NotSupportedError(fmt::format("`{}` on a flexible shaft ([shaft] in {}, model.md §18): only {} analyse it so "
                                        "far (sweep: its Campbell diagram in omega)",
                                        command, scene.file, commands_handling(&Handles::shaft)));
}

bool two_ball_storage(const Scene& scene) {
  return scene.balls.size() == 2 && scene.law != FrictionLaw::lugre && scene.race.round() && !scene.support &&
         !scene.shaft;
}

}  // namespace abu
