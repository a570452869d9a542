// simulate on an unround race on a flexible shaft (docs/model.md §18.20): the race's field on the
// shaft against the shaft's own round field (a race round to rounding) and against the rigid
// composed field (one disc on one bearing), its Jacobian against differences of the field, the
// one-node shaft's trajectories against the rigid simulate on the same race, and a settling run
// against the race's equilibria on the shaft. The fixed-frame reference is
// tests/reference/shaft_simulation_reference.py --race.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "../src/dynamics/shaft_field.hpp"  // internal to src/dynamics: the field alone
#include "abu/analysis/shaft_race_end.hpp"
#include "abu/analysis/shaft_states.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/machine_field.hpp"

namespace {

using abu::ShaftSystem;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

abu::Scene scene_of(const std::string& relative) { return abu::load_scene(std::string(ABU_SOURCE_DIR) + "/" + relative); }

ShaftSystem system_of(const abu::Scene& scene, double omega) {
  abu::Scene s = scene;
  s.omega = omega;
  return abu::shaft_system_of(s);
}

// Every amplitude 1e-300: not round() (the race's code runs), yet the paths are circles to rounding.
abu::RaceShape round_to_rounding(int n) {
  abu::RaceShape race;
  race.balls.assign(std::size_t(n), {{1, 1e-300, 0.4}, {2, 1e-300, 1.1}});
  return race;
}

// A state of natural size (as test_shaft_simulation.cpp): translations ~ L, tilts ~ 10 L, angles
// in [0, 2 pi), rates times omega, the balls' rates ~ 5 % of omega.
double natural_size(const ShaftSystem& sys, int i) {
  const double L = abu::displacement_scale(abu::shaft_summary_params(sys)), w = sys.balancer.omega;
  const int d = sys.configuration_size(), ns = sys.shaft_dofs(), c = i % d;
  const double size = c >= ns ? 3.0 : (c % 4 < 2 ? L : 10.0 * L);
  return i < d ? size : (c >= ns ? 0.05 : 1.0) * w * size;
}

Eigen::VectorXd random_state(const ShaftSystem& sys, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int d = sys.configuration_size(), ns = sys.shaft_dofs();
  Eigen::VectorXd x(2 * d);
  for (int i = 0; i < 2 * d; ++i) x(i) = natural_size(sys, i) * unit(rng) + ((i % d) >= ns && i < d ? 3.0 : 0.0);
  return x;
}

Eigen::VectorXd field_at(abu::shaft_detail::ShaftOde& ode, const Eigen::VectorXd& x) {
  Eigen::VectorXd f(x.size());
  REQUIRE(ode.field(x.data(), f.data()));
  return f;
}

// max over the acceleration rows of |a - b| / (the largest |b| of the row's block: translations,
// tilts, balls).
double block_error(const ShaftSystem& sys, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const int d = sys.configuration_size(), ns = sys.shaft_dofs();
  const auto block = [&](int i) { return i >= ns ? 2 : (i % 4 < 2 ? 0 : 1); };
  double scale[3] = {0, 0, 0}, worst = 0;
  for (int i = 0; i < d; ++i) scale[block(i)] = std::max(scale[block(i)], std::abs(b(d + i)));
  for (int i = 0; i < d; ++i) worst = std::max(worst, std::abs(a(d + i) - b(d + i)) / scale[block(i)]);
  return worst;
}

// The rigid rotor of a one-node shaft (model.md §18.9): the disc's mass, the bearing's k and c.
abu::ParamsN rigid_of(const ShaftSystem& sys) {
  abu::ParamsN rigid = sys.balancer;
  rigid.rotor.mass = sys.spec.discs[0].mass;
  rigid.rotor.stiffness = sys.spec.bearings[0].stiffness;
  rigid.rotor.damping = sys.spec.bearings[0].damping;
  return rigid;
}

}  // namespace

