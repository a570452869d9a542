// The flexible rotor's field and Jacobian for simulate_shaft (shaft_field.hpp, model.md §18.16).
#include "shaft_field.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "abu/model/friction.hpp"
#include "abu/model/machine_field.hpp"

namespace abu::shaft_detail {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using BallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, max_balls, max_balls>;
using BallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_balls, 1>;

// y += S x, S column-major sparse: no temporaries.
void add_product(const Sparse& s, const double* x, double* y) {
  for (int k = 0; k < s.outerSize(); ++k) {
    const double xk = x[k];
    if (xk == 0.0) continue;
    for (Sparse::InnerIterator it(s, k); it; ++it) y[it.row()] += it.value() * xk;
  }
}

}  // namespace

// The balls' terms at the balancer node (model.md (18.16.3), (18.20.1)).
struct ShaftOde::BallTerms {
  Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, max_balls> bq;  // A's coupling rows u1_b, u2_b
  BallVector inertia, rows;                                       // A's ball diagonal, b_beta
  double f1 = 0, f2 = 0;                                          // the node's force
};

ShaftOde::ShaftOde(const ShaftSystem& sys, const RaceShape* race)
    : sys_(sys),
      ns_(sys.shaft_dofs()),
      n_(sys.n_balls()),
      d_(sys.configuration_size()),
      b_(sys.balancer_dof()),
      k_(sys.fixed.stiffness),
      c_(sys.fixed.damping),
      g_(sys.fixed.gyroscopic) {
  // M_tot: the shaft's and discs' mass with the balls' translating mass at the balancer node.
  Eigen::MatrixXd mtot = Eigen::MatrixXd(sys.fixed.mass);
  double balls = 0;
  for (const auto& ball : sys.balancer.balls) balls += ball.mass;
  mtot(b_, b_) += balls;
  mtot(b_ + 1, b_ + 1) += balls;
  const Eigen::LLT<Eigen::MatrixXd> llt(mtot);  // positive definite: every dof has inertia (§18.9)
  minv_ = llt.solve(Eigen::MatrixXd::Identity(ns_, ns_));
  h_ = minv_.block<2, 2>(b_, b_);
  for (const auto& ball : sys.balancer.balls) {
    const double l = ball.race_radius, a = ball.mass * l;
    a_.push_back(a);
    inertia_.push_back(ball.inertia_factor * a * l);
    l_.push_back(l);
    euler_.push_back(a * (l - (ball.inertia_factor - 1.0) * ball.radius));
  }
  for (const ShaftBearing& b : sys.spec.bearings)
    if (b.anisotropic) bearings_.push_back({4 * b.node, *b.anisotropic});
  v_.resize(ns_);
  w_.resize(ns_);
  acc_.resize(ns_);
  if (race != nullptr && !race->round()) {
    race_ = *race;
    unround_ = true;
  }
  rigid_x_.setZero(2 * n_ + 4);
  share_mass_.setZero(n_ + 2, n_ + 2);
  share_force_.setZero(n_ + 2);
}

void ShaftOde::rigid_view(const double* y, State<double, any_balls>& x) const {
  x(0) = y[b_], x(1) = y[b_ + 1], x(n_ + 2) = y[d_ + b_], x(n_ + 3) = y[d_ + b_ + 1];
  for (int i = 0; i < n_; ++i) x(2 + i) = y[ns_ + i], x(n_ + 4 + i) = y[d_ + ns_ + i];
}

void ShaftOde::round_ball_terms(const double* y, BallTerms& t) const {
  // (18.6.2) with the run-up terms of (9.2)-(9.4) at the node.
  const double w = omega_, w2 = w * w, wd = omega_dot_;
  const double *u = y, *beta = y + ns_, *ud = y + d_, *bd = y + d_ + ns_;
  const double q1 = u[b_], q2 = u[b_ + 1], qd1 = ud[b_], qd2 = ud[b_ + 1];
  t.f1 = w2 * sys_.balancer.rotor.unbalance;
  t.f2 = -wd * sys_.balancer.rotor.unbalance;
  for (int i = 0; i < n_; ++i) {
    const double a = a_[std::size_t(i)], sb = std::sin(beta[i]), cb = std::cos(beta[i]);
    const double spin = (bd[i] + w) * (bd[i] + w);
    t.f1 += a * (spin * cb + wd * sb);
    t.f2 += a * (spin * sb - wd * cb);
    t.bq(0, i) = -a * sb;
    t.bq(1, i) = a * cb;
    t.inertia(i) = inertia_[std::size_t(i)];
    t.rows(i) = l_[std::size_t(i)] * friction_force(sys_.balancer, i, bd[i]) +
                a * ((-2.0 * w * qd2 - w2 * q1) * sb - (2.0 * w * qd1 - w2 * q2) * cb) -
                wd * (a * (q1 * cb + q2 * sb) + euler_[std::size_t(i)]);
  }
}

