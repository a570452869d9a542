// The unround race (model.md §11): the round limit against the round model, the
// linearization (§11.5) against central differences of b (§11.3), the eccentric race's
// exact solution (§11.4), the first-order residual whirl (§11.6) and the search's count.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "abu/continuation/unround_branches.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/unround_spectrum.hpp"
#include "abu/model/model.hpp"
#include "abu/model/unround_race.hpp"

using namespace abu;

namespace {
using L = long double;

// The default scene (data/scenes/default.toml) with n balls and a chosen law.
ParamsN base(int n = 2, FrictionLaw law = FrictionLaw::viscous, double omega = 900.0) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = omega;
  p.law = law;
  p.kappa = 1e3;
  p.balls.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) p.balls[std::size_t(i)] = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-3, 0.001, 0.003, 0.1};
  return p;
}

RaceShape same_for_all(int n, RaceHarmonics h) { return RaceShape{std::vector<RaceHarmonics>(std::size_t(n), h)}; }

L rel(L a, L b, L scale) { return std::abs(a - b) / scale; }
}  // namespace

TEST_CASE("unround race: a round race gives model.md §3 and §6 to rounding", "[unround]") {
  // An unround shape with zero amplitudes is the round race; every entry of A, b and the
  // linearization must agree with the round model to 1e-15 of the row's size (both are
  // evaluated in long double; the formulas differ, so only rounding may differ).
  for (int n : {2, 3}) {
    const auto p = base(n, FrictionLaw::coulomb).cast<L>();
    const RaceShape round = same_for_all(n, {{2, 0.0, 0.3}});
    State<L, any_balls> x(2 * n + 4);
    for (int k = 0; k < 2 * n + 4; ++k) x(k) = 0.1L * std::sin(1.7L * k + 0.3L);
    x(0) = 3e-6L, x(1) = -2e-6L, x(n + 2) = 1e-4L, x(n + 3) = -3e-4L;
    const auto b_round = generalized_forces(p, x);
    const auto b_unround = unround_generalized_forces(p, round, x);
    for (int i = 0; i < n + 2; ++i) CHECK(rel(b_round(i), b_unround(i), b_round.cwiseAbs().maxCoeff()) < 1e-15L);
    // The linearization at every equilibrium of the round model (s'' = 0 there; off
    // equilibrium model.hpp's stiffness also holds (dA/ds) s'').
    const EquilibriumSetN eqs = find_equilibria(base(n, FrictionLaw::coulomb));
    for (const auto& e : eqs.list) {
    const Coordinates<L, any_balls> s = e.position;
    const auto lin_round = linearize(p, at_rest<L, any_balls>(s));
    const auto lin = unround_linearization(p, round, s);
    for (int i = 0; i < n + 2; ++i)
      for (int j = 0; j < n + 2; ++j) {
        CHECK(rel(lin.mass(i, j), lin_round.mass(i, j), lin_round.mass.row(i).cwiseAbs().maxCoeff()) < 1e-15L);
        CHECK(rel(lin.damping(i, j), lin_round.damping(i, j), lin_round.damping.row(i).cwiseAbs().maxCoeff()) <
              1e-15L);
        CHECK(rel(lin.stiffness(i, j), lin_round.stiffness(i, j), lin_round.stiffness.row(i).cwiseAbs().maxCoeff()) <
              1e-15L);
      }
    }
  }
}

TEST_CASE("unround race: the linearization is the derivative of b (§11.5 against §11.3)", "[unround]") {
  // Central differences in long double with step h: truncation ~ h^2 |b'''|, rounding
  // ~ 1e-19 / h; h = 1e-6 (relative) keeps both below 1e-9 of the entries' size.
  const int n = 2;
  const auto p = base(n, FrictionLaw::viscous).cast<L>();
  const RaceShape race{{{{2, 3e-3, 0.4}, {3, 1e-3, 1.1}}, {{1, 2e-3, 0.7}, {2, 1e-3, -0.2}}}};
  State<L, any_balls> x = State<L, any_balls>::Zero(2 * n + 4);
  x(0) = 2e-6L, x(1) = -1e-6L, x(2) = 2.1L, x(3) = 4.0L;
  const Coordinates<L, any_balls> s = x.head(n + 2);
  const auto lin = unround_linearization(p, race, s);
  const L scale_q = 1e-5L;
  for (int j = 0; j < 2 * (n + 2); ++j) {
    const bool velocity = j >= n + 2;
    const int c = velocity ? j - (n + 2) : j;
    const L h = (c < 2 ? scale_q : 1.0L) * 1e-6L * (velocity ? 1e-2L : 1.0L);
    State<L, any_balls> xp = x, xm = x;
    xp(j) += h, xm(j) -= h;
    const auto d = ((unround_generalized_forces(p, race, xp) - unround_generalized_forces(p, race, xm)) / (2 * h))
                       .eval();
    const auto& analytic = velocity ? lin.damping : lin.stiffness;
    for (int i = 0; i < n + 2; ++i) {
      const L size = analytic.row(i).cwiseAbs().maxCoeff();
      INFO("row " << i << " column " << j);
      CHECK(std::abs(-d(i) - analytic(i, c)) <= 1e-8L * size);
    }
  }
  // The mass matrix: b's dependence on s'' is -A s'' by construction; check A against
  // the kinetic energy's Hessian through its symmetry and the ball diagonal j m s'^2.
  CHECK((lin.mass - lin.mass.transpose()).cwiseAbs().maxCoeff() == 0);
}

