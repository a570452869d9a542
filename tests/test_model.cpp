// The equations of motion (model.md §3, §4, §6): analytic Jacobian and parameter
// derivatives against complex-step and central differences at states far from
// equilibrium, the friction laws against the §4 table, the mass matrix, and the
// agreement of the double and long double instantiations.
//
// Errors are measured in natural units: each row i of a Jacobian column or of df/dp is
// divided by the natural scale w_i of state component i (displacement scale for q, 1 for
// angles, omega times those for the rates), so that micrometres and radians count alike,
// and reported relative to the norm of the reference column in those units.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "abu/model/friction.hpp"
#include "abu/model/model.hpp"
#include "abu/core/params.hpp"

using namespace abu;

namespace {

using cplx = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

struct Case {
  FrictionLaw law;
  double kappa;  // arctan sharpness; unused by none/viscous
};
// Every law at the default scene's sharpness, and the stiff kappa = 1e6 for the dry laws.
const std::vector<Case> kCases{{FrictionLaw::none, 1e3},     {FrictionLaw::viscous, 1e3},
                               {FrictionLaw::coulomb, 1e3},  {FrictionLaw::coulomb, 1e6},
                               {FrictionLaw::stribeck, 1e4}, {FrictionLaw::stribeck, 1e6}};

std::string describe(const Case& c, bool unequal) {
  return std::string(to_string(c.law)) + " kappa=" + std::to_string(c.kappa) + (unequal ? " unequal" : " equal");
}

// The default scene (data/scenes/default.toml) with every law's coefficients. With
// `unequal` every ball differs in every coefficient, so index mix-ups cannot cancel.
template <int N = 2>
ParamsT<double, N> make_params(Case c, bool unequal = true) {
  ParamsT<double, N> p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = c.law;
  p.kappa = c.kappa;
  for (int i = 0; i < N; ++i) {
    // mass, l, r, j, mu, d, mu_c, mu_s, v_s
    BallT<double> b{3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-4, 0.001, 0.003, 0.1};
    if (unequal && i > 0) {
      const double t = i;
      b = {b.mass * (1 + 0.3 * t), b.race_radius * (1 - 0.05 * t), b.radius, i == 1 ? 1.0 : 1.4,
           b.mu * (1 + 0.5 * t),   b.d * (1 + 0.7 * t),             b.mu_c * (1 + 0.4 * t),
           b.mu_s * (1 + 0.2 * t), b.v_s * (1 - 0.3 * t)};
    }
    p.balls[std::size_t(i)] = b;
  }
  return p;
}

// Natural scale of each state component (row weights of the error norms).
template <int N>
State<double, N> natural_scale(const ParamsT<double, N>& p) {
  const double d = displacement_scale(p);
  State<double, N> w = State<double, N>::Ones();
  w.template head<2>().setConstant(d);
  w.template segment<2>(N + 2).setConstant(p.omega * d);
  w.template tail<N>().setConstant(p.omega);
  return w;
}

// Length over which f varies in ball rate i at beta_dot = v: the arctan changes over
// sqrt(v^2 + 1/kappa^2), the Stribeck exponential over v_s; otherwise f is quadratic in
// beta_dot (centrifugal (beta_dot + omega)^2) and omega is the scale.
template <int N>
double rate_scale(const ParamsT<double, N>& p, int i, double v) {
  switch (p.law) {
    case FrictionLaw::coulomb: return std::hypot(v, 1 / p.kappa);
    case FrictionLaw::stribeck: return std::min(std::hypot(v, 1 / p.kappa), p.balls[std::size_t(i)].v_s);
    default: return p.omega;
  }
}

// Off-equilibrium state: |q| up to twice the displacement scale, any angles, rotor rates
// up to omega times that, ball rates of both signs log-uniform in [0.1/kappa, 0.3] rad/s
// (through the arctan knee and the Stribeck drop v_s = 0.1 alike).
template <int N>
State<double, N> random_state(const ParamsT<double, N>& p, std::mt19937& rng) {
  std::uniform_real_distribution<double> sym(-1, 1), angle(0, 2 * kPi), lg(std::log(0.1 / p.kappa), std::log(0.3));
  const double d = displacement_scale(p);
  State<double, N> x;
  for (int i = 0; i < 2; ++i) x(i) = 2 * d * sym(rng), x(N + 2 + i) = p.omega * d * sym(rng);
  for (int i = 0; i < N; ++i) x(2 + i) = angle(rng), x(N + 4 + i) = std::copysign(std::exp(lg(rng)), sym(rng));
  return x;
}

// max_j ||W^-1 (test_j - ref_j)|| / ||W^-1 ref_j|| over the columns.
template <class Mat, class Vec>
double max_column_error(const Mat& ref, const Mat& test, const Vec& w) {
  double worst = 0;
  for (Eigen::Index j = 0; j < ref.cols(); ++j) {
    const double norm = ref.col(j).cwiseQuotient(w).norm();
    worst = std::max(worst, (test.col(j) - ref.col(j)).cwiseQuotient(w).norm() / norm);
  }
  return worst;
}

template <int N>
StateMatrix<double, N> complex_step_jacobian(const ParamsT<double, N>& p, const State<double, N>& x) {
  const auto pc = p.template cast<cplx>();
  StateMatrix<double, N> J;
  for (int j = 0; j < x.size(); ++j) {
    State<cplx, N> xc = x.template cast<cplx>();
    const double h = 1e-30 * std::max(1.0, std::abs(x(j)));
    xc(j) += cplx(0, h);
    J.col(j) = vector_field(pc, xc).imag() / h;
  }
  return J;
}

// Central differences with h_j = cbrt(eps) * scale_j. Truncation error is
// (h/L)^2/6 ~ eps^(2/3) = 4e-11 relative times the third-derivative ratio of the
// nonlinearity (O(1) for atan and exp at their own scale L); rounding error is
// eps ||f|| / h_j. `budget` receives, per column, 1e-6 (truncation with four orders of
// margin) plus 100 eps ||f|| / (h_j ||J_j||) (rounding, with margin for the A solve).
template <int N>
StateMatrix<double, N> central_difference_jacobian(const ParamsT<double, N>& p, const State<double, N>& x,
                                                   const StateMatrix<double, N>& ref, State<double, N>& budget) {
  const State<double, N> w = natural_scale(p);
  State<double, N> step = w;
  for (int i = 0; i < N; ++i) step(N + 4 + i) = rate_scale(p, i, x(N + 4 + i));
  const double fnorm = vector_field(p, x).cwiseQuotient(w).norm();
  StateMatrix<double, N> J;
  for (int j = 0; j < x.size(); ++j) {
    State<double, N> xp = x, xm = x;
    xp(j) += std::cbrt(kEps) * step(j);
    xm(j) -= std::cbrt(kEps) * step(j);
    const double h = (xp(j) - xm(j)) / 2;  // the step actually taken
    J.col(j) = (vector_field(p, xp) - vector_field(p, xm)) / (2 * h);
    budget(j) = 1e-6 + 100 * kEps * fnorm / (h * ref.col(j).cwiseQuotient(w).norm());
  }
  return J;
}

// Runs checks (1a) and (1b) at `count` random states.
template <int N>
void check_jacobian(const ParamsT<double, N>& p, std::mt19937& rng, int count) {
  const State<double, N> w = natural_scale(p);
  for (int k = 0; k < count; ++k) {
    const State<double, N> x = random_state(p, rng);
    INFO("state " << k << ": " << x.transpose());
    const StateMatrix<double, N> J = jacobian(p, x);
    // Complex step has no subtractive cancellation: its only error is rounding in the
    // evaluation of f, as is the analytic formula's; 1e-13 is ~500 eps (seen: < 1e-15).
    CHECK(max_column_error(J, complex_step_jacobian(p, x), w) < 1e-13);
    State<double, N> budget;
    const StateMatrix<double, N> Jfd = central_difference_jacobian(p, x, J, budget);
    for (int j = 0; j < x.size(); ++j) {
      INFO("column " << j);
      CHECK((Jfd.col(j) - J.col(j)).cwiseQuotient(w).norm() / J.col(j).cwiseQuotient(w).norm() < budget(j));
    }
  }
}

// Mutable access to the parameter a ParamRef names, for any scalar (ball b).
template <class T, int N>
T& field(ParamsT<T, N>& p, Quantity q, int b) {
  auto& ball = p.balls[std::size_t(b)];
  switch (q) {
    case Quantity::omega: return p.omega;
    case Quantity::unbalance: return p.rotor.unbalance;
    case Quantity::stiffness: return p.rotor.stiffness;
    case Quantity::damping: return p.rotor.damping;
    case Quantity::rotor_mass: return p.rotor.mass;
    case Quantity::kappa: return p.kappa;
    case Quantity::ball_mass: return ball.mass;
    case Quantity::race_radius: return ball.race_radius;
    case Quantity::ball_radius: return ball.radius;
    case Quantity::mu: return ball.mu;
    case Quantity::d: return ball.d;
    case Quantity::mu_c: return ball.mu_c;
    case Quantity::mu_s: return ball.mu_s;
    case Quantity::v_s: return ball.v_s;
    case Quantity::sigma0: return ball.sigma0;
    case Quantity::sigma1: return ball.sigma1;
    case Quantity::sigma2: return ball.sigma2;
    case Quantity::density: return ball.density;
    case Quantity::rolling_length: return ball.rolling_length;
    case Quantity::surface_radius: return ball.surface_radius;
  }
  return p.omega;
}

// The single references a reference stands for: every ball for `m`, `mu`, ...
std::vector<ParamRef> components(ParamRef ref, int n_balls) {
  if (!is_per_ball(ref.quantity) || ref.ball >= 0) return {ref};
  std::vector<ParamRef> out;
  for (int i = 0; i < n_balls; ++i) out.push_back({ref.quantity, i});
  return out;
}

// dF/dmu_c = -N (1 - e) sign with e = exp(-(v/v_s)^2): the library and the complex step
// alike form 1 - e from a rounded e, which costs eps e / (1 - e) relative when
// |v| << v_s (inherent to that form; tiny in absolute terms). The extra tolerance.
template <int N>
double mu_c_rounding(const ParamsT<double, N>& p, const State<double, N>& x, ParamRef ref) {
  if (ref.quantity != Quantity::mu_c) return 0;
  double worst = 0;
  for (const ParamRef one : components(ref, N)) {
    const double v = x(N + 4 + one.ball) / p.balls[std::size_t(one.ball)].v_s;
    worst = std::max(worst, std::exp(-v * v) / -std::expm1(-v * v));
  }
  return 4 * kEps * worst;
}

const char* const kSymbols[] = {"omega", "U",  "k",  "c",  "M_r", "m",     "m1",   "m2",   "l",    "l1",   "l2",
                                "r",     "mu", "mu1", "mu2", "d",   "d2",    "kappa", "mu_c", "mu_c1", "mu_s", "mu_s2",
                                "v_s",   "v_s1"};

}  // namespace

