// The outcome study (docs/model.md §21): the points of the design, the order-statistic and
// Wilson intervals against their definitions and by simulated coverage, the bare rotor against
// a time integration, and a study's runs against `simulate` from the same starts.
#include <catch2/catch.hpp>

#include <gsl/gsl_qrng.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

#include "abu/analysis/outcomes.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/sampling.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/input/scene.hpp"
#include "scene_texts.hpp"

using namespace abu;

namespace {

// The default scene (data/scenes/default.toml's values, scene_texts.hpp).
const std::string kDry = abu::testing::kBase;

// P(B = i), B ~ Binomial(n, p), summed in long double from lgamma: independent of GSL's cdf.
long double pmf(int n, int i, double p) {
  const long double l = std::lgamma((long double)n + 1) - std::lgamma((long double)i + 1) -
                        std::lgamma((long double)(n - i) + 1) + i * std::log((long double)p) +
                        (n - i) * std::log1p(-(long double)p);
  return std::exp(l);
}
long double cdf(int n, int k, double p) {
  long double s = 0;
  for (int i = 0; i <= k; ++i) s += pmf(n, i, p);
  return s;
}

}  // namespace

TEST_CASE("order-statistic ranks bound the quantile with the stated confidence, and no tighter pair does",
          "[outcomes][statistics]") {
  for (int n : {10, 20, 37, 64, 256, 1000})
    for (double p : {0.5, 0.9}) {
      const OrderRanks r = quantile_ranks(n, p, 0.95);
      INFO("n = " << n << ", p = " << p << ", ranks " << r.low << ", " << r.high);
      // Each tail at most 2.5 % (1e-12: summation error), and one rank further in exceeds it.
      if (r.low >= 1) {
        CHECK(cdf(n, r.low - 1, p) <= 0.025 + 1e-12);
        if (r.low < n) CHECK(cdf(n, r.low, p) > 0.025);
      } else {
        CHECK(cdf(n, 0, p) > 0.025);
      }
      if (r.high <= n) {
        CHECK(1 - cdf(n, r.high - 1, p) <= 0.025 + 1e-12);
        if (r.high > 1) CHECK(1 - cdf(n, r.high - 2, p) > 0.025);
      } else {
        CHECK(1 - cdf(n, n - 1, p) > 0.025);
      }
    }
  // n = 20, p = 0.9: no upper rank exists (P(B = 20) = 0.12 > 2.5 %).
  CHECK(quantile_ranks(20, 0.9, 0.95).high == 21);
}

TEST_CASE("the quantile intervals cover the true quantile in at least 95 % of samples", "[outcomes][statistics]") {
  // 4000 samples of 40 exponential values; the true median ln 2 and 90th percentile ln 10. The
  // coverage is at least 95 % by construction; 3 standard errors (0.010) below it fails.
  std::mt19937_64 rng(12345);
  std::exponential_distribution<double> e(1.0);
  int cover50 = 0, cover90 = 0, bounded90 = 0;
  const int trials = 4000;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> v(40);
    for (double& x : v) x = e(rng);
    const QuantileEstimate m = quantile_estimate(v, 0.5), q = quantile_estimate(v, 0.9);
    REQUIRE(m.low);
    REQUIRE(m.high);
    cover50 += *m.low <= std::log(2.0) && std::log(2.0) <= *m.high;
    if (q.low && q.high) {
      ++bounded90;
      cover90 += *q.low <= std::log(10.0) && std::log(10.0) <= *q.high;
    }
  }
  CHECK(double(cover50) / trials >= 0.95 - 0.010);
  CHECK(bounded90 == trials);  // 40 values bound the 90th percentile on both sides
  CHECK(double(cover90) / trials >= 0.95 - 0.010);
}

