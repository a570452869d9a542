// Simulation on an unround race (model.md §15.6-§15.7): the field against the round model
// (§3, §9) in the round limit, the analytic Jacobian and omega derivative against central
// differences, l''' against differences of l'', the eccentric race's exact whirl |q| = d
// (11.4.4) reached by integration, and an oval's run ending on the equilibrium of §11.4.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "abu/dynamics/simulation.hpp"
#include "abu/dynamics/unround_simulation.hpp"
#include "abu/linear/unround_spectrum.hpp"
#include "abu/model/model.hpp"
#include "abu/model/unround_field.hpp"

using namespace abu;

namespace {

// The default scene (data/scenes/default.toml) with a chosen law; viscous d = 1e-3.
ParamsN base(FrictionLaw law = FrictionLaw::viscous, double omega = 900.0) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = omega;
  p.law = law;
  p.kappa = 1e3;
  p.balls.resize(2);
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-3, 0.001, 0.003, 0.1};
  return p;
}

RaceShape both(RaceHarmonics h) { return RaceShape{{h, h}}; }

// A state off equilibrium: every term of (11.3.4) and (15.6.1) is nonzero.
State<double, any_balls> moving_state() {
  State<double, any_balls> x(8);
  x << 2e-6, -1e-6, 2.1, 4.0, 3e-4, -2e-4, 0.7, -1.3;
  return x;
}

}  // namespace

