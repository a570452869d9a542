// simulate on a flexible shaft (docs/model.md §18.16): the structured field against the model's
// own shaft_field, the Jacobian (run-up terms included) against differences of the field, the
// one-node shaft against the rigid simulate, and the end of settling runs against the shaft's
// equilibria. The fixed-frame reference is tests/reference/shaft_simulation_reference.py.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "../src/dynamics/shaft_field.hpp"  // internal to src/dynamics: the field alone
#include "abu/analysis/shaft_states.hpp"
#include "abu/core/errors.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/input/scene.hpp"

namespace {

using abu::ShaftSystem;

ShaftSystem system_of(const std::string& relative, double omega) {
  abu::Scene scene = abu::load_scene(std::string(ABU_SOURCE_DIR) + "/" + relative);
  scene.omega = omega;
  return abu::shaft_system_of(scene);
}

// The natural size of component i of the state: L for translations, 10 L for tilts, 3 rad for
// angles, and omega times those for the rates (the balls' 5 %).
double natural_size(const ShaftSystem& sys, int i) {
  const double L = abu::displacement_scale(abu::shaft_summary_params(sys)), w = sys.balancer.omega;
  const int d = sys.configuration_size(), ns = sys.shaft_dofs(), c = i % d;
  const double size = c >= ns ? 3.0 : (c % 4 < 2 ? L : 10.0 * L);
  return i < d ? size : (c >= ns ? 0.05 : 1.0) * w * size;
}

// A state of natural size: translations ~ L, tilts ~ L / 0.1 m, angles in [0, 2 pi), rates
// times omega; the balls' rates ~ 5 % of omega.
Eigen::VectorXd random_state(const ShaftSystem& sys, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double L = abu::displacement_scale(abu::shaft_summary_params(sys)), w = sys.balancer.omega;
  const int d = sys.configuration_size(), ns = sys.shaft_dofs();
  Eigen::VectorXd x(2 * d);
  for (int i = 0; i < d; ++i) {
    const double size = i >= ns ? 3.0 : (i % 4 < 2 ? L : 10.0 * L);
    x(i) = (i >= ns ? 3.0 + size * unit(rng) : size * unit(rng));
    x(d + i) = (i >= ns ? 0.05 : 1.0) * w * size * unit(rng);
  }
  return x;
}

// max over i of |a_i - b_i| / max_j |b_j| over the block of i (translations, tilts, balls) of
// the acceleration half.
double block_error(const ShaftSystem& sys, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const int d = sys.configuration_size(), ns = sys.shaft_dofs();
  const auto block = [&](int i) { return i >= ns ? 2 : (i % 4 < 2 ? 0 : 1); };
  double scale[3] = {0, 0, 0}, worst = 0;
  for (int i = 0; i < d; ++i) scale[block(i)] = std::max(scale[block(i)], std::abs(b(d + i)));
  for (int i = 0; i < d; ++i) worst = std::max(worst, std::abs(a(d + i) - b(d + i)) / scale[block(i)]);
  return worst;
}

}  // namespace

TEST_CASE("shaft simulation: the structured field is shaft_field", "[shaft_simulate]") {
  // Two routes to A^-1 b: the model's sparse LDL^T of A(beta), and M_tot^-1 with the balls'
  // Schur complement (18.16.3). A's condition number (tilt inertia 1e-7 against masses ~1 kg)
  // bounds their difference by ~cond(A) eps ~ 1e-9 of a block's largest entry; measured
  // <= 1e-12. The position half is the state's rates, copied: equal exactly.
  std::mt19937 rng(7);
  for (const char* scene : {"data/scenes/shaft.toml", "tests/scenes/shaft/sim_four_elements.toml"}) {
    CAPTURE(scene);
    const ShaftSystem sys = system_of(scene, 700.0);
    abu::shaft_detail::ShaftOde ode(sys);
    ode.set_speed(700.0, 0.0);
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::VectorXd x = random_state(sys, rng);
      Eigen::VectorXd f(x.size());
      REQUIRE(ode.field(x.data(), f.data()));
      const Eigen::VectorXd ref = abu::shaft_field(sys, x);
      CHECK(f.head(sys.configuration_size()) == ref.head(sys.configuration_size()));
      CHECK(block_error(sys, f, ref) <= 1e-9);
    }
  }
}

