#include "abu/scan/scan.hpp"

#include <cmath>
#include <optional>

#include "abu/core/cancel.hpp"
#include "abu/equilibria/ball_permutations.hpp"
#include "abu/linear/aligned_reduced.hpp"
#include "abu/linear/balanced_reduced.hpp"
#include "abu/linear/lugre_spectrum.hpp"
#include "abu/linear/spectrum_counts.hpp"

namespace abu {

Spectrum equilibrium_spectrum(const Params& p, const Equilibrium& e, SpectrumMethod method) {
  const auto lin = linearize(p.cast<long double>(), e.state());
  Spectrum sp = compute_spectrum(lin, method, e.structural_zeros);
  // Eigenvalues left inside their bands: the certified count decides where it can.
  if (!e.singular()) certify_counts(sp, lin);
  return sp;
}

SpectrumN equilibrium_spectrum(const ParamsN& p, const EquilibriumN& e, SpectrumMethod method) {
  if (p.law == FrictionLaw::lugre) return lugre_zero_bristle_spectrum(p, e.position);  // model.md §12.8
  const auto lin = linearize(p.cast<long double>(), e.state());
  if (!e.on_balanced_set) return compute_spectrum(lin, method, e.structural_zeros);
  return compute_normal_spectrum(lin, balanced_tangent_basis(p, e.position), method);
}

namespace {
// The spectrum of a permutation image: the same eigenvalues, ball i's eigenvector entry
// the source's entry of ball ball_of[i] (T' = P T P^T).
SpectrumN permuted(const SpectrumN& of, const PermutationImage& image, int n_balls) {
  SpectrumN sp = of;
  for (int k = 0; k < sp.count; ++k) {
    const auto& x = of.vectors[std::size_t(k)];
    auto& y = sp.vectors[std::size_t(k)];
    if (x.size() != n_balls + 2) continue;
    for (int i = 0; i < n_balls; ++i) y(2 + i) = x(2 + image.ball_of[std::size_t(i)]);
  }
  return sp;
}
// An aligned equilibrium of equal balls from its two-ball pencil and relative modes (model.md
// §13.10); nothing where the reduction does not apply or a condition number is not finite (a
// double root of (13.10.2)): the full spectrum then.
std::optional<SpectrumN> aligned_equal_spectrum(const ParamsN& p, const EquilibriumN& e) {
  const AlignedReduction r = aligned_reduction(p, e);
  if (!r.applies) return std::nullopt;
  const auto pl = p.cast<long double>();
  const AlignedPencil a = aligned_pencil(r, linearize(pl, e.state()), e);
  if (!a.applies) return std::nullopt;
  SpectrumN sp = aligned_spectrum(a, r, side_friction(pl, r), e);
  for (int k = 0; k < sp.count; ++k)
    if (!std::isfinite(sp.condition[std::size_t(k)])) return std::nullopt;
  return sp;
}
}  // namespace

AnalysisN analyze(const ParamsN& p, const BalancedSampling& sampling, SpectrumMethod method) {
  AnalysisN a;
  ParamsN where = p;  // LuGre: the z = 0 equilibria are the frictionless model's (model.md §12.3)
  if (p.law == FrictionLaw::lugre) where.law = FrictionLaw::none;
  a.equilibria = find_equilibria(where, sampling);
  a.unbalance = p.rotor.unbalance;
  for (const auto& b : p.balls) a.capacity += b.mass * b.race_radius;
  const auto points = a.equilibria.points();
  a.spectra.resize(points.size());
  a.representative.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) a.representative[k] = int(k);
  if (p.law == FrictionLaw::lugre) {
    for (std::size_t k = 0; k < points.size(); ++k) a.spectra[k] = equilibrium_spectrum(p, points[k], method);
    return a;
  }
  // Equal balls (model.md §13.9): one spectrum per class of permutation images, copied to
  // the others with the balls' eigenvector entries permuted; the balanced samples of equal
  // balls from the reduced problem in g. The copy comes from a member whose refinement
  // converged: where the first did not (a QR value kept), the next members compute their
  // own until one does, as each did before.
  PermutationClasses classes;
  find_permutation_classes(ball_kinds(p), points, classes);
  const BalancedReduction reduction = balanced_reduction(p);
  std::vector<int> source(points.size(), -1);  // per class: a member to copy from
  for (std::size_t k = 0; k < points.size(); ++k) {
    const PermutationImage& image = classes.images[k];
    const auto rep = std::size_t(image.representative);
    if (const int from = source[rep]; from >= 0) {
      const PermutationImage relative = relative_to(image, classes.images[std::size_t(from)], from, p.n_balls());
      a.spectra[k] = permuted(a.spectra[std::size_t(from)], relative, p.n_balls());
      a.representative[k] = from;
      continue;
    }
    if (method == SpectrumMethod::refined && reducible(reduction, points[k]))
      a.spectra[k] = reduced_normal_spectrum(reduction, p, points[k]);
    else if (const auto aligned = method == SpectrumMethod::refined ? aligned_equal_spectrum(p, points[k])
                                                                    : std::nullopt)
      a.spectra[k] = *aligned;
    else
      a.spectra[k] = equilibrium_spectrum(p, points[k], method);
    if (method != SpectrumMethod::refined || a.spectra[k].converged) source[rep] = int(k);
  }
  return a;
}

Analysis analyze(const Params& p, SpectrumMethod method) {
  Analysis a;
  a.equilibria = find_equilibria(p);
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) a.spectra[i] = equilibrium_spectrum(p, points[i], method);
  return a;
}

std::vector<double> grid_values(double from, double to, int steps, bool logarithmic) {
  std::vector<double> values(std::size_t(steps) + 1);
  for (int i = 0; i <= steps; ++i) {
    const double t = double(i) / double(steps);
    double v = logarithmic ? std::exp(std::log(from) + t * (std::log(to) - std::log(from)))
                           : from + t * (to - from);
    if (i == 0) v = from;
    if (i == steps) v = to;
    values[std::size_t(i)] = v;
  }
  return values;
}

double sweep_memory_estimate(std::size_t values, bool omega) {
  return 20e6 + double(values) * (omega ? 2.0 * double(sizeof(Analysis)) + 2 * 12.5e3 : 2e3);
}

SweepResult sweep(const Params& base, ParamRef param, const std::vector<double>& values) {
  SweepResult r;
  r.param = param;
  r.values = values;
  r.points.reserve(values.size());
  Params p = base;
  for (double v : values) {
    throw_if_stopped("sweep");
    set(p, param, v);
    r.points.push_back(analyze(p));
  }
  return r;
}

}  // namespace abu
