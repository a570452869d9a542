// What a simulation ended in (model.md §15.2, §15.3) and the nearest balanced configuration
// (simulation.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/dynamics/simulation.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu {

namespace {

constexpr double kPi = std::numbers::pi;

double natural_frequency(double k, double M) { return std::sqrt(k / M); }

double scaled_distance_q_beta(const double* a, const double* b, int n, double L) {
  double d = std::max(std::abs(a[0] - b[0]), std::abs(a[1] - b[1])) / L;
  for (int i = 0; i < n; ++i) d = std::max(d, std::abs(std::remainder(a[2 + i] - b[2 + i], 2 * kPi)));
  return d;
}

}  // namespace

template <int N>
std::optional<std::vector<double>> nearest_balanced_angles(const ParamsT<double, N>& p, const std::vector<double>& beta) {
  const int n = ball_count(p);
  double capacity = 0, largest = p.rotor.unbalance;
  for (const auto& b : p.balls) {
    capacity += b.mass * b.race_radius;
    largest = std::max(largest, b.mass * b.race_radius);
  }
  // The polygon inequality (model.md §13.4): the set exists iff max(U, a_i) <= (U + sum a)/2.
  if (largest > 0.5 * (capacity + p.rotor.unbalance) * (1 + 1e-12)) return std::nullopt;
  // Wrapped first: after a long run-up the continuous angles reach hundreds of radians, whose
  // rounding (ulp 1e-13 at 557 rad) keeps |W| above the 1e-14 tolerance below.
  std::vector<double> b = beta;
  for (auto& v : b) v = std::remainder(v, 2 * kPi);
  const double scale = capacity + p.rotor.unbalance;
  for (int iter = 0; iter < 60; ++iter) {
    // W = U + sum a_j e^{i beta_j}; G = dW/dbeta (2 x n); minimal-norm step -G^T (G G^T)^-1 W.
    double w1 = p.rotor.unbalance, w2 = 0, g11 = 0, g12 = 0, g22 = 0;
    for (int j = 0; j < n; ++j) {
      const double a = p.balls[std::size_t(j)].mass * p.balls[std::size_t(j)].race_radius;
      w1 += a * std::cos(b[std::size_t(j)]);
      w2 += a * std::sin(b[std::size_t(j)]);
      const double gx = -a * std::sin(b[std::size_t(j)]), gy = a * std::cos(b[std::size_t(j)]);
      g11 += gx * gx;
      g12 += gx * gy;
      g22 += gy * gy;
    }
    if (std::hypot(w1, w2) <= 1e-14 * scale) {
      for (auto& v : b) v = std::remainder(v, 2 * kPi);
      return b;
    }
    // Levenberg-Marquardt damping keeps the step finite where G is rank-deficient (collinear balls).
    const double mu = 1e-10 * (g11 + g22);
    const double a11 = g11 + mu, a22 = g22 + mu, det = a11 * a22 - g12 * g12;
    if (!(det > 0)) return std::nullopt;
    const double y1 = (a22 * w1 - g12 * w2) / det, y2 = (a11 * w2 - g12 * w1) / det;
    for (int j = 0; j < n; ++j) {
      const double a = p.balls[std::size_t(j)].mass * p.balls[std::size_t(j)].race_radius;
      const double gx = -a * std::sin(b[std::size_t(j)]), gy = a * std::cos(b[std::size_t(j)]);
      double step = -(gx * y1 + gy * y2);
      step = std::clamp(step, -0.5, 0.5);  // at most half a radian per iteration
      b[std::size_t(j)] += step;
    }
  }
  return std::nullopt;
}

// The residual over the final window and its two references (model.md §21.1).
template <int N>
void residual_figures(const ParamsT<double, N>& p, const std::vector<TrajectorySample<N>>& samples, std::size_t w0,
                      const SimulationOptions& o, SimulationSummary& s) {
  for (std::size_t k = w0; k < samples.size(); ++k)
    s.residual_q_abs = std::max(s.residual_q_abs, std::hypot(samples[k].x(0), samples[k].x(1)));
  const double w = samples.back().omega;
  std::complex<double> held = p.rotor.unbalance;
  for (int i = 0; i < ball_count(p); ++i)
    held += p.balls[std::size_t(i)].mass * p.balls[std::size_t(i)].race_radius * std::polar(1.0, samples.front().x(2 + i));
  const AnisotropicSupport* support = o.support && !o.support->isotropic() ? o.support : nullptr;
  s.bare_rotor_q_abs = steady_whirl_radius(p.total_mass(), p.rotor.stiffness, p.rotor.damping, support, w,
                                           std::complex<double>(p.rotor.unbalance));
  s.balls_held_q_abs = steady_whirl_radius(p.total_mass(), p.rotor.stiffness, p.rotor.damping, support, w, held);
}