TEST_CASE("shaft simulation: the Jacobian is the derivative of the field, run-up terms included", "[shaft_simulate]") {
  // At omega' = 0 the Jacobian is the model's shaft_jacobian (checked against differences of
  // shaft_field in test_shaft.cpp): both solve A with K and C of linearize_shaft, by a dense and
  // a sparse Cholesky, equal to ~cond(A) eps: 1e-9 of a row block's largest entry.
  // The run-up share J(omega') - J(0) is the derivative of g = f(omega') - f(0), the omega'
  // terms of (18.16.2), linear in u and smooth in beta: central differences of g with steps
  // 1e-3 of each component's natural size have truncation ~1e-7 and rounding eps |f| / h,
  // measured ~1e-5 of the share's largest entry; 1e-4 of it still catches a missing term (the
  // smallest, on the ball rows, is 2.6e-3 of it here).
  std::mt19937 rng(11);
  for (const char* scene : {"tests/scenes/shaft/sim_four_elements.toml", "tests/scenes/shaft/one_node.toml"}) {
    CAPTURE(scene);
    const ShaftSystem sys = system_of(scene, 600.0);
    abu::shaft_detail::ShaftOde ode(sys);
    const Eigen::VectorXd x = random_state(sys, rng);
    const int dim = int(x.size()), d = sys.configuration_size();
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMajor still(dim, dim), running(dim, dim);
    Eigen::VectorXd dfdt(dim);
    ode.set_speed(600.0, 0.0);
    REQUIRE(ode.jacobian(x.data(), still.data(), dfdt.data()));
    CHECK(dfdt.isZero(0.0));
    const Eigen::MatrixXd ref = Eigen::MatrixXd(abu::shaft_jacobian(sys, x));
    double worst = 0;
    for (int i = d; i < dim; ++i) {
      const double scale = ref.row(i).cwiseAbs().maxCoeff();
      worst = std::max(worst, (still.row(i) - ref.row(i)).cwiseAbs().maxCoeff() / scale);
    }
    CHECK(worst <= 1e-9);
    CHECK(still.topRows(d) == ref.topRows(d));

    const double omega_dot = 2.0e4;
    ode.set_speed(600.0, omega_dot);
    REQUIRE(ode.jacobian(x.data(), running.data(), dfdt.data()));
    const RowMajor share = running - still;
    const auto g = [&](const Eigen::VectorXd& at) {
      Eigen::VectorXd f1(dim), f0(dim);
      ode.set_speed(600.0, omega_dot);
      REQUIRE(ode.field(at.data(), f1.data()));
      ode.set_speed(600.0, 0.0);
      REQUIRE(ode.field(at.data(), f0.data()));
      return Eigen::VectorXd(f1 - f0);
    };
    double worst_share = 0;
    for (int j = 0; j < dim; ++j) {
      const double h = 1e-3 * natural_size(sys, j);
      Eigen::VectorXd xp = x, xm = x;
      xp(j) += h;
      xm(j) -= h;
      worst_share = std::max(worst_share, (share.col(j) - (g(xp) - g(xm)) / (2 * h)).cwiseAbs().maxCoeff());
    }
    CHECK(worst_share <= 1e-4 * share.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("shaft simulation: a one-node shaft runs the rigid trajectory, its tilts at 0", "[shaft_simulate]") {
  // model.md §18.9: one disc on one bearing is the rigid rotor of §3 plus a decoupled tilt
  // pair. Both routes integrate the same q, beta with the same method and error control; each
  // keeps its global error within ~8 rtol of the scaled size (model.md §15.1, measured 0.4 to
  // 8), so they agree to 2 x 8 rtol: 20 rtol (L + |q|) on q, 20 rtol rad on beta.
  const ShaftSystem sys = system_of("tests/scenes/shaft/one_node.toml", 900.0);
  abu::ParamsN rigid = sys.balancer;
  rigid.rotor.mass = sys.spec.discs[0].mass;
  rigid.rotor.stiffness = sys.spec.bearings[0].stiffness;
  rigid.rotor.damping = sys.spec.bearings[0].damping;
  const double L = abu::displacement_scale(rigid), rtol = 1e-9;
  for (const auto& speed : {abu::SpeedProfile::constant(900.0), abu::SpeedProfile::ramp(300.0, 900.0, 3000.0)}) {
    CAPTURE(speed.describe());
    abu::SimulationOptions o;
    o.t_end = 0.3;
    o.every = 1e-3;
    o.rtol = rtol;
    o.method = abu::IntegrationMethod::bsimp;
    const abu::ShaftSimulationResult s = abu::simulate_shaft(sys, speed, abu::shaft_start_at_rest(sys, {2.0, 4.0}), o);
    const auto r = abu::simulate(rigid, speed, abu::start_at_rest(rigid, std::vector<double>{2.0, 4.0}), o);
    REQUIRE(s.run.status == abu::SimulationStatus::completed);
    REQUIRE(r.status == abu::SimulationStatus::completed);
    REQUIRE(s.run.samples.size() == r.samples.size());
    double worst_q = 0, worst_beta = 0;
    for (std::size_t k = 0; k < r.samples.size(); ++k) {
      REQUIRE(s.run.samples[k].t == r.samples[k].t);
      const auto &a = s.run.samples[k].x, &b = r.samples[k].x;
      const double size = L + std::hypot(b(0), b(1));
      worst_q = std::max({worst_q, std::abs(a(0) - b(0)) / size, std::abs(a(1) - b(1)) / size});
      worst_beta = std::max({worst_beta, std::abs(a(2) - b(2)), std::abs(a(3) - b(3))});
    }
    CHECK(worst_q <= 20 * rtol);
    CHECK(worst_beta <= 20 * rtol);
    CHECK(s.x_end(2) == 0.0);  // psi1, psi2 and their rates: nothing couples them to the rest
    CHECK(s.x_end(3) == 0.0);
    CHECK(s.x_end(sys.configuration_size() + 2) == 0.0);
    CHECK(s.x_end(sys.configuration_size() + 3) == 0.0);
  }
}

TEST_CASE("shaft simulation: settling runs end at the shaft's equilibria", "[shaft_simulate]") {
  // The four-element shaft with three balls: above its first critical speed (600 rad/s) the
  // balls balance (q -> 0 on the whole shaft, W(beta) -> 0); below it (150 rad/s) they gather
  // on the heavy side, the aligned state of find_shaft_equilibria (model.md §18.8). The run is
  // judged settled within the settle tolerance eps = 1e-3 of the scaled distance (§15.2), so
  // the end state lies within ~eps (|q| / L, rad) of the equilibrium it settles to; 2 eps here.
  const double eps = 1e-3;
  abu::SimulationOptions o;
  o.t_end = 3.0;
  o.every = 2e-3;
  o.method = abu::IntegrationMethod::rk8pd;
  {
    const ShaftSystem sys = system_of("tests/scenes/shaft/sim_four_elements.toml", 600.0);
    const auto r = abu::simulate_shaft(sys, abu::SpeedProfile::constant(600.0),
                                       abu::shaft_start_at_rest(sys, {0.5, 2.0, 4.0}), o);
    REQUIRE(r.run.status == abu::SimulationStatus::completed);
    CHECK(r.run.summary.outcome == abu::SimulationOutcome::balanced);
    const double L = r.run.displacement_scale;
    for (int k = 0; k < sys.nodes(); ++k) CHECK(std::hypot(r.x_end(4 * k), r.x_end(4 * k + 1)) <= 2 * eps * L);
    double w1 = sys.balancer.rotor.unbalance, w2 = 0, capacity = w1;
    for (int i = 0; i < sys.n_balls(); ++i) {
      const double a = sys.balancer.balls[std::size_t(i)].mass * sys.balancer.balls[std::size_t(i)].race_radius;
      w1 += a * std::cos(r.x_end(sys.ball_dof(i)));
      w2 += a * std::sin(r.x_end(sys.ball_dof(i)));
      capacity += a;
    }
    CHECK(std::hypot(w1, w2) <= 2 * eps * capacity);
  }
  {
    const ShaftSystem sys = system_of("tests/scenes/shaft/sim_four_elements.toml", 150.0);
    const auto r = abu::simulate_shaft(sys, abu::SpeedProfile::constant(150.0),
                                       abu::shaft_start_at_rest(sys, {0.5, 2.0, 4.0}), o);
    REQUIRE(r.run.status == abu::SimulationStatus::completed);
    REQUIRE(r.run.summary.outcome == abu::SimulationOutcome::aligned);
    const double L = r.run.displacement_scale;
    // The equilibrium nearest the end state in the scaled distance of §15.2 (configuration only).
    double best = 1e300;
    const abu::ShaftEquilibriumSet set = abu::find_shaft_equilibria(sys);
    for (const auto& e : set.list) {
      double dist = 0;
      for (int i = 0; i < sys.configuration_size(); ++i) {
        const double diff = r.x_end(i) - e.position(i);
        dist = std::max(dist, i >= sys.shaft_dofs() ? std::abs(std::remainder(diff, 2 * std::numbers::pi))
                                                    : std::abs(diff) / (i % 4 < 2 ? L : L / 0.2));
      }
      best = std::min(best, dist);
    }
    CHECK(best <= 2 * eps);
  }
}

TEST_CASE("shaft simulation: stop_at_sample ends the run at that sample, as the rigid route", "[shaft_simulate]") {
  // basin's settle test on a shaft (model.md §18.21): the callback sees each sample's balancer
  // view (2n + 4 values); returning true ends the run there. The stopped run must be the full
  // run up to that sample (the same steps: samples equal to rounding, 1e-12 of L), end at that
  // sample's time with x_end the whole state whose view is that sample, and say stopped_early.
  const ShaftSystem sys = system_of("tests/scenes/shaft/sim_four_elements.toml", 600.0);
  abu::SimulationOptions o;
  o.t_end = 0.5;
  o.every = 1e-3;
  o.method = abu::IntegrationMethod::rk8pd;
  const Eigen::VectorXd x0 = abu::shaft_start_at_rest(sys, {0.5, 2.0, 4.0});
  const auto full = abu::simulate_shaft(sys, abu::SpeedProfile::constant(600.0), x0, o);
  REQUIRE(full.run.status == abu::SimulationStatus::completed);
  int seen = 0;
  o.stop_at_sample = [&](double t, const double* x) {
    ++seen;
    CHECK(x[2] == full.run.samples[std::size_t(seen - 1)].x(2));  // the view: ball 1's angle
    return t >= 0.2371;
  };
  const auto stopped = abu::simulate_shaft(sys, abu::SpeedProfile::constant(600.0), x0, o);
  REQUIRE(stopped.run.status == abu::SimulationStatus::completed);
  CHECK(stopped.run.stopped_early);
  const auto& last = stopped.run.samples.back();
  CHECK(last.t == Approx(0.238).margin(1e-12));
  CHECK(stopped.run.t_reached == last.t);
  CHECK(int(stopped.run.samples.size()) == seen);
  const double L = stopped.run.displacement_scale;
  const auto& same = full.run.samples[stopped.run.samples.size() - 1];
  for (int i = 0; i < same.x.size(); ++i) CHECK(std::abs(last.x(i) - same.x(i)) <= 1e-12 * (i < 2 ? L : 1.0));
  const int b = 4 * sys.spec.balancer_node;
  CHECK(stopped.x_end(b) == last.x(0));
  CHECK(stopped.x_end(sys.ball_dof(0)) == last.x(2));
}

TEST_CASE("shaft simulation: bad input is refused naming the rule", "[shaft_simulate]") {
  const ShaftSystem sys = system_of("tests/scenes/shaft/sim_four_elements.toml", 600.0);
  abu::SimulationOptions o;
  CHECK_THROWS_AS(abu::shaft_start_at_rest(sys, {1.0, 2.0}), abu::InputError);
  CHECK_THROWS_WITH(abu::simulate_shaft(sys, abu::SpeedProfile::constant(600.0), Eigen::VectorXd::Zero(8), o),
                    Catch::Contains("2 (4 N_nodes + n) = 2 (4 x 5 + 3) = 46 values"));
  o.t_end = -1;
  CHECK_THROWS_WITH(abu::simulate_shaft(sys, abu::SpeedProfile::constant(600.0),
                                        abu::shaft_start_at_rest(sys, {1.0, 2.0, 3.0}), o),
                    Catch::Contains("end time must be > 0"));
  // Above shaft_simulation_max_states the dense Jacobians are refused with the size and memory.
  abu::ShaftSpec big = sys.spec;
  big.elements.assign(150, sys.spec.elements[0]);
  const ShaftSystem large = abu::make_shaft_system(big, sys.balancer);
  CHECK_THROWS_WITH(abu::simulate_shaft(large, abu::SpeedProfile::constant(600.0),
                                        abu::shaft_start_at_rest(large, {1.0, 2.0, 3.0}), abu::SimulationOptions{}),
                    Catch::Contains("= 1214 values; simulate takes at most 1000") && Catch::Contains("MB"));
}

TEST_CASE("shaft simulation: the one-node field is the rigid field of model.md §9", "[shaft_simulate]") {
  // The same equations (18.16.2) with one node: q, beta and their rates obey (9.1)-(9.4) at any
  // omega'. Both evaluate closed forms with O(10) operations per entry: 1e-12 of a block.
  const ShaftSystem sys = system_of("tests/scenes/shaft/one_node.toml", 700.0);
  abu::ParamsN rigid = sys.balancer;
  rigid.rotor.mass = sys.spec.discs[0].mass;
  rigid.rotor.stiffness = sys.spec.bearings[0].stiffness;
  rigid.rotor.damping = sys.spec.bearings[0].damping;
  rigid.omega = 650.0;  // the speed of the profile, not the scene's: the friction's N follows it
  abu::shaft_detail::ShaftOde ode(sys);
  std::mt19937 rng(3);
  for (const double omega_dot : {0.0, -5e3, 2e4}) {
    ode.set_speed(650.0, omega_dot);
    const Eigen::VectorXd x = random_state(sys, rng);
    Eigen::VectorXd f(x.size());
    REQUIRE(ode.field(x.data(), f.data()));
    const int n = sys.n_balls(), d = sys.configuration_size();
    abu::State<double, abu::any_balls> xr(2 * n + 4);
    const int map[] = {0, 1};
    for (int k : map) xr(k) = x(k), xr(n + 2 + k) = x(d + k);
    for (int i = 0; i < n; ++i) xr(2 + i) = x(4 + i), xr(n + 4 + i) = x(d + 4 + i);
    const auto fr = abu::vector_field(rigid, xr, omega_dot);
    const double qs = std::max(std::abs(fr(n + 2)), std::abs(fr(n + 3)));
    double bs = 0;
    for (int i = 0; i < n; ++i) bs = std::max(bs, std::abs(fr(n + 4 + i)));
    CAPTURE(omega_dot);
    CHECK(std::abs(f(d) - fr(n + 2)) <= 1e-12 * qs);
    CHECK(std::abs(f(d + 1) - fr(n + 3)) <= 1e-12 * qs);
    for (int i = 0; i < n; ++i) CHECK(std::abs(f(d + 4 + i) - fr(n + 4 + i)) <= 1e-12 * bs);
  }
}