TEST_CASE("Wilson's interval solves its score equation at both ends", "[outcomes][statistics]") {
  const double z = 1.959963984540054;
  for (auto [k, n] : {std::pair{12, 256}, {0, 50}, {50, 50}, {1, 3}, {500, 1000}}) {
    const ProportionEstimate e = proportion_estimate(k, n);
    INFO(k << " of " << n << ": [" << e.low << ", " << e.high << "]");
    CHECK(e.value == Approx(double(k) / n));
    // (k/n - p)^2 = z^2 p (1 - p) / n at p = low and p = high (1e-12 absolute: rounding).
    for (double p : {e.low, e.high})
      CHECK(std::abs(std::pow(double(k) / n - p, 2) - z * z * p * (1 - p) / n) < 1e-12);
    CHECK(e.low <= e.value);
    CHECK(e.value <= e.high);
  }
  // 12 of 256: 4.69 % in [2.70, 8.01] % (scipy: the same formula, 0.0270149, 0.0801330).
  const ProportionEstimate e = proportion_estimate(12, 256);
  CHECK(e.low == Approx(0.0270149).epsilon(1e-5));
  CHECK(e.high == Approx(0.0801330).epsilon(1e-5));
}

TEST_CASE("the design's points: GSL's Sobol sequence shifted modulo 1, reproducible from the seed",
          "[outcomes][statistics]") {
  const auto a = sample_points(1024, 3, SampleDesign::sobol, 7), b = sample_points(1024, 3, SampleDesign::sobol, 7);
  CHECK(a == b);
  CHECK(a != sample_points(1024, 3, SampleDesign::sobol, 8));
  // The same sequence as GSL gives, up to one shift per coordinate.
  gsl_qrng* q = gsl_qrng_alloc(gsl_qrng_sobol, 3);
  std::vector<double> x(3), shift(3);
  for (int k = 0; k < 1024; ++k) {
    gsl_qrng_get(q, x.data());
    for (int d = 0; d < 3; ++d) {
      const double s = std::fmod(a[std::size_t(3 * k + d)] - x[std::size_t(d)] + 2.0, 1.0);
      if (k == 0) shift[std::size_t(d)] = s;
      CHECK(std::abs(std::remainder(s - shift[std::size_t(d)], 1.0)) < 1e-14);
      CHECK(a[std::size_t(3 * k + d)] >= 0.0);
      CHECK(a[std::size_t(3 * k + d)] < 1.0);
    }
  }
  gsl_qrng_free(q);
  // Low discrepancy: each coordinate's mean within 2e-3 of 1/2 (independent points: 0.009 is one
  // standard error at 1024 points).
  for (int d = 0; d < 3; ++d) {
    double m = 0;
    for (int k = 0; k < 1024; ++k) m += a[std::size_t(3 * k + d)];
    CHECK(std::abs(m / 1024 - 0.5) < 2e-3);
  }
  CHECK_THROWS_AS(sample_points(8, 41, SampleDesign::sobol, 1), InputError);
  CHECK(sample_points(8, 41, SampleDesign::random, 1).size() == 8 * 41);
}

TEST_CASE("the bare rotor's whirl: (16.5.1), and on an anisotropic support a time integration's",
          "[outcomes]") {
  Scene s = parse_scene(kDry, "dry.toml");
  const double w = 600, M = 0.12 + 2 * 3.3e-5;
  const std::complex<double> W(6e-7, 2e-7);
  CHECK(steady_whirl_radius(s, w, W) ==
        Approx(w * w * std::abs(W) / std::abs(std::complex<double>(7500 - M * w * w, 2.0 * w))).epsilon(1e-12));
  // Anisotropic: M x'' + C x' + K x = w^2 Re(W e^{i w t}, -i W e^{i w t}) integrated by RK4
  // (h = period / 2000) over 60 s (the slowest mode decays as exp(-c t / 2M), 1e-60), then the
  // largest radius over the last period: 1e-6 relative (RK4's error at that step, and the sampling).
  s.support = AnisotropicSupport{6000, 9000, 800, 1.5, 3.0, 0.2};
  const auto& a = *s.support;
  const double T = 2 * M_PI / w, h = T / 2000;
  double x = 0, y = 0, vx = 0, vy = 0, t = 0, best = 0;
  const auto acc = [&](double tt, double px, double py, double ux, double uy, double& ax, double& ay) {
    const std::complex<double> f = w * w * W * std::polar(1.0, w * tt);
    ax = (f.real() - a.k_x * px - a.k_xy * py - a.c_x * ux - a.c_xy * uy) / M;
    ay = (f.imag() - a.k_xy * px - a.k_y * py - a.c_xy * ux - a.c_y * uy) / M;
  };
  const long steps = long(60.0 / T) * 2000;
  for (long k = 0; k < steps + 2000; ++k) {
    double a1x, a1y, a2x, a2y, a3x, a3y, a4x, a4y;
    acc(t, x, y, vx, vy, a1x, a1y);
    acc(t + h / 2, x + h / 2 * vx, y + h / 2 * vy, vx + h / 2 * a1x, vy + h / 2 * a1y, a2x, a2y);
    acc(t + h / 2, x + h / 2 * (vx + h / 2 * a1x), y + h / 2 * (vy + h / 2 * a1y), vx + h / 2 * a2x, vy + h / 2 * a2y,
        a3x, a3y);
    acc(t + h, x + h * (vx + h / 2 * a2x), y + h * (vy + h / 2 * a2y), vx + h * a3x, vy + h * a3y, a4x, a4y);
    x += h * (vx + h / 6 * (a1x + a2x + a3x));
    y += h * (vy + h / 6 * (a1y + a2y + a3y));
    vx += h / 6 * (a1x + 2 * a2x + 2 * a3x + a4x);
    vy += h / 6 * (a1y + 2 * a2y + 2 * a3y + a4y);
    t += h;
    if (k >= steps) best = std::max(best, std::hypot(x, y));
  }
  CHECK(steady_whirl_radius(s, w, W) == Approx(best).epsilon(1e-6));
}

