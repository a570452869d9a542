// What the two shooting problems of the dynamics layer share (docs/model.md §17.2, §10.14):
// one GSL odeiv2 stepper/control/evolve set that integrates a system over one shooting
// interval, stopping at sample times, and the extreme of cyclic uniform samples.
// Internal to src/dynamics (periodic_orbits.cpp, forced_orbits.cpp).
#pragma once

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "abu/continuation/bordered.hpp"
#include "abu/core/cancel.hpp"

namespace abu::detail {

// One GSL stepper/control/evolve set for a system size (rtol = atol on every component).
class FlowIntegrator {
 public:
  FlowIntegrator(const gsl_odeiv2_step_type* type, int dim, double rtol, std::string_view what)
      : dim_(dim), what_(what), step_(gsl_odeiv2_step_alloc(type, std::size_t(dim))),
        control_(gsl_odeiv2_control_standard_new(rtol, rtol, 1.0, 0.0)),
        evolve_(gsl_odeiv2_evolve_alloc(std::size_t(dim))) {}
  ~FlowIntegrator() {
    gsl_odeiv2_evolve_free(evolve_);
    gsl_odeiv2_control_free(control_);
    gsl_odeiv2_step_free(step_);
  }
  FlowIntegrator(const FlowIntegrator&) = delete;
  FlowIntegrator& operator=(const FlowIntegrator&) = delete;
  int dimension() const { return dim_; }
  long steps() const { return steps_; }  ///< steps taken so far (accepted and rejected)
  // Integrates y of `sys` from t0 to t0 + h, stopping at every t0 + target in between
  // (targets ascending, the last h); false with why.
  bool run(gsl_odeiv2_system& sys, double t0, double* y, double h, const std::vector<double>& targets,
           const std::function<void(const double*)>& at_target, std::string_view& why) {
    gsl_odeiv2_evolve_reset(evolve_);
    gsl_odeiv2_step_reset(step_);
    double t = t0, dt = std::min(first_step_, h);
    for (double target : targets) {
      while (t < t0 + target) {
        const int st = gsl_odeiv2_evolve_apply(evolve_, control_, step_, &sys, &t, t0 + target, &dt, y);
        if (st != GSL_SUCCESS) {
          why = "the integrator failed (a non-finite field or a step below rounding)";
          return false;
        }
        if ((++steps_ & 1023) == 0) throw_if_stopped(what_);
        if (steps_ > 50'000'000) {
          why = "the integrator needed more than 5e7 steps";
          return false;
        }
      }
      if (at_target) at_target(y);
    }
    first_step_ = std::max(dt, 1e-12 * h);
    return true;
  }

 private:
  int dim_;
  std::string_view what_;
  gsl_odeiv2_step* step_;
  gsl_odeiv2_control* control_;
  gsl_odeiv2_evolve* evolve_;
  double first_step_ = 1e-6;
  long steps_ = 0;
};

// One evaluation of a shooting problem at its unknowns u: the residuals, their Jacobian and
// the intervals' transition matrices (the Floquet factors), cached by the problem.
struct ShootingEvaluation {
  Eigen::VectorXd u;
  Eigen::VectorXd residual;
  Eigen::MatrixXd jacobian;
  std::vector<Eigen::MatrixXd> transitions;
  bool ok = false;
  std::string_view why;
};

// The System part of a shooting problem (continuation/bordered.hpp) from its cached
// evaluation `at(u)`: Newton stops at the integration's noise (rtol), not at eps.
template <class Problem>
class ShootingSystem {
 public:
  using Vec = Eigen::VectorXd;
  using Jacobian = Eigen::MatrixXd;
  ShootingSystem(double rtol, double residual_factor) : rtol_(rtol), residual_factor_(residual_factor) {}
  Vec residual(const Vec& u) const { return self().at(u).residual; }
  Jacobian jacobian(const Vec& u) const { return self().at(u).jacobian; }
  double residual_size(const Vec& u) const {
    const ShootingEvaluation& e = self().at(u);
    return e.ok ? e.residual.cwiseAbs().maxCoeff() : 1e300;
  }
  arclength::NewtonSettings newton() const {
    arclength::NewtonSettings s;
    s.max_iterations = 10;
    s.step_tolerance = 10 * rtol_;
    s.stall_tolerance = 1e7 * rtol_;
    s.residual_tolerance = residual_factor_ * rtol_;
    return s;
  }

