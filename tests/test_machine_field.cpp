// The composed rigid-rotor field (model/machine_field.hpp, docs/model.md §20) on random
// combinations of its parts — 2, 3 and 5 balls of unequal sizes, each on its own unround
// path (offset circle and harmonics 2..4), an anisotropic support with cross terms, every
// smooth friction law, constant speed and a run-up: its Jacobian and its derivatives in
// omega, in the support's angle and in the anisotropy scale against central differences of
// the field; on a round race, model.md §3's code with the support's force against the
// unround race's formulas; with a part absent, model.md §3's field itself.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "abu/model/machine_field.hpp"
#include "abu/model/model.hpp"

using namespace abu;

namespace {

struct Combination {
  ParamsN p;
  RaceShape race;
  AnisotropicSupport support;
  State<double, any_balls> x;
  double theta = 0, omega_dot = 0, delta = 1;
};

// A random machine around the default scene (data/scenes/default.toml): ball masses and race
// radii within a factor 1.5 of 3.3e-5 kg and 18 mm, path harmonics up to 3e-3 relative, the
// support's principal stiffnesses k (1 +- 0.2) with a cross term, a state off equilibrium
// (every term of (11.3.4), (15.6.1) and (10.14.1) nonzero).
Combination random_combination(std::mt19937& rng, int n, FrictionLaw law) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Combination c;
  c.p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  c.p.omega = 900.0 * (1 + 0.3 * u(rng));
  c.p.law = law;
  c.p.kappa = 1e3;
  c.p.balls.resize(std::size_t(n));
  for (auto& b : c.p.balls) {
    b = {3.3e-5 * (1.2 + 0.3 * u(rng)), 0.018 * (1 + 0.3 * u(rng)), 1e-3, 1.4, 0.002, 1e-3, 0.001, 0.003, 0.1};
    RaceHarmonics h{{1, 2e-3 * std::abs(u(rng)), 3 * u(rng)}};
    for (int k = 2; k <= 4; ++k) h.push_back({k, 3e-3 * std::abs(u(rng)), 3 * u(rng)});
    c.race.balls.push_back(h);
  }
  const double k = 7500.0, cd = 2.0;
  c.support = {k * (1 + 0.2 * u(rng)), k * (1 + 0.2 * u(rng)), 0.05 * k * u(rng),
               cd * (1 + 0.3 * u(rng)), cd * (1 + 0.3 * u(rng)), 0.1 * cd * u(rng)};
  c.p.rotor.stiffness = c.support.mean_stiffness();
  c.p.rotor.damping = c.support.mean_damping();
  c.x = State<double, any_balls>(2 * n + 4);
  c.x(0) = 2e-6 * u(rng), c.x(1) = 2e-6 * u(rng);
  for (int i = 0; i < n; ++i) c.x(2 + i) = 3 * u(rng), c.x(n + 4 + i) = u(rng);
  c.x(n + 2) = 3e-4 * u(rng), c.x(n + 3) = 3e-4 * u(rng);
  c.theta = 3 * u(rng);
  c.delta = 0.5 + 0.5 * std::abs(u(rng));
  return c;
}

State<double, any_balls> field_of(const Combination& c, const ParamsN& p, const State<double, any_balls>& x,
                                  double theta, double delta) {
  MachineFieldValue v;
  machine_field(p, RigidMachine{&c.race, &c.support, delta}, x, theta, c.omega_dot, v, false);
  return v.field;
}

// |a - b| <= tol * size + floor_i, entry by entry (floor: a difference quotient's rounding).
void check_close(const State<double, any_balls>& a, const State<double, any_balls>& b, double tol, double size,
                 const State<double, any_balls>& floor = {}) {
  for (int i = 0; i < a.size(); ++i) {
    INFO("row " << i << ": " << a(i) << " against " << b(i));
    CHECK(std::abs(a(i) - b(i)) <= tol * size + (floor.size() ? floor(i) : 0.0));
  }
}

}  // namespace

// The fourth-order central difference of g at 0 with step h: truncation h^4 |g^(5)| / 30.
template <class G>
State<double, any_balls> derivative(G&& g, double h) {
  return ((8.0 * (g(h) - g(-h)) - (g(2 * h) - g(-2 * h))) / (12.0 * h)).eval();
}