void ShaftOde::race_ball_terms(const double* y, BallTerms& t) {
  // (18.20.1): the balls' share of the composed rigid machine (ball_share_terms: (11.3.3),
  // (11.3.4) and (15.6.1) without the rotor's M, k, c, U) on the node's (u1, u2) as q.
  rigid_view(y, rigid_x_);
  ball_share_terms(sys_.balancer, race_, rigid_x_, omega_dot_, share_mass_, share_force_);
  t.f1 = omega_ * omega_ * sys_.balancer.rotor.unbalance + share_force_(0);
  t.f2 = -omega_dot_ * sys_.balancer.rotor.unbalance + share_force_(1);
  for (int i = 0; i < n_; ++i) {
    t.bq(0, i) = share_mass_(0, 2 + i);
    t.bq(1, i) = share_mass_(1, 2 + i);
    t.inertia(i) = share_mass_(2 + i, 2 + i);
    t.rows(i) = share_force_(2 + i);
  }
}

void ShaftOde::add_deviator(const double* u, const double* ud) {
  // (18.19.2): the deviatoric bearing force on the rotating axes is -(K_dev u + C_dev (u' + omega J u));
  // w holds the restoring forces, so it gains K_dev u + C_dev (u' + omega J u).
  for (const Bearing& b : bearings_) {
    const BearingDeviator dev = bearing_deviator(b.support, theta_);
    const int k = b.dof;
    const Eigen::Vector2d uk(u[k], u[k + 1]), vk(ud[k] - omega_ * u[k + 1], ud[k + 1] + omega_ * u[k]);
    const Eigen::Vector2d g = dev.stiffness * uk + dev.damping * vk;
    w_[k] += g(0);
    w_[k + 1] += g(1);
  }
}

bool ShaftOde::field(const double* y, double* f) {
  ++rhs_count;
  const double w = omega_, w2 = w * w, wd = omega_dot_;
  sys_.balancer.omega = w;  // the friction laws' normal force m l omega^2 (model.md §4)
  const double *u = y, *ud = y + d_;
  std::copy(y + d_, y + 2 * d_, f);  // s' (the configuration's rates)
  // w = K u + C (omega Jr u + u') + G (omega^2 Jr u + omega u' + omega'/2 u)   (18.16.2)
  for (int k = 0; k < ns_; k += 2) {
    v_[k] = -w * u[k + 1] + ud[k];
    v_[k + 1] = w * u[k] + ud[k + 1];
  }
  w_.setZero();
  add_product(k_, u, w_.data());
  add_product(c_, v_.data(), w_.data());
  for (int k = 0; k < ns_; ++k) v_[k] = w * v_[k] + 0.5 * wd * u[k];
  add_product(g_, v_.data(), w_.data());
  if (deviator_on_) add_deviator(u, ud);
  // The force on the balancer node, the balls' coupling B(beta) and their rows: on circles
  // (18.6.2) with the run-up terms of (9.2)-(9.4), or on the race's paths (18.20.1).
  BallTerms t;
  t.bq.resize(2, n_);
  t.inertia.resize(n_);
  t.rows.resize(n_);
  if (unround_)
    race_ball_terms(y, t);
  else
    round_ball_terms(y, t);
  const auto& bq = t.bq;
  BallVector& rows = t.rows;
  w_[b_] -= t.f1;
  w_[b_ + 1] -= t.f2;
  // The shaft's accelerations without the balls' inertial coupling (18.16.3):
  // a0 = -M_tot^-1 w + omega^2 u - 2 omega Jr u' - omega' Jr u (M_tot commutes with Jr).
  acc_.noalias() = minv_ * w_;
  for (int k = 0; k < ns_; k += 2) {
    acc_[k] = -acc_[k] + w2 * u[k] + 2.0 * w * ud[k + 1] + wd * u[k + 1];
    acc_[k + 1] = -acc_[k + 1] + w2 * u[k + 1] - 2.0 * w * ud[k] - wd * u[k];
  }
  // The balls: (D - B^T H B) beta'' = rows - B^T a0_b, H the node block of M_tot^-1.
  const Eigen::Vector2d a0b(acc_[b_], acc_[b_ + 1]);
  BallMatrix schur = -(bq.transpose() * h_ * bq);
  for (int i = 0; i < n_; ++i) schur(i, i) += t.inertia(i);
  rows -= bq.transpose() * a0b;
  const Eigen::LLT<BallMatrix> ball_llt(schur);
  if (ball_llt.info() != Eigen::Success) return false;
  const BallVector bdd = ball_llt.solve(rows);
  // u'' = a0 - M_tot^-1 E_b B beta''.
  const Eigen::Vector2d node = bq * bdd;
  double* sdd = f + d_;
  for (int k = 0; k < ns_; ++k) sdd[k] = acc_[k] - minv_(k, b_) * node(0) - minv_(k, b_ + 1) * node(1);
  for (int i = 0; i < n_; ++i) sdd[ns_ + i] = bdd(i);
  for (int k = 0; k < 2 * d_; ++k)
    if (!std::isfinite(f[k])) return false;
  return true;
}

