// A flexible shaft whose balls roll on an unround race (shaft_race.hpp, model.md §18.18).
#include "abu/model/shaft_race.hpp"

#include <vector>

#include "abu/model/machine_field.hpp"

namespace abu {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The rigid layout (q1, q2, beta, 0...) of the balls at rest on the balancer node's translation.
State<double, any_balls> rigid_rest_state(const ShaftSystem& sys, const Eigen::VectorXd& s) {
  const int n = sys.n_balls(), ns = sys.shaft_dofs(), b = sys.balancer_dof();
  State<double, any_balls> x = State<double, any_balls>::Zero(2 * (n + 2));
  x(0) = s(b), x(1) = s(b + 1);
  for (int i = 0; i < n; ++i) x(2 + i) = s(ns + i);
  return x;
}

// Rigid index (0, 1: q; 2 + i: beta_i) -> the shaft's configuration index.
int scatter_index(const ShaftSystem& sys, int k) { return k < 2 ? sys.balancer_dof() + k : sys.shaft_dofs() + k - 2; }

// m + factor * (the d x d block `share` scattered onto the balancer node and the balls).
Sparse plus_scattered(const ShaftSystem& sys, const Sparse& m, const DofMatrix<double, any_balls>& share, double factor) {
  const int size = sys.configuration_size(), d = sys.n_balls() + 2;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(m.nonZeros() + d * d));
  for (int k = 0; k < m.outerSize(); ++k)
    for (Sparse::InnerIterator it(m, k); it; ++it) t.emplace_back(int(it.row()), int(it.col()), it.value());
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c)
      if (share(r, c) != 0.0) t.emplace_back(scatter_index(sys, r), scatter_index(sys, c), factor * share(r, c));
  Sparse out(size, size);
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}

// The shaft's rotating-frame matrices (18.5) padded to the configuration size (the ball rows 0).
Sparse padded(const ShaftSystem& sys, const Sparse& shaft) {
  Sparse out(sys.configuration_size(), sys.configuration_size());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(shaft.nonZeros()));
  for (int k = 0; k < shaft.outerSize(); ++k)
    for (Sparse::InnerIterator it(shaft, k); it; ++it) t.emplace_back(int(it.row()), int(it.col()), it.value());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace

Eigen::VectorXd shaft_race_static_forces(const ShaftSystem& sys, const RaceShape& race, const Eigen::VectorXd& s) {
  const int ns = sys.shaft_dofs(), d = sys.n_balls() + 2;
  const ShaftRotatingMatrices r = rotating_matrices(sys);
  const BallShare share = ball_share(sys.balancer, race, rigid_rest_state(sys, s), Coordinates<double, any_balls>::Zero(d));
  Eigen::VectorXd out = Eigen::VectorXd::Zero(sys.configuration_size());
  out.head(ns) = -(r.stiffness * s.head(ns));  // (18.5.3) at rest; K_r holds the balls' translating mass
  out(sys.balancer_dof()) += sys.balancer.omega * sys.balancer.omega * sys.balancer.rotor.unbalance;
  for (int k = 0; k < d; ++k) out(scatter_index(sys, k)) += share.force(k);
  return out;
}

ShaftLinearization linearize_shaft_on_race(const ShaftSystem& sys, const RaceShape& race, const Eigen::VectorXd& s) {
  const int d = sys.n_balls() + 2;
  const ShaftRotatingMatrices r = rotating_matrices(sys);
  const BallShare share = ball_share(sys.balancer, race, rigid_rest_state(sys, s), Coordinates<double, any_balls>::Zero(d));
  ShaftLinearization lin;
  // (18.18.2): A = the shaft's M_tot + the balls' couplings; C = -db/ds', K = -db/ds (s'' = 0).
  lin.mass = plus_scattered(sys, padded(sys, r.mass), share.mass, 1.0);
  lin.damping = plus_scattered(sys, padded(sys, r.damping), share.force_velocity, -1.0);
  lin.stiffness = plus_scattered(sys, padded(sys, r.stiffness), share.force_position, -1.0);
  return lin;
}

}  // namespace abu