TEST_CASE("a study's runs are `simulate`'s from the same starts, whatever the thread count", "[outcomes]") {
  const Scene s = parse_scene(kDry, "dry.toml");
  OutcomeOptions o;
  o.samples = 6;
  o.sim.t_end = 0.5;
  o.uncertain.push_back({"mu", 0.001, 0.003});
  o.threads = 1;
  const SpeedProfile speed = SpeedProfile::ramp(100, 900, 2000);
  const OutcomeStudy one = analyze_outcomes(s, speed, o);
  o.threads = 2;
  const OutcomeStudy two = analyze_outcomes(s, speed, o);
  REQUIRE(one.samples.size() == 6);
  for (std::size_t k = 0; k < 6; ++k) {
    const OutcomeSample &a = one.samples[k], &b = two.samples[k];
    CHECK(a.residual == b.residual);  // bit for bit
    CHECK(a.peak == b.peak);
    CHECK(a.outcome == b.outcome);
    // Again by hand: the scene with this run's mu, simulate from rest at its angles.
    Scene at = s;
    at.balls[0].mu = at.balls[1].mu = a.inputs[0];
    Params p = params_of<2>(at);
    p.omega = 100;
    SimulationOptions so;
    so.t_end = 0.5;
    const auto r = simulate(p, speed, start_at_rest(p, a.beta0), so);
    double residual = 0;
    for (const auto& x : r.samples)
      if (x.t >= r.summary.window_from) residual = std::max(residual, std::hypot(x.x(0), x.x(1)));
    CHECK(a.residual == residual);
    CHECK(a.peak == r.summary.max_q_abs);
    CHECK(a.inputs[0] >= 0.001);
    CHECK(a.inputs[0] <= 0.003);
  }
  CHECK(one.summary.runs == 6);
  CHECK(one.summary.residual.worst.value ==
        std::max_element(one.samples.begin(), one.samples.end(), [](const auto& x, const auto& y) {
          return x.residual < y.residual;
        })->residual);
}

TEST_CASE("a study refuses inputs it cannot vary before any run", "[outcomes]") {
  const Scene s = parse_scene(kDry, "dry.toml");
  const SpeedProfile speed = SpeedProfile::constant(900);
  const auto refused = [&](UncertainInput u, std::string_view what) {
    OutcomeOptions o;
    o.samples = 4;
    o.uncertain = {u};
    INFO(u.name << " " << u.low << ":" << u.high);
    try {
      analyze_outcomes(s, speed, o);
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK_THAT(e.what(), Catch::Contains(std::string(what)));
    }
  };
  refused({"omega", 800, 900}, "profile");
  refused({"zeta", 1, 2}, "names no parameter");
  refused({"mu", 0.003, 0.001}, "LOW <= HIGH");
  refused({"r", 1e-3, 0.02}, "radius");  // r above the race radius at the high end
  CHECK_THROWS_AS(parse_uncertain("mu=0.001"), InputError);
  CHECK(parse_uncertain("mu=0.001:0.003").high == 0.003);
}