TEST_CASE("unround race: a round race's equilibria are the round model's (n = 2)", "[unround]") {
  const ParamsN p = base(2, FrictionLaw::coulomb);
  const UnroundResult r = find_unround_equilibria(p, same_for_all(2, {}));
  const EquilibriumSetN round = find_equilibria(p);
  REQUIRE(r.list.size() == round.list.size());
  CHECK(r.doubt == "");
  for (const auto& e : round.list) {
    const auto match = std::find_if(r.list.begin(), r.list.end(), [&](const UnroundEquilibrium& u) {
      L d = 0;
      for (int i = 2; i < 4; ++i) {
        const L x = std::abs(std::remainder(u.position(i) - L(e.position(i)), 2 * std::numbers::pi_v<L>));
        d = std::max(d, x);
      }
      return d < 1e-12L;
    });
    REQUIRE(match != r.list.end());
    CHECK(std::abs(match->position(0) - L(e.position(0))) <= 1e-12L * 1e-5L);
    CHECK(std::abs(match->position(1) - L(e.position(1))) <= 1e-12L * 1e-5L);
  }
}

TEST_CASE("unround race: an eccentric race leaves |q| = d exactly (§11.4)", "[unround]") {
  // The race circle's centre at D = d e^{i phi}: q = -D solves every ball condition; the
  // balls then balance the shifted unbalance. |q| = d to rounding (1e-12 relative).
  const double l = 0.018, eps = 2e-4, phi = 0.7;
  const ParamsN p = base(2, FrictionLaw::coulomb);
  const UnroundResult r = find_unround_equilibria(p, same_for_all(2, {{1, eps, phi}}));
  CHECK(r.doubt == "");
  const std::complex<double> D = std::polar(l * eps, phi);
  int centred = 0;
  for (const auto& e : r.list)
    if (std::abs(std::complex<double>(double(e.position(0)), double(e.position(1))) + D) <= 1e-12 * std::abs(D)) {
      ++centred;
      CHECK(std::abs(e.amplitude - l * eps) <= 1e-12 * l * eps);
    }
  CHECK(centred == 2);  // the two mirror solutions of the shifted balancing problem
  REQUIRE(r.best_stable);
  CHECK(std::abs(r.list[*r.best_stable].amplitude - l * eps) <= 1e-12 * l * eps);
}

TEST_CASE("unround race: the first-order residual whirl of §11.6 at small eps", "[unround]") {
  // q from the race normals through the round-race balanced angles (11.6.1), computed
  // here from (5.5); the exact solution differs by O(eps) relative (§11.6): at eps =
  // 1e-9 that is below 1e-4.
  const double l = 0.018, U = 6e-7, m = 3.3e-5;
  for (auto [k, phase] : {std::pair{2, 0.0}, {2, 1.0}, {3, 0.5}}) {
    const double eps = 1e-9;
    const RaceShape race = same_for_all(2, {{k, eps, phase}});
    const UnroundResult r = find_unround_equilibria(base(2), race);
    CHECK(r.doubt == "");
    for (int sheet : {-1, 1}) {
      const double b1 = std::numbers::pi - sheet * std::acos(U / (2 * m * l));
      const double b2 = std::numbers::pi + sheet * std::acos(U / (2 * m * l));
      auto d1 = [&, k = k, phase = phase](double b) { return -l * k * eps * std::sin(k * b - phase); };
      const double s21 = std::sin(b2 - b1);
      const std::complex<double> q((d1(b2) * std::cos(b1) - d1(b1) * std::cos(b2)) / s21,
                                   (d1(b2) * std::sin(b1) - d1(b1) * std::sin(b2)) / s21);
      const auto near = std::min_element(r.list.begin(), r.list.end(), [&](const auto& a, const auto& b) {
        return std::abs(std::remainder(double(a.position(2)) - b1, 2 * std::numbers::pi)) <
               std::abs(std::remainder(double(b.position(2)) - b1, 2 * std::numbers::pi));
      });
      INFO("k " << k << " phase " << phase << " sheet " << sheet);
      CHECK(std::abs(std::complex<double>(double(near->position(0)), double(near->position(1))) - q) <= 1e-4 * std::abs(q));
    }
  }
}

