// coulomb-set balls on a flexible shaft (model.md §18.17): the stick set of the rigid balancer
// the balls see through the shaft. Checked by the rigid reduction (one disc on one bearing is
// the rigid rotor of §3: the same set) and by a second computation of the friction demand from
// the shaft's own static equations, without the equivalent rigid balancer.
#include <catch2/catch.hpp>

#include <Eigen/SparseLU>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/equilibria/shaft_stick_set.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/model/shaft_system.hpp"
#include "shaft_parts.hpp"

using namespace abu;
using abu::testing::balls;
using abu::testing::small_rotor;

namespace {
double relative(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); }
}  // namespace

// One disc on one bearing: K_eff + i C_eff = k - omega^2 M_tot + i c omega exactly (18.9), so the
// equivalent rigid balancer is the rigid rotor itself, up to the rounding of k_eq = Re + omega^2 M
// (a few eps of k relative). The stick set's figures are continuous in k, c away from the set's
// topology changes; measured: area 1.1e-15, V 1.4e-16 relative at worst. 1e-11 leaves room for
// the area's adaptive Simpson and interval bisections (resolved to ~1e-10 absolute per column, so a
// last-bit change of k could in principle move a bisection end by more than rounding).
TEST_CASE("shaft stick set: one disc on one bearing gives the rigid rotor's stick set", "[shaft_stick_set]") {
  // The whole torus (the bound decides) and three components (1e-4 at 900 rad/s, model.md §14.4;
  // the smaller islands of 2e-5 cost seconds per set and are the rigid scan's own tests').
  for (auto [mu, omega] : {std::pair{2e-3, 400.0}, {2e-3, 900.0}, {1e-4, 400.0}, {1e-4, 900.0}}) {
      ParamsN p = balls(2, FrictionLaw::coulomb_set, omega);
      for (auto& b : p.balls) b.mu = mu;
      ShaftSpec spec;
      spec.discs = {{0, p.rotor.mass, 3.5e-4, 2e-4}};
      spec.bearings = {{0, p.rotor.stiffness, p.rotor.damping, 40.0, 0.02}};
      StickSetOptions o;
      o.trace = false;
      const ShaftStickSet shaft = shaft_stick_set(stuck_balls_shaft(spec, p), o);
      const StickSet rigid = stick_set(p, o);
      INFO("mu " << mu << " omega " << omega);
      CHECK(relative(shaft.equivalent.rotor.stiffness, p.rotor.stiffness) < 1e-12);
      CHECK(relative(shaft.equivalent.rotor.damping, p.rotor.damping) < 1e-12);
      REQUIRE(shaft.set.components.size() == rigid.components.size());
      CHECK(relative(shaft.set.area, rigid.area) < 1e-11);
      CHECK(relative(shaft.set.worst_q_abs, rigid.worst_q_abs) < 1e-11);
      CHECK(relative(shaft.set.worst_q_abs_any, rigid.worst_q_abs_any) < 1e-11);
      CHECK(relative(shaft.set.bare_rotor_q_abs, rigid.bare_rotor_q_abs) < 1e-12);
      // A single node: the worst deflection is the balancer node's own.
      CHECK(shaft.shaft.worst_node == 0);
      CHECK(shaft.shaft.worst_deflection == shaft.set.worst_q_abs);
    }
}

// The friction demand from the shaft's own equations: with the balls held at beta, the shaft rows
// of b(s, 0) = 0 are linear in u (K_r u = omega^2 W(beta) e_b, one sparse solve); the ball rows'
// remainder is the torque friction must supply, m_i l_i omega^2 (q2 cos b_i - q1 sin b_i)
// (the static Jacobian's ball rows, model.md (14.1) times l_i), so
//     s_i = -r_i / (mu_i m_i l_i^2 omega^2)
// must equal stick_point's s_i of the equivalent rigid balancer, and every node's |u_k| / |q| the
// deflection ratio (18.17.2). Random arrangements, three speeds across the small rotor's first
// critical speeds, Euler-Bernoulli and Timoshenko. Tolerance 1e-12 of max(1, |s|) (measured
// 5.9e-15): both come from sparse LUs of the same matrix, one solve for a unit force and one for
// the balls' force, multiplied out in different orders; |q| and the ratios likewise (1e-12).
TEST_CASE("shaft stick set: the friction demand from the shaft's static equations", "[shaft_stick_set]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
  for (bool timoshenko : {false, true})
    for (double omega : {150.0, 700.0, 2500.0}) {
      ParamsN p = balls(3, FrictionLaw::coulomb_set, omega);
      const ShaftSystem sys = stuck_balls_shaft(small_rotor(timoshenko), p);
      const ShaftStickSet set = shaft_stick_set(sys, {.trace = false, .grid_budget = 1L << 12});
      ParamsN free_balls = p;  // the static equations without friction: the ball rows' remainder is the demand
      free_balls.law = FrictionLaw::none;
      const ShaftSystem free_sys = make_shaft_system(small_rotor(timoshenko), free_balls);
      const ShaftRotatingMatrices r = rotating_matrices(free_sys);
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(r.stiffness);
      REQUIRE(lu.info() == Eigen::Success);
      const int ns = sys.shaft_dofs(), b = sys.balancer_dof(), n = sys.n_balls();
      const double w2 = omega * omega;
      for (int trial = 0; trial < 40; ++trial) {
        std::vector<double> beta(static_cast<std::size_t>(n), 0.0);
        for (double& x : beta) x = angle(rng);
        Eigen::VectorXd force = Eigen::VectorXd::Zero(ns);
        force(b) = w2 * p.rotor.unbalance;
        for (int i = 0; i < n; ++i) {
          const auto& ball = p.balls[std::size_t(i)];
          force(b) += w2 * ball.mass * ball.race_radius * std::cos(beta[std::size_t(i)]);
          force(b + 1) += w2 * ball.mass * ball.race_radius * std::sin(beta[std::size_t(i)]);
        }
        Eigen::VectorXd x = Eigen::VectorXd::Zero(sys.state_size());
        x.head(ns) = lu.solve(force);
        for (int i = 0; i < n; ++i) x(ns + i) = beta[std::size_t(i)];
        const Eigen::VectorXd res = shaft_generalized_forces(free_sys, x);
        const StickPoint sp = stick_point(set.equivalent, beta);
        const double q = std::hypot(x(b), x(b + 1));
        CHECK(relative(std::hypot(sp.q1, sp.q2), q) < 1e-12);
        for (int i = 0; i < n; ++i) {
          const auto& ball = p.balls[std::size_t(i)];
          const double s_full = -res(ns + i) / (ball.mu * ball.mass * ball.race_radius * ball.race_radius * w2);
          INFO("omega " << omega << " trial " << trial << " ball " << i + 1);
          CHECK(std::abs(s_full - sp.s[std::size_t(i)]) < 1e-12 * std::max(1.0, std::abs(s_full)));
        }
        for (int k = 0; k < sys.nodes(); ++k)
          CHECK(relative(std::hypot(x(4 * k), x(4 * k + 1)) / q, set.shaft.deflection_ratio[std::size_t(k)]) < 1e-12);
      }
    }
}