TEST_CASE("analytic Jacobian matches complex-step and central differences off equilibrium", "[model]") {
  const Case c = GENERATE(from_range(kCases));
  const bool unequal = GENERATE(false, true);
  INFO(describe(c, unequal));
  std::mt19937 rng(20240601u + unsigned(c.law) * 10u + unsigned(unequal));
  check_jacobian(make_params<2>(c, unequal), rng, 25);
}

TEST_CASE("analytic Jacobian for three unequal balls", "[model]") {
  const Case c = GENERATE(from_range(kCases));
  INFO(describe(c, true));
  std::mt19937 rng(77u);
  check_jacobian(make_params<3>(c, true), rng, 20);
}

TEST_CASE("the off-equilibrium term (dA/ds) s'' is included and matters", "[model]") {
  const Case c = GENERATE(from_range(kCases));
  INFO(describe(c, true));
  const auto p = make_params<2>(c, true);
  const auto pc = p.cast<cplx>();
  const State<double, 2> w = natural_scale(p);
  std::mt19937 rng(4242u);
  for (int k = 0; k < 20; ++k) {
    const State<double, 2> x = random_state(p, rng);
    INFO("state " << k << ": " << x.transpose());
    const Linearization<double, 2> lin = linearize(p, x);
    const StateMatrix<double, 2> J = jacobian(p, x);
    // Same linearization, Schur-complement solve vs LU: both backward stable, so they
    // agree to rounding; 1e-14 is ~50 eps.
    CHECK(max_column_error(J, jacobian(lin), w) < 1e-14);
    // (dA/ds) s'' built independently: dA/dbeta_j by complex step of mass_matrix (exact
    // to rounding), times the accelerations of vector_field.
    const Coordinates<double, 2> accel = vector_field(p, x).tail<4>();
    DofMatrix<double, 2> dA_accel = DofMatrix<double, 2>::Zero();
    for (int j = 2; j < 4; ++j) {
      Coordinates<cplx, 2> s = x.head<4>().cast<cplx>();
      s(j) += cplx(0, 1e-30);
      dA_accel.col(j) = mass_matrix<cplx, 2>(pc, s).imag() / 1e-30 * accel;
    }
    Linearization<double, 2> at_equilibrium_form = lin;
    at_equilibrium_form.stiffness -= dA_accel;
    const StateMatrix<double, 2> Jcs = complex_step_jacobian(p, x);
    CHECK(max_column_error(Jcs, J, w) < 1e-13);  // as in the Jacobian test
    // Without the term the beta columns are off by A^-1 (dA/ds) s''/|column|, of order
    // |s''_beta| / omega^2 ~ 1e-3 here: 1e-6 is far below that and far above rounding.
    CHECK(max_column_error(Jcs, jacobian(at_equilibrium_form), w) > 1e-6);
  }
}

