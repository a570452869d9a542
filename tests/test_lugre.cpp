// LuGre friction (model.md §12): the (3n + 4) field against its definition, the analytic
// Jacobian against central differences (smooth states) and one-sided differences (balls
// at rest, (12.9)), the equilibrium family (12.5), the normal spectrum two ways (12.10),
// and the scene rules.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Eigenvalues>

#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/lugre.hpp"
#include "abu/model/model.hpp"

using namespace abu;

namespace {

using LD = long double;

// A rotor of the default kind with n balls that differ in every coefficient (so that
// index mix-ups cannot cancel), LuGre parameters of the order of model.md §12.5's example.
ParamsT<LD, any_balls> lugre_ring(int n, double omega = 700.0) {
  ParamsT<LD, any_balls> p;
  p.rotor = {0.11L, 6900.0L, 1.7L, 5.1e-7L};
  p.omega = omega;
  p.law = FrictionLaw::lugre;
  p.balls.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const LD f = 1 + 0.09L * i;
    auto& b = p.balls[std::size_t(i)];
    b.mass = 3.1e-5L * f;
    b.race_radius = 0.017L * (1 + 0.013L * i);
    b.radius = 1e-3L;
    b.inertia_factor = i % 2 ? 1.0L : 1.4L;
    b.mu_c = 0.0017L * f;
    b.mu_s = 0.0041L * f;
    b.v_s = 0.43L * f;
    b.sigma0 = 170.0L * f;
    b.sigma1 = 0.031L * f;
    b.sigma2 = 1.3e-4L * f;
  }
  return p;
}

// q(beta) of (5.4): q = omega^2 W(beta) / (K + iC).
Coordinates<LD, any_balls> with_rotor_at_rest(const ParamsT<LD, any_balls>& p, std::vector<LD> beta) {
  const int n = p.n_balls();
  std::complex<LD> W = p.rotor.unbalance;
  for (int i = 0; i < n; ++i)
    W += p.balls[std::size_t(i)].mass * p.balls[std::size_t(i)].race_radius * std::polar(1.0L, beta[std::size_t(i)]);
  const LD w2 = p.omega * p.omega;
  const std::complex<LD> q = w2 * W / std::complex<LD>(p.rotor.stiffness - w2 * p.total_mass(), p.rotor.damping * p.omega);
  Coordinates<LD, any_balls> s(n + 2);
  s(0) = q.real();
  s(1) = q.imag();
  for (int i = 0; i < n; ++i) s(2 + i) = beta[std::size_t(i)];
  return s;
}

// Natural size of each state component: q in 1e-5 m, angles and rates 1, z in mu_s/sigma0.
LugreState<LD> natural_sizes(const ParamsT<LD, any_balls>& p) {
  const int n = p.n_balls(), d = n + 2;
  LugreState<LD> h = LugreState<LD>::Ones(3 * n + 4);
  h(0) = h(1) = 1e-5L;
  h(d) = h(d + 1) = 1e-5L * p.omega;
  for (int i = 0; i < n; ++i) h(2 * d + i) = p.balls[std::size_t(i)].mu_s / p.balls[std::size_t(i)].sigma0;
  return h;
}

// max over entries of |J - J_ref| / (the column's largest |J_ref| entry times the
// row's natural size over the column's): a relative, unit-free error per entry.
LD scaled_error(const LugreMatrix<LD>& J, const LugreMatrix<LD>& ref) {
  LD worst = 0;
  for (Eigen::Index c = 0; c < J.cols(); ++c) {
    const LD norm = std::max(ref.col(c).cwiseAbs().maxCoeff(), LD(1e-300));
    worst = std::max(worst, (J.col(c) - ref.col(c)).cwiseAbs().maxCoeff() / norm);
  }
  return worst;
}

// df/dx by central differences of the field (with omega' = omega_dot), steps 1e-6 of each
// component's natural size.
LugreMatrix<LD> central_differences(const ParamsT<LD, any_balls>& p, const LugreState<LD>& x, LD omega_dot) {
  const int m = int(x.size());
  const auto h = natural_sizes(p);
  LugreMatrix<LD> fd(m, m);
  for (int k = 0; k < m; ++k) {
    LugreState<LD> xp = x, xm = x;
    const LD step = 1e-6L * h(k);
    xp(k) += step;
    xm(k) -= step;
    fd.col(k) = (lugre_vector_field(p, xp, omega_dot) - lugre_vector_field(p, xm, omega_dot)) / (2 * step);
  }
  return fd;
}

}  // namespace