TEST_CASE("machine field: the Jacobian and the omega, angle and anisotropy derivatives on random combinations",
          "[machine_field]") {
  // Fourth-order central differences with steps h of 1e-3 of each variable's natural size (q:
  // 1e-6 m, q': 1e-3 m/s, angles 1 rad, ball rates 1e-3 rad/s — the arctan laws bend over
  // 1 / kappa = 1e-3 rad/s —, omega, theta 1 rad): truncation
  // ~1e-12 of a column's size, rounding 3 eps |f_i| / h in row i (allowed: 100 eps |f_i| / h).
  // 1e-8 of the column's largest entry beyond that still catches a missing term (each term
  // here is above 1e-4 of its column). The field is affine in delta: f(delta) - f(0) is
  // A^-1 g delta to rounding (1e-9).
  std::mt19937 rng(20261206);
  int cases = 0;
  for (int n : {2, 3, 5})
    for (FrictionLaw law : {FrictionLaw::viscous, FrictionLaw::coulomb, FrictionLaw::stribeck})
      for (double wd : {0.0, 180.0}) {
        Combination c = random_combination(rng, n, law);
        c.omega_dot = wd;
        const int dim = 2 * n + 4;
        INFO("n = " << n << ", law " << to_string(law) << ", omega' = " << wd);
        MachineFieldValue v;
        machine_field(c.p, RigidMachine{&c.race, &c.support, c.delta}, c.x, c.theta, wd, v, true);
        const auto rounding = [&](double h) { return State<double, any_balls>(100 * 2.3e-16 * v.field.cwiseAbs() / h); };
        for (int j = 0; j < dim; ++j) {
          const double scale = j < 2 ? 1e-6 : j < n + 2 ? 1.0 : 1e-3;
          const auto col = derivative(
              [&](double h) {
                auto xh = c.x;
                xh(j) += h;
                return field_of(c, c.p, xh, c.theta, c.delta);
              },
              1e-3 * scale);
          const double size = std::max(col.cwiseAbs().maxCoeff(), v.jacobian.col(j).cwiseAbs().maxCoeff());
          INFO("column " << j);
          check_close(v.jacobian.col(j), col, 1e-8, size, rounding(1e-3 * scale));
        }
        const auto fw = derivative(
            [&](double h) {
              ParamsN ph = c.p;
              ph.omega += h;
              return field_of(c, ph, c.x, c.theta, c.delta);
            },
            1e-3 * c.p.omega);
        INFO("omega derivative");
        check_close(v.omega_derivative, fw, 1e-8, fw.cwiseAbs().maxCoeff(), rounding(1e-3 * c.p.omega));
        const auto ft = derivative([&](double h) { return field_of(c, c.p, c.x, c.theta + h, c.delta); }, 1e-3);
        REQUIRE(ft.cwiseAbs().maxCoeff() > 0);  // the support turns: the field depends on theta
        INFO("angle derivative");
        check_close(v.angle_derivative, ft, 1e-8, ft.cwiseAbs().maxCoeff(), rounding(1e-3));
        const State<double, any_balls> fd =
            (field_of(c, c.p, c.x, c.theta, c.delta) - field_of(c, c.p, c.x, c.theta, 0.0)) / c.delta;
        INFO("delta derivative");
        check_close(v.delta_derivative, fd, 1e-9, fd.cwiseAbs().maxCoeff());
        ++cases;
      }
  CHECK(cases == 18);
}

TEST_CASE("machine field: on a round race, model.md §3's code with the support's force is the unround race's",
          "[machine_field]") {
  // Two codes for one field: on a round race machine_field takes model.md §3's A and b at the
  // mean support plus A^-1 g (model.hpp); on a race with amplitudes of 1e-30 (round to
  // rounding) the unround race's formulas (11.3.3)-(11.3.4) plus g. They differ in their
  // formulas only: 1e-12 of each row's size, for the field, the Jacobian and every derivative,
  // at constant speed and in a run-up.
  std::mt19937 rng(7);
  for (int n : {2, 4})
    for (double wd : {0.0, 250.0}) {
      Combination c = random_combination(rng, n, FrictionLaw::coulomb);
      const RaceShape round;
      RaceShape nearly_round;
      for (int i = 0; i < n; ++i) nearly_round.balls.push_back({{2, 1e-30, 0.3}});
      REQUIRE(!nearly_round.round());
      MachineFieldValue v, a;
      machine_field(c.p, RigidMachine{&round, &c.support, c.delta}, c.x, c.theta, wd, v, true);
      machine_field(c.p, RigidMachine{&nearly_round, &c.support, c.delta}, c.x, c.theta, wd, a, true);
      check_close(v.field, a.field, 1e-12, a.field.cwiseAbs().maxCoeff());
      for (int i = 0; i < c.x.size(); ++i)
        for (int j = 0; j < c.x.size(); ++j)
          CHECK(std::abs(v.jacobian(i, j) - a.jacobian(i, j)) <= 1e-12 * a.jacobian.row(i).cwiseAbs().maxCoeff());
      check_close(v.delta_derivative, a.delta_derivative, 1e-12, a.delta_derivative.cwiseAbs().maxCoeff());
      check_close(v.angle_derivative, a.angle_derivative, 1e-12, a.angle_derivative.cwiseAbs().maxCoeff());
      check_close(v.omega_derivative, a.omega_derivative, 1e-12, a.omega_derivative.cwiseAbs().maxCoeff());
    }
}

TEST_CASE("machine field: absent parts cost nothing and change nothing", "[machine_field]") {
  // No race, a round race or an isotropic support: model.md §3's field and
  // Jacobian themselves (the same code: equal to the last bit), with zero angle and delta
  // derivatives; the omega derivative is model.hpp's parameter_derivative.
  std::mt19937 rng(11);
  Combination c = random_combination(rng, 3, FrictionLaw::stribeck);
  const RaceShape round;
  const AnisotropicSupport isotropic{c.p.rotor.stiffness, c.p.rotor.stiffness, 0.0, c.p.rotor.damping, c.p.rotor.damping, 0.0};
  for (const RigidMachine& m : {RigidMachine{}, RigidMachine{&round, nullptr}, RigidMachine{nullptr, &isotropic}}) {
    REQUIRE(m.base());
    MachineFieldValue v;
    machine_field(c.p, m, c.x, c.theta, 0.0, v, true);
    CHECK(v.field == vector_field(c.p, c.x));
    CHECK(v.jacobian == jacobian(c.p, c.x));
    CHECK(v.angle_derivative.isZero(0.0));
    CHECK(v.delta_derivative.isZero(0.0));
  }
}
