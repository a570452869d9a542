// The stick set of set-valued Coulomb friction on an unround race (model.md §20.5): the race's
// equilibria (§11.4) are its seeds, and V is measured over the components that hold the stable
// one of least |q|. Which one is stable takes the equilibria's spectra (unround_spectrum.hpp),
// so this sits in the linear layer, on the equilibria layer's stick_set_on_race.
//
//   abu::StickSet set = abu::stick_set(p, race);   // p.law == FrictionLaw::coulomb_set
#pragma once

#include "abu/core/params.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// The stick set on an unround race: the grid method for every n (two balls too, at the
/// stated resolution), the race's equilibria as seeds, V over the components holding its
/// stable equilibrium of least |q|. A round `race` gives stick_set(p, options). Throws as
/// stick_set(p, options) does (NotSupportedError: some mu_i <= 0, or K = C = 0).
StickSet stick_set(const ParamsN& p, const RaceShape& race, const StickSetOptions& options = {});

}  // namespace abu
