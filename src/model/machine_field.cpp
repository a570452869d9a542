// The composed rigid-rotor field (machine_field.hpp, docs/model.md §20): the unround race's
// A and b (model.md §11.3, the run-up's Euler terms §15.6) plus the anisotropic support's
// force (10.14.1); model.md §3's field when neither part is present.
#include "abu/model/machine_field.hpp"

#include <Eigen/Cholesky>
#include <array>
#include <cmath>
#include <numbers>

#include "abu/model/friction.hpp"
#include "abu/model/mass_derivative.hpp"
#include "abu/model/unround_field.hpp"

namespace abu {

bool RigidMachine::unround() const { return race != nullptr && !race->round(); }
bool RigidMachine::anisotropic() const { return support != nullptr && !support->isotropic(); }

namespace {

// Everything (15.6.2)-(15.6.4) needs of ball i's path at beta_i: p' = u + iv, p'' = u' + iv',
// p''' = u'' + iv'' = (l''' - 3 l' + i (3 l'' - l)) e^{i beta}, s' = |p'|, s'', s'''.
struct BallPath {
  double ell = 0, d1 = 0, d2 = 0, u = 0, v = 0, du = 0, dv = 0, ddu = 0, ddv = 0, sp = 0, spp = 0, sppp = 0;
};

BallPath ball_path(const RaceHarmonics& h, double l, double beta, bool third) {
  const PathPoint<double> pt = path_point<double>(h, l, beta);
  BallPath b;
  b.ell = pt.ell, b.d1 = pt.d1, b.d2 = pt.d2, b.u = pt.u, b.v = pt.v, b.du = pt.du, b.dv = pt.dv;
  b.sp = pt.speed, b.spp = pt.dspeed;
  if (third) {
    const double d3 = path_third_derivative(h, l, beta), cb = std::cos(beta), sb = std::sin(beta);
    b.ddu = (d3 - 3 * pt.d1) * cb - (3 * pt.d2 - pt.ell) * sb;
    b.ddv = (d3 - 3 * pt.d1) * sb + (3 * pt.d2 - pt.ell) * cb;
    // s''' = d/dbeta [l' (l + l'') / s'] = (l'' (l + l'') + l' (l' + l''') - s''^2) / s'
    b.sppp = (pt.d2 * (pt.ell + pt.d2) + pt.d1 * (pt.d1 + d3) - pt.dspeed * pt.dspeed) / pt.speed;
  }
  return b;
}

using Paths = std::array<BallPath, max_balls>;
using Dof = Coordinates<double, any_balls>;
using DofM = DofMatrix<double, any_balls>;

const RaceHarmonics& harmonics_of(const RaceShape& race, int i) {
  static const RaceHarmonics round;
  return std::size_t(i) < race.balls.size() ? race.balls[std::size_t(i)] : round;
}

Paths paths_at(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x, bool third) {
  Paths out{};
  for (int i = 0; i < p.n_balls(); ++i)
    out[std::size_t(i)] = ball_path(harmonics_of(race, i), p.balls[std::size_t(i)].race_radius, x(2 + i), third);
  return out;
}

// A(beta) of (11.3.3); without the translating mass M (`rotor` false) the balls' share only.
DofM mass_of(const ParamsN& p, const Paths& paths, bool rotor = true) {
  const int n = p.n_balls();
  DofM A = DofM::Zero(n + 2, n + 2);
  if (rotor) A(0, 0) = A(1, 1) = p.total_mass();
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const auto& g = paths[std::size_t(i)];
    A(0, 2 + i) = A(2 + i, 0) = b.mass * g.u;
    A(1, 2 + i) = A(2 + i, 1) = b.mass * g.v;
    A(2 + i, 2 + i) = b.inertia_factor * b.mass * g.sp * g.sp;
  }
  return A;
}

// b(s, s') of (11.3.4) plus the run-up's Euler terms (15.6.1); without the rotor's own terms
// (M, k, c, U: `rotor` false) the balls' share only.
Dof forces_of(const ParamsN& p, const Paths& paths, const State<double, any_balls>& x, double wd, bool rotor = true) {
  const int n = p.n_balls();
  const double w = p.omega, w2 = w * w, M = p.total_mass();
  const double q1 = x(0), q2 = x(1), dq1 = x(n + 2), dq2 = x(n + 3);
  const auto& r = p.rotor;
  Dof b = Dof::Zero(n + 2);
  if (rotor) {
    b(0) = w2 * r.unbalance + M * (2 * w * dq2 + w2 * q1) - r.damping * (dq1 - w * q2) - r.stiffness * q1 + M * wd * q2;
    b(1) = M * (-2 * w * dq1 + w2 * q2) - r.damping * (dq2 + w * q1) - r.stiffness * q2 - wd * r.unbalance - M * wd * q1;
  }
  for (int i = 0; i < n; ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const auto& g = paths[std::size_t(i)];
    const double m = ball.mass, db = x(n + 4 + i), cb = std::cos(x(2 + i)), sb = std::sin(x(2 + i));
    b(0) += m * (w2 * g.ell * cb - g.du * db * db + 2 * w * g.v * db + wd * g.ell * sb);
    b(1) += m * (w2 * g.ell * sb - g.dv * db * db - 2 * w * g.u * db - wd * g.ell * cb);
    const double F = friction_force(p, i, g.sp * db / ball.race_radius);
    b(2 + i) = g.sp * F + m * w2 * g.ell * g.d1 - m * (g.u * (-2 * w * dq2 - w2 * q1) + g.v * (2 * w * dq1 - w2 * q2)) -
               ball.inertia_factor * m * g.sp * g.spp * db * db -
               m * wd * (g.v * q1 - g.u * q2 + g.ell * g.ell) + (ball.inertia_factor - 1) * m * ball.radius * wd * g.sp;
  }
  return b;
}


// The support's anisotropic part on the rotating axes at the spin angle theta (10.14.1):
// dK = K_rot - k_bar I, dC = C_rot - c_bar I, and their theta derivatives (pure second
// harmonics: 2 times their value a quarter of their period, pi/4, later).
struct Anisotropy {
  Eigen::Matrix2d dK = Eigen::Matrix2d::Zero(), dC = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d dK_theta = Eigen::Matrix2d::Zero(), dC_theta = Eigen::Matrix2d::Zero();
};

Anisotropy anisotropy_at(const AnisotropicSupport& s, double theta) {
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  Anisotropy a;
  a.dK = rotating_stiffness(s, 1.0, theta) - s.mean_stiffness() * I;
  a.dC = rotating_damping(s, 1.0, theta) - s.mean_damping() * I;
  const double quarter = std::numbers::pi / 4;
  a.dK_theta = 2.0 * (rotating_stiffness(s, 1.0, theta + quarter) - s.mean_stiffness() * I);
  a.dC_theta = 2.0 * (rotating_damping(s, 1.0, theta + quarter) - s.mean_damping() * I);
  return a;
}

// g of (10.14.1): -dK q - dC (q' + omega J2 q), J2 q = (-q2, q1).
Eigen::Vector2d support_force(const Eigen::Matrix2d& dK, const Eigen::Matrix2d& dC, double omega,
                              const Eigen::Vector2d& q, const Eigen::Vector2d& qdot) {
  return -dK * q - dC * (qdot + omega * Eigen::Vector2d(-q(1), q(0)));
}

// The base model (§3, §9): f, and J, df/domega from model.hpp.
void base_field(const ParamsN& p, const State<double, any_balls>& x, double wd, MachineFieldValue& out, bool derivatives) {
  out.field = wd == 0 ? vector_field(p, x) : vector_field(p, x, wd);
  if (!derivatives) return;
  out.jacobian = wd == 0 ? jacobian(p, x) : jacobian(p, x, wd);
  out.omega_derivative = parameter_derivative(p, x, ParamRef{Quantity::omega, -1});
  out.angle_derivative = State<double, any_balls>::Zero(x.size());
  out.delta_derivative = State<double, any_balls>::Zero(x.size());
}

// A round race on an anisotropic support: model.md §3's A and b (model.hpp) at the mean
// support plus delta A^-1 (g, 0), with (20.2) and the mean field's derivatives (§10.14).
void round_race_field(const ParamsN& p, const RigidMachine& m, const State<double, any_balls>& x, double theta,
                      double wd, MachineFieldValue& out, bool derivatives) {
  base_field(p, x, wd, out, derivatives);
  const Eigen::Index d = x.size() / 2;
  const Dof pos = x.head(d);
  const Eigen::Vector2d q = x.head<2>(), qdot = x.segment<2>(d);
  const Eigen::LLT<DofM> llt(mass_matrix(p, pos));  // A is SPD (model.md §3)
  const Anisotropy a = anisotropy_at(*m.support, theta);
  Dof g = Dof::Zero(d);
  g.head<2>() = support_force(a.dK, a.dC, p.omega, q, qdot);
  const Dof accel = llt.solve(g);  // A^-1 g: the full anisotropy's acceleration
  out.field.segment(d, d) += m.delta * accel;
  if (!derivatives) return;
  out.delta_derivative.segment(d, d) = accel;
  Dof gt = Dof::Zero(d);
  gt.head<2>() = support_force(a.dK_theta, a.dC_theta, p.omega, q, qdot);
  out.angle_derivative.segment(d, d) = m.delta * llt.solve(gt);
  Eigen::Matrix2d J2;
  J2 << 0.0, -1.0, 1.0, 0.0;
  Dof gw = Dof::Zero(d);
  gw.head<2>() = -m.delta * (a.dC * (J2 * q));
  out.omega_derivative.segment(d, d) += llt.solve(gw);
  // (20.2), and the change of A(beta) at fixed delta g: -(dA/ds) A^-1 delta g.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, dof_capacity<any_balls>,
                2 * dof_capacity<any_balls>>
      rhs = Eigen::MatrixXd::Zero(d, 2 * d);
  rhs.block(0, 0, 2, 2) = -m.delta * (a.dK + p.omega * a.dC * J2);
  rhs.block(0, d, 2, 2) = -m.delta * a.dC;
  rhs.leftCols(d) -= mass_derivative_times(p, pos, Dof(m.delta * accel));
  out.jacobian.block(d, 0, d, 2 * d) += llt.solve(rhs);
}

// Bs = db/ds - (dA/ds) s'' and Bv = db/ds' of (15.6.2), (15.6.4) with s'' = acc, and db/domega
// (15.6.5): the race's and the mean support's terms.
void race_derivatives(const ParamsN& p, const Paths& paths, const State<double, any_balls>& x, double wd,
                      const Dof& acc, DofM& Bs, DofM& Bv, Dof& bw, bool rotor = true) {
  const int n = p.n_balls(), d = n + 2;
  const double w = p.omega, w2 = w * w, M = p.total_mass();
  const auto& r = p.rotor;
  const double q1 = x(0), q2 = x(1), dq1 = x(n + 2), dq2 = x(n + 3);
  Bs = DofM::Zero(d, d), Bv = DofM::Zero(d, d);
  bw = Dof::Zero(d);
  if (rotor) {  // the rotor's own terms (M, k, c, U)
    Bs(0, 0) = M * w2 - r.stiffness, Bs(0, 1) = r.damping * w + M * wd;
    Bs(1, 0) = -r.damping * w - M * wd, Bs(1, 1) = M * w2 - r.stiffness;
    Bv(0, 0) = -r.damping, Bv(0, 1) = 2 * M * w;
    Bv(1, 0) = -2 * M * w, Bv(1, 1) = -r.damping;
    bw(0) = 2 * w * r.unbalance + M * (2 * dq2 + 2 * w * q1) + r.damping * q2;
    bw(1) = M * (-2 * dq1 + 2 * w * q2) - r.damping * q1;
  }
  for (int i = 0; i < n; ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const auto& g = paths[std::size_t(i)];
    const double m = ball.mass, j = ball.inertia_factor, db = x(n + 4 + i), l = ball.race_radius;
    const double nu = g.sp * db / l, F = friction_force(p, i, nu), Fv = friction_slope(p, i, nu);
    const double cb = std::cos(x(2 + i)), sb = std::sin(x(2 + i));
    const int c = 2 + i;
    // Rotor rows.
    Bs(0, c) = m * (w2 * g.u - g.ddu * db * db + 2 * w * g.dv * db + wd * g.v);
    Bs(1, c) = m * (w2 * g.v - g.ddv * db * db - 2 * w * g.du * db - wd * g.u);
    Bv(0, c) = m * (-2 * g.du * db + 2 * w * g.v);
    Bv(1, c) = m * (-2 * g.dv * db - 2 * w * g.u);
    // Ball row.
    Bs(c, 0) = m * w2 * g.u - m * wd * g.v;
    Bs(c, 1) = m * w2 * g.v + m * wd * g.u;
    Bv(c, 0) = -2 * w * m * g.v;
    Bv(c, 1) = 2 * w * m * g.u;
    Bs(c, c) = g.spp * F + g.sp * Fv * g.spp * db / l + m * w2 * (g.d1 * g.d1 + g.ell * g.d2) -
               m * (g.du * (-2 * w * dq2 - w2 * q1) + g.dv * (2 * w * dq1 - w2 * q2)) -
               j * m * (g.spp * g.spp + g.sp * g.sppp) * db * db - m * wd * (g.dv * q1 - g.du * q2 + 2 * g.ell * g.d1) +
               (j - 1) * m * ball.radius * wd * g.spp;
    Bv(c, c) = g.sp * Fv * g.sp / l - 2 * j * m * g.sp * g.spp * db;
    // (dA/dbeta_i) s'': column i of A moves only in rows 0, 1 (m u', m v') and in the
    // diagonal (2 j m s' s''), row i symmetrically.
    Bs(0, c) -= m * g.du * acc(c);
    Bs(1, c) -= m * g.dv * acc(c);
    Bs(c, c) -= m * g.du * acc(0) + m * g.dv * acc(1) + 2 * j * m * g.sp * g.spp * acc(c);
    // db/domega (15.6.5); the Euler terms do not depend on omega.
    bw(0) += m * (2 * w * g.ell * cb + 2 * g.v * db);
    bw(1) += m * (2 * w * g.ell * sb - 2 * g.u * db);
    const double dF = friction_partial(p, i, nu, Quantity::omega);
    bw(c) = g.sp * dF + 2 * m * w * g.ell * g.d1 - m * (g.u * (-2 * dq2 - 2 * w * q1) + g.v * (2 * dq1 - 2 * w * q2));
  }
}

}  // namespace

