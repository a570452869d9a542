#include "abu/scan/scan.hpp"

#include <cmath>

#include "abu/core/cancel.hpp"
#include "abu/linear/lugre_spectrum.hpp"

namespace abu {

Spectrum equilibrium_spectrum(const Params& p, const Equilibrium& e, SpectrumMethod method) {
  return compute_spectrum(linearize(p.cast<long double>(), e.state()), method, e.structural_zeros);
}

SpectrumN equilibrium_spectrum(const ParamsN& p, const EquilibriumN& e, SpectrumMethod method) {
  if (p.law == FrictionLaw::lugre) return lugre_zero_bristle_spectrum(p, e.position);  // model.md §12.8
  const auto lin = linearize(p.cast<long double>(), e.state());
  if (!e.on_balanced_set) return compute_spectrum(lin, method, e.structural_zeros);
  return compute_normal_spectrum(lin, balanced_tangent_basis(p, e.position), method);
}

AnalysisN analyze(const ParamsN& p, const BalancedSampling& sampling, SpectrumMethod method) {
  AnalysisN a;
  ParamsN where = p;  // LuGre: the z = 0 equilibria are the frictionless model's (model.md §12.3)
  if (p.law == FrictionLaw::lugre) where.law = FrictionLaw::none;
  a.equilibria = find_equilibria(where, sampling);
  a.unbalance = p.rotor.unbalance;
  for (const auto& b : p.balls) a.capacity += b.mass * b.race_radius;
  const auto points = a.equilibria.points();
  a.spectra.reserve(points.size());
  for (const auto& e : points) a.spectra.push_back(equilibrium_spectrum(p, e, method));
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