TEST_CASE("parameter derivatives match complex-step and central differences", "[model]") {
  const Case c = GENERATE(from_range(kCases));
  INFO(describe(c, true));
  const auto p = make_params<2>(c, true);
  const State<double, 2> w = natural_scale(p);
  std::mt19937 rng(99u + unsigned(c.law));
  for (int k = 0; k < 10; ++k) {
    const State<double, 2> x = random_state(p, rng);
    const double fnorm = vector_field(p, x).cwiseQuotient(w).norm();
    INFO("state " << k << ": " << x.transpose());
    for (const char* symbol : kSymbols) {
      const ParamRef ref = *parse_param(symbol, 2);
      if (!law_uses(c.law, ref.quantity)) continue;
      INFO("parameter " << symbol);
      const State<double, 2> df = parameter_derivative(p, x, ref);
      if (ref.quantity == Quantity::ball_radius) {
        CHECK(df.isZero(0));  // r does not enter model.md §3: exactly zero
        continue;
      }
      // Complex step: the same i h added to every ball the reference names.
      auto pc = p.cast<cplx>();
      const double h = 1e-30 * std::abs(get(p, ref));
      for (const ParamRef one : components(ref, 2)) field(pc, one.quantity, std::max(one.ball, 0)) += cplx(0, h);
      const State<double, 2> dfcs = vector_field(pc, State<cplx, 2>(x.cast<cplx>())).imag() / h;
      const double norm = df.cwiseQuotient(w).norm();
      CHECK(norm > 0);
      // As for the Jacobian, plus the rounding of 1 - e for mu_c (see mu_c_rounding).
      CHECK((dfcs - df).cwiseQuotient(w).norm() / norm < 1e-13 + mu_c_rounding(p, x, ref));
      // Central differences through `set`, one ball at a time (every-ball: their sum),
      // step cbrt(eps) |p|; budget as in central_difference_jacobian.
      State<double, 2> dffd = State<double, 2>::Zero();
      double budget = 1e-6;
      for (const ParamRef one : components(ref, 2)) {
        const double value = get(p, one), step = std::cbrt(kEps) * std::abs(value);
        auto pp = p, pm = p;
        set(pp, one, value + step);
        set(pm, one, value - step);
        const double hh = (get(pp, one) - get(pm, one)) / 2;
        dffd += (vector_field(pp, x) - vector_field(pm, x)) / (2 * hh);
        budget += 100 * kEps * fnorm / (hh * norm);
      }
      CHECK((dffd - df).cwiseQuotient(w).norm() / norm < budget);
    }
  }
}