void ShaftOde::add_runup_shaft_stiffness() {
  // omega' (M_tot Jr + G / 2) of (18.16.2), M_tot the shaft block of mass_.
  auto kk = kc_.leftCols(d_);
  kk.topLeftCorner(ns_, ns_) += 0.5 * omega_dot_ * Eigen::MatrixXd(g_);
  for (int k = 0; k < ns_; ++k) {  // omega' M_tot Jr: column k of Jr is +-e_{k+-1}
    const int partner = k % 2 == 0 ? k + 1 : k - 1;
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    // (M_tot Jr)(:, k) = sign * M_tot(:, partner), M_tot the shaft block of A.
    kk.col(k).head(ns_) += omega_dot_ * sign * mass_.col(partner).head(ns_);
  }
}

bool ShaftOde::round_matrices(const double* y) {
  const double wd = omega_dot_;
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(y, 2 * d_);
  // (18.7.1)-(18.7.2) at omega' = 0: linearize_shaft's C and K, its K holding (dA/ds) s'' with
  // the accelerations of omega' = 0.
  const ShaftLinearization lin = linearize_shaft(sys_, x);
  mass_ = Eigen::MatrixXd(lin.mass);
  kc_.resize(d_, 2 * d_);
  kc_.leftCols(d_) = Eigen::MatrixXd(lin.stiffness);
  kc_.rightCols(d_) = Eigen::MatrixXd(lin.damping);
  if (wd == 0.0 && !anisotropic()) return true;
  // The run-up terms' share of K = -db/ds + (dA/ds) s'' (18.16.4): -d/ds of the omega' terms
  // of b, and (dA/ds) times the change of s'' that omega' and the bearings' deviatoric force
  // make (linearize_shaft's s'' is that of the mean shaft at omega' = 0, (18.19.6)).
  if (!field(y, f_plus_.data())) return false;
  omega_dot_ = 0.0;
  deviator_on_ = false;
  const bool ok = field(y, f_still_.data());
  omega_dot_ = wd;
  deviator_on_ = true;
  if (!ok) return false;
  auto kk = kc_.leftCols(d_);
  if (wd != 0.0) add_runup_shaft_stiffness();
  const double q1 = y[b_], q2 = y[b_ + 1];
  for (int i = 0; i < n_; ++i) {
    const double a = a_[std::size_t(i)], sb = std::sin(y[ns_ + i]), cb = std::cos(y[ns_ + i]);
    const int col = ns_ + i;
    const double dbdd = f_plus_[std::size_t(d_ + ns_ + i)] - f_still_[std::size_t(d_ + ns_ + i)];
    const double dq1 = f_plus_[std::size_t(d_ + b_)] - f_still_[std::size_t(d_ + b_)];
    const double dq2 = f_plus_[std::size_t(d_ + b_ + 1)] - f_still_[std::size_t(d_ + b_ + 1)];
    kk(b_, col) += -wd * a * cb - a * cb * dbdd;
    kk(b_ + 1, col) += -wd * a * sb - a * sb * dbdd;
    kk(col, b_) += wd * a * cb;
    kk(col, b_ + 1) += wd * a * sb;
    kk(col, col) += wd * a * (q2 * cb - q1 * sb) - a * (cb * dq1 + sb * dq2);
  }
  return true;
}

bool ShaftOde::race_matrices(const double* y) {
  // (18.20.3): A = M_tot + S_A, C = D_r - S_v, K = K_r + omega' (M_tot Jr + G/2) - S_s, the
  // share's Bs = db/ds - (dA/ds) s'' taken at the field's own accelerations s'' (and omega').
  if (!field(y, f_plus_.data())) return false;
  rigid_view(y, rigid_x_);
  Coordinates<double, any_balls> acc(n_ + 2);
  acc(0) = f_plus_[std::size_t(d_ + b_)];
  acc(1) = f_plus_[std::size_t(d_ + b_ + 1)];
  for (int i = 0; i < n_; ++i) acc(2 + i) = f_plus_[std::size_t(d_ + ns_ + i)];
  const BallShare share = ball_share(sys_.balancer, race_, rigid_x_, acc, omega_dot_);
  const ShaftRotatingMatrices r = rotating_matrices(sys_);  // at sys_.balancer.omega = omega
  mass_.setZero(d_, d_);
  mass_.topLeftCorner(ns_, ns_) = Eigen::MatrixXd(r.mass);
  kc_.setZero(d_, 2 * d_);
  kc_.topLeftCorner(ns_, ns_) = Eigen::MatrixXd(r.stiffness);
  kc_.block(0, d_, ns_, ns_) = Eigen::MatrixXd(r.damping);
  if (omega_dot_ != 0.0) add_runup_shaft_stiffness();
  const auto at = [&](int k) { return k < 2 ? b_ + k : ns_ + k - 2; };  // rigid index -> configuration
  for (int rr = 0; rr < n_ + 2; ++rr)
    for (int c = 0; c < n_ + 2; ++c) {
      mass_(at(rr), at(c)) += share.mass(rr, c);
      kc_(at(rr), at(c)) -= share.force_position(rr, c);
      kc_(at(rr), d_ + at(c)) -= share.force_velocity(rr, c);
    }
  return true;
}