void machine_field(const ParamsN& p, const RigidMachine& m, const State<double, any_balls>& x, double theta,
                   double wd, MachineFieldValue& out, bool derivatives) {
  if (m.base()) return base_field(p, x, wd, out, derivatives);
  if (!m.unround()) return round_race_field(p, m, x, theta, wd, out, derivatives);
  const int n = p.n_balls(), d = n + 2;
  const Paths paths = paths_at(p, *m.race, x, derivatives);
  const auto llt = mass_of(p, paths).llt();  // A is SPD (model.md §11.3)
  Dof b = forces_of(p, paths, x, wd);
  const bool aniso = m.anisotropic();
  const Eigen::Vector2d q = x.head<2>(), qdot = x.segment<2>(d);
  Anisotropy a;
  Dof g = Dof::Zero(d);
  if (aniso) {
    a = anisotropy_at(*m.support, theta);
    g.head<2>() = support_force(a.dK, a.dC, p.omega, q, qdot);
    b += m.delta * g;
  }
  const Dof acc = llt.solve(b);  // s''
  out.field = State<double, any_balls>(2 * d);
  out.field.head(d) = x.tail(d);
  out.field.tail(d) = acc;
  if (!derivatives) return;
  DofM Bs, Bv;
  Dof bw;
  race_derivatives(p, paths, x, wd, acc, Bs, Bv, bw);
  out.angle_derivative = State<double, any_balls>::Zero(2 * d);
  out.delta_derivative = State<double, any_balls>::Zero(2 * d);
  if (aniso) {
    // (10.14.2): d(delta g)/dq = -delta (dK + omega dC J2), d(delta g)/dq' = -delta dC;
    // d(delta g)/domega = -delta dC J2 q; d(delta g)/dtheta with dK', dC'.
    Eigen::Matrix2d J2;
    J2 << 0.0, -1.0, 1.0, 0.0;
    Bs.topLeftCorner<2, 2>() -= m.delta * (a.dK + p.omega * a.dC * J2);
    Bv.topLeftCorner<2, 2>() -= m.delta * a.dC;
    bw.head<2>() -= m.delta * a.dC * (J2 * q);
    Dof gt = Dof::Zero(d);
    gt.head<2>() = support_force(a.dK_theta, a.dC_theta, p.omega, q, qdot);
    out.angle_derivative.tail(d) = m.delta * llt.solve(gt);
    out.delta_derivative.tail(d) = llt.solve(g);
  }
  out.jacobian = StateMatrix<double, any_balls>::Zero(2 * d, 2 * d);
  out.jacobian.topRightCorner(d, d).setIdentity();
  out.jacobian.bottomLeftCorner(d, d) = llt.solve(Bs);
  out.jacobian.bottomRightCorner(d, d) = llt.solve(Bv);
  out.omega_derivative = State<double, any_balls>::Zero(2 * d);
  out.omega_derivative.tail(d) = llt.solve(bw);
}

BallShare ball_share(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x,
                     const Coordinates<double, any_balls>& acc, double omega_dot) {
  const Paths paths = paths_at(p, race, x, true);
  BallShare out;
  out.mass = mass_of(p, paths, false);
  out.force = forces_of(p, paths, x, omega_dot, false);
  Dof bw;
  race_derivatives(p, paths, x, omega_dot, acc, out.force_position, out.force_velocity, bw, false);
  return out;
}

void ball_share_terms(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x, double omega_dot,
                      DofMatrix<double, any_balls>& mass, Coordinates<double, any_balls>& force) {
  const Paths paths = paths_at(p, race, x, false);
  mass = mass_of(p, paths, false);
  force = forces_of(p, paths, x, omega_dot, false);
}

}  // namespace abu