 private:
  const Problem& self() const { return static_cast<const Problem&>(*this); }
  double rtol_, residual_factor_;
};

// Parabola through three equally spaced samples: the extreme value.
inline double parabolic_peak(double a, double b, double c) {
  const double den = a - 2 * b + c;
  if (den == 0) return b;
  const double s = 0.5 * (a - c) / den;
  if (std::abs(s) > 1) return b;
  return b - 0.25 * (a - c) * s;
}

// The largest of cyclic uniform samples (spacing dt) whose rates are known as well (from
// the state itself: d|q|/dt from q and q', beta' for beta): the quintic through the largest
// sample and its two neighbours matching value and rate at each, maximized by Newton. Its
// error is O(dt^6) where the parabola of cyclic_max's is O(dt^4) (model.md §17.9: at M = 5
// intervals of 16 samples the parabola left 4.3e-6 in a cycle's amplitude against the
// independent reference, the quintic 7.7e-12). The parabola's value if the quintic's
// maximum is not interior.
inline double cyclic_max(const std::vector<double>& v, const std::vector<double>& rate, double dt) {
  const std::size_t n = v.size();
  const std::size_t k = std::size_t(std::max_element(v.begin(), v.end()) - v.begin());
  const std::size_t a = (k + n - 1) % n, c = (k + 1) % n;
  const double fallback = std::max(v[k], parabolic_peak(v[a], v[k], v[c]));
  if (rate.size() != n || !(dt > 0)) return fallback;
  // p(s) = sum c_i s^i on s in [-1, 1] (t = s dt): p(-1), p(0), p(1) and dt-scaled p'.
  Eigen::Matrix<double, 6, 6> A;
  Eigen::Matrix<double, 6, 1> rhs;
  const double nodes[3] = {-1.0, 0.0, 1.0};
  const std::size_t at[3] = {a, k, c};
  for (int j = 0; j < 3; ++j) {
    const double x = nodes[j];
    for (int i = 0; i < 6; ++i) {
      A(2 * j, i) = std::pow(x, i);
      A(2 * j + 1, i) = i == 0 ? 0.0 : i * std::pow(x, i - 1);
    }
    rhs(2 * j) = v[at[j]];
    rhs(2 * j + 1) = rate[at[j]] * dt;
  }
  const Eigen::Matrix<double, 6, 1> coef = A.partialPivLu().solve(rhs);
  const auto d1 = [&](double x) { return coef(1) + x * (2 * coef(2) + x * (3 * coef(3) + x * (4 * coef(4) + x * 5 * coef(5)))); };
  const auto d2 = [&](double x) { return 2 * coef(2) + x * (6 * coef(3) + x * (12 * coef(4) + x * 20 * coef(5))); };
  double x = 0;
  for (int it = 0; it < 20; ++it) {
    const double curvature = d2(x);
    if (!(curvature < 0)) return fallback;  // not a maximum
    const double step = d1(x) / curvature;
    x -= step;
    if (!(std::abs(x) <= 1)) return fallback;
    if (std::abs(step) <= 1e-15) break;
  }
  const double peak = coef(0) + x * (coef(1) + x * (coef(2) + x * (coef(3) + x * (coef(4) + x * coef(5)))));
  return std::isfinite(peak) ? std::max(peak, v[k]) : fallback;
}

// The largest of cyclic uniform samples, refined by a parabola.
inline double cyclic_max(const std::vector<double>& v) {
  const std::size_t n = v.size();
  const std::size_t k = std::size_t(std::max_element(v.begin(), v.end()) - v.begin());
  return parabolic_peak(v[(k + n - 1) % n], v[k], v[(k + 1) % n]);
}

// The largest value of a smooth periodic function from N uniform samples over its period:
// the maximum of its trigonometric interpolant (harmonics |k| < N/2), found by Newton on
// the interpolant's derivative from the largest sample. Spectrally accurate where the
// parabola of cyclic_max is accurate to the fourth power of the sample spacing only.
inline double periodic_max(const std::vector<double>& v) {
  const std::size_t n = v.size();
  if (n < 3) return n ? *std::max_element(v.begin(), v.end()) : 0.0;
  const std::size_t kmax = (n - 1) / 2;
  std::vector<double> a(kmax + 1, 0.0), b(kmax + 1, 0.0);  // v(theta) = a0 + sum a_k cos k theta + b_k sin k theta
  const double step = 2.0 * 3.14159265358979323846 / double(n);
  for (std::size_t k = 0; k <= kmax; ++k) {
    for (std::size_t j = 0; j < n; ++j) {
      const double th = step * double((k * j) % n);
      a[k] += v[j] * std::cos(th);
      b[k] += v[j] * std::sin(th);
    }
    a[k] *= (k == 0 ? 1.0 : 2.0) / double(n);
    b[k] *= 2.0 / double(n);
  }
  const auto value = [&](double th, double& d1, double& d2) {
    double f = a[0];
    d1 = d2 = 0;
    for (std::size_t k = 1; k <= kmax; ++k) {
      const double c = std::cos(double(k) * th), s = std::sin(double(k) * th), kk = double(k);
      f += a[k] * c + b[k] * s;
      d1 += kk * (-a[k] * s + b[k] * c);
      d2 -= kk * kk * (a[k] * c + b[k] * s);
    }
    return f;
  };
  const std::size_t top = std::size_t(std::max_element(v.begin(), v.end()) - v.begin());
  double th = step * double(top), d1 = 0, d2 = 0;
  double best = value(th, d1, d2);
  for (int it = 0; it < 30 && d2 < 0; ++it) {
    const double move = std::clamp(-d1 / d2, -step, step);
    const double f = value(th + move, d1, d2);
    if (!(f >= best)) break;
    th += move;
    best = f;
    if (std::abs(move) < 1e-15) break;
  }
  return best;
}

}  // namespace abu::detail
