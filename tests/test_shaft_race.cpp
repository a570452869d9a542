// A flexible shaft whose balls roll on an unround race (model.md §18.18): the balls' share of the
// composed machine scattered onto the shaft. Checked by (1) a round race through the same path
// giving the shaft's own round-race linearization (§18.7) term for term, (2) one disc on one
// bearing giving the rigid unround race's equilibria and every eigenvalue (§11.4, §11.5) plus the
// tilt pair of (18.9.1), (3) K of (18.18.2) against central differences of the static forces.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <complex>

#include "abu/analysis/shaft_states.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/equilibria/shaft_race_equilibria.hpp"
#include "abu/linear/unround_spectrum.hpp"
#include "abu/model/shaft_race.hpp"
#include "shaft_parts.hpp"

using namespace abu;
using abu::testing::balls;
using abu::testing::small_rotor;

namespace {
double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

RaceShape oval_and_offset(int n) {
  RaceShape race;
  race.balls.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) race.balls[std::size_t(i)] = {{1, 4e-5 * (1 + i), 0.3}, {2, 2e-4, 0.7 + 0.2 * i}};
  return race;
}
}  // namespace

// A round race (no harmonics) through the balls' share is the round model of §18.7: the same A,
// C and K at every equilibrium. Both are sums of the same few products in another order:
// 1e-13 of the largest entry.
TEST_CASE("shaft on a race: a round race reproduces the shaft's own linearization", "[shaft_race]") {
  for (int n : {2, 3})
    for (double omega : {300.0, 900.0}) {
      const ShaftSystem sys = make_shaft_system(small_rotor(false), balls(n, FrictionLaw::viscous, omega));
      const RaceShape round{std::vector<RaceHarmonics>(std::size_t(n))};
      for (const ShaftEquilibrium& e : find_shaft_equilibria(sys).list) {
        const ShaftLinearization a = linearize_shaft(sys, e.state());
        const ShaftLinearization b = linearize_shaft_on_race(sys, round, e.position);
        INFO("n " << n << " omega " << omega << " " << to_string(e.family));
        CHECK(max_abs(Eigen::MatrixXd(a.mass - b.mass)) <= 1e-13 * max_abs(Eigen::MatrixXd(a.mass)));
        CHECK(max_abs(Eigen::MatrixXd(a.damping - b.damping)) <= 1e-13 * max_abs(Eigen::MatrixXd(a.damping)));
        CHECK(max_abs(Eigen::MatrixXd(a.stiffness - b.stiffness)) <= 1e-13 * max_abs(Eigen::MatrixXd(a.stiffness)));
        const Eigen::VectorXd fa = shaft_generalized_forces(sys, e.state()).head(sys.configuration_size());
        const Eigen::VectorXd fb = shaft_race_static_forces(sys, round, e.position);
        CHECK((fa - fb).cwiseAbs().maxCoeff() <= 1e-13 * (fa.cwiseAbs().maxCoeff() + 1.0));
      }
    }
}

// One disc on one bearing (§18.9): the shaft's equilibria on an unround race are the rigid
// race's (angles to 1e-9 rad, |q| to 1e-9 relative: the equivalent balancer's k is the bearing's
// to rounding, the polish stops at 1e-15 of the static rows), and each of the rigid race's
// 2n + 4 eigenvalues is among the shaft's 2n + 8 (to 1e-8 of its modulus: ARPACK's residuals
// here are ~1e-13 relative, the rigid spectra refined in long double).
TEST_CASE("shaft on a race: one disc on one bearing is the rigid unround race", "[shaft_race]") {
  // Two balls: the box search of three takes from seconds to many minutes per speed on this race
  // (its leaves); the race's terms per ball are the same code for any n.
  for (int n : {2})
    for (double omega : {250.0, 900.0}) {
      const ParamsN p = balls(n, FrictionLaw::viscous, omega);
      const RaceShape race = oval_and_offset(n);
      ShaftSpec spec;
      spec.discs = {{0, p.rotor.mass, 3.5e-4, 2e-4}};
      spec.bearings = {{0, p.rotor.stiffness, p.rotor.damping, 40.0, 0.02}};
      const ShaftSystem sys = make_shaft_system(spec, p);
      const UnroundResult rigid = find_unround_equilibria(p, race);
      const ShaftStates shaft = analyze_shaft_race_states(sys, race, {.eigenvalues = 2 * n + 8, .band = 0.0});
      REQUIRE(shaft.states.size() == rigid.list.size());
      for (std::size_t k = 0; k < rigid.list.size(); ++k) {
        const auto& re = rigid.list[k];
        const ShaftState& se = shaft.states[k];
        INFO("n " << n << " omega " << omega << " equilibrium " << k + 1);
        CHECK(se.eq.status.ok());
        CHECK(std::abs(se.q_abs - re.amplitude) <= 1e-9 * re.amplitude);
        for (int i = 0; i < n; ++i) {
          const double d = std::remainder(se.eq.position(sys.ball_dof(i)) - double(re.position(2 + i)), 2 * M_PI);
          CHECK(std::abs(d) < 1e-9);
        }
        for (int j = 0; j < re.spectrum.count; ++j) {
          const std::complex<double> lambda = re.spectrum.eigenvalues[std::size_t(j)];
          double nearest = INFINITY;
          for (const auto& ep : se.spectrum.eigenpairs) nearest = std::min(nearest, std::abs(ep.value - lambda));
          CHECK(nearest <= 1e-8 * std::max(1.0, std::abs(lambda)));
        }
      }
    }
}

// K = -db/ds at rest (18.18.2) against central differences of b(s, 0) on the small rotor at an
// equilibrium of an unround race and off it: steps 1e-6 of each coordinate's scale (|u| ~ 1e-6 m,
// angles ~ 1 rad), truncation ~ h^2 |b'''|: 1e-6 of the largest column entry.
TEST_CASE("shaft on a race: K against differences of the static forces", "[shaft_race]") {
  const ParamsN p = balls(2, FrictionLaw::viscous, 700.0);
  const ShaftSystem sys = make_shaft_system(small_rotor(true), p);
  const RaceShape race = oval_and_offset(2);
  const ShaftRaceEquilibria set = find_shaft_race_equilibria(sys, race);
  REQUIRE(!set.list.empty());
  Eigen::VectorXd s = set.list.front().position;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) s(sys.ball_dof(0)) += 0.4, s(sys.balancer_dof()) *= 1.3;  // off equilibrium
    const Eigen::MatrixXd K(linearize_shaft_on_race(sys, race, s).stiffness);
    for (int c = 0; c < sys.configuration_size(); ++c) {
      const double h = c >= sys.shaft_dofs() ? 1e-6 : 1e-6 * std::max(1e-6, s.head(sys.shaft_dofs()).cwiseAbs().maxCoeff());
      Eigen::VectorXd a = s, b = s;
      a(c) += h, b(c) -= h;
      const Eigen::VectorXd diff = -(shaft_race_static_forces(sys, race, a) - shaft_race_static_forces(sys, race, b)) / (2 * h);
      INFO("pass " << pass << " column " << c);
      CHECK((diff - K.col(c)).cwiseAbs().maxCoeff() <= 1e-6 * std::max(1.0, K.col(c).cwiseAbs().maxCoeff()));
    }
  }
}