TEST_CASE("shaft on a race, simulated: a race round to rounding is the shaft's own round field", "[shaft_race_sim]") {
  // Amplitudes 1e-300 change l(beta) by 1e-300 relative: below rounding, so the race's code
  // (ball_share_terms, (18.20.1)) evaluates the round field (18.6.2) in another order. Field:
  // the same closed forms, 1e-12 of each block. Jacobian: the round route takes (dA/ds) s''
  // from linearize_shaft plus the run-up correction (18.16.4), the race's from the field's own
  // s'' (18.20.3): the same K to rounding, both through a dense Cholesky of A, 1e-9 of each row's
  // largest entry (cond(A) eps, as test_shaft_simulation.cpp's Jacobian check).
  const abu::Scene scene = scene_of("tests/scenes/shaft/sim_four_elements.toml");
  const ShaftSystem sys = system_of(scene, 600.0);
  const abu::RaceShape race = round_to_rounding(sys.n_balls());
  REQUIRE(!race.round());
  abu::shaft_detail::ShaftOde round(sys), on_race(sys, &race);
  REQUIRE(on_race.unround());
  std::mt19937 rng(5);
  const int dim = sys.state_size(), d = sys.configuration_size();
  for (const double omega_dot : {0.0, 2e4}) {
    CAPTURE(omega_dot);
    round.set_speed(600.0, omega_dot);
    on_race.set_speed(600.0, omega_dot);
    const Eigen::VectorXd x = random_state(sys, rng);
    CHECK(block_error(sys, field_at(on_race, x), field_at(round, x)) <= 1e-12);
    RowMajor ja(dim, dim), jb(dim, dim);
    Eigen::VectorXd ta(dim), tb(dim);
    REQUIRE(round.jacobian(x.data(), ja.data(), ta.data()));
    REQUIRE(on_race.jacobian(x.data(), jb.data(), tb.data()));
    double worst = 0;
    for (int r = d; r < dim; ++r) worst = std::max(worst, (ja.row(r) - jb.row(r)).cwiseAbs().maxCoeff() / ja.row(r).cwiseAbs().maxCoeff());
    CHECK(worst <= 1e-9);
    CHECK((ta - tb).cwiseAbs().maxCoeff() <= 1e-9 * (ta.cwiseAbs().maxCoeff() + 1e-300));
  }
}

TEST_CASE("shaft on a race, simulated: round to rounding runs the round trajectory", "[shaft_race_sim]") {
  // The same field to ~1e-16 per evaluation: rk8pd's steps and the samples (from each step's
  // interpolant) follow the same path; measured differences are rounding grown over the run,
  // 1e-12 (L + |q|) and 1e-12 rad asserted (a term lost would differ by the race's O(1) share).
  const abu::Scene scene = scene_of("tests/scenes/shaft/sim_four_elements.toml");
  const ShaftSystem sys = system_of(scene, 600.0);
  const abu::RaceShape race = round_to_rounding(sys.n_balls());
  for (const auto& speed : {abu::SpeedProfile::constant(600.0), abu::SpeedProfile::ramp(300.0, 600.0, 18000.0)}) {
    CAPTURE(speed.describe());
    abu::SimulationOptions o;
    o.t_end = 0.03;
    o.every = 5e-4;
    o.rtol = 1e-9;
    o.method = abu::IntegrationMethod::rk8pd;
    const auto x0 = abu::shaft_start_at_rest(sys, {0.5, 2.0, 4.0});
    const auto a = abu::simulate_shaft(sys, speed, x0, o);
    o.race = &race;
    const auto b = abu::simulate_shaft(sys, speed, x0, o);
    REQUIRE(a.run.status == abu::SimulationStatus::completed);
    REQUIRE(b.run.status == abu::SimulationStatus::completed);
    CHECK(b.run.unround_race);
    REQUIRE(a.run.samples.size() == b.run.samples.size());
    const double L = a.run.displacement_scale;
    double worst_q = 0, worst_beta = 0;
    for (std::size_t k = 0; k < a.run.samples.size(); ++k) {
      const auto &p = a.run.samples[k].x, &q = b.run.samples[k].x;
      const double size = L + std::hypot(p(0), p(1));
      worst_q = std::max({worst_q, std::abs(p(0) - q(0)) / size, std::abs(p(1) - q(1)) / size});
      for (int i = 0; i < sys.n_balls(); ++i) worst_beta = std::max(worst_beta, std::abs(p(2 + i) - q(2 + i)));
    }
    CHECK(worst_q <= 1e-12);
    CHECK(worst_beta <= 1e-12);
  }
}

