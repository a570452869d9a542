// The parts of a scene's machine that decide how a question is answered: the one place that
// reads them off a scene (a rigid rotor or a flexible shaft, an isotropic or anisotropic
// support, a round or unround race, the friction law), and the refusals of a question a part
// cannot answer yet, each naming what answers it instead.
//
//   switch (abu::route_of(scene)) { case abu::Route::shaft: ...; case abu::Route::rigid: ...; }
#pragma once

#include <string>
#include <string_view>

#include "abu/input/scene.hpp"

namespace abu {

/// How a scene is analysed: the part that sets the method. A scene has at most one of the
/// extensions (refuse_combined_extensions); `rigid` is the base model of model.md §3 with a
/// smooth law (none, viscous, coulomb, stribeck), any ball count.
enum class Route { rigid, lugre, set_valued, unround, anisotropic, shaft, unround_anisotropic };
std::string_view to_string(Route route);

/// The route of a scene (after refuse_combined_extensions, which it calls).
Route route_of(const Scene& scene);
/// An unround race on an anisotropic support (model.md §20), nothing else beyond §3.
bool unround_on_anisotropic_support(const Scene& scene);
/// coulomb-set balls on an unround race, an isotropic support (model.md §20.5).
bool set_valued_on_unround_race(const Scene& scene);
/// coulomb-set balls on a flexible shaft with a round race (model.md §18.17).
bool set_valued_on_shaft(const Scene& scene);
/// A smooth law's balls on a flexible shaft with anisotropic bearings, a round race (model.md §18.19).
bool anisotropic_bearings_on_shaft(const Scene& scene);
/// A smooth law's balls on an unround race on a flexible shaft (model.md §18.18).
bool unround_on_shaft(const Scene& scene);

/// Commands built on the (2n + 4) vector field of the base model (sweep, continue, map,
/// simulate) refuse a scene that needs more (exit 2, naming what to use instead): LuGre
/// friction (model.md §12, InputError at the `law` key), an unround race (§11) or an
/// anisotropic support (§10) (NotSupportedError), `coulomb-set` friction (§14, not a vector
/// field; InputError at the `law` key) — except what `handles` says the command carries
/// itself: LuGre's bristle states (model.md §12.7), the event-driven stick-slip of
/// `coulomb-set` (§14.5), an unround race (its own path, unround_commands.hpp, §11.10).
struct Handles {
  bool lugre = false;       ///< the 3n + 4 LuGre state (§12.7, §12.8)
  bool set_valued = false;  ///< coulomb-set, event-driven stick-slip (§14.5–§14.8) or the stick set (§14.10)
  bool unround = false;     ///< an unround race (§11.10)
  bool anisotropic = false; ///< an anisotropic support, balanced states by Floquet (§10.11–§10.13)
  bool shaft = false;       ///< a flexible shaft ([shaft], model.md §18)
  /// an unround race on an anisotropic support at once, with a smooth law (the composed field, model.md §20)
  bool unround_anisotropic = false;
  /// coulomb-set balls on an unround race (the stick set on the race's paths, model.md §20.5)
  bool unround_set_valued = false;
  /// coulomb-set balls on a flexible shaft (the equivalent rigid balancer's stick set, model.md §18.17)
  bool shaft_set_valued = false;
  /// an unround race on a flexible shaft (the race's equilibria on it, model.md §18.18)
  bool shaft_unround = false;
  /// anisotropic bearings on a flexible shaft (its pi/omega-periodic field, model.md §18.19)
  bool shaft_anisotropic = false;
};
/// A scene that combines two of the extensions (anisotropic support, unround race, LuGre,
/// coulomb-set, a shaft) is refused (NotSupportedError, naming the commands that answer it
/// where some do) unless `handles` answers that combination: an unround race on an
/// anisotropic support (model.md §20). Every command calls it (refuse_unmodelled does).
void refuse_combined_extensions(const Scene& scene, Handles handles = {});

/// The parts each command answers for, whatever its route: the one table the refusals quote
/// (docs/cli.md, "Which command answers what"). Unknown commands handle the base model only.
Handles handles_of(std::string_view command);
/// The commands that handle a part, for a message: "`equilibria`, `sweep` and `map`".
std::string commands_handling(bool Handles::*part);

/// Refuses what `command` does not handle on the path it takes (`handles`, a subset of
/// handles_of(command)), naming the commands that do.
void refuse_unmodelled(const Scene& scene, std::string_view command, Handles handles);

/// Whether a run of the scene's rigid rotor takes the two-ball fixed-size storage (the fast
/// path of the general code): two balls, the round race, an isotropic support, no LuGre
/// bristles and no shaft. Otherwise the any-ball storage (model.md §13, §12.7, §15.6, §20).
bool two_ball_storage(const Scene& scene);

}  // namespace abu
