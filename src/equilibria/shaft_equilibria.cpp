// Equilibria of the flexible rotor with its balls (model.md §18.8).
#include "abu/equilibria/shaft_equilibria.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include <Eigen/SparseLU>

namespace abu {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

double capacity(const ParamsN& p) {
  double c = p.rotor.unbalance;
  for (const auto& b : p.balls) c += b.mass * b.race_radius;
  return c;
}

double balancer_disc_mass(const ShaftSystem& sys) {
  double m = 0.0;
  for (const ShaftDisc& d : sys.spec.discs)
    if (d.node == sys.spec.balancer_node) m += d.mass;
  return m;
}

/// Length over which the tilt rows' moments are measured: the shaft, or the race if longer.
double reference_length(const ShaftSystem& sys) {
  double l = 0.0;
  for (const ShaftElement& e : sys.spec.elements) l += e.length;
  for (const auto& b : sys.balancer.balls) l = std::max(l, double(b.race_radius));
  return l;
}

/// The static equations' residual b(s, 0) and the natural size of each row (18.8.4):
/// shaft rows (|K_r| |u|)_i + omega^2 (U + sum a) (times the reference length on tilt
/// rows), ball rows a_i omega^2 (|q| + d), d = (U + sum a) / M as static_force_scale.
double shaft_static_residual(const ShaftSystem& sys, const ShaftRotatingMatrices& r, const Eigen::VectorXd& s) {
  const int ns = sys.shaft_dofs(), size = sys.configuration_size(), b = sys.balancer_dof();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * size);
  x.head(size) = s;
  const Eigen::VectorXd res = shaft_generalized_forces(sys, x);
  const ParamsN& p = sys.balancer;
  const double w2 = p.omega * p.omega, cap = capacity(p);
  Sparse abs_k = r.stiffness.cwiseAbs();
  const Eigen::VectorXd ku = abs_k * s.head(ns).cwiseAbs();
  const double lref = reference_length(sys);
  const double q = std::hypot(s(b), s(b + 1));
  const double d = cap / (balancer_disc_mass(sys) + [&] {
                     double m = 0.0;
                     for (const auto& ball : p.balls) m += ball.mass;
                     return m;
                   }());
  double worst = 0.0;
  for (int i = 0; i < ns; ++i) {
    const double floor = w2 * cap * ((i % 4) < 2 ? 1.0 : lref);
    const double scale = ku(i) + floor;
    if (scale > 0.0) worst = std::max(worst, std::abs(res(i)) / scale);
  }
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const double scale = ball.mass * ball.race_radius * w2 * (q + d);
    if (scale > 0.0) worst = std::max(worst, std::abs(res(ns + i)) / scale);
  }
  return worst;
}

/// db/ds at s' = 0 (the static Jacobian, minus (18.7.2)'s stiffness without the s'' term).
Sparse static_jacobian(const ShaftSystem& sys, const ShaftRotatingMatrices& r, const Eigen::VectorXd& s) {
  const int ns = sys.shaft_dofs(), size = sys.configuration_size(), b = sys.balancer_dof();
  const ParamsN& p = sys.balancer;
  const double w = p.omega, w2 = w * w;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(r.stiffness.nonZeros() + 5 * sys.n_balls()));
  for (int k = 0; k < r.stiffness.outerSize(); ++k)
    for (Sparse::InnerIterator it(r.stiffness, k); it; ++it) t.emplace_back(int(it.row()), int(it.col()), -it.value());
  const double q1 = s(b), q2 = s(b + 1);
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const double a = ball.mass * ball.race_radius, sb = std::sin(s(ns + i)), cb = std::cos(s(ns + i));
    const int col = ns + i;
    t.emplace_back(b, col, -a * w2 * sb);
    t.emplace_back(b + 1, col, a * w2 * cb);
    t.emplace_back(col, b, -a * w2 * sb);
    t.emplace_back(col, b + 1, a * w2 * cb);
    t.emplace_back(col, col, a * w2 * (-q1 * cb - q2 * sb));
  }
  Sparse j(size, size);
  j.setFromTriplets(t.begin(), t.end());
  j.makeCompressed();
  return j;
}

ShaftEquilibrium copy_fields(const EquilibriumN& e, int size) {
  ShaftEquilibrium out;
  out.family = e.family;
  out.pattern = e.pattern;
  out.member = e.member;
  out.position = Eigen::VectorXd::Zero(size);
  out.is_set = e.is_set;
  out.on_balanced_set = e.on_balanced_set;
  out.structural_zeros = e.structural_zeros;
  return out;
}

}  // namespace

Eigen::VectorXd ShaftEquilibrium::state() const {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * position.size());
  x.head(position.size()) = position;
  return x;
}

std::optional<Eigen::VectorXcd> node_receptances(const ShaftSystem& sys) {
  const ShaftRotatingMatrices r = rotating_matrices(sys);
  Eigen::SparseLU<Sparse> lu;
  lu.compute(r.stiffness);
  if (lu.info() != Eigen::Success) return std::nullopt;
  Eigen::VectorXd force = Eigen::VectorXd::Zero(sys.shaft_dofs());
  force(sys.balancer_dof()) = 1.0;
  const Eigen::VectorXd u = lu.solve(force);
  if (lu.info() != Eigen::Success || !u.allFinite()) return std::nullopt;
  // K_r commutes with the 90-degree rotation of every pair, so a unit force along a1 gives
  // each node's complex receptance: u1_k + i u2_k = H_k (model.md (18.8.1), (18.17.2)).
  Eigen::VectorXcd h(sys.nodes());
  for (int k = 0; k < sys.nodes(); ++k) h(k) = std::complex<double>(u(4 * k), u(4 * k + 1));
  return h;
}