TEST_CASE("lugre: steady sliding gives the stribeck law in its sign limit plus sigma2 (model.md 12.1)", "[lugre]") {
  const auto p = lugre_ring(2);
  const auto& b = p.balls[1];
  const LD N = b.mass * b.race_radius * p.omega * p.omega;
  for (LD v : {-2.0L, -0.3L, 0.05L, 0.9L}) {
    const LD g = lugre_level(b, v);
    const LD z = (v > 0 ? 1 : -1) * g / b.sigma0;  // z' = 0 there
    CHECK(std::abs(bristle_rate(b, v, z)) <= 1e-15L * std::abs(v));
    const LD F = lugre_force(p, 1, v, z);
    const LD stribeck = -N * ((v > 0 ? 1 : -1) * g + b.sigma2 * v);
    CHECK(std::abs(F - stribeck) <= 1e-15L * std::abs(stribeck));
  }
}

// Central differences in long double with steps 1e-6 of each component's natural size:
// truncation ~1e-12 and rounding ~1e-19/1e-6 = 1e-13 relative to the column, so 1e-8 has
// a margin of 1e4; a wrong sign or a missing term is O(1e-3) or more.
TEST_CASE("lugre: analytic Jacobian equals central differences at moving states (model.md 12.6-12.8)", "[lugre]") {
  for (int n : {2, 3, 5}) {
    const auto p = lugre_ring(n);
    const int d = n + 2, m = 3 * n + 4;
    std::vector<LD> beta;
    for (int i = 0; i < n; ++i) beta.push_back(0.4L + 1.3L * i);
    const auto s = with_rotor_at_rest(p, beta);
    LugreState<LD> x = LugreState<LD>::Zero(m);
    x.head(d) = s;
    x(d) = 3e-4L, x(d + 1) = -2e-4L;
    for (int i = 0; i < n; ++i) {
      x(d + 2 + i) = (i % 2 ? -1 : 1) * (0.2L + 0.3L * i);                      // both signs, within and beyond v_s
      x(2 * d + i) = (0.7L - 0.4L * i) * p.balls[std::size_t(i)].mu_s / p.balls[std::size_t(i)].sigma0;
    }
    const auto J = lugre_jacobian(p, x, RestSide::forward);
    const LugreMatrix<LD> fd = central_differences(p, x, 0.0L);
    INFO("n = " << n);
    CHECK(scaled_error(J, fd) < 1e-8L);
  }
}

// During a run-up (model.md (12.11), (12.12)): the Jacobian with omega' against central
// differences of the field with omega' (as above: 1e-8 has a margin of 1e4), the Euler
// terms against the frictionless model's (f is affine in omega'), and df/domega against a
// central difference in omega (step 1e-6 omega: truncation 1e-12, rounding 1e-13).
TEST_CASE("lugre: run-up field, its Jacobian and df/domega (model.md 12.11-12.12)", "[lugre]") {
  for (int n : {2, 4}) {
    auto p = lugre_ring(n);
    const int d = n + 2, m = 3 * n + 4;
    const LD omega_dot = 350.0L;
    LugreState<LD> x = LugreState<LD>::Zero(m);
    for (int i = 0; i < n; ++i) x(2 + i) = 0.3L + 1.1L * i;
    x(0) = 2e-6L, x(1) = -1e-6L, x(d) = 3e-4L, x(d + 1) = 1e-4L;
    for (int i = 0; i < n; ++i) {
      x(d + 2 + i) = (i % 2 ? -1 : 1) * (0.15L + 0.2L * i);
      x(2 * d + i) = (0.5L - 0.3L * i) * p.balls[std::size_t(i)].mu_s / p.balls[std::size_t(i)].sigma0;
    }
    const auto J = lugre_jacobian(p, x, RestSide::forward, omega_dot);
    const LugreMatrix<LD> fd = central_differences(p, x, omega_dot);
    INFO("n = " << n);
    CHECK(scaled_error(J, fd) < 1e-8L);
    // f(x, omega') - f(x, 0) is the frictionless model's omega' part (friction has no omega').
    auto free = p;
    free.law = FrictionLaw::none;
    const State<LD, any_balls> xm = x.head(2 * d);
    const LugreState<LD> euler = lugre_vector_field(p, x, omega_dot) - lugre_vector_field(p, x);
    const State<LD, any_balls> euler_free = vector_field(free, xm, omega_dot) - vector_field(free, xm);
    CHECK((euler.head(2 * d) - euler_free).cwiseAbs().maxCoeff() <= 1e-15L * euler_free.cwiseAbs().maxCoeff());
    CHECK(euler.tail(n).cwiseAbs().maxCoeff() == 0.0L);
    const LugreState<LD> dfw = lugre_omega_derivative(p, x);
    const LD w0 = p.omega, dw = 1e-6L * w0;
    p.omega = w0 + dw;
    const LugreState<LD> fp = lugre_vector_field(p, x);
    p.omega = w0 - dw;
    const LugreState<LD> fm = lugre_vector_field(p, x);
    p.omega = w0;
    const LugreState<LD> dfw_fd = (fp - fm) / (2 * dw);
    for (int k = 0; k < m; ++k)
      CHECK(std::abs(dfw(k) - dfw_fd(k)) <= 1e-8L * std::max(dfw_fd.segment(d, d).cwiseAbs().maxCoeff(), LD(1e-300)));
  }
}

