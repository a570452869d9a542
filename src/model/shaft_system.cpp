// The flexible rotor with its balls in the rotating frame (model.md §18.5–§18.7).
#include "abu/model/shaft_system.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>

#include "abu/core/errors.hpp"
#include "abu/model/friction.hpp"

namespace abu {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

/// Jr: +90° rotation of every (u1, u2) and (psi1, psi2) pair, Jr (a, b) = (-b, a) (18.5.1).
Sparse quarter_turn(int dofs) {
  Triplets t;
  t.reserve(std::size_t(dofs));
  for (int k = 0; k < dofs; k += 2) {
    t.emplace_back(k, k + 1, -1.0);
    t.emplace_back(k + 1, k, 1.0);
  }
  Sparse j(dofs, dofs);
  j.setFromTriplets(t.begin(), t.end());
  return j;
}

double ball_mass_sum(const ParamsN& p) {
  double m = 0.0;
  for (const auto& b : p.balls) m += b.mass;
  return m;
}

void append(Triplets& t, const Sparse& m, int row0, int col0, double factor) {
  for (int k = 0; k < m.outerSize(); ++k)
    for (Sparse::InnerIterator it(m, k); it; ++it) t.emplace_back(row0 + int(it.row()), col0 + int(it.col()), factor * it.value());
}

Sparse from_triplets(int rows, int cols, const Triplets& t) {
  Sparse m(rows, cols);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

}  // namespace

ShaftSystem make_shaft_system(const ShaftSpec& spec, const ParamsN& balancer) {
  if (auto why = shaft_spec_violation(spec)) throw std::invalid_argument(*why);
  if (balancer.n_balls() < 1) throw std::invalid_argument("the balancer needs at least one ball");
  for (int i = 0; i < balancer.n_balls(); ++i) {
    const auto& b = balancer.balls[std::size_t(i)];
    if (!(b.mass > 0.0) || !(b.race_radius > 0.0) || !(b.inertia_factor >= 1.0))
      throw std::invalid_argument("ball " + std::to_string(i + 1) + ": mass and race radius must be > 0, j >= 1");
  }
  if (balancer.law == FrictionLaw::lugre || balancer.law == FrictionLaw::coulomb_set)
    throw std::invalid_argument("the flexible rotor takes the smooth friction laws (none, viscous, coulomb, stribeck)");
  return ShaftSystem{spec, balancer, assemble_shaft(spec)};
}

ShaftRotatingMatrices rotating_matrices(const ShaftSystem& sys) {
  const int n = sys.shaft_dofs(), b = sys.balancer_dof();
  const double w = sys.balancer.omega;
  Sparse mass = sys.fixed.mass;
  {
    // The balls' translating mass at the balancer node: M = M_r + sum m_i of (1.1).
    // (Built in one initializer: GCC 12's -Wnull-dereference flags emplace_back into an
    // empty vector here, a false positive.)
    const double m = ball_mass_sum(sys.balancer);
    const Triplets t{{b, b, m}, {b + 1, b + 1, m}};
    mass += from_triplets(n, n, t);
  }
  const Sparse jr = quarter_turn(n);
  const Sparse mj = mass * jr, cj = sys.fixed.damping * jr, gj = sys.fixed.gyroscopic * jr;
  ShaftRotatingMatrices out;
  out.damping = sys.fixed.damping + w * sys.fixed.gyroscopic + 2.0 * w * mj;
  out.stiffness = sys.fixed.stiffness - (w * w) * mass + w * cj + (w * w) * gj;
  out.mass = std::move(mass);
  for (Sparse* m : {&out.mass, &out.damping, &out.stiffness}) {
    m->prune(0.0);
    m->makeCompressed();
  }
  return out;
}

namespace {

Sparse mass_matrix(const ShaftSystem& sys, const Sparse& shaft_mass, const Eigen::VectorXd& s) {
  const int ns = sys.shaft_dofs(), size = sys.configuration_size(), b = sys.balancer_dof();
  Triplets t;
  t.reserve(std::size_t(shaft_mass.nonZeros() + 5 * sys.n_balls()));
  append(t, shaft_mass, 0, 0, 1.0);
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = sys.balancer.balls[std::size_t(i)];
    const double a = ball.mass * ball.race_radius, beta = s(ns + i);
    const int col = ns + i;
    // (3.8): rotor rows -a sin beta, a cos beta; ball diagonal j m l^2.
    t.emplace_back(b, col, -a * std::sin(beta));
    t.emplace_back(col, b, -a * std::sin(beta));
    t.emplace_back(b + 1, col, a * std::cos(beta));
    t.emplace_back(col, b + 1, a * std::cos(beta));
    t.emplace_back(col, col, ball.inertia_factor * ball.mass * ball.race_radius * ball.race_radius);
  }
  return from_triplets(size, size, t);
}

Eigen::VectorXd forces(const ShaftSystem& sys, const ShaftRotatingMatrices& r, const Eigen::VectorXd& x) {
  const int ns = sys.shaft_dofs(), size = sys.configuration_size(), b = sys.balancer_dof();
  const ParamsN& p = sys.balancer;
  const double w = p.omega, w2 = w * w;
  const auto u = x.head(ns), ud = x.segment(size, ns);
  Eigen::VectorXd out(size);
  // Shaft rows (18.5.3): -(K_r u + D_r u') + the unbalance and the balls' centrifugal pull.
  out.head(ns) = -(r.stiffness * u) - (r.damping * ud);
  out(b) += w2 * p.rotor.unbalance;
  const double q1 = x(b), q2 = x(b + 1), qd1 = x(size + b), qd2 = x(size + b + 1);
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const double a = ball.mass * ball.race_radius, beta = x(ns + i), bd = x(size + ns + i);
    const double sb = std::sin(beta), cb = std::cos(beta), spin = (bd + w) * (bd + w);
    out(b) += a * spin * cb;
    out(b + 1) += a * spin * sb;
    // Ball row (3.9) with q the balancer node's translation.
    out(ns + i) = ball.race_radius * friction_force(p, i, bd) + a * ((-2.0 * w * qd2 - w2 * q1) * sb -
                                                                     (2.0 * w * qd1 - w2 * q2) * cb);
  }
  return out;
}

