// model.md §11.5: the spectra of an unround race's equilibria (see the header).
#include "abu/linear/unround_spectrum.hpp"

#include <utility>

namespace abu {

namespace {
// The root with the eigenvalues of the rotating-frame Jacobian at it (model.md §11.5).
UnroundEquilibrium with_spectrum(UnroundRoot root, const LongParamsN& p, const RaceShape& race) {
  SpectrumN spectrum = compute_spectrum<any_balls>(unround_linearization(p, race, root.position));
  return UnroundEquilibrium{std::move(root), std::move(spectrum)};
}
}  // namespace

UnroundEquilibrium unround_equilibrium_at(const LongParamsN& p, const RaceShape& race, const UnroundAngles& beta) {
  return with_spectrum(unround_root_at(p, race, beta), p, race);
}

UnroundResult find_unround_equilibria(const ParamsN& pd, const RaceShape& race, const UnroundSearch& search) {
  UnroundRoots roots = find_unround_roots(pd, race, search);
  const LongParamsN p = pd.cast<long double>();
  UnroundResult result;
  result.search = roots.search;
  result.doubt = std::move(roots.doubt);
  result.list.reserve(roots.list.size());
  for (UnroundRoot& root : roots.list) result.list.push_back(with_spectrum(std::move(root), p, race));
  for (std::size_t k = 0; k < result.list.size(); ++k)
    if (result.list[k].spectrum.stability == Stability::stable) {
      result.best_stable = k;
      break;
    }
  return result;
}

}  // namespace abu
