// Simulation (model.md §9, §15): the run-up terms' derivatives, conservation of the Jacobi
// integral, the observed order of convergence, the decay of a perturbed equilibrium at its
// rightmost eigenvalue's rate, omega' = 0 run-up = constant speed, samples between steps against
// runs that end there, the speed profiles.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <random>

#include "abu/core/errors.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/scan.hpp"

using namespace abu;

namespace {

Scene default_scene() { return load_scene(std::string(ABU_SOURCE_DIR) + "/data/scenes/default.toml"); }

template <int N>
State<double, N> random_state(const ParamsT<double, N>& p, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = ball_count(p);
  const double L = displacement_scale(p);
  State<double, N> x(2 * n + 4);
  x(0) = L * u(rng), x(1) = L * u(rng);
  for (int i = 0; i < n; ++i) x(2 + i) = 3 * u(rng), x(n + 4 + i) = 0.05 * u(rng);
  x(n + 2) = L * p.omega * u(rng), x(n + 3) = L * p.omega * u(rng);
  return x;
}

// The scaled max-norm error used everywhere in model.md §15.1.
template <int N>
double scaled_error(const ParamsT<double, N>& p, const State<double, N>& a, const State<double, N>& b, double w) {
  const int n = ball_count(p);
  const double L = displacement_scale(p);
  double e = 0;
  for (int i = 0; i < 2 * n + 4; ++i) {
    const bool angle = i >= 2 && i < n + 2, vel = i >= n + 2, rotor = i < 2 || (i >= n + 2 && i < n + 4);
    const double s = angle ? 1.0 : (rotor ? L : 1.0) * (vel ? w : 1.0);
    e = std::max(e, std::abs(a(i) - b(i)) / s);
  }
  return e;
}

// Kinetic energy in the fixed frame (model.md §3 kinematics, §9's ball spin energy) and the
// support's potential; for c = 0 and friction none at constant omega the Jacobi integral
// h = T2 - T0 + V is conserved (T split by degree in the rotating-frame velocities).
template <int N>
double kinetic(const ParamsT<double, N>& p, const State<double, N>& x) {
  const int n = ball_count(p);
  using C = std::complex<double>;
  const C I(0, 1);
  const double w = p.omega;
  const C q(x(0), x(1)), qd(x(n + 2), x(n + 3));
  const double eps = p.rotor.unbalance / p.rotor.mass;  // rotor centre of mass on a1
  double T = 0.5 * p.rotor.mass * std::norm(qd + I * w * (q + eps));
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const double bd = x(n + 4 + i);
    const C v = qd + I * w * q + I * b.race_radius * (bd + w) * std::exp(I * x(2 + i));
    const double spin_inertia = (b.inertia_factor - 1) * b.mass * b.radius * b.radius;
    T += 0.5 * b.mass * std::norm(v) + 0.5 * spin_inertia * std::pow(w - b.race_radius / b.radius * bd, 2);
  }
  return T;
}
template <int N>
double jacobi_integral(const ParamsT<double, N>& p, const State<double, N>& x) {
  const int n = ball_count(p);
  State<double, N> minus = x, rest = x;
  minus.tail(n + 2) = -x.tail(n + 2);
  rest.tail(n + 2).setZero();
  const double V = 0.5 * p.rotor.stiffness * (x(0) * x(0) + x(1) * x(1));
  return 0.5 * (kinetic(p, x) + kinetic(p, minus)) - 2 * kinetic(p, rest) + V;
}

}  // namespace

TEST_CASE("run-up: omega' = 0 is the constant-speed vector field exactly", "[simulation][model]") {
  const Params p = params_of<2>(default_scene());
  std::mt19937 rng(7);
  for (int k = 0; k < 20; ++k) {
    const State<double, 2> x = random_state(p, rng);
    CHECK(vector_field(p, x, 0.0) == vector_field(p, x));
    CHECK(jacobian(p, x, 0.0) == jacobian(p, x));
  }
}