TEST_CASE("unround simulation: a round race gives the field and Jacobian of model.md §3 and §9", "[unround_simulation]") {
  // An amplitude of 1e-30 is round to rounding but takes the unround race's formulas (a
  // race with every amplitude zero is model.md §3's code itself, machine_field.hpp): the two
  // codes differ in their formulas only, so the field and Jacobian (also with omega' != 0,
  // the run-up terms of §9 against (15.6.1)) must agree to rounding: 1e-12 of the largest
  // entry of each row.
  for (FrictionLaw law : {FrictionLaw::viscous, FrictionLaw::coulomb}) {
    const ParamsN p = base(law);
    const RaceShape round = both({{2, 1e-30, 0.3}});
    REQUIRE(!round.round());
    const auto x = moving_state();
    for (double wd : {0.0, 150.0}) {
      const auto f0 = wd == 0 ? vector_field(p, x) : vector_field(p, x, wd);
      const auto f1 = unround_vector_field(p, round, x, wd);
      for (int i = 0; i < 8; ++i) CHECK(std::abs(f0(i) - f1(i)) <= 1e-12 * f0.cwiseAbs().maxCoeff());
      const auto J0 = wd == 0 ? jacobian(p, x) : jacobian(p, x, wd);
      const auto J1 = unround_jacobian(p, round, x, wd);
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) CHECK(std::abs(J0(i, j) - J1(i, j)) <= 1e-12 * J0.row(i).cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("unround simulation: l''' against central differences of l''", "[unround_simulation]") {
  // Step h = 1e-5 rad: truncation h^2 |l^(5)| / 6 ~ 1e-10 k^5 eps l, rounding 1e-16 l k^2 / h;
  // 1e-7 of the largest |l'''| covers both for orders up to 5.
  const RaceHarmonics h{{1, 0.05, 0.7}, {2, 0.01, 0.3}, {5, 2e-3, 1.9}};
  const double l = 0.018, step = 1e-5;
  double scale = 0;
  for (int k = 0; k < 64; ++k) scale = std::max(scale, std::abs(path_third_derivative(h, l, 0.1 * k)));
  for (int k = 0; k < 64; ++k) {
    const double b = 0.1 * k;
    const double fd = (path_point<double>(h, l, b + step).d2 - path_point<double>(h, l, b - step).d2) / (2 * step);
    CHECK(std::abs(path_third_derivative(h, l, b) - fd) <= 1e-7 * scale);
  }
}

TEST_CASE("unround simulation: the Jacobian and df/domega are the derivatives of the field", "[unround_simulation]") {
  // Central differences with steps of 1e-6 of each component's scale (q: 1e-6 m, angles:
  // 1 rad, velocities their size): truncation ~ 1e-12 relative, rounding ~ 1e-10 of a
  // column's size; 1e-6 of the column's largest entry leaves a wide margin and would
  // still catch any missing term (each is at least 1e-4 of its column here).
  const RaceShape race{{{{1, 2e-3, 0.7}, {2, 3e-3, 0.4}, {3, 1e-3, 1.1}}, {{2, 1e-3, -0.2}}}};
  for (FrictionLaw law : {FrictionLaw::viscous, FrictionLaw::coulomb}) {
    const ParamsN p = base(law);
    const auto x = moving_state();
    const double scales[8] = {1e-6, 1e-6, 1, 1, 1e-3, 1e-3, 1, 1};
    for (double wd : {0.0, 150.0}) {
      const auto J = unround_jacobian(p, race, x, wd);
      for (int j = 0; j < 8; ++j) {
        const double h = 1e-6 * scales[j];
        auto xp = x, xm = x;
        xp(j) += h;
        xm(j) -= h;
        const auto col = ((unround_vector_field(p, race, xp, wd) - unround_vector_field(p, race, xm, wd)) / (2 * h)).eval();
        const double size = std::max(col.cwiseAbs().maxCoeff(), J.col(j).cwiseAbs().maxCoeff());
        for (int i = 0; i < 8; ++i) CHECK(std::abs(J(i, j) - col(i)) <= 1e-6 * size);
      }
    }
    const double h = 1e-6 * p.omega;
    ParamsN pp = p, pm = p;
    pp.omega += h;
    pm.omega -= h;
    const auto fw = unround_omega_derivative(p, race, x);
    const auto fd = ((unround_vector_field(pp, race, x) - unround_vector_field(pm, race, x)) / (2 * h)).eval();
    for (int i = 0; i < 8; ++i) CHECK(std::abs(fw(i) - fd(i)) <= 1e-6 * fd.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("unround simulation: the eccentric race's run ends at |q| = d (11.4.4)", "[unround_simulation]") {
  // Both balls on the circle offset by d = l eps_1 (model.md §11.4): the exact residual whirl
  // is |q| = d at q = -D. From the round race's balanced angles at rest the run settles
  // (viscous balls, spectral abscissa about -1 1/s); after 40 s the transient is below
  // e^-30 of its start, so |q| must equal d to 1e-7 relative (integration rtol 1e-10).
  const ParamsN p = base();
  const double eps1 = 2e-4, phi = 0.7, d = 0.018 * eps1;
  const RaceShape race = both({{1, eps1, phi}});
  SimulationOptions o;
  o.t_end = 40;
  o.every = 0.05;
  o.rtol = 1e-10;
  o.race = &race;
  const double g = std::acos(p.rotor.unbalance / (2 * 3.3e-5 * 0.018));
  const auto r = simulate(p, SpeedProfile::constant(p.omega), start_at_rest(p, {std::numbers::pi - g, std::numbers::pi + g}), o);
  REQUIRE(r.status == SimulationStatus::completed);
  REQUIRE(r.unround_race);
  const double q_abs = std::hypot(r.x_end(0), r.x_end(1));
  CHECK(std::abs(q_abs - d) <= 1e-7 * d);
  CHECK(std::abs(r.x_end(0) + d * std::cos(phi)) <= 1e-7 * d);  // q = -D
  CHECK(std::abs(r.x_end(1) + d * std::sin(phi)) <= 1e-7 * d);
  // And the end is matched to one of the two solutions of (11.4.4) in the search's list.
  SimulationSummary s = r.summary;
  classify_unround_end(s, p, find_unround_equilibria(p, race), o.settle_tolerance);
  CHECK(s.outcome == SimulationOutcome::equilibrium);
  CHECK(std::abs(s.unround_q_abs - d) <= 1e-10 * d);
}

TEST_CASE("unround simulation: an oval's run ends on the stable equilibrium of §11.4", "[unround_simulation]") {
  // Default scene, oval eps_2 = 1e-6 (model.md §11.9: 6 equilibria, the stable mirror pair
  // of least |q| = 3.661e-8 m). From the round balanced angles the balls settle on one of
  // that pair; after 40 s (abscissa about -1 1/s) the end state must equal it to 1e-6 in
  // the scaled distance (q / L, rad), far inside the settle tolerance 1e-3.
  const ParamsN p = base();
  const RaceShape race = both({{2, 1e-6, 0.0}});
  SimulationOptions o;
  o.t_end = 40;
  o.every = 0.05;
  o.rtol = 1e-10;
  o.race = &race;
  const double g = std::acos(p.rotor.unbalance / (2 * 3.3e-5 * 0.018));
  const auto r = simulate(p, SpeedProfile::constant(p.omega), start_at_rest(p, {std::numbers::pi - g, std::numbers::pi + g}), o);
  REQUIRE(r.status == SimulationStatus::completed);
  const UnroundResult found = find_unround_equilibria(p, race);
  REQUIRE(found.best_stable);
  SimulationSummary s = r.summary;
  classify_unround_end(s, p, found, o.settle_tolerance);
  REQUIRE(s.outcome == SimulationOutcome::equilibrium);
  const auto& e = found.list[std::size_t(s.unround_member - 1)];
  CHECK(e.spectrum.stability == Stability::stable);
  CHECK(std::abs(e.amplitude - found.list[*found.best_stable].amplitude) <= 1e-12 * e.amplitude);  // the mirror pair
  CHECK(unround_distance(p, r.x_end, e) <= 1e-6);
  CHECK(std::abs(std::hypot(r.x_end(0), r.x_end(1)) - 3.661e-8) <= 1e-3 * 3.661e-8);  // §11.9, 4 digits printed
}
