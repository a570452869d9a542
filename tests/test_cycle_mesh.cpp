// The cycle shooting's linear algebra and mesh (docs/model.md §17.2, §17.9), internal to
// src/dynamics: the block-cyclic bordered LU against Eigen's dense LU of the same matrix, and
// the mesh that spreads the transition matrices' growth over the intervals.
#include <catch2/catch.hpp>

#include <Eigen/LU>
#include <cmath>
#include <random>
#include <vector>

#include "../src/dynamics/cycle_mesh.hpp"
#include "../src/dynamics/cycle_period_shift.hpp"
#include "../src/dynamics/cyclic_jacobian.hpp"

namespace {

// The dense (8M + 2)^2 matrix [J; d^T] of a block-cyclic Jacobian.
Eigen::MatrixXd dense(const abu::detail::CyclicJacobian<8>& J, const Eigen::VectorXd& d) {
  const int m = J.blocks(), n = 8 * m + 2;
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < m; ++j) {
    D.block(8 * j, 8 * j, 8, 8) += J.diag[std::size_t(j)];
    D.block(8 * j, 8 * ((j + 1) % m), 8, 8) += Eigen::MatrixXd(J.next[std::size_t(j)].asDiagonal());
    D.block(8 * j, 8 * m, 8, 2) = J.border[std::size_t(j)];
  }
  D.block(8 * m, 0, 1, 8) = J.phase.transpose();
  D.row(8 * m + 1) = d.transpose();
  return D;
}

}  // namespace

TEST_CASE("cycle shooting: the block-cyclic bordered LU solves as the dense LU does", "[periodic_orbits]") {
  // Random blocks of a growing orbit (|diag| ~ 3 .. 3e3: transition matrices growing e^8 per
  // interval), the weighted successor diagonals -1/w, a dense border row. Both solves are
  // backward stable, the matrix's condition is ~1e4: the solutions agree to 1e-10 relative
  // and the structured one's residual is at rounding (1e-13 of |b|).
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  for (int m : {1, 2, 3, 7, 40}) {
    abu::detail::CyclicJacobian<8> J;
    J.resize(m);
    const double scale = m > 3 ? 3e3 : 3.0;
    for (int j = 0; j < m; ++j) {
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) J.diag[std::size_t(j)](a, b) = scale * g(rng) / (1 + a + b);
      J.next[std::size_t(j)].setConstant(-1.0 / std::sqrt((1.0 + 0.5 * ((j + 1) % m)) / m));
      for (int a = 0; a < 8; ++a) J.border[std::size_t(j)](a, 0) = g(rng), J.border[std::size_t(j)](a, 1) = g(rng);
    }
    for (int a = 0; a < 8; ++a) J.phase(a) = g(rng);
    const int n = 8 * m + 2;
    Eigen::VectorXd d(n), b(n);
    for (int i = 0; i < n; ++i) d(i) = g(rng), b(i) = g(rng);
    const Eigen::MatrixXd D = dense(J, d);
    const Eigen::VectorXd want = D.partialPivLu().solve(b);
    const Eigen::VectorXd got = abu::detail::CyclicBorderedLu<8>(J, d).solve(b);
    INFO("M = " << m);
    CHECK((got - want).norm() <= 1e-10 * want.norm());
    CHECK((D * got - b).norm() <= 1e-13 * D.norm() * got.norm());
  }
}

TEST_CASE("cycle shooting: a singular panel gives a non-finite solve, not a wrong one", "[periodic_orbits]") {
  abu::detail::CyclicJacobian<8> J;
  J.resize(3);  // every block zero: the panels have no pivot
  const Eigen::VectorXd d = Eigen::VectorXd::Ones(26), b = Eigen::VectorXd::Ones(26);
  CHECK_FALSE(abu::detail::CyclicBorderedLu<8>(J, d).solve(b).allFinite());
}