TEST_CASE("shaft on a race, simulated: the Jacobian is the derivative of the field", "[shaft_race_sim]") {
  // Central differences of the field with steps 1e-4 of each component's natural size:
  // truncation ~1e-8 and rounding eps |f| / h ~1e-12 relative to each column's scale; 1e-5 of
  // the row block's largest entry (a dropped term of (15.6.4) or of (dA/ds) s'' is ~1e-3 of it
  // or more). df/dt = omega' df/domega against a central difference in omega (step 0.05 rad/s),
  // 1e-6 of its largest entry: the program's own difference (step 1e-5 omega) carries rounding
  // eps |f| / (2e-5 omega) ~ 1e-7 of it here (|f| up to 1e9 in the tilt rows of a random state).
  const abu::Scene scene = scene_of("tests/scenes/shaft/race_four_elements.toml");
  const ShaftSystem sys = system_of(scene, 600.0);
  const abu::RaceShape race = abu::race_shape(scene);
  abu::shaft_detail::ShaftOde ode(sys, &race);
  REQUIRE(ode.unround());
  std::mt19937 rng(17);
  const int dim = sys.state_size(), d = sys.configuration_size();
  for (const double omega_dot : {0.0, 2e4}) {
    CAPTURE(omega_dot);
    ode.set_speed(600.0, omega_dot);
    const Eigen::VectorXd x = random_state(sys, rng);
    RowMajor j(dim, dim);
    Eigen::VectorXd dfdt(dim);
    REQUIRE(ode.jacobian(x.data(), j.data(), dfdt.data()));
    RowMajor num(dim, dim);
    for (int c = 0; c < dim; ++c) {
      const double h = 1e-4 * natural_size(sys, c);
      Eigen::VectorXd xp = x, xm = x;
      xp(c) += h;
      xm(c) -= h;
      num.col(c) = (field_at(ode, xp) - field_at(ode, xm)) / (2 * h);
    }
    double worst = 0;
    for (int r = d; r < dim; ++r) {
      double scale = 0;
      for (int c = 0; c < dim; ++c) scale = std::max(scale, std::abs(num(r, c)) * natural_size(sys, c));
      for (int c = 0; c < dim; ++c) worst = std::max(worst, std::abs(j(r, c) - num(r, c)) * natural_size(sys, c) / scale);
    }
    CHECK(worst <= 1e-5);
    const double dw = 0.05;  // truncation (dw / omega)^2 ~ 1e-8; rounding eps |f| / dw ~ 1e-8 of the result
    ode.set_speed(600.0 + dw, omega_dot);
    const Eigen::VectorXd fp = field_at(ode, x);
    ode.set_speed(600.0 - dw, omega_dot);
    const Eigen::VectorXd fm = field_at(ode, x);
    ode.set_speed(600.0, omega_dot);
    const Eigen::VectorXd ref = omega_dot * (fp - fm) / (2 * dw);
    CHECK((dfdt - ref).cwiseAbs().maxCoeff() <= 1e-6 * (omega_dot * ((fp - fm) / (2 * dw)).cwiseAbs().maxCoeff() + 1e-300));
  }
}

TEST_CASE("shaft on a race, simulated: one disc on one bearing is the rigid unround race", "[shaft_race_sim]") {
  // Field: the one-node shaft's q, beta rows are the composed rigid field (20.1) on the same race
  // (model.md §18.9), both from ball_share's code plus the rotor's terms written twice; 1e-12 of
  // each block at omega' = 0, -5e3 and 2e4 rad/s^2. Trajectories: both routes integrate the same
  // equations with the same method and error control, each within ~8 rtol of the scaled size
  // (model.md §15.1), so 20 rtol (L + |q|) on q and 20 rtol rad on beta; the tilts stay 0.
  const abu::Scene scene = scene_of("tests/scenes/shaft/one_node_viscous.toml");
  const ShaftSystem sys = system_of(scene, 900.0);
  abu::RaceShape race;
  race.balls = {{{1, 3e-3, 0.4}, {2, 2e-3, 1.1}}, {{1, 3e-3, 0.4}, {2, 3e-3, 2.0}}};
  abu::ParamsN rigid = rigid_of(sys);
  const abu::RigidMachine machine{&race, nullptr};
  {
    abu::shaft_detail::ShaftOde ode(sys, &race);
    std::mt19937 rng(23);
    const int n = sys.n_balls(), d = sys.configuration_size();
    for (const double omega_dot : {0.0, -5e3, 2e4}) {
      CAPTURE(omega_dot);
      ode.set_speed(650.0, omega_dot);
      rigid.omega = 650.0;
      const Eigen::VectorXd x = random_state(sys, rng);
      const Eigen::VectorXd f = field_at(ode, x);
      abu::State<double, abu::any_balls> xr(2 * n + 4);
      for (int k = 0; k < 2; ++k) xr(k) = x(k), xr(n + 2 + k) = x(d + k);
      for (int i = 0; i < n; ++i) xr(2 + i) = x(4 + i), xr(n + 4 + i) = x(d + 4 + i);
      abu::MachineFieldValue v;
      abu::machine_field(rigid, machine, xr, 0.0, omega_dot, v, false);
      const double qs = std::max(std::abs(v.field(n + 2)), std::abs(v.field(n + 3)));
      double bs = 0;
      for (int i = 0; i < n; ++i) bs = std::max(bs, std::abs(v.field(n + 4 + i)));
      CHECK(std::abs(f(d) - v.field(n + 2)) <= 1e-12 * qs);
      CHECK(std::abs(f(d + 1) - v.field(n + 3)) <= 1e-12 * qs);
      for (int i = 0; i < n; ++i) CHECK(std::abs(f(d + 4 + i) - v.field(n + 4 + i)) <= 1e-12 * bs);
    }
  }
  rigid.omega = 900.0;
  const double L = abu::displacement_scale(rigid), rtol = 1e-9;
  for (const auto& speed : {abu::SpeedProfile::constant(900.0), abu::SpeedProfile::ramp(300.0, 900.0, 3000.0)}) {
    CAPTURE(speed.describe());
    abu::SimulationOptions o;
    o.t_end = 0.3;
    o.every = 1e-3;
    o.rtol = rtol;
    o.method = abu::IntegrationMethod::rk8pd;
    o.race = &race;
    const auto s = abu::simulate_shaft(sys, speed, abu::shaft_start_at_rest(sys, {2.0, 4.0}), o);
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
  }
}

