// model.md §11.3 / §15.6: the unround race's field for integration, its analytic Jacobian
// and its omega derivative (see unround_field.hpp).
#include "abu/model/unround_field.hpp"

#include <Eigen/Cholesky>
#include <array>
#include <cmath>

#include "abu/model/friction.hpp"

namespace abu {

double path_third_derivative(const RaceHarmonics& h, double l, double beta) {
  // l = E H (11.1.1): l''' = E''' H + 3 E'' H' + 3 E' H'' + E H'''. The offset circle
  // (x = beta - phi_1, S = sqrt(l^2 - d^2 sin^2 x), S' = -d^2 sin 2x / (2 S)), differentiating
  // E'' of (11.1.3) once more:
  //   E''' = d sin x + 2 d^2 sin 2x / S - 3 d^4 sin 4x / (4 S^3) - 3 d^6 sin^3 2x / (8 S^5)   (15.6.3)
  double e0 = l, e1 = 0, e2 = 0, e3 = 0;
  double h0 = 1, h1 = 0, h2 = 0, h3 = 0;
  for (const auto& harmonic : h) {
    if (harmonic.amplitude == 0.0) continue;
    if (harmonic.order == 1) {
      const double d = l * harmonic.amplitude, x = beta - harmonic.phase;
      const double sx = std::sin(x), cx = std::cos(x), s2 = std::sin(2 * x), c2 = std::cos(2 * x);
      const double S = std::sqrt(l * l - d * d * sx * sx), d2 = d * d, d4 = d2 * d2;
      e0 = d * cx + S;
      e1 = -d * sx - d2 * sx * cx / S;
      e2 = -d * cx - d2 * c2 / S - d4 * sx * sx * cx * cx / (S * S * S);
      e3 = d * sx + 2 * d2 * s2 / S - 0.75 * d4 * std::sin(4 * x) / (S * S * S) -
           0.375 * d4 * d2 * s2 * s2 * s2 / (S * S * S * S * S);
    } else {
      const double k = harmonic.order, arg = k * beta - harmonic.phase, eps = harmonic.amplitude;
      const double c = std::cos(arg), s = std::sin(arg);
      h0 += eps * c;
      h1 -= eps * k * s;
      h2 -= eps * k * k * c;
      h3 += eps * k * k * k * s;
    }
  }
  return e3 * h0 + 3 * e2 * h1 + 3 * e1 * h2 + e0 * h3;
}

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

// A(beta) of (11.3.3).
DofM mass_of(const ParamsN& p, const Paths& paths) {
  const int n = p.n_balls();
  DofM A = DofM::Zero(n + 2, n + 2);
  A(0, 0) = A(1, 1) = p.total_mass();
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const auto& g = paths[std::size_t(i)];
    A(0, 2 + i) = A(2 + i, 0) = b.mass * g.u;
    A(1, 2 + i) = A(2 + i, 1) = b.mass * g.v;
    A(2 + i, 2 + i) = b.inertia_factor * b.mass * g.sp * g.sp;
  }
  return A;
}

// b(s, s') of (11.3.4) plus the run-up's Euler terms (15.6.1).
Dof forces_of(const ParamsN& p, const Paths& paths, const State<double, any_balls>& x, double wd) {
  const int n = p.n_balls();
  const double w = p.omega, w2 = w * w, M = p.total_mass();
  const double q1 = x(0), q2 = x(1), dq1 = x(n + 2), dq2 = x(n + 3);
  const auto& r = p.rotor;
  Dof b(n + 2);
  b(0) = w2 * r.unbalance + M * (2 * w * dq2 + w2 * q1) - r.damping * (dq1 - w * q2) - r.stiffness * q1 + M * wd * q2;
  b(1) = M * (-2 * w * dq1 + w2 * q2) - r.damping * (dq2 + w * q1) - r.stiffness * q2 - wd * r.unbalance - M * wd * q1;
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

}  // namespace