TEST_CASE("unround race: equilibria appear in pairs as eps grows (index sum 0)", "[unround]") {
  // Poincare-Hopf on the torus: the indices sum to 0, so the count is even and every
  // pair born at a fold carries opposite indices. The counts for an oval (k = 2, phase
  // 0) in the default scene: 6 at eps = 1e-6 (the round race's, no q = 0 any more),
  // more once the race lobes capture the balls.
  for (double eps : {1e-6, 1e-4, 1e-3}) {
    const UnroundResult r = find_unround_equilibria(base(2), same_for_all(2, {{2, eps, 0.0}}));
    INFO("eps " << eps);
    CHECK(r.doubt == "");
    CHECK(r.search.index_sum == 0);
    CHECK(r.list.size() % 2 == 0);
    for (const auto& e : r.list) CHECK(e.residual < 1e-13);
    if (eps == 1e-6) {
      CHECK(r.list.size() == 6);
      CHECK(r.list[0].amplitude > 0);
    }
  }
}

TEST_CASE("unround race: the reference values of model.md §11.9", "[unround]") {
  // Published values (4 significant digits, so a 5e-4 relative tolerance) for the default
  // scene with one oval on both balls.
  SECTION("counts and the smallest residual whirl, phase 0") {
    struct Row {
      double eps;
      std::size_t count;
      double smallest;
    };
    for (const Row& row : {Row{1e-6, 6, 3.661e-8}, Row{1e-4, 10, 3.351e-6}, Row{1e-3, 16, 4.983e-6}}) {
      const UnroundResult r = find_unround_equilibria(base(2), same_for_all(2, {{2, row.eps, 0.0}}));
      INFO("eps " << row.eps);
      CHECK(r.list.size() == row.count);
      CHECK(std::abs(r.list[0].amplitude / row.smallest - 1) < 5e-4);
      CHECK(std::abs(r.list[1].amplitude / r.list[0].amplitude - 1) < 1e-12);  // the mirror pair
    }
  }
  SECTION("the near-balanced branch, phase 1, viscous d = 1e-3") {
    struct Row {
      double eps, q, beta1, beta2, abscissa;
    };
    // beta to 1e-4 rad (printed to 4 decimals), the abscissa to 4 digits.
    for (const Row& row : {Row{5e-6, 1.708e-7, 2.0826, 4.1466, -5.207}, Row{4e-5, 1.791e-6, 1.7144, 3.8975, -0.922},
                           Row{2e-4, 4.930e-6, 0.6421, 3.5705, -8.329}}) {
      const UnroundResult r = find_unround_equilibria(base(2), same_for_all(2, {{2, row.eps, 1.0}}));
      INFO("eps " << row.eps);
      const auto it = std::find_if(r.list.begin(), r.list.end(), [&](const UnroundEquilibrium& e) {
        return std::abs(double(e.position(2)) - row.beta1) < 2e-4 && std::abs(double(e.position(3)) - row.beta2) < 2e-4;
      });
      REQUIRE(it != r.list.end());
      CHECK(std::abs(it->amplitude / row.q - 1) < 5e-4);
      CHECK(std::abs(it->spectrum.abscissa / row.abscissa - 1) < 1e-3);
      CHECK(it->spectrum.stability == Stability::stable);
    }
  }
}

namespace {
// Branch crossings of the level e = f (f strictly between the branch points' factors).
std::vector<UnroundBranchPoint> crossings(const UnroundBranches& b, double f) {
  std::vector<UnroundBranchPoint> out;
  for (const auto& br : b.branches)
    for (std::size_t k = 0; k + 1 < br.points.size(); ++k)
      if ((br.points[k].factor - f) * (br.points[k + 1].factor - f) < 0) out.push_back(br.points[k]);
  return out;
}
}  // namespace