Eigen::VectorXd accelerations(const Sparse& a, const Eigen::VectorXd& rhs) {
  Eigen::SimplicialLDLT<Sparse> ldlt(a);
  if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any())
    throw NumericalError("shaft_field: the mass matrix A(beta) is not positive definite (model.md §18.9)");
  return ldlt.solve(rhs);
}

}  // namespace

Eigen::SparseMatrix<double> shaft_mass_matrix(const ShaftSystem& sys, const Eigen::VectorXd& s) {
  return mass_matrix(sys, rotating_matrices(sys).mass, s);
}

Eigen::VectorXd shaft_generalized_forces(const ShaftSystem& sys, const Eigen::VectorXd& x) {
  return forces(sys, rotating_matrices(sys), x);
}

Eigen::VectorXd shaft_field(const ShaftSystem& sys, const Eigen::VectorXd& x) {
  const int size = sys.configuration_size();
  const ShaftRotatingMatrices r = rotating_matrices(sys);
  Eigen::VectorXd f(2 * size);
  f.head(size) = x.tail(size);
  f.tail(size) = accelerations(mass_matrix(sys, r.mass, x.head(size)), forces(sys, r, x));
  return f;
}

ShaftLinearization linearize_shaft(const ShaftSystem& sys, const Eigen::VectorXd& x) {
  const int ns = sys.shaft_dofs(), size = sys.configuration_size(), b = sys.balancer_dof();
  const ParamsN& p = sys.balancer;
  const double w = p.omega, w2 = w * w;
  const ShaftRotatingMatrices r = rotating_matrices(sys);
  ShaftLinearization lin;
  lin.mass = mass_matrix(sys, r.mass, x.head(size));
  const Eigen::VectorXd sdd = accelerations(lin.mass, forces(sys, r, x));
  Triplets c, k;
  c.reserve(std::size_t(r.damping.nonZeros() + 8 * sys.n_balls()));
  k.reserve(std::size_t(r.stiffness.nonZeros() + 8 * sys.n_balls()));
  append(c, r.damping, 0, 0, 1.0);
  append(k, r.stiffness, 0, 0, 1.0);
  const double q1 = x(b), q2 = x(b + 1), qd1 = x(size + b), qd2 = x(size + b + 1);
  const double qdd1 = sdd(b), qdd2 = sdd(b + 1);
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const double a = ball.mass * ball.race_radius, beta = x(ns + i), bd = x(size + ns + i), bdd = sdd(ns + i);
    const double sb = std::sin(beta), cb = std::cos(beta), spin = (bd + w) * (bd + w);
    const int col = ns + i;
    // C = -db/ds' (18.7.1); at rest this is (6.4).
    c.emplace_back(b, col, -2.0 * a * (bd + w) * cb);
    c.emplace_back(b + 1, col, -2.0 * a * (bd + w) * sb);
    c.emplace_back(col, b, 2.0 * w * a * cb);
    c.emplace_back(col, b + 1, 2.0 * w * a * sb);
    c.emplace_back(col, col, -ball.race_radius * friction_slope(p, i, bd));
    // K = -db/ds + (dA/ds) s'' (18.7.2); at rest and s'' = 0 this is (6.3); the last
    // terms are (6.6).
    k.emplace_back(b, col, a * spin * sb - a * cb * bdd);
    k.emplace_back(b + 1, col, -a * spin * cb - a * sb * bdd);
    k.emplace_back(col, b, w2 * a * sb);
    k.emplace_back(col, b + 1, -w2 * a * cb);
    k.emplace_back(col, col,
                   -a * ((-2.0 * w * qd2 - w2 * q1) * cb + (2.0 * w * qd1 - w2 * q2) * sb) -
                       a * (cb * qdd1 + sb * qdd2));
  }
  lin.damping = from_triplets(size, size, c);
  lin.stiffness = from_triplets(size, size, k);
  return lin;
}