TEST_CASE("field_derivatives equals vector_field, jacobian and parameter_derivative", "[model]") {
  // The fused evaluation of the cycle shooting (model.md §17.9) only shares sin/cos and
  // s'' = A^-1 b between the three, in the same operations: equal values (bitwise with this
  // build; 1e-14 relative to each quantity's norm in natural units leaves room for a compiler
  // contracting the two paths differently into FMAs). An index or sign slip would be O(1).
  const Case c = GENERATE(from_range(kCases));
  INFO(describe(c, true));
  const auto p = make_params<2>(c, true);
  const State<double, 2> w = natural_scale(p);
  std::mt19937 rng(7u + unsigned(c.law));
  for (int k = 0; k < 6; ++k) {
    const State<double, 2> x = random_state(p, rng);
    INFO("state " << k << ": " << x.transpose());
    for (const char* symbol : {"omega", "m", "mu", "c", "U"}) {
      const ParamRef ref = *parse_param(symbol, 2);
      INFO("parameter " << symbol);
      const FieldDerivatives<double, 2> d = field_derivatives(p, x, ref);
      const State<double, 2> f = vector_field(p, x);
      CHECK((d.field - f).cwiseQuotient(w).norm() <= 1e-14 * f.cwiseQuotient(w).norm());
      const StateMatrix<double, 2> J = jacobian(p, x);
      const StateMatrix<double, 2> Jw = w.cwiseInverse().asDiagonal() * J * w.asDiagonal();
      const StateMatrix<double, 2> dJw = w.cwiseInverse().asDiagonal() * (d.jacobian - J) * w.asDiagonal();
      CHECK(dJw.norm() <= 1e-14 * Jw.norm());
      const State<double, 2> fp = parameter_derivative(p, x, ref);
      CHECK((d.parameter_derivative - fp).cwiseQuotient(w).norm() <= 1e-14 * fp.cwiseQuotient(w).norm());
    }
  }
}