TEST_CASE("unround race: continuation in the unroundness agrees with the complete search (§11.10)", "[unround][unround_branches]") {
  // An oval (k = 2, phase 0) of 1e-4 on both balls of the default scene, e in [0, 3]: the
  // count grows from 6 (round race) to 16 at e = 3 through folds (§11.9). Every branch
  // point checked is an equilibrium the search finds at its own e, beta to 1e-10 rad and
  // |q| to 1e-10 relative (both solve g = 0 to rounding: Newton in long double); the
  // number of branches crossing e = 0.5 and e = 2 is the search's count there.
  const ParamsN p = base(2);
  const RaceShape race = same_for_all(2, {{2, 1e-4, 0.0}});
  const UnroundBranches b = continue_unround(p, race, 3.0);
  CHECK(b.doubt == "");
  REQUIRE(!b.branches.empty());
  int folds = 0;
  for (const auto& br : b.branches)
    for (const auto& s : br.specials) folds += s.kind == "LP" ? 1 : 0;
  CHECK(folds >= 2);  // 6 -> 16 equilibria: pairs born at folds inside (0, 3)
  for (double f : {0.5, 2.0}) {
    const UnroundResult r = find_unround_equilibria(p, scaled_race(race, f));
    INFO("e " << f);
    CHECK(crossings(b, f).size() == r.list.size());
  }
  // Points spread over the branches against the search at their own factor.
  int checked = 0;
  for (const auto& br : b.branches)
    for (std::size_t k = 0; k < br.points.size(); k += 29) {
      const auto& pt = br.points[k];
      const UnroundResult r = find_unround_equilibria(p, scaled_race(race, pt.factor));
      const auto match = std::find_if(r.list.begin(), r.list.end(), [&](const UnroundEquilibrium& e) {
        L d = 0;
        for (int i = 2; i < 4; ++i)
          d = std::max(d, std::abs(std::remainder(e.position(i) - pt.state.position(i), 2 * std::numbers::pi_v<L>)));
        return d < 1e-10L;
      });
      INFO("branch point at e " << pt.factor);
      REQUIRE(match != r.list.end());
      CHECK(std::abs(match->amplitude - pt.state.amplitude) <= 1e-10 * match->amplitude + 1e-20);
      CHECK(match->spectrum.stability == pt.state.spectrum.stability);
      ++checked;
    }
  CHECK(checked >= 6);
}

TEST_CASE("unround race: the eccentric race's balanced branch keeps |q| = e d (§11.4, §11.10)", "[unround][unround_branches]") {
  // Along e the exact solution q = -e D of (11.4.4) is followed from the round race's
  // balanced states: every point's |q| = e l eps to 1e-12 relative.
  const double l = 0.018, eps = 2e-4, phi = 0.7;
  const ParamsN p = base(2, FrictionLaw::coulomb);
  const UnroundBranches b = continue_unround(p, same_for_all(2, {{1, eps, phi}}), 3.0);
  int on = 0;
  for (const auto& br : b.branches) {
    if (br.start_factor != 0 || br.points.front().state.amplitude > 1e-15) continue;  // the balanced states
    ++on;
    CHECK(br.points.back().factor == Approx(3.0).epsilon(1e-15));
    for (const auto& pt : br.points)
      CHECK(std::abs(pt.state.amplitude - pt.factor * l * eps) <= 1e-12 * pt.factor * l * eps + 1e-20);
  }
  CHECK(on == 2);
}

TEST_CASE("unround race: four balls by multistart, said to be not proven complete (§11.11)", "[unround]") {
  // n = 4, a small oval (eps_2 = 1e-6, Lambda ~ 0.01): every equilibrium found solves the
  // static equations to rounding (residual < 1e-13); each aligned equilibrium of the round
  // race (isolated, nondegenerate) moves by about k eps l / |q| rad (the race's slope l l'
  // against the rotor's pull l |q| in g_i, §11.4: 7e-3 rad at |q| = 5.3 um) and is found
  // within 10 times that, its |q| within 1 %; the
  // balanced set (dimension 2) leaves isolated near-balanced equilibria (|q| = O(eps l) <
  // 1e-7 m), at least one stable; and the list says it is not proven complete.
  const ParamsN p = base(4);
  const RaceShape race = same_for_all(4, {{2, 1e-6, 0.3}});
  const UnroundResult r = find_unround_equilibria(p, race);
  CHECK(r.doubt.find("not proven complete") != std::string::npos);
  for (const auto& e : r.list) CHECK(e.residual < 1e-13);
  int aligned = 0;
  for (const auto& round : find_equilibria(p).list) {
    if (round.family == Family::balanced) continue;
    ++aligned;
    const double q_round = std::hypot(round.position(0), round.position(1));
    const double shift = 10 * 2 * 1e-6 * 0.018 / q_round;
    const auto near = std::any_of(r.list.begin(), r.list.end(), [&](const UnroundEquilibrium& u) {
      L d = 0;
      for (int i = 2; i < 6; ++i)
        d = std::max(d, std::abs(std::remainder(u.position(i) - L(round.position(i)), 2 * std::numbers::pi_v<L>)));
      return d < shift && std::abs(u.amplitude / q_round - 1) < 0.01;
    });
    INFO("round aligned |q| " << q_round << " beta " << round.position(2) << " " << round.position(3) << " "
                              << round.position(4) << " " << round.position(5));
    CHECK(near);
  }
  CHECK(aligned > 0);
  const auto balanced = std::count_if(r.list.begin(), r.list.end(), [](const auto& e) { return e.amplitude < 1e-7; });
  CHECK(balanced >= 2);
  REQUIRE(r.best_stable);
  CHECK(r.list[*r.best_stable].amplitude < 1e-7);
}