// At rest with z != 0 the field has a kink in each v_i; one-sided differences (step
// 1e-7 rad/s; error O(step^2 / v_s^2) ~ 1e-13 from g's curvature, rounding 1e-12) must give
// each side's column.
TEST_CASE("lugre: one-sided Jacobians at rest equal one-sided differences (model.md 12.9)", "[lugre]") {
  const int n = 3;
  const auto p = lugre_ring(n);
  const int d = n + 2;
  const auto s = with_rotor_at_rest(p, {0.9L, 2.4L, 4.4L});
  const LugreState<LD> x = lugre_equilibrium(p, s);
  for (int i = 0; i < n; ++i) CHECK(x(2 * d + i) != 0.0L);  // a stuck state, not z = 0
  for (RestSide side : {RestSide::forward, RestSide::backward}) {
    const auto J = lugre_jacobian(p, x, side);
    const LD sign = side == RestSide::forward ? 1 : -1;
    const LugreState<LD> f0 = lugre_vector_field(p, x);
    for (int i = 0; i < n; ++i) {
      const int k = d + 2 + i;
      const LD step = 1e-7L;
      LugreState<LD> xs = x;
      xs(k) += sign * step;
      const LugreState<LD> col = (lugre_vector_field(p, xs) - f0) / (sign * step);
      const LD norm = J.col(k).cwiseAbs().maxCoeff();
      INFO("side " << to_string(side) << ", ball " << i + 1);
      CHECK((J.col(k) - col).cwiseAbs().maxCoeff() <= 1e-8L * norm);
      // (12.9): c = 1 -+ sigma0 z / mu_s = 1 +- tau / mu_s
      CHECK(std::abs(J(2 * d + i, k) - lugre_rest_slope(p, s, i, side)) <= 1e-18L);
    }
    // the two sides differ where z != 0: the field is not differentiable there
    CHECK(std::abs(lugre_rest_slope(p, s, 0, RestSide::forward) - lugre_rest_slope(p, s, 0, RestSide::backward)) > 1e-3L);
  }
}

TEST_CASE("lugre: every configuration is an equilibrium with sigma0 z = -tau (model.md 12.5)", "[lugre]") {
  for (int n : {2, 4}) {
    const auto p = lugre_ring(n);
    std::vector<LD> beta;
    for (int i = 0; i < n; ++i) beta.push_back(1.0L + 1.2L * i * i);
    const auto s = with_rotor_at_rest(p, beta);
    const auto x = lugre_equilibrium(p, s);
    const auto f = lugre_vector_field(p, x);
    // natural sizes of f: accelerations ~ omega^2 times the state sizes
    const auto h = natural_sizes(p);
    LD worst = 0;
    for (Eigen::Index k = 0; k < f.size(); ++k) worst = std::max(worst, std::abs(f(k)) / (h(k) * p.omega * p.omega));
    INFO("n = " << n);
    CHECK(worst < 1e-15L);  // long double rounding ~1e-19 times condition ~1e3
    // and without the bristles holding the balls it is not an equilibrium
    LugreState<LD> x0 = x;
    x0.tail(n).setZero();
    CHECK((lugre_vector_field(p, x0) - f).cwiseAbs().maxCoeff() > 1e-6L);
  }
}