TEST_CASE("friction laws follow model.md section 4", "[model]") {
  const Case c = GENERATE(from_range(kCases));
  INFO(describe(c, true));
  const auto p = make_params<2>(c, true);
  const auto pc = p.cast<cplx>();
  std::mt19937 rng(5u);
  std::uniform_real_distribution<double> sym(-1, 1), lg(std::log(0.01 / c.kappa), std::log(3.0));
  for (int i = 0; i < 2; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const double normal = b.mass * b.race_radius * p.omega * p.omega;  // N_i = m_i l_i omega^2
    INFO("ball " << i);
    // The table of §4, written out here independently of friction.cpp.
    const auto expected = [&](double v) {
      const double sgn = 2 / kPi * std::atan(p.kappa * v);
      switch (c.law) {
        case FrictionLaw::none: return 0.0;
        case FrictionLaw::viscous: return -b.d * b.race_radius * v;
        case FrictionLaw::coulomb: return -b.mu * normal * sgn;
        case FrictionLaw::stribeck:
          return -normal * (b.mu_c + (b.mu_s - b.mu_c) * std::exp(-(v / b.v_s) * (v / b.v_s))) * sgn;
        case FrictionLaw::lugre: break;  // not a function of beta_dot alone (test_lugre.cpp)
        case FrictionLaw::coulomb_set: break;  // not a vector field (model.md §4): no force law
      }
      return 0.0;
    };
    for (int k = 0; k < 50; ++k) {
      const double v = std::copysign(std::exp(lg(rng)), sym(rng));
      INFO("beta_dot = " << v);
      // Same formula, other evaluation order: a few roundings, 1e-14 relative.
      CHECK(friction_force(p, i, v) == Approx(expected(v)).epsilon(1e-14).margin(0));
      // The slope against complex step of the force (no cancellation; rounding only).
      const double h = 1e-30 * std::max(1.0, std::abs(v));
      const double slope_cs = friction_force(pc, i, cplx(v, h)).imag() / h;
      CHECK(friction_slope(p, i, v) == Approx(slope_cs).epsilon(1e-13).margin(0));
    }
    // Smooth laws never move an equilibrium: F(0) = 0 exactly.
    CHECK(friction_force(p, i, 0.0) == 0.0);
    // Slope at rest (§4, §7): coulomb -(2/pi) mu N kappa; stribeck that with mu = mu_s.
    const double mu0 = c.law == FrictionLaw::coulomb ? b.mu : b.mu_s;
    const double slope0 = c.law == FrictionLaw::viscous ? -b.d * b.race_radius
                          : c.law == FrictionLaw::none  ? 0.0
                                                        : -(2 / kPi) * mu0 * normal * p.kappa;
    CHECK(friction_slope(p, i, 0.0) == Approx(slope0).epsilon(1e-15).margin(0));  // a few roundings
    if (c.law == FrictionLaw::stribeck) {
      auto pcoul = p;
      pcoul.law = FrictionLaw::coulomb;
      for (auto& ball : pcoul.balls) ball.mu = ball.mu_s;
      CHECK(friction_slope(p, i, 0.0) == Approx(friction_slope(pcoul, i, 0.0)).epsilon(1e-15).margin(0));
    }
  }
}