TEST_CASE("run-up: Jacobian and df/domega' against the complex step (model.md §9)", "[simulation][model]") {
  using cplx = std::complex<double>;
  Scene scene = default_scene();
  for (int n : {2, 4}) {
    Scene s = scene;
    s.balls.resize(std::size_t(n), scene.balls[0]);
    for (int i = 0; i < n; ++i) s.balls[std::size_t(i)].mass *= 1 + 0.1 * i;  // unequal balls
    const ParamsN p = params_of<any_balls>(s);
    const ParamsT<cplx, any_balls> pc = p.cast<cplx>();
    std::mt19937 rng(11 + n);
    for (double wd : {300.0, -2000.0}) {
      for (int k = 0; k < 5; ++k) {
        const State<double, any_balls> x = random_state(p, rng);
        const StateMatrix<double, any_balls> J = jacobian(p, x, wd);
        const double h = 1e-30;
        double worst = 0;
        for (int j = 0; j < x.size(); ++j) {
          State<cplx, any_balls> xc = x.cast<cplx>();
          xc(j) += cplx(0, h);
          const State<double, any_balls> col = vector_field(pc, xc, cplx(wd)).imag() / h;
          const double scale = std::max(1.0, col.cwiseAbs().maxCoeff());
          worst = std::max(worst, (J.col(j) - col).cwiseAbs().maxCoeff() / scale);
        }
        // Complex step is exact to rounding; J's entries are sums of O(10) products.
        CHECK(worst < 1e-12);
        const State<double, any_balls> dfw = angular_acceleration_derivative(p, x);
        const State<double, any_balls> cs =
            vector_field(pc, State<cplx, any_balls>(x.cast<cplx>()), cplx(wd, 1e-30)).imag() / 1e-30;
        CHECK((dfw - cs).cwiseAbs().maxCoeff() <= 1e-12 * std::max(1.0, cs.cwiseAbs().maxCoeff()));
        // f is affine in omega' (model.md §9).
        const State<double, any_balls> f0 = vector_field(p, x, 0.0), f1 = vector_field(p, x, wd);
        CHECK((f1 - f0 - wd * dfw).cwiseAbs().maxCoeff() <= 1e-9 * std::max(1.0, f1.cwiseAbs().maxCoeff()));
      }
    }
  }
}

TEST_CASE("simulation: the Jacobi integral is conserved when c = 0 and friction none", "[simulation]") {
  Scene scene = default_scene();
  scene.rotor.damping = 0;
  scene.law = FrictionLaw::none;
  scene.kappa = 0;
  for (auto& b : scene.balls) b.mu = 0;
  SimulationOptions o;
  o.t_end = 0.2;
  o.every = 1e-3;
  o.rtol = 1e-11;
  const auto speed = SpeedProfile::constant(900);
  {
    const Params p = params_of<2>(scene);
    const auto r = simulate(p, speed, start_at_rest(p, {2.0, 4.0}), o);
    REQUIRE(r.status == SimulationStatus::completed);
    CHECK(r.method == IntegrationMethod::rk8pd);  // not stiff without friction
    const double h0 = jacobi_integral(p, r.samples.front().x);
    // Scale: the balls' relative-motion energy is of order m l omega^2 L (their centrifugal
    // potential across the excursion); the drift must be a tolerance-level fraction of it.
    double energy_scale = 0;
    for (const auto& b : p.balls) energy_scale += b.mass * b.race_radius * p.omega * p.omega * displacement_scale(p);
    double drift = 0;
    for (const auto& s : r.samples) drift = std::max(drift, std::abs(jacobi_integral(p, s.x) - h0));
    INFO("drift " << drift << " J, scale " << energy_scale << " J");
    CHECK(drift < 1e-8 * energy_scale);
  }
  {  // any n: three balls on the bounded-dynamic path
    Scene s3 = scene;
    s3.balls.push_back(scene.balls[0]);
    const ParamsN p = params_of<any_balls>(s3);
    const auto r = simulate(p, speed, start_at_rest(p, {1.0, 2.5, 5.0}), o);
    REQUIRE(r.status == SimulationStatus::completed);
    const double h0 = jacobi_integral(p, r.samples.front().x);
    double energy_scale = 0;
    for (const auto& b : p.balls) energy_scale += b.mass * b.race_radius * p.omega * p.omega * displacement_scale(p);
    double drift = 0;
    for (const auto& s : r.samples) drift = std::max(drift, std::abs(jacobi_integral(p, s.x) - h0));
    CHECK(drift < 1e-8 * energy_scale);
  }
}