// (12.10): det(lambda - J_c) = lambda^n det T_c(lambda) / det A. The dense eigenvalues of
// the full (3n + 4) J in long double (absolute error ~ 1e-19 |J| ~ 1e-14 1/s here) must
// contain n values within that of 0 and the spring-dashpot ones (refined solver, 1e-12
// relative) to 1e-9 relative each.
TEST_CASE("lugre: full Jacobian spectrum = n zeros + spring-dashpot spectrum (model.md 12.10)", "[lugre]") {
  const int n = 3;
  const auto p = lugre_ring(n);
  const auto s = with_rotor_at_rest(p, {0.3L, 2.2L, 4.0L});
  const auto x = lugre_equilibrium(p, s);
  for (RestSide side : {RestSide::forward, RestSide::backward}) {
    const auto J = lugre_jacobian(p, x, side);
    Eigen::EigenSolver<Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic>> es(J);
    REQUIRE(es.info() == Eigen::Success);
    std::vector<std::complex<LD>> full(es.eigenvalues().data(), es.eigenvalues().data() + es.eigenvalues().size());
    std::sort(full.begin(), full.end(), [](auto a, auto b) { return std::abs(a) < std::abs(b); });
    const LD scale = J.cwiseAbs().maxCoeff();
    for (int k = 0; k < n; ++k) CHECK(std::abs(full[std::size_t(k)]) < 1e-12L * scale);
    const SpectrumN sd = compute_spectrum<any_balls>(lugre_rest_linearization(p, s, side));
    REQUIRE(sd.count == 2 * n + 4);
    for (int k = 0; k < sd.count; ++k) {
      const std::complex<LD> lam(sd.eigenvalues[std::size_t(k)].real(), sd.eigenvalues[std::size_t(k)].imag());
      LD best = 1e300L;
      for (std::size_t j = std::size_t(n); j < full.size(); ++j) best = std::min(best, std::abs(full[j] - lam));
      INFO("side " << to_string(side) << ", eigenvalue " << lam);
      CHECK(best <= 1e-9L * std::abs(lam) + 1e-12L * scale);
    }
  }
}

namespace {
constexpr const char* kLugreScene = R"(rolling = true
[rotor]
mass = 0.12
stiffness = 7500.0
damping = 2.0
unbalance = 6.0e-7
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
sigma0 = 240.0
mu_s = 0.005
[friction]
law = "lugre"
sigma0 = 200.0
sigma1 = 0.037
sigma2 = 1.0e-4
mu_c = 0.002
mu_s = 0.004
v_s = 0.5
[speed]
omega = 900.0
)";
}  // namespace

TEST_CASE("lugre scene: coefficients per ball, overrides checked against the law's rules", "[lugre][scene]") {
  Scene s = parse_scene(kLugreScene, "lugre.toml");
  REQUIRE(s.law == FrictionLaw::lugre);
  CHECK(s.law_line == 18);
  CHECK(s.balls[0].sigma0 == 200.0);
  CHECK(s.balls[1].sigma0 == 240.0);  // the ball's own value replaces [friction]'s
  CHECK(s.balls[0].mu_s == 0.004);
  CHECK(s.balls[1].mu_s == 0.005);
  CHECK(s.balls[1].sigma1 == 0.037);
  CHECK(s.balls[1].v_s == 0.5);
  // mu_c <= mu_s and mu_c > 0 per ball, also through --set (exit 2 via InputError)
  CHECK_THROWS_AS(apply_override(s, "mu_c=0.0045"), InputError);   // above ball 1's mu_s 0.004
  CHECK_NOTHROW(apply_override(s, "mu_c2=0.0045"));                // below ball 2's 0.005
  CHECK_THROWS_AS(apply_override(s, "mu_s1=0.001"), InputError);   // below mu_c 0.002
  CHECK_THROWS_AS(apply_override(s, "mu_c=0"), InputError);
  CHECK_THROWS_AS(apply_override(s, "sigma0=0"), InputError);
  CHECK_THROWS_AS(apply_override(s, "sigma1=-1"), InputError);
  CHECK_THROWS_AS(apply_override(s, "kappa=1000"), InputError);    // not a LuGre coefficient
  CHECK_NOTHROW(apply_override(s, "sigma2=0"));
  CHECK(s.balls[0].sigma2 == 0.0);
  // and a LuGre coefficient on a scene of another law
  std::string coulomb = kLugreScene;
  coulomb = coulomb.substr(0, coulomb.find("[friction]")) + "[friction]\nlaw = \"coulomb\"\nmu = 0.002\nkappa = 1e3\n[speed]\nomega = 900.0\n";
  coulomb.replace(coulomb.find("sigma0 = 240.0\nmu_s = 0.005\n"), 28, "");
  Scene c = parse_scene(coulomb, "coulomb.toml");
  CHECK_THROWS_AS(apply_override(c, "sigma0=100"), InputError);
}
