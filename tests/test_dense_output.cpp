// The dense output of `simulate` (model.md §15.1, §15.4) on functions known in closed form:
// the quintic Hermite interpolant's order, its error estimates against the true error, and the
// located maximum of |q| against the analytic one.
#include <catch2/catch.hpp>

#include <cmath>

#include "../src/dynamics/dense_output.hpp"  // internal to the dynamics layer

using namespace abu;

namespace {

// y = (cos(w t), 0.5 sin(1.3 w t)) with y' and y'' in closed form.
constexpr double w = 7.0;
void exact(double t, double* y, double* f, double* g) {
  y[0] = std::cos(w * t), f[0] = -w * std::sin(w * t), g[0] = -w * w * std::cos(w * t);
  const double v = 1.3 * w;
  y[1] = 0.5 * std::sin(v * t), f[1] = 0.5 * v * std::cos(v * t), g[1] = -0.5 * v * v * std::sin(v * t);
}

dense::Step step_of(double t0, double h) {
  dense::Step s;
  s.dim = 2;
  s.t0 = t0, s.t1 = t0 + h;
  exact(s.t0, s.y0, s.f0, s.g0);
  exact(s.t1, s.y1, s.f1, s.g1);
  return s;
}

double max_error(const dense::Step& s) {
  double worst = 0, x[2], y[2], f[2], g[2];
  for (int k = 0; k <= 200; ++k) {
    const double t = s.t0 + (s.t1 - s.t0) * k / 200;
    s.state_at(t, x);
    exact(t, y, f, g);
    worst = std::max({worst, std::abs(x[0] - y[0]), std::abs(x[1] - y[1])});
  }
  return worst;
}

}  // namespace

TEST_CASE("dense output: the quintic Hermite interpolant is of order 6, its estimates follow its error",
          "[simulation][dense]") {
  const auto unit = [](int, double) { return 1.0; };  // tolerance 1: the estimates themselves
  const double t0 = 0.3;
  double previous = 0;
  for (double h : {0.08, 0.04, 0.02}) {
    const dense::Step s = step_of(t0, h);
    double x[2], y[2], f[2], g[2];
    s.state_at(s.t1, x);
    exact(s.t1, y, f, g);
    CHECK(x[0] == y[0]);  // the step's end exactly, not through the basis
    const double err = max_error(s);
    // (15.1.3): error = y^(6)(xi) h^6 s^3 (1 - s)^3 / 720, so halving h divides it by 2^6 = 64
    // up to the change of y^(6) over the step (h w <= 0.56 here: within 30 %).
    if (previous > 0) CHECK(previous / err == Approx(64).epsilon(0.3));
    previous = err;
    // (15.1.4) from the state one step back: the sixth divided difference estimates y^(6) / 720,
    // so the estimate matches the error at mid-step to the same 30 %; (15.1.5) bounds it.
    double yp[2], fp[2], gp[2];
    exact(t0 - h, yp, fp, gp);
    const double sixth = s.error_ratio(t0 - h, yp, unit);
    const double cubic = s.cubic_ratio(unit);
    INFO("h = " << h << ": error " << err << ", estimate " << sixth << ", cautious " << cubic);
    CHECK(sixth == Approx(err).epsilon(0.3));
    CHECK(cubic > 3 * err);
  }
}

TEST_CASE("dense output: the largest |q| inside a step is located to the interpolant's accuracy",
          "[simulation][dense]") {
  // q = r(t) (cos w t, sin w t), r = 1 + 0.1 cos(nu (t - tp)): |q| = r, its maximum 1.1 at tp.
  const double nu = 2.0, tp = 0.4137;
  const auto q_exact = [&](double t, double* y, double* f, double* g) {
    const double r = 1 + 0.1 * std::cos(nu * (t - tp)), r1 = -0.1 * nu * std::sin(nu * (t - tp)),
                 r2 = -0.1 * nu * nu * std::cos(nu * (t - tp));
    const double c = std::cos(w * t), s = std::sin(w * t);
    y[0] = r * c, f[0] = r1 * c - r * w * s, g[0] = r2 * c - 2 * r1 * w * s - r * w * w * c;
    y[1] = r * s, f[1] = r1 * s + r * w * c, g[1] = r2 * s + 2 * r1 * w * c - r * w * w * s;
  };
  dense::Step s;
  s.dim = 2;
  s.t0 = 0.40, s.t1 = 0.43;
  q_exact(s.t0, s.y0, s.f0, s.g0);
  q_exact(s.t1, s.y1, s.f1, s.g1);
  const dense::QPeak pk = s.q_peak(s.t0, s.t1, s.y0, s.y1);
  // The interpolant's error here is at most (h (w + nu))^6 / 46080 |q| = 1e-8 (h = 0.03): the
  // value to that, the time to where r stays within it of 1.1, sqrt(2 * 1e-8 / (0.1 nu^2)) = 2.2e-4 s.
  CHECK(pk.q_abs == Approx(1.1).epsilon(1e-8));
  CHECK(std::abs(pk.t - tp) < 2.2e-4);
  // Only a part of the step, ending before the maximum: the largest |q| is that part's end.
  double x[2];
  s.state_at(0.41, x);
  const dense::QPeak part = s.q_peak(s.t0, 0.41, s.y0, x);
  CHECK(part.t == 0.41);
  CHECK(part.q_abs == std::hypot(x[0], x[1]));
}

TEST_CASE("dense output: the samples' clock gives every k * every and t_end once", "[simulation][dense]") {
  dense::SampleClock clock{0.3, 1.0};
  std::vector<double> times;
  for (double t = clock.next(); std::isfinite(t); t = clock.next()) clock.taken(t), times.push_back(t);
  REQUIRE(times.size() == 4);
  CHECK(times[2] == 0.8999999999999999);  // 3 * 0.3 in doubles, as the samples' times are formed
  CHECK(times[3] == 1.0);
}