TEST_CASE("simulation: observed order of convergence", "[simulation]") {
  // Non-stiff viscous balls through omega_n: rk8pd's error falls like steps^-8 (order 8 of
  // the 8(9) pair); the BDF converges as its tolerance tightens.
  Scene scene = default_scene();
  scene.law = FrictionLaw::viscous;
  scene.kappa = 0;
  for (auto& b : scene.balls) b.mu = 0, b.d = 1e-4;
  const Params p = params_of<2>(scene);
  const auto speed = SpeedProfile::ramp(150, 350, 2000);
  SimulationOptions o;
  o.t_end = 0.15;
  o.record = false;
  o.method = IntegrationMethod::rk8pd;
  o.rtol = 1e-13;
  const State<double, 2> x0 = start_at_rest(p, {2.0, 4.0});
  const auto ref = simulate(p, speed, x0, o);
  REQUIRE(ref.status == SimulationStatus::completed);
  for (auto method : {IntegrationMethod::rk8pd, IntegrationMethod::bdf}) {
    std::vector<double> err, steps;
    for (double tol : {1e-6, 1e-8, 1e-10}) {
      o.method = method;
      o.rtol = tol;
      const auto r = simulate(p, speed, x0, o);
      REQUIRE(r.status == SimulationStatus::completed);
      err.push_back(scaled_error(p, r.x_end, ref.x_end, 350.0));
      steps.push_back(double(r.stats.steps));
      // Tolerance proportionality: the global error within three decades of the tolerance
      // for rk8pd; GSL's msbdf controls the local error of its variable-order BDF only, and
      // its global error on 8 whirl periods was measured at 300 .. 1000 times the tolerance.
      CHECK(err.back() < (method == IntegrationMethod::rk8pd ? 1e3 : 1e4) * tol);
    }
    const double order = -std::log(err.back() / err.front()) / std::log(steps.back() / steps.front());
    INFO(to_string(method) << ": errors " << err[0] << " " << err[1] << " " << err[2] << ", steps " << steps[0] << " "
                           << steps[1] << " " << steps[2] << ", observed order " << order);
    if (method == IntegrationMethod::rk8pd) {
      CHECK(order > 6.0);
      CHECK(order < 10.0);
    } else {
      // msbdf raises its order (1..5) as the tolerance tightens, so error against steps
      // falls faster than any one order; only convergence is a property here.
      CHECK(err[1] < err[0] / 10);
      CHECK(err[2] < err[1] / 10);
    }
  }
}