template <int N>
SimulationSummary summarize(const ParamsT<double, N>& p, const SpeedProfile& speed,
                            const std::vector<TrajectorySample<N>>& samples, const SimulationOptions& o) {
  SimulationSummary s;
  if (samples.empty()) return s;
  const int n = ball_count(p), d = n + 2;
  const double L = displacement_scale(p);
  s.omega_n = natural_frequency(p.rotor.stiffness, p.total_mass());
  const auto& last = samples.back();
  s.t_end = last.t;
  s.state_end.assign(last.x.data(), last.x.data() + last.x.size());
  for (const auto& smp : samples) {
    const double qa = std::hypot(smp.x(0), smp.x(1));
    if (qa > s.max_q_abs) s.max_q_abs = qa, s.t_max_q_abs = smp.t;
    if (speed.omega_dot(smp.t) != 0 || (smp.t > 0 && speed.omega_dot(std::nextafter(smp.t, 0.0)) != 0))
      s.max_q_abs_run_up = std::max(s.max_q_abs_run_up.value_or(0.0), qa);
  }
  s.t_omega_n = speed.crossings(s.omega_n, s.t_end);
  s.speed_changing_at_end = s.t_end > 0 && speed.omega_dot(std::nextafter(s.t_end, 0.0)) != 0;

  // Final window (model.md §15.2): the last `final_window` of the run, at least 3 samples.
  s.window_from = s.t_end * (1 - o.final_window);
  std::size_t w0 = samples.size() - 1;
  while (w0 > 0 && samples[w0 - 1].t >= s.window_from) --w0;
  if (samples.size() - w0 < 3) w0 = samples.size() >= 3 ? samples.size() - 3 : 0;
  s.window_from = samples[w0].t;
  const double span = s.t_end - s.window_from;
  const double w_bar = span > 0 ? (speed.angle(s.t_end) - speed.angle(s.window_from)) / span : last.omega;
  s.omega_mean_window = w_bar;
  residual_figures(p, samples, w0, o, s);

  // Stall (model.md §15.3): ball i slips against the rotor by more than 5 % of the spin speed
  // on average while its mean fixed-frame speed lies within 15 % of omega_n.
  s.ball_speed_fixed.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const double rel = span > 0 ? (last.x(2 + i) - samples[w0].x(2 + i)) / span : last.x(d + 2 + i);
    const double fixed = w_bar + rel;
    s.ball_speed_fixed[std::size_t(i)] = fixed;
    if (std::abs(rel) > 0.05 * w_bar && std::abs(fixed - s.omega_n) <= 0.15 * s.omega_n) s.stalled_balls.push_back(i + 1);
  }
  s.stalled = !s.stalled_balls.empty();

  // Settled: every sample of the window within settle_tolerance of the end state in the
  // scaled distance (q / L, angles in rad, q' / (L omega), beta' / omega).
  const auto distance = [&](const State<double, N>& a, const State<double, N>& b, double w) {
    double dist = scaled_distance_q_beta(a.data(), b.data(), n, L);
    dist = std::max(dist, std::max(std::abs(a(d) - b(d)), std::abs(a(d + 1) - b(d + 1))) / (L * w));
    for (int i = 0; i < n; ++i) dist = std::max(dist, std::abs(a(d + 2 + i) - b(d + 2 + i)) / w);
    return dist;
  };
  bool settled = !s.speed_changing_at_end;
  double speed_at_end = 0;
  for (int i = 0; i < d; ++i) speed_at_end = std::max(speed_at_end, std::abs(last.x(d + i)) / (i < 2 ? L * last.omega : last.omega));
  if (speed_at_end > o.settle_tolerance) settled = false;
  for (std::size_t k = w0; settled && k < samples.size(); ++k)
    if (distance(samples[k].x, last.x, last.omega) > o.settle_tolerance) settled = false;
  const double q_abs = std::hypot(last.x(0), last.x(1));
  if (settled) {
    std::size_t k = samples.size();
    while (k > 0 && distance(samples[k - 1].x, last.x, last.omega) <= o.settle_tolerance) --k;
    s.settle_time = samples[k < samples.size() ? k : samples.size() - 1].t;
    double capacity = p.rotor.unbalance, w1 = p.rotor.unbalance, w2 = 0;
    for (int i = 0; i < n; ++i) {
      const double a = p.balls[std::size_t(i)].mass * p.balls[std::size_t(i)].race_radius;
      capacity += a;
      w1 += a * std::cos(last.x(2 + i));
      w2 += a * std::sin(last.x(2 + i));
    }
    const double phi = std::atan2(last.x(1), last.x(0));
    bool on_line = q_abs > 0;
    for (int i = 0; i < n; ++i) on_line = on_line && std::abs(std::sin(last.x(2 + i) - phi)) <= 1e-2;
    if (q_abs <= 1e-2 * L && std::hypot(w1, w2) <= 1e-2 * capacity) {
      s.outcome = SimulationOutcome::balanced;
      s.note = fmt::format("at rest with |q| = {:.3g} L and residual unbalance |W| = {:.3g} of U + sum m l", q_abs / L,
                           std::hypot(w1, w2) / capacity);
    } else if (on_line) {
      s.outcome = SimulationOutcome::aligned;
      const double ref = std::cos(last.x(2) - phi);
      for (int i = 0; i < n; ++i) s.pattern += std::cos(last.x(2 + i) - phi) * ref >= 0 ? '+' : '-';
      s.note = fmt::format("at rest with every ball on the line of q (|q| = {:.4g} m), pattern {}", q_abs, s.pattern);
    } else {
      s.outcome = SimulationOutcome::rest;
      s.note = "at rest off every equilibrium: the balls creep too slowly to move within the window (dry friction; the stick set of model.md (5.10))";
    }
    return s;
  }
  // Periodic (a steady oscillation, not a verified periodic orbit): the two halves of the
  // window have the same range of |q| to 2 % of its largest value, and something moves.
  const std::size_t mid = w0 + (samples.size() - w0) / 2;
  double lo[2] = {1e300, 1e300}, hi[2] = {0, 0};
  for (std::size_t k = w0; k < samples.size(); ++k) {
    const int half = k < mid ? 0 : 1;
    const double qa = std::hypot(samples[k].x(0), samples[k].x(1));
    lo[half] = std::min(lo[half], qa);
    hi[half] = std::max(hi[half], qa);
  }
  const double top = std::max(hi[0], hi[1]);
  if (!s.speed_changing_at_end && samples.size() - w0 >= 8 && top > 0 && std::abs(hi[0] - hi[1]) <= 0.02 * top &&
      std::abs(lo[0] - lo[1]) <= 0.02 * top) {
    s.outcome = SimulationOutcome::periodic;
    s.note = fmt::format("steady oscillation: |q| in [{:.4g}, {:.4g}] m in both halves of the final window{}", lo[1],
                         hi[1], s.stalled ? " (stalled balls)" : "");
  } else {
    s.outcome = SimulationOutcome::not_settled;
    s.note = s.speed_changing_at_end ? "the speed is still changing at the end of the run"
                                     : "still moving at the end of the run (neither at rest nor a steady oscillation)";
  }
  return s;
}

#define ABU_INSTANTIATE_SIMULATION_SUMMARY(N)                                                       \
  template std::optional<std::vector<double>> nearest_balanced_angles<N>(const ParamsT<double, N>&, \
                                                                         const std::vector<double>&); \
  template SimulationSummary summarize<N>(const ParamsT<double, N>&, const SpeedProfile&,            \
                                          const std::vector<TrajectorySample<N>>&, const SimulationOptions&);
ABU_INSTANTIATE_SIMULATION_SUMMARY(2)
ABU_INSTANTIATE_SIMULATION_SUMMARY(any_balls)
#undef ABU_INSTANTIATE_SIMULATION_SUMMARY

}  // namespace abu