ShaftPencil shaft_pencil(const ShaftLinearization& lin) {
  const int n = int(lin.mass.rows());
  Triplets ta, tb;
  ta.reserve(std::size_t(n + lin.stiffness.nonZeros() + lin.damping.nonZeros()));
  tb.reserve(std::size_t(n + lin.mass.nonZeros()));
  for (int i = 0; i < n; ++i) {
    ta.emplace_back(i, n + i, 1.0);
    tb.emplace_back(i, i, 1.0);
  }
  append(ta, lin.stiffness, n, 0, -1.0);
  append(ta, lin.damping, n, n, -1.0);
  append(tb, lin.mass, n, n, 1.0);
  return {from_triplets(2 * n, 2 * n, ta), from_triplets(2 * n, 2 * n, tb)};
}

Eigen::SparseMatrix<double> shaft_jacobian(const ShaftSystem& sys, const Eigen::VectorXd& x) {
  const ShaftLinearization lin = linearize_shaft(sys, x);
  const int n = int(lin.mass.rows());
  Eigen::SimplicialLDLT<Sparse> ldlt(lin.mass);
  if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any())
    throw NumericalError("shaft_jacobian: the mass matrix A(beta) is not positive definite (model.md §18.9)");
  const Eigen::MatrixXd ak = ldlt.solve(Eigen::MatrixXd(lin.stiffness));
  const Eigen::MatrixXd ac = ldlt.solve(Eigen::MatrixXd(lin.damping));
  Triplets t;
  for (int i = 0; i < n; ++i) t.emplace_back(i, n + i, 1.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (ak(i, j) != 0.0) t.emplace_back(n + i, j, -ak(i, j));
      if (ac(i, j) != 0.0) t.emplace_back(n + i, n + j, -ac(i, j));
    }
  return from_triplets(2 * n, 2 * n, t);
}

}  // namespace abu