bool ShaftOde::jacobian(const double* y, double* dfdy, double* dfdt) {
  ++jacobian_count;
  const int dim = 2 * d_;
  const double wd = omega_dot_;
  sys_.balancer.omega = omega_;
  f_plus_.resize(std::size_t(dim));
  f_minus_.resize(std::size_t(dim));
  f_still_.resize(std::size_t(dim));
  if (!(unround_ ? race_matrices(y) : round_matrices(y))) return false;
  // The bearings' deviatoric blocks (18.19.4): K += K_dev + omega C_dev J, C += C_dev at their nodes.
  for (const Bearing& b : bearings_) {
    const BearingDeviator dev = bearing_deviator(b.support, theta_);
    kc_.block<2, 2>(b.dof, b.dof) += deviator_position_stiffness(dev, omega_);
    kc_.block<2, 2>(b.dof, d_ + b.dof) += dev.damping;
  }
  llt_.compute(mass_);
  if (llt_.info() != Eigen::Success) return false;
  sol_ = llt_.solve(kc_);
  for (int r = 0; r < dim; ++r)
    for (int c = 0; c < dim; ++c) dfdy[r * dim + c] = r < d_ ? (c == d_ + r ? 1.0 : 0.0) : -sol_(r - d_, c);
  // df/dt = omega' df/domega, by a central difference in omega (relative error ~1e-10).
  if (wd != 0.0) {
    const double w = omega_, dw = 1e-5 * std::max(std::abs(w), 1.0);
    omega_ = w + dw;
    const bool ok1 = field(y, f_plus_.data());
    omega_ = w - dw;
    const bool ok2 = field(y, f_minus_.data());
    omega_ = w;
    if (!ok1 || !ok2) return false;
    for (int r = 0; r < dim; ++r) dfdt[r] = wd * (f_plus_[std::size_t(r)] - f_minus_[std::size_t(r)]) / (2 * dw);
  } else {
    std::fill(dfdt, dfdt + dim, 0.0);
  }
  if (anisotropic()) {
    // + omega df/dtheta: A does not depend on theta, so d s''/dtheta = -A^-1 dw/dtheta, with
    // dw/dtheta the deviator's derivative (bearing_deviator_rate) on the node's u, u' + omega J u.
    theta_rhs_.setZero(d_);
    for (const Bearing& b : bearings_) {
      const BearingDeviator rate = bearing_deviator_rate(b.support, theta_);
      const int k = b.dof;
      const Eigen::Vector2d uk(y[k], y[k + 1]), vk(y[d_ + k] - omega_ * y[k + 1], y[d_ + k + 1] + omega_ * y[k]);
      theta_rhs_.segment<2>(k) -= rate.stiffness * uk + rate.damping * vk;
    }
    theta_rhs_ = llt_.solve(theta_rhs_);
    for (int r = 0; r < d_; ++r) dfdt[d_ + r] += omega_ * theta_rhs_[r];
  }
  for (int r = 0; r < dim * dim; ++r)
    if (!std::isfinite(dfdy[r])) return false;
  return true;
}

StiffnessProbe ShaftOde::probe(const double* y) {
  const int dim = 2 * d_;
  std::vector<double> j(std::size_t(dim * dim)), t(j.size() / std::size_t(dim));
  const double inf = std::numeric_limits<double>::infinity();
  if (!jacobian(y, j.data(), t.data())) return {inf, inf};
  const Eigen::MatrixXd jm = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      j.data(), dim, dim);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(jm, false);
  if (es.info() != Eigen::Success || !es.eigenvalues().allFinite()) {
    const double norm = jm.cwiseAbs().rowwise().sum().maxCoeff();  // bounds every |lambda|
    return {norm, 0.0};
  }
  StiffnessProbe p;
  for (const auto& l : es.eigenvalues()) {
    p.decay = std::max(p.decay, std::abs(l.real()));
    if (std::abs(l.imag()) > std::abs(l.real())) p.oscillation = std::max(p.oscillation, std::abs(l.imag()));
  }
  return p;
}

}  // namespace abu::shaft_detail