TEST_CASE("shaft on a race, simulated: a settling run ends at one of the race's equilibria", "[shaft_race_sim]") {
  // race_four_elements.toml at 600 rad/s has eight equilibria, two of them stable (members 1 and
  // 3, `equilibria`). From the balls at (0.5, 2) rad the run settles (§15.2, eps = 1e-3) and
  // §15.7's rule names the equilibrium within eps; its configuration, the whole shaft included,
  // lies within 2 eps (|u| / L per node translation, rad) of that equilibrium's.
  const abu::Scene scene = scene_of("tests/scenes/shaft/race_four_elements.toml");
  const ShaftSystem sys = system_of(scene, 600.0);
  const abu::RaceShape race = abu::race_shape(scene);
  abu::SimulationOptions o;
  o.t_end = 3.0;
  o.every = 2e-3;
  o.method = abu::IntegrationMethod::rk8pd;
  o.race = &race;
  auto r = abu::simulate_shaft(sys, abu::SpeedProfile::constant(600.0), abu::shaft_start_at_rest(sys, {0.5, 2.0}), o);
  REQUIRE(r.run.status == abu::SimulationStatus::completed);
  const double L = r.run.displacement_scale, eps = o.settle_tolerance;
  const std::vector<abu::ShaftRaceTarget> targets = abu::shaft_race_targets(sys, race, 600.0);
  REQUIRE(targets.size() >= 2);
  abu::classify_shaft_race_end(r.run.summary, sys, L, targets, eps);
  REQUIRE(r.run.summary.outcome == abu::SimulationOutcome::equilibrium);
  const int member = r.run.summary.unround_member;
  const auto hit = std::find_if(targets.begin(), targets.end(), [&](const auto& t) { return t.eq.member == member; });
  REQUIRE(hit != targets.end());
  CHECK(hit->verdict == "stable");
  CHECK(r.run.summary.unround_q_abs == hit->q_abs);
  double dist = 0;
  for (int i = 0; i < sys.configuration_size(); ++i) {
    const double diff = r.x_end(i) - hit->eq.position(i);
    dist = std::max(dist, i >= sys.shaft_dofs() ? std::abs(std::remainder(diff, 2 * std::numbers::pi))
                                                : std::abs(diff) / (i % 4 < 2 ? L : L / 0.2));
  }
  CHECK(dist <= 2 * eps);
  // An unround race on anisotropic bearings is not modelled: refused.
  abu::ShaftSpec aniso = sys.spec;
  aniso.bearings[0].anisotropic = abu::AnisotropicSupport{2.2e4, 1.8e4, 0.0, 10.0, 10.0, 0.0};
  const ShaftSystem bad = abu::make_shaft_system(aniso, sys.balancer);
  CHECK_THROWS_AS(abu::simulate_shaft(bad, abu::SpeedProfile::constant(600.0), abu::shaft_start_at_rest(bad, {0.5, 2.0}), o),
                  std::invalid_argument);
}