TEST_CASE("simulation: a perturbed equilibrium decays at its rightmost eigenvalue's rate", "[simulation]") {
  // Viscous balls (rates of order 1/s), above omega_n: the balanced state is stable.
  Scene scene = default_scene();
  scene.law = FrictionLaw::viscous;
  scene.kappa = 0;
  for (auto& b : scene.balls) b.mu = 0, b.d = 2e-3;
  scene.omega = 600;
  const Params p = params_of<2>(scene);
  const Analysis a = analyze(p);
  const auto& e = a.equilibria.points()[0];
  REQUIRE(e.family == Family::balanced);
  const auto& sp = a.spectra[0];
  const std::complex<double> lambda = sp.eigenvalues[0];
  INFO("rightmost eigenvalue " << lambda);
  REQUIRE(lambda.real() < 0);
  const double eps = 1e-6;
  const State<double, 2> x0 = perturbed_equilibrium(p, e.position_si(), lambda, sp.vectors[0], eps);
  // Compare distances a whole number of periods apart, where the mode's shape repeats.
  const double period = std::abs(lambda.imag()) > 0 ? 2 * M_PI / std::abs(lambda.imag()) : 0.1;
  const int per = 64, periods = std::max(1, int(std::ceil(2.0 / std::abs(lambda.real()) / period)));
  SimulationOptions o;
  o.every = period / per;
  o.t_end = o.every * per * periods;
  o.rtol = 1e-11;
  const auto r = simulate(p, SpeedProfile::constant(p.omega), x0, o);
  REQUIRE(r.status == SimulationStatus::completed);
  const State<double, 2> xe = at_rest<double, 2>(e.position_si());
  const auto dist = [&](std::size_t k) { return scaled_error(p, r.samples[k].x, xe, p.omega); };
  const std::size_t k1 = std::size_t(per), k2 = r.samples.size() - 1;
  const double rate = std::log(dist(k2) / dist(k1)) / (r.samples[k2].t - r.samples[k1].t);
  INFO("observed rate " << rate << " 1/s over " << r.samples[k2].t - r.samples[k1].t << " s");
  // Linear to O(eps) and the tolerance 1e-11 << eps e^{-2}: the rate to 1 %.
  CHECK(rate == Approx(lambda.real()).epsilon(0.01));
}

TEST_CASE("simulation: a run-up with omega' = 0 equals the constant-speed run", "[simulation]") {
  const Params p = params_of<2>(default_scene());
  SimulationOptions o;
  o.t_end = 0.1;
  o.every = 1e-3;
  o.rtol = 1e-10;
  const State<double, 2> x0 = start_at_rest(p, {2.0, 4.0});
  const auto constant = simulate(p, SpeedProfile::constant(900), x0, o);
  // A profile that holds 900 rad/s over three points: breakpoints restart the integrator.
  const auto flat = SpeedProfile::piecewise_linear({{0, 900}, {0.03, 900}, {0.07, 900}}, "test");
  const auto runup = simulate(p, flat, x0, o);
  REQUIRE(constant.status == SimulationStatus::completed);
  REQUIRE(runup.status == SimulationStatus::completed);
  REQUIRE(constant.samples.size() == runup.samples.size());
  CHECK(runup.stats.restarts == 2);
  double worst = 0;
  for (std::size_t k = 0; k < constant.samples.size(); ++k) {
    if (constant.samples[k].t <= 0.03) CHECK(constant.samples[k].x == runup.samples[k].x);  // the same computation
    worst = std::max(worst, scaled_error(p, constant.samples[k].x, runup.samples[k].x, 900.0));
  }
  CHECK(worst < 1e-7);  // two runs at tolerance 1e-10 (coulomb, stiff: errors grow ~ 1e2 times)
}

TEST_CASE("simulation: a sample between steps equals the end of a run to its time (dense output)", "[simulation]") {
  // model.md §15.1: a sample comes from the quintic Hermite interpolant of the step that holds it
  // (where the interpolant reaches it); a run whose t_end is the sample's time ends there
  // exactly, on its own steps. Both are within 10 rtol of the true state (the global error of the calibrated tolerance),
  // so within 20 rtol of each other; an interpolant of lower order (a cubic's error (h omega)^4 /
  // 384 is ~1e-3 at these steps, h omega ~ 1), or samples taken from the wrong step, miss by far more.
  const Scene viscous = load_scene(std::string(ABU_SOURCE_DIR) + "/data/scenes/viscous.toml");
  struct Case {
    Params p;
    SpeedProfile speed;
    IntegrationMethod method;
  };
  const Case cases[] = {{params_of<2>(default_scene()), SpeedProfile::constant(900), IntegrationMethod::bsimp},
                        {params_of<2>(viscous), SpeedProfile::ramp(100, 400, 1000), IntegrationMethod::rk8pd},
                        {params_of<2>(viscous), SpeedProfile::ramp(100, 400, 1000), IntegrationMethod::bsimp}};
  for (const auto& c : cases) {
    SimulationOptions o;
    o.rtol = 1e-9;
    o.method = c.method;
    o.t_end = 0.5;
    o.every = o.t_end / 7;  // sample times that are no breakpoint and no multiple of a step
    const State<double, 2> x0 = start_at_rest(c.p, {2.0, 4.0});
    const auto run = simulate(c.p, c.speed, x0, o);
    REQUIRE(run.status == SimulationStatus::completed);
    REQUIRE(run.method == c.method);
    REQUIRE(run.samples.size() == 8);
    for (std::size_t k = 1; k + 1 < run.samples.size(); ++k) {
      SimulationOptions to = o;
      to.t_end = run.samples[k].t;
      to.record = false;
      const auto end = simulate(c.p, c.speed, x0, to);
      const double e = scaled_error(c.p, run.samples[k].x, end.x_end, c.speed.max_omega());
      INFO(to_string(c.method) << " sample at t = " << to.t_end << ": " << e << " (scaled)");
      CHECK(e <= 20 * o.rtol);
    }
  }
}

