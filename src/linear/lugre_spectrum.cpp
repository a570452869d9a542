#include "abu/linear/lugre_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace abu {

namespace {

using LD = long double;
using DenseLD = Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic>;

// Route (b) of model.md §12.5: J_c restricted to {w = 0}, w_i = z_i - c_i beta_i, whose
// functionals are left null vectors of J_c (w' = 0 in the linearization). The state is
// first scaled to natural sizes (a similarity: eigenvalues unchanged), so that the dense
// QR's absolute error eps ||J|| is not dominated by the units of q.
std::vector<std::complex<LD>> deflated_full_spectrum(const ParamsT<LD, any_balls>& p, const LugreState<LD>& x,
                                                     RestSide side) {
  const int n = p.n_balls(), d = n + 2, m = 3 * n + 4;
  const LugreMatrix<LD> J = lugre_jacobian(p, x, side);
  Eigen::Matrix<LD, Eigen::Dynamic, 1> size = Eigen::Matrix<LD, Eigen::Dynamic, 1>::Ones(m);
  const LD q_scale = displacement_scale(p);
  size(0) = size(1) = q_scale;
  size(d) = size(d + 1) = q_scale * p.omega;
  for (int i = 0; i < n; ++i) {
    size(d + 2 + i) = p.omega;
    size(2 * d + i) = p.balls[std::size_t(i)].mu_s / p.balls[std::size_t(i)].sigma0;
  }
  const DenseLD Js = size.cwiseInverse().asDiagonal() * DenseLD(J) * size.asDiagonal();
  DenseLD L = DenseLD::Zero(n, m);  // w_i in scaled coordinates
  for (int i = 0; i < n; ++i) {
    L(i, 2 * d + i) = size(2 * d + i);
    L(i, 2 + i) = -J(2 * d + i, d + 2 + i) * size(2 + i);  // c_i
  }
  Eigen::HouseholderQR<DenseLD> qr(L.transpose());
  const DenseLD Q = DenseLD(qr.householderQ()).rightCols(m - n);  // orthonormal basis of ker L
  const DenseLD B = Q.transpose() * Js * Q;
  Eigen::EigenSolver<DenseLD> es(B, false);
  std::vector<std::complex<LD>> out;
  if (es.info() != Eigen::Success) return out;
  for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k) out.push_back(es.eigenvalues()(k));
  return out;
}

LugreSideSpectrum side_spectrum(const ParamsT<LD, any_balls>& p, const Coordinates<LD, any_balls>& s,
                                const LugreState<LD>& x, RestSide side, bool zero_bristle) {
  LugreSideSpectrum out;
  out.side = side;
  out.zeros = p.n_balls();
  out.normal = compute_spectrum<any_balls>(lugre_rest_linearization(p, s, side, zero_bristle));
  std::vector<std::complex<LD>> other = deflated_full_spectrum(p, x, side);
  if (int(other.size()) != out.normal.count) {
    out.route_deviation = std::numeric_limits<double>::infinity();
    return out;
  }
  // Pair greedily, largest modulus first, each with its nearest unused partner.
  std::vector<int> order(std::size_t(out.normal.count));
  for (int k = 0; k < out.normal.count; ++k) order[std::size_t(k)] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(out.normal.eigenvalues[std::size_t(a)]) > std::abs(out.normal.eigenvalues[std::size_t(b)]);
  });
  std::vector<bool> used(other.size(), false);
  double worst = 0.0;
  for (int k : order) {
    const std::complex<LD> lam(out.normal.eigenvalues[std::size_t(k)].real(), out.normal.eigenvalues[std::size_t(k)].imag());
    std::size_t best = 0;
    LD best_d = std::numeric_limits<LD>::infinity();
    for (std::size_t j = 0; j < other.size(); ++j)
      if (!used[j] && std::abs(other[j] - lam) < best_d) best_d = std::abs(other[j] - lam), best = j;
    used[best] = true;
    worst = std::max(worst, double(best_d / std::max(std::abs(lam), LD(1e-300))));
  }
  out.route_deviation = worst;
  return out;
}

}  // namespace

SpectrumN lugre_zero_bristle_spectrum(const ParamsN& p, const Coordinates<long double, any_balls>& s) {
  return compute_spectrum<any_balls>(lugre_rest_linearization(p.cast<LD>(), s, RestSide::forward, true));
}

std::string_view LugreRest::verdict() const {
  if (non_smooth) return "non-smooth";
  return to_string(forward.normal.stability);
}

Coordinates<long double, any_balls> lugre_configuration(const ParamsN& p, const std::vector<double>& beta) {
  const int n = p.n_balls();
  const auto pl = p.cast<LD>();
  std::complex<LD> W = pl.rotor.unbalance;
  for (int i = 0; i < n; ++i) {
    const auto& b = pl.balls[std::size_t(i)];
    W += b.mass * b.race_radius * std::complex<LD>(std::cos(LD(beta[std::size_t(i)])), std::sin(LD(beta[std::size_t(i)])));
  }
  const LD w2 = pl.omega * pl.omega;
  const std::complex<LD> q = w2 * W / std::complex<LD>(pl.rotor.stiffness - w2 * pl.total_mass(), pl.rotor.damping * pl.omega);
  Coordinates<LD, any_balls> s(n + 2);
  s(0) = q.real();
  s(1) = q.imag();
  for (int i = 0; i < n; ++i) s(2 + i) = beta[std::size_t(i)];
  return s;
}

LugreRest analyze_lugre_rest(const ParamsN& p, const Coordinates<long double, any_balls>& s, bool zero_bristle) {
  const int n = p.n_balls(), d = n + 2;
  const auto pl = p.cast<LD>();
  LugreRest r;
  r.position = s.cast<double>();
  r.zero_bristle = zero_bristle;
  LugreState<LD> x = lugre_equilibrium(pl, s);
  if (zero_bristle) x.tail(n).setZero();
  for (int i = 0; i < n; ++i) {
    r.bristle.push_back(double(x(2 * d + i)));
    r.load_ratio.push_back(zero_bristle ? 0.0 : double(lugre_load_ratio(pl, s, i)));
    if (std::abs(r.load_ratio.back()) > 1.0) r.reachable = false;
  }
  {  // rotor rows of b(s, 0): the configuration must carry its own q(beta)
    ParamsT<LD, any_balls> free = pl;
    free.law = FrictionLaw::none;
    const auto b = generalized_forces(free, at_rest<LD, any_balls>(s));
    const auto scale = static_force_scale(free, s);
    r.rotor_residual = double(std::max(std::abs(b(0) / scale(0)), std::abs(b(1) / scale(1))));
  }
  // At z = 0 both one-sided slopes are 1 and the Jacobian is an ordinary one.
  r.forward = side_spectrum(pl, s, x, RestSide::forward, zero_bristle);
  r.backward = zero_bristle ? r.forward : side_spectrum(pl, s, x, RestSide::backward, false);
  if (zero_bristle) r.backward.side = RestSide::backward;
  r.stable = r.forward.normal.stability == Stability::stable && r.backward.normal.stability == Stability::stable;
  r.non_smooth = r.forward.normal.stability != r.backward.normal.stability;
  return r;
}

}  // namespace abu
