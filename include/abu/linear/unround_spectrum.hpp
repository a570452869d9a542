// The equilibria of an unround race with their spectra and stability (model.md §11.4-§11.5):
// the zeros of the reduced ball conditions that equilibria/unround_equilibria.hpp finds, each
// with the eigenvalues of the rotating-frame Jacobian there, and the stable one of least |q|.
//
//   abu::UnroundResult r = abu::find_unround_equilibria(p, race);
//   for (const auto& e : r.list) ... e.amplitude ... e.spectrum.stability ...
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "abu/equilibria/unround_equilibria.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// An equilibrium of the race (position, residual, index, |q|) and its spectrum.
struct UnroundEquilibrium : UnroundRoot {
  SpectrumN spectrum;  ///< eigenvalues of the rotating-frame Jacobian [1/s]
};

struct UnroundResult {
  std::vector<UnroundEquilibrium> list;  ///< sorted by |q|, then by beta
  UnroundSearchReport search;
  std::optional<std::size_t> best_stable;  ///< the stable equilibrium of least |q|
  std::string doubt;  ///< empty when the search is complete, else what makes the list doubtful
};

/// The equilibrium at angles beta that solve g = 0 (unround_root_at) with its spectrum (§11.5).
/// The continuation in the unroundness (§11.10) takes its points from here.
UnroundEquilibrium unround_equilibrium_at(const LongParamsN& p, const RaceShape& race, const UnroundAngles& beta);

/// Every equilibrium of an unround race (find_unround_roots: complete for n = 2, 3, `doubt`
/// says otherwise), each with its spectrum, and the stable one of least |q|. Throws
/// NumericalError for K = C = 0 (no q(beta)).
UnroundResult find_unround_equilibria(const ParamsN& p, const RaceShape& race, const UnroundSearch& search = {});

}  // namespace abu