std::optional<std::complex<double>> balancer_dynamic_stiffness(const ShaftSystem& sys) {
  const std::optional<Eigen::VectorXcd> h = node_receptances(sys);
  if (!h) return std::nullopt;
  // A unit force along a1 at the balancer node deflects it by q = h (18.8.1).
  const std::complex<double> hb = (*h)(sys.spec.balancer_node);
  if (hb == 0.0) return std::nullopt;
  const std::complex<double> z = 1.0 / hb;
  if (!std::isfinite(z.real()) || !std::isfinite(z.imag())) return std::nullopt;
  return z;
}

ParamsN equivalent_rigid_params(const ShaftSystem& sys, std::complex<double> dynamic_stiffness) {
  ParamsN p = sys.balancer;
  const double w = p.omega;
  p.rotor.mass = balancer_disc_mass(sys);
  // K = k - omega^2 M and C = c omega of (1.4) equal to the shaft's (18.8.2).
  p.rotor.stiffness = dynamic_stiffness.real() + w * w * p.total_mass();
  p.rotor.damping = w != 0.0 ? dynamic_stiffness.imag() / w : 0.0;
  return p;
}

ShaftEquilibrium shaft_equilibrium_from_rigid(const ShaftSystem& sys, const EquilibriumN& rigid) {
  const int ns = sys.shaft_dofs(), size = sys.configuration_size(), b = sys.balancer_dof();
  const ShaftRotatingMatrices r = rotating_matrices(sys);
  ShaftEquilibrium out = copy_fields(rigid, size);
  for (int i = 0; i < sys.n_balls(); ++i) out.position(ns + i) = double(rigid.position(2 + i));
  if (rigid.family == Family::balanced) {
    // u = 0 on the whole shaft: b's shaft rows are omega^2 W(beta) = 0 at node b only.
    out.residual = shaft_static_residual(sys, r, out.position);
    out.newton_iterations = rigid.newton_iterations;
    out.status = rigid.status;
    return out;
  }
  // The shaft's deflection under omega^2 W(beta) at the balancer node (18.8.3).
  const ParamsN& p = sys.balancer;
  const double w2 = p.omega * p.omega;
  Eigen::VectorXd force = Eigen::VectorXd::Zero(ns);
  force(b) = w2 * p.rotor.unbalance;
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    force(b) += w2 * ball.mass * ball.race_radius * std::cos(out.position(ns + i));
    force(b + 1) += w2 * ball.mass * ball.race_radius * std::sin(out.position(ns + i));
  }
  Eigen::SparseLU<Sparse> lu(r.stiffness);
  if (lu.info() != Eigen::Success) {
    out.status = {Outcome::numerical_issue, "the rotating-frame shaft stiffness is singular"};
    return out;
  }
  out.position.head(ns) = lu.solve(force);
  // Newton on the sparse static equations b(s, 0) = 0, from there.
  out.residual = shaft_static_residual(sys, r, out.position);
  double best = out.residual;
  int it = 0;
  for (; it < 20 && out.residual > 1e-15; ++it) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * size);
    x.head(size) = out.position;
    const Eigen::VectorXd res = shaft_generalized_forces(sys, x);
    Eigen::SparseLU<Sparse> jlu(static_jacobian(sys, r, out.position));
    if (jlu.info() != Eigen::Success) break;
    const Eigen::VectorXd step = jlu.solve(res);
    if (!step.allFinite()) break;
    const Eigen::VectorXd trial = out.position - step;
    const double trial_residual = shaft_static_residual(sys, r, trial);
    if (!(trial_residual < best)) break;  // at rounding level: no further progress
    out.position = trial;
    out.residual = best = trial_residual;
  }
  out.newton_iterations = it;
  for (int i = 0; i < sys.n_balls(); ++i) out.position(ns + i) = double(wrap_angle(out.position(ns + i)));
  out.residual = shaft_static_residual(sys, r, out.position);
  // Rounding level of the double solve: a few eps times the condition of the rows.
  if (out.residual <= 1e-10)
    out.status = rigid.status.ok() ? Status{} : rigid.status;
  else
    out.status = {Outcome::not_converged, "Newton on the shaft's static equations stalled above 1e-10"};
  return out;
}

ShaftEquilibriumSet find_shaft_equilibria(const ShaftSystem& sys, const BalancedSampling& sampling) {
  ShaftEquilibriumSet set;
  set.dynamic_stiffness = balancer_dynamic_stiffness(sys);
  ParamsN rigid;
  if (set.dynamic_stiffness) {
    rigid = equivalent_rigid_params(sys, *set.dynamic_stiffness);
  } else {
    // Only the balanced states (W = 0) do not depend on the support.
    rigid = equivalent_rigid_params(sys, {1.0, 0.0});
    set.status = {Outcome::numerical_issue,
                  "the rotating-frame shaft stiffness is singular at this speed (an undamped critical speed): "
                  "aligned equilibria not computed"};
  }
  const EquilibriumSetN rigid_set = find_equilibria(rigid, sampling);
  set.degeneracy = rigid_set.degeneracy;
  set.balanced_set = rigid_set.balanced_set;
  for (const EquilibriumN& e : rigid_set.points()) {
    if (!set.dynamic_stiffness && e.family != Family::balanced) continue;
    set.list.push_back(shaft_equilibrium_from_rigid(sys, e));
    set.status.merge(set.list.back().status);
  }
  return set;
}

}  // namespace abu
