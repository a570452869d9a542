// Equilibria of a flexible shaft whose balls roll on an unround race (shaft_race_equilibria.hpp,
// model.md §18.18).
#include "abu/equilibria/shaft_race_equilibria.hpp"

#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>

namespace abu {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The natural size of each static row (as (18.8.4)): shaft rows (|K_r| |u|)_i + omega^2 (U + sum
// m_i l_i) (times the shaft's length on tilt rows), ball rows m_i l_i omega^2 (|q| + l_i).
double static_residual(const ShaftSystem& sys, const RaceShape& race, const Eigen::VectorXd& s) {
  const int ns = sys.shaft_dofs(), b = sys.balancer_dof();
  const ParamsN& p = sys.balancer;
  const Eigen::VectorXd res = shaft_race_static_forces(sys, race, s);
  const double w2 = p.omega * p.omega;
  double cap = p.rotor.unbalance, length = 0.0;
  for (const auto& ball : p.balls) cap += ball.mass * ball.race_radius, length = std::max(length, double(ball.race_radius));
  for (const ShaftElement& e : sys.spec.elements) length += e.length;
  const Eigen::VectorXd ku = rotating_matrices(sys).stiffness.cwiseAbs() * s.head(ns).cwiseAbs();
  const double q = std::hypot(s(b), s(b + 1));
  double worst = 0.0;
  for (int i = 0; i < ns; ++i) {
    const double scale = ku(i) + w2 * cap * ((i % 4) < 2 ? 1.0 : length);
    if (scale > 0.0) worst = std::max(worst, std::abs(res(i)) / scale);
  }
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const double scale = ball.mass * ball.race_radius * w2 * (q + ball.race_radius);
    if (scale > 0.0) worst = std::max(worst, std::abs(res(ns + i)) / scale);
  }
  return worst;
}

// The shaft state of one equilibrium of the equivalent balancer: u under the balls' static load,
// then Newton on b(s, 0) = 0 with the static Jacobian -K of (18.18.2), kept while it lowers the
// residual.
ShaftEquilibrium shaft_state_of(const ShaftSystem& sys, const RaceShape& race, const UnroundRoot& root, int member,
                                Eigen::SparseLU<Sparse>& kr) {
  const int ns = sys.shaft_dofs(), size = sys.configuration_size();
  ShaftEquilibrium e;
  e.family = Family::aligned;  // not read: on_unround_race names it
  e.on_unround_race = true;
  e.member = member;
  e.position = Eigen::VectorXd::Zero(size);
  for (int i = 0; i < sys.n_balls(); ++i) e.position(ns + i) = double(root.position(2 + i));
  // The balls' pull at rest does not depend on u: b(0 + beta) minus its shaft part is the load.
  const Eigen::VectorXd load = shaft_race_static_forces(sys, race, e.position).head(ns);
  e.position.head(ns) = kr.solve(load);
  e.residual = static_residual(sys, race, e.position);
  int it = 0;
  for (; it < 20 && e.residual > 1e-15; ++it) {
    Eigen::SparseLU<Sparse> jlu(linearize_shaft_on_race(sys, race, e.position).stiffness);
    if (jlu.info() != Eigen::Success) break;
    const Eigen::VectorXd step = jlu.solve(shaft_race_static_forces(sys, race, e.position));
    if (!step.allFinite()) break;
    const Eigen::VectorXd trial = e.position + step;  // K ds = b: -db/ds ds = b
    const double r = static_residual(sys, race, trial);
    if (!(r < e.residual)) break;
    e.position = trial, e.residual = r;
  }
  e.newton_iterations = it;
  for (int i = 0; i < sys.n_balls(); ++i) e.position(ns + i) = double(wrap_angle(e.position(ns + i)));
  e.residual = static_residual(sys, race, e.position);
  e.status = e.residual <= 1e-10 ? Status{}
                                 : Status{Outcome::not_converged, "Newton on the shaft's static equations stalled above 1e-10"};
  return e;
}

}  // namespace

ShaftRaceEquilibria find_shaft_race_equilibria(const ShaftSystem& sys, const RaceShape& race,
                                               const UnroundSearch& search) {
  ShaftRaceEquilibria out;
  out.dynamic_stiffness = balancer_dynamic_stiffness(sys);
  if (!out.dynamic_stiffness) {
    out.status = {Outcome::numerical_issue,
                  "the rotating-frame shaft stiffness is singular at this speed (an undamped critical speed): the "
                  "balls' load has no static response, no equilibrium computed"};
    return out;
  }
  const UnroundRoots roots = find_unround_roots(equivalent_rigid_params(sys, *out.dynamic_stiffness), race, search);
  out.search = roots.search;
  out.doubt = roots.doubt;
  Eigen::SparseLU<Sparse> kr(rotating_matrices(sys).stiffness);
  for (std::size_t k = 0; k < roots.list.size(); ++k) {
    out.list.push_back(shaft_state_of(sys, race, roots.list[k], int(k) + 1, kr));
    out.status.merge(out.list.back().status);
  }
  return out;
}

}  // namespace abu
