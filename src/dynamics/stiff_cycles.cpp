// The frozen-spectra multipliers of the stiff cycle route (stiff_cycles.hpp, docs/model.md §17.13).
#include "stiff_cycles.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/model/model.hpp"

namespace abu::detail {

int replace_unresolved_multipliers(const Params& p, const std::vector<Eigen::VectorXd>& samples, double period,
                                   long total_steps, std::vector<std::complex<double>>& values,
                                   std::vector<double>& log_moduli, double& liouville) {
  const std::size_t n = samples.size();
  const int dim = int(values.size());
  liouville = 0;
  if (n == 0 || dim == 0 || total_steps <= 0) return 0;
  const double dt = period / double(n), h = period / double(total_steps);
  // Frozen spectra at every sample, sorted by real part, descending (ties: Im descending); a
  // mode's exponent is the periodic trapezoid sum of its eigenvalue (model.md (17.13.1)).
  std::vector<std::complex<double>> exponent(std::size_t(dim), 0.0);
  double trace = 0;
  Eigen::EigenSolver<Eigen::MatrixXd> es;
  std::vector<std::complex<double>> ev(static_cast<std::size_t>(dim));
  for (const Eigen::VectorXd& x : samples) {
    const State<double, 2> s = x;
    const Eigen::MatrixXd J = jacobian(p, s);
    trace += J.trace() * dt;
    es.compute(J, false);
    if (es.info() != Eigen::Success) return -1;
    for (int k = 0; k < dim; ++k) ev[std::size_t(k)] = es.eigenvalues()(k);
    std::sort(ev.begin(), ev.end(), [](std::complex<double> a, std::complex<double> b) {
      if (a.real() != b.real()) return a.real() > b.real();
      return a.imag() > b.imag();
    });
    for (int k = 0; k < dim; ++k) exponent[std::size_t(k)] += ev[std::size_t(k)] * dt;
  }
  // Unresolved: a mode whose mean frozen rate per step is below -1/2 (the slow ones move
  // by omega_H h ~ 1e-2 per step).
  std::vector<std::complex<double>> fast;
  for (const auto& e : exponent)
    if (e.real() / period * h < -0.5) fast.push_back(e);
  const int nf = int(fast.size());
  if (nf == 0 || nf >= dim) return 0;
  values.resize(std::size_t(dim - nf));
  log_moduli.resize(std::size_t(dim - nf));
  for (const auto& e : fast) {
    // |mu| = e^{Re}: below 1e-308 it shows as 0; the argument of a fast pair (Im * T, some
    // 1e6 rad) is not resolved by the frozen average and is not reported.
    values.emplace_back(std::exp(e.real()), 0.0);
    log_moduli.push_back(e.real());
  }
  // Descending by modulus (by its logarithm: the fast ones underflow to 0).
  std::vector<std::size_t> order(values.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return log_moduli[a] > log_moduli[b]; });
  std::vector<std::complex<double>> v2;
  std::vector<double> l2;
  for (std::size_t i : order) v2.push_back(values[i]), l2.push_back(log_moduli[i]);
  values = std::move(v2);
  log_moduli = std::move(l2);
  double sum = 0;
  for (double l : log_moduli) sum += l;
  liouville = std::abs(sum - trace) / std::abs(trace);
  return nf;
}

}  // namespace abu::detail