State<double, any_balls> unround_vector_field(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x,
                                              double omega_dot) {
  const int n = p.n_balls(), d = n + 2;
  const Paths paths = paths_at(p, race, x, false);
  const Dof acc = mass_of(p, paths).llt().solve(forces_of(p, paths, x, omega_dot));
  State<double, any_balls> f(2 * d);
  f.head(d) = x.tail(d);
  f.tail(d) = acc;
  return f;
}

StateMatrix<double, any_balls> unround_jacobian(const ParamsN& p, const RaceShape& race,
                                                const State<double, any_balls>& x, double wd) {
  const int n = p.n_balls(), d = n + 2;
  const Paths paths = paths_at(p, race, x, true);
  const auto llt = mass_of(p, paths).llt();
  const Dof acc = llt.solve(forces_of(p, paths, x, wd));  // s''
  const double w = p.omega, w2 = w * w, M = p.total_mass();
  const auto& r = p.rotor;
  const double q1 = x(0), q2 = x(1), dq1 = x(n + 2), dq2 = x(n + 3);
  // Bs = db/ds - (dA/ds) s'' and Bv = db/ds' (model.md (15.6.2), (15.6.4)).
  DofM Bs = DofM::Zero(d, d), Bv = DofM::Zero(d, d);
  Bs(0, 0) = M * w2 - r.stiffness, Bs(0, 1) = r.damping * w + M * wd;
  Bs(1, 0) = -r.damping * w - M * wd, Bs(1, 1) = M * w2 - r.stiffness;
  Bv(0, 0) = -r.damping, Bv(0, 1) = 2 * M * w;
  Bv(1, 0) = -2 * M * w, Bv(1, 1) = -r.damping;
  for (int i = 0; i < n; ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const auto& g = paths[std::size_t(i)];
    const double m = ball.mass, j = ball.inertia_factor, db = x(n + 4 + i), l = ball.race_radius;
    const double nu = g.sp * db / l, F = friction_force(p, i, nu), Fv = friction_slope(p, i, nu);
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
  }
  StateMatrix<double, any_balls> J = StateMatrix<double, any_balls>::Zero(2 * d, 2 * d);
  J.topRightCorner(d, d).setIdentity();
  J.bottomLeftCorner(d, d) = llt.solve(Bs);
  J.bottomRightCorner(d, d) = llt.solve(Bv);
  return J;
}

State<double, any_balls> unround_omega_derivative(const ParamsN& p, const RaceShape& race,
                                                  const State<double, any_balls>& x) {
  const int n = p.n_balls(), d = n + 2;
  const Paths paths = paths_at(p, race, x, false);
  const double w = p.omega, M = p.total_mass();
  const auto& r = p.rotor;
  const double q1 = x(0), q2 = x(1), dq1 = x(n + 2), dq2 = x(n + 3);
  // db/domega of (11.3.4) at fixed x (15.6.5); the Euler terms do not depend on omega.
  Dof b(d);
  b(0) = 2 * w * r.unbalance + M * (2 * dq2 + 2 * w * q1) + r.damping * q2;
  b(1) = M * (-2 * dq1 + 2 * w * q2) - r.damping * q1;
  for (int i = 0; i < n; ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const auto& g = paths[std::size_t(i)];
    const double m = ball.mass, db = x(n + 4 + i), cb = std::cos(x(2 + i)), sb = std::sin(x(2 + i));
    b(0) += m * (2 * w * g.ell * cb + 2 * g.v * db);
    b(1) += m * (2 * w * g.ell * sb - 2 * g.u * db);
    const double dF = friction_partial(p, i, g.sp * db / ball.race_radius, Quantity::omega);
    b(2 + i) = g.sp * dF + 2 * m * w * g.ell * g.d1 - m * (g.u * (-2 * dq2 - 2 * w * q1) + g.v * (2 * dq1 - 2 * w * q2));
  }
  State<double, any_balls> f = State<double, any_balls>::Zero(2 * d);
  f.tail(d) = mass_of(p, paths).llt().solve(b);
  return f;
}

}  // namespace abu