TEST_CASE("mass matrix is SPD and the accelerations solve A s'' = b", "[model]") {
  const Case c = GENERATE(from_range(kCases));
  INFO(describe(c, true));
  const auto p = make_params<2>(c, true);
  std::mt19937 rng(11u);
  for (int k = 0; k < 25; ++k) {
    const State<double, 2> x = random_state(p, rng);
    INFO("state " << k << ": " << x.transpose());
    const DofMatrix<double, 2> A = mass_matrix<double, 2>(p, x.head<4>());
    CHECK(A == A.transpose());  // built symmetric, exactly
    CHECK(A.llt().info() == Eigen::Success);
    CHECK(Eigen::SelfAdjointEigenSolver<DofMatrix<double, 2>>(A).eigenvalues().minCoeff() > 0);
    // Componentwise backward error of the solve: |A s'' - b|_i against the size of the
    // terms that make row i, sum_j |A_ij s''_j| + |b_i|. A stable solve leaves a few eps.
    const Coordinates<double, 2> accel = vector_field(p, x).tail<4>();
    const Coordinates<double, 2> b = generalized_forces(p, x);
    const Coordinates<double, 2> size = A.cwiseAbs() * accel.cwiseAbs() + b.cwiseAbs();
    CHECK((A * accel - b).cwiseAbs().cwiseQuotient(size).maxCoeff() < 1e-14);
    CHECK(vector_field(p, x).head<4>() == x.tail<4>());  // s' is copied, exactly
  }
}

TEST_CASE("long double and double evaluate the same equations", "[model]") {
  const Case c = GENERATE(from_range(kCases));
  INFO(describe(c, true));
  const auto p = make_params<2>(c, true);
  const auto pl = p.cast<long double>();
  const State<double, 2> w = natural_scale(p);
  std::mt19937 rng(13u);
  std::uniform_int_distribution<int> turns(-5, 5);
  for (int k = 0; k < 20; ++k) {
    State<double, 2> x = random_state(p, rng);
    // Angles also outside [0, 2 pi) (integrations wind up): any turn, either sign.
    for (int i = 2; i < 4; ++i) x(i) += 2 * kPi * turns(rng);
    INFO("state " << k << ": " << x.transpose());
    const State<long double, 2> xl = x.cast<long double>();
    // Double rounding against 64-bit-mantissa rounding of the same formulas: the
    // difference is the double evaluation's own error, a few eps; 1e-14 relative.
    const State<double, 2> f = vector_field(p, x);
    const State<double, 2> fl = vector_field(pl, xl).cast<double>();
    CHECK((f - fl).cwiseQuotient(w).norm() / fl.cwiseQuotient(w).norm() < 1e-14);
    CHECK(max_column_error(StateMatrix<double, 2>(jacobian(pl, xl).cast<double>()), jacobian(p, x), w) < 1e-14);
  }
}