TEST_CASE("cycle shooting: the mesh spreads the growth evenly, with hysteresis", "[periodic_orbits]") {
  using abu::detail::CycleMesh;
  const CycleMesh uniform = CycleMesh::uniform(5, true);
  CHECK(uniform.intervals() == 5);
  CHECK(uniform.weight(2) == Approx(std::sqrt(0.2)).epsilon(1e-15));
  // Growth 1 per interval, largest multiplier e^5, a target of 3: ceil((5 + 3) / 3) = 3
  // intervals; content 1 + 3/5 in each old one, so equal thirds.
  std::vector<double> theta = abu::detail::equidistributed_nodes(uniform, {1, 1, 1, 1, 1}, 5.0, 3.0, 2, 100);
  REQUIRE(theta.size() == 3);
  CHECK(theta[1] == Approx(1.0 / 3).epsilon(1e-12));
  CHECK(theta[2] == Approx(2.0 / 3).epsilon(1e-12));
  // The same with at least 5 intervals and an even growth: the mesh stays (nothing returned).
  CHECK(abu::detail::equidistributed_nodes(uniform, {1, 1, 1, 1, 1}, 5.0, 3.0, 5, 100).empty());
  // The number comes from the product's growth, not from the sum of the intervals' norms
  // (which counts each interval's non-normal transient): growth 2 in each of 5 intervals but a
  // largest multiplier e^1 -> ceil(4 / 3) = 2 intervals, halves.
  theta = abu::detail::equidistributed_nodes(uniform, {2, 2, 2, 2, 2}, 1.0, 3.0, 2, 100);
  REQUIRE(theta.size() == 2);
  CHECK(theta[1] == Approx(0.5).epsilon(1e-12));
  // Growth 20 in the third interval alone, largest multiplier e^20: ceil(23 / 3) = 8
  // intervals; content 20.6 there, 0.6 elsewhere, 23 in all, 2.875 each; every new node falls in the third (theta 0.4 .. 0.6, cumulative
  // content 1.2 .. 21.8), at 0.4 + 0.2 (2.875 i - 1.2) / 20.6, i = 1..7; the last interval
  // holds the rest of it and the two after.
  theta = abu::detail::equidistributed_nodes(uniform, {0, 0, 20, 0, 0}, 20.0, 3.0, 2, 100);
  REQUIRE(theta.size() == 8);
  CHECK(theta[0] == 0.0);
  CHECK(theta[1] == Approx(0.4 + 0.2 * (2.875 - 1.2) / 20.6).epsilon(1e-12));
  CHECK(theta[7] == Approx(0.4 + 0.2 * (2.875 * 7 - 1.2) / 20.6).epsilon(1e-12));
  for (std::size_t i = 1; i < theta.size(); ++i) CHECK(theta[i] > theta[i - 1]);
  // At most m_max intervals.
  CHECK(abu::detail::equidistributed_nodes(uniform, {0, 0, 20, 0, 0}, 20.0, 3.0, 2, 4).size() == 4);
}

TEST_CASE("cycle shooting: the Newton matrix carried to another period by the linearized flow", "[periodic_orbits]") {
  // A linear flow y' = A y + g s (A with a fast lightly damped pair like the rotor's, -8 +- 530i
  // 1/s, and slow entries; s the scaled parameter): Phi(h) = e^{A h}, the parameter column
  // z(h) = int_0^h e^{A t} g dt and f(phi(h)) = A phi(h) y0 + ... are known at any h. Blocks
  // integrated at h (here: the exact exponentials at h, weighted 1/w) carried by dh = 1e-3 s
  // must equal those at h + dh: for a linear flow the carried blocks are exact, so the
  // agreement is the exponentials' rounding (1e-12 relative, asserted 1e-10); the unshifted
  // blocks differ by ~|A| dh ~ 0.5 (the fast pair's rotation), which is what the shift removes.
  using abu::cycle_problem::Generator;
  constexpr int n = abu::cycle_flow::kDim;
  Generator a = Generator::Zero();
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = 0.3 * g(rng);
  a(0, 0) = a(1, 1) = -8.0;
  a(0, 1) = 530.0;
  a(1, 0) = -530.0;
  for (int i = 0; i < n; ++i) a(i, n) = g(rng);
  Eigen::Matrix<double, n, 1> y0;
  for (int i = 0; i < n; ++i) y0(i) = g(rng);
  const double w = 0.7, h = 0.12, dh = 1e-3;
  // The blocks at length x: Phi / w, the period column A phi + g s (s = 0: the field at the end
  // is A Phi y0, its scale factor 1 here), the parameter column z.
  const auto blocks = [&](double x) {
    abu::detail::CyclicJacobian<n> J;
    J.resize(1);
    const Generator e = Generator(a * x).exp();
    J.diag[0] = e.topLeftCorner<n, n>() / w;
    J.border[0].col(0) = a.topLeftCorner<n, n>() * (e.topLeftCorner<n, n>() * y0);
    J.border[0].col(1) = e.topRightCorner<n, 1>();
    return J;
  };
  const abu::detail::CyclicJacobian<n> at_h = blocks(h), want = blocks(h + dh);
  const abu::detail::CyclicJacobian<n> got = abu::cycle_problem::shift_periods(at_h, {a}, {dh});
  CHECK((got.diag[0] - want.diag[0]).norm() <= 1e-10 * want.diag[0].norm());
  CHECK((got.border[0] - want.border[0]).norm() <= 1e-10 * want.border[0].norm());
  CHECK((at_h.diag[0] - want.diag[0]).norm() > 0.1 * want.diag[0].norm());
  // dh = 0 leaves the blocks as they are.
  const abu::detail::CyclicJacobian<n> same = abu::cycle_problem::shift_periods(at_h, {a}, {0.0});
  CHECK(same.diag[0] == at_h.diag[0]);
}