TEST_CASE("speed profiles: ramps, files, crossings and bad input", "[simulation]") {
  const auto r = SpeedProfile::ramp(100, 400, 200);
  CHECK(r.omega(0) == 100);
  CHECK(r.omega(0.5) == Approx(200));
  CHECK(r.omega_dot(0.5) == 200);
  CHECK(r.omega(10) == 400);
  CHECK(r.omega_dot(10) == 0);
  CHECK(r.angle(1.5) == Approx(100 * 1.5 + 0.5 * 200 * 1.5 * 1.5));
  CHECK(r.angle(2.0) == Approx(100 * 1.5 + 0.5 * 200 * 1.5 * 1.5 + 400 * 0.5));
  REQUIRE(r.crossings(250, 5).size() == 1);
  CHECK(r.crossings(250, 5)[0] == Approx(0.75));
  const auto down = SpeedProfile::parse_ramp("400:100:300");
  CHECK(down.omega_dot(0.1) == -300);
  CHECK_THROWS_AS(SpeedProfile::parse_ramp("100:-5:10"), InputError);
  CHECK_THROWS_AS(SpeedProfile::parse_ramp("100:0:10"), InputError);  // a ramp ends at omega > 0
  const auto from_rest = SpeedProfile::parse_ramp("0:100:10");          // and may start at rest
  CHECK(from_rest.omega(0) == 0.0);
  CHECK(from_rest.omega(5) == Approx(50));
  CHECK(from_rest.end_of_change() == Approx(10));
  // Typed in rpm (the factor 2 pi / 60 on every value): 600 rpm = 62.83 rad/s at 60 rpm/s.
  const auto rpm = SpeedProfile::parse_ramp("0:600:60", "--ramp", 2 * M_PI / 60);
  CHECK(rpm.omega(10) == Approx(20 * M_PI).epsilon(1e-14));
  CHECK(rpm.omega_dot(1) == Approx(2 * M_PI).epsilon(1e-14));
  CHECK_THROWS_AS(SpeedProfile::parse_ramp("100:200:0"), InputError);
  CHECK_THROWS_AS(SpeedProfile::parse_ramp("100:200"), InputError);
  CHECK_THROWS_AS(SpeedProfile::parse_ramp("100:200:5:6"), InputError);
  CHECK_THROWS_AS(SpeedProfile::piecewise_linear({{0, 100}, {0.5, 200}, {0.5, 300}}, "t"), InputError);
  CHECK_THROWS_AS(SpeedProfile::piecewise_linear({{0.1, 100}}, "t"), InputError);
  const Params p = params_of<2>(default_scene());
  SimulationOptions o;
  o.t_end = -1;
  CHECK_THROWS_AS(simulate(p, r, start_at_rest(p, {1, 2}), o), InputError);
  o.t_end = 1;
  const ParamsN pn = params_of<any_balls>(default_scene());
  o.t_end = 0.01;
  CHECK_THROWS_AS(simulate(pn, r, State<double, any_balls>(State<double, any_balls>::Zero(6)), o), InputError);
  CHECK_THROWS_AS(start_at_rest(p, {1, 2, 3}), InputError);
}
