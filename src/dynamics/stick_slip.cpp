// Event-driven stick-slip dynamics of set-valued Coulomb friction (stick_slip.hpp,
// model.md §14.5-§14.8).
#include "abu/dynamics/stick_slip.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "abu/core/errors.hpp"
#include "abu/core/gsl_errors.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "dense_output.hpp"

namespace abu {

namespace {

constexpr double kPi = std::numbers::pi;
using BallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, max_balls, max_balls>;
using BallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, max_balls, 1>;

// One smooth phase: the frictionless field of §3 / §9 plus the friction forces of the
// current modes (model.md (14.5.1)-(14.5.4)).
template <int N>
struct Phase {
  ParamsT<double, N> free;  // law none; omega follows the profile
  double segment_t0 = 0, segment_omega0 = 0, omega_dot = 0;
  int n = 0, d = 0, dim = 0;
  double force_scale[max_balls] = {};  // mu_i m_i l_i omega_max^2 [N]: the switching functions' unit
  bool stuck[max_balls] = {};
  double sigma[max_balls] = {};        // slip direction +-1 (F_i = -sigma_i mu_i N_i)
  unsigned long rhs = 0;
  void set_time(double t) { free.omega = segment_omega0 + omega_dot * (t - segment_t0); }
  double friction_limit(int i) const {  // mu_i N_i, N_i = m_i l_i omega^2 (1.6)
    const auto& b = free.balls[std::size_t(i)];
    return b.mu * b.mass * b.race_radius * free.omega * free.omega;
  }
};

template <int N>
State<double, N> load(const double y[], int dim) {
  State<double, N> x(dim);
  for (int i = 0; i < dim; ++i) x(i) = y[i];
  return x;
}

// s'' = s0'' + sum_j c_j F_j with c_j = A^-1 e_{2+j} l_j (14.5.2); the stuck balls' forces
// from beta_S'' = 0 (14.5.3). Writes the accelerations and every ball's friction force.
template <int N>
void phase_accelerations(Phase<N>& c, const State<double, N>& x, Coordinates<double, N>& acc, double* force) {
  const int n = c.n, d = c.d;
  ++c.rhs;
  const State<double, N> f0 = c.omega_dot == 0 ? vector_field(c.free, x) : vector_field(c.free, x, c.omega_dot);
  acc = f0.tail(d);
  const DofMatrix<double, N> A = mass_matrix(c.free, Coordinates<double, N>(x.head(d)));
  const Eigen::LDLT<DofMatrix<double, N>> ldlt(A);
  DofMatrix<double, N> cols = DofMatrix<double, N>::Zero(d, d);  // column j < n: c_j
  int stuck_index[max_balls];
  int k = 0;
  for (int j = 0; j < n; ++j) {
    Coordinates<double, N> e = Coordinates<double, N>::Zero(d);
    e(2 + j) = c.free.balls[std::size_t(j)].race_radius;
    cols.col(j) = ldlt.solve(e);
    if (c.stuck[j]) {
      stuck_index[k++] = j;
      force[j] = 0;
    } else {
      force[j] = -c.sigma[j] * c.friction_limit(j);
      acc += cols.col(j) * force[j];
    }
  }
  if (k == 0) return;
  BallMatrix G(k, k);
  BallVector rhs(k);
  for (int a = 0; a < k; ++a) {
    rhs(a) = -acc(2 + stuck_index[a]);
    for (int b = 0; b < k; ++b) G(a, b) = cols(2 + stuck_index[a], stuck_index[b]);
  }
  const BallVector fs = G.partialPivLu().solve(rhs);
  for (int a = 0; a < k; ++a) {
    force[stuck_index[a]] = fs(a);
    acc += cols.col(stuck_index[a]) * fs(a);
  }
  for (int a = 0; a < k; ++a) acc(2 + stuck_index[a]) = 0.0;  // exactly: the constraint (14.5.1)
}

// (14.5.2)-(14.5.3) at time t and state y.
template <int N>
Coordinates<double, N> accelerations_at(Phase<N>& c, double t, const double y[], double* force) {
  c.set_time(t);
  Coordinates<double, N> acc;
  phase_accelerations(c, load<N>(y, c.dim), acc, force);
  return acc;
}

template <int N>
int phase_rhs(double t, const double y[], double dydt[], void* params) {
  auto& c = *static_cast<Phase<N>*>(params);
  double force[max_balls];
  const Coordinates<double, N> acc = accelerations_at(c, t, y, force);
  for (int i = 0; i < c.d; ++i) {
    dydt[i] = y[c.d + i];
    dydt[c.d + i] = acc(i);
  }
  for (int i = 0; i < c.n; ++i)
    if (c.stuck[i]) dydt[2 + i] = 0.0;
  for (int i = 0; i < c.dim; ++i)
    if (!std::isfinite(dydt[i])) return GSL_EBADFUNC;
  return GSL_SUCCESS;
}

// The phase's field for the dense output (model.md §15.1): f, and y'' = d/dt f(t, y(t)) by
// differences along (1, f) (no Jacobian of the constrained field; dense_output.hpp).
template <int N>
struct PhaseField {
  Phase<N>* ph;
  bool central;       // the central difference (rtol < 1e-9), else the forward one
  double time_scale;  // 1 / (omega_max + omega_n)
  int rhs(double t, const double* y, double* f) const { return phase_rhs<N>(t, y, f, ph); }
  int second(double t, const double* y, const double* f, double* g) const {
    const auto field = [this](double tt, const double* yy, double* ff) { return phase_rhs<N>(tt, yy, ff, ph); };
    return dense::second_by_difference(field, ph->dim, time_scale, central, t, y, f, g);
  }
};

// Switching functions (model.md §14.6): a slipping ball sigma_i beta_i' (> 0 while it slips),
// a stuck ball (mu_i N_i - |F_i|) / force_scale_i (>= 0 while it can stick).
template <int N>
void switching_functions(Phase<N>& c, double t, const double y[], double* g) {
  double force[max_balls];
  accelerations_at(c, t, y, force);
  for (int i = 0; i < c.n; ++i)
    g[i] = c.stuck[i] ? (c.friction_limit(i) - std::abs(force[i])) / c.force_scale[i] : c.sigma[i] * y[c.d + 2 + i];
}

// Did ball i switch between g0 (start of the step) and g1? A ball just released at zero speed
// has g0 = 0 and moves off with g1 > 0.
bool switched(bool stuck, double g0, double g1) {
  if (stuck) return g1 < 0;
  return (g0 > 0 && g1 <= 0) || (g0 == 0 && g1 < 0);
}

struct SwitchCounts {
  unsigned long sticks = 0, slips = 0, reversals = 0;
};

// The modes at an instant (model.md §14.6): every ball at zero relative speed is a candidate
// for stick; while some stuck ball needs more than mu_i N_i, the one that needs the most
// (relative to its limit) slips, against the force it needed. Greedy, exact for one ball
// switching at a time (the generic case; isolated events).
template <int N>
void settle_modes(Phase<N>& c, double t, double y[], const bool* was_stuck, const double* was_sigma, SwitchCounts& counts) {
  for (int i = 0; i < c.n; ++i)
    if (!c.stuck[i] && y[c.d + 2 + i] == 0.0) c.stuck[i] = true;
  for (int round = 0; round < c.n; ++round) {
    double force[max_balls];
    accelerations_at(c, t, y, force);
    int worst = -1;
    double worst_excess = 0;
    for (int i = 0; i < c.n; ++i) {
      if (!c.stuck[i]) continue;
      const double excess = (std::abs(force[i]) - c.friction_limit(i)) / c.force_scale[i];
      if (excess > worst_excess) worst = i, worst_excess = excess;
    }
    if (worst < 0) break;
    c.stuck[worst] = false;
    c.sigma[worst] = force[worst] > 0 ? -1.0 : 1.0;  // slips against the force it needed
  }
  for (int i = 0; i < c.n; ++i) {
    if (c.stuck[i] && !was_stuck[i]) ++counts.sticks;
    if (!c.stuck[i] && was_stuck[i]) ++counts.slips;
    if (!c.stuck[i] && !was_stuck[i] && c.sigma[i] != was_sigma[i]) ++counts.reversals;
  }
}

const gsl_odeiv2_step_type* smooth_phase_stepper(IntegrationMethod m) {
  switch (m) {
    case IntegrationMethod::automatic:
    case IntegrationMethod::rk8pd: return gsl_odeiv2_step_rk8pd;
    case IntegrationMethod::rkf45: return gsl_odeiv2_step_rkf45;
    default:
      throw InputError("--method", 0, "",
                       fmt::format("'{}' needs a Jacobian; with friction law 'coulomb-set' the smooth phases are not "
                                   "stiff (model.md §14.6): use auto, rk8pd or rkf45",
                                   to_string(m)));
  }
}

struct StepDeleter {
  void operator()(gsl_odeiv2_step* s) const { gsl_odeiv2_step_free(s); }
};
struct ControlDeleter {
  void operator()(gsl_odeiv2_control* c) const { gsl_odeiv2_control_free(c); }
};
struct EvolveDeleter {
  void operator()(gsl_odeiv2_evolve* e) const { gsl_odeiv2_evolve_free(e); }
};

}  // namespace

template <int N>
StickSlipEnd stick_slip_end(const ParamsT<double, N>& p, double omega, const State<double, N>& x,
                            const std::vector<int>& stuck) {
  const int n = ball_count(p);
  ParamsN pn;
  pn.rotor = p.rotor;
  pn.omega = omega;
  pn.law = FrictionLaw::coulomb_set;
  pn.balls.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) pn.balls[std::size_t(i)] = p.balls[std::size_t(i)];
  StickSlipEnd e;
  e.stuck = stuck;
  for (int i = 0; i < n; ++i) {
    double b = std::fmod(x(2 + i), 2 * kPi);
    if (b < 0) b += 2 * kPi;
    e.beta.push_back(b);
  }
  const StickPoint sp = stick_point(pn, e.beta);
  e.s = sp.s;
  for (double s : e.s) e.max_abs_s = std::max(e.max_abs_s, std::abs(s));
  e.q_abs = std::hypot(x(0), x(1));
  e.q_abs_static = std::hypot(sp.q1, sp.q2);
  e.all_stuck = std::all_of(stuck.begin(), stuck.end(), [](int s) { return s != 0; });
  e.in_set = e.all_stuck && e.max_abs_s <= 1 + stick_set_tolerance;
  return e;
}

template <int N>
StickSlipResult<N> simulate_stick_slip(const ParamsT<double, N>& p, const SpeedProfile& speed,
                                       const State<double, N>& x0, const SimulationOptions& o) {
  quiet_gsl_errors();
  const int n = ball_count(p), d = n + 2, dim = 2 * d;
  check_simulation_input(o, dim, x0.data(), int(x0.size()), n);
  for (const auto& b : p.balls)
    if (!(b.mu > 0))
      throw NotSupportedError("coulomb-set stick-slip needs mu_i > 0 for every ball (model.md §14.2: with mu_i = 0 "
                              "a ball sticks only on a line)");
  const double every = o.every > 0 ? std::min(o.every, o.t_end) : o.t_end / 2000;
  const gsl_odeiv2_step_type* stepper = smooth_phase_stepper(o.method);

  StickSlipResult<N> out;
  SimulationResult<N>& r = out.run;
  const auto wall0 = std::chrono::steady_clock::now();
  const double L = displacement_scale(p);
  const double w_max = speed.max_omega();
  const double w_n = std::sqrt(p.rotor.stiffness / p.total_mass());
  r.displacement_scale = L;
  r.method = o.method == IntegrationMethod::rkf45 ? IntegrationMethod::rkf45 : IntegrationMethod::rk8pd;

  Phase<N> ph;
  ph.free = p;
  ph.free.law = FrictionLaw::none;
  ph.n = n;
  ph.d = d;
  ph.dim = dim;
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    ph.force_scale[i] = b.mu * b.mass * b.race_radius * w_max * w_max;
    ph.sigma[i] = x0(d + 2 + i) < 0 ? -1.0 : 1.0;
  }
  gsl_odeiv2_system sys{&phase_rhs<N>, nullptr, std::size_t(dim), &ph};

  // Error control in the model's scaling (model.md §15.1, GSL's scaled control: angles
  // relative too, D = rtol (1 + |beta|) for them).
  double scale[2 * max_balls + 4];
  for (int i = 0; i < dim; ++i) {
    const bool angle = i >= 2 && i < d, velocity = i >= d, rotor = i < 2 || (i >= d && i < d + 2);
    scale[i] = angle ? 1.0 : (rotor ? L : 1.0) * (velocity ? w_max : 1.0);
  }
  std::unique_ptr<gsl_odeiv2_step, StepDeleter> step(gsl_odeiv2_step_alloc(stepper, std::size_t(dim)));
  std::unique_ptr<gsl_odeiv2_step, StepDeleter> probe(gsl_odeiv2_step_alloc(stepper, std::size_t(dim)));
  std::unique_ptr<gsl_odeiv2_control, ControlDeleter> control(
      gsl_odeiv2_control_scaled_new(o.rtol, o.rtol, 1.0, 0.0, scale, std::size_t(dim)));
  std::unique_ptr<gsl_odeiv2_evolve, EvolveDeleter> evolve(gsl_odeiv2_evolve_alloc(std::size_t(dim)));
  if (!step || !probe || !control || !evolve) throw NumericalError("stick-slip: GSL could not allocate the integrator");

  double y[2 * max_balls + 4], y0[2 * max_balls + 4], yprobe[2 * max_balls + 4], yerr[2 * max_balls + 4];
  double g0[max_balls], g1[max_balls];
  for (int i = 0; i < dim; ++i) y[i] = x0(i);
  double t = 0, h = std::min(1e-3 / (w_max + w_n), 1e-2 * o.t_end);

  const auto mask = [&] {
    std::uint32_t m = 0;
    for (int i = 0; i < n; ++i)
      if (ph.stuck[i]) m |= 1u << i;
    return m;
  };
  const auto record = [&](double time, const double* x) {
    if (!o.record) return;
    TrajectorySample<N> s;
    s.t = time;
    s.omega = speed.omega(time);
    s.x = load<N>(x, dim);
    r.samples.push_back(s);
    out.stuck_mask.push_back(mask());
    if (o.progress) o.progress(time);
    if (o.stop_at_sample && o.stop_at_sample(time, x)) r.stopped_early = true;
  };
  std::vector<double> breaks = speed.breakpoints(0.0, o.t_end);
  breaks.push_back(o.t_end);
  std::size_t next_break = 0;
  const auto begin_segment = [&](double at) {
    ph.segment_t0 = at;
    ph.segment_omega0 = speed.omega(at);
    ph.omega_dot = speed.omega_dot(at);
  };
  const auto switch_modes = [&](double at) {
    bool was_stuck[max_balls];
    double was_sigma[max_balls];
    std::copy(ph.stuck, ph.stuck + n, was_stuck);
    std::copy(ph.sigma, ph.sigma + n, was_sigma);
    SwitchCounts counts;
    settle_modes(ph, at, y, was_stuck, was_sigma, counts);
    out.sticks += counts.sticks;
    out.slips += counts.slips;
    out.reversals += counts.reversals;
    for (int i = 0; i < n; ++i)
      if (ph.stuck[i]) y[d + 2 + i] = 0.0;
  };
  begin_segment(0.0);
  switch_modes(0.0);  // balls at rest relative to the race stick if they can
  out.sticks = out.slips = out.reversals = 0;  // the start's modes are not switches
  if (o.record) r.samples.reserve(std::size_t(std::ceil(o.t_end / every)) + 2);
  record(0.0, y);

  unsigned long at_one_instant = 0;
  double last_event = -1;
  const unsigned long max_events_at_one_instant = 1000;
  bool stop = false;
  const auto fail = [&](std::string why) {
    r.status = SimulationStatus::failed;
    r.reason = fmt::format("at t = {:.9g} s (omega = {:.9g} rad/s): {}", t, speed.omega(t), why);
    stop = true;
  };
  unsigned long rejected = 0;  // by the evolve objects before their resets
  // GSL's evolve takes the last step's end field as the next step's start field: after the state
  // changed outside it (an event, a retaken step, a breakpoint) it is reset, its count kept.
  const auto reset_evolve = [&] {
    rejected += evolve->failed_steps;
    gsl_odeiv2_evolve_reset(evolve.get());
  };

  // Dense output (model.md §15.1, §14.6): the smooth phases stepped freely to the next breakpoint
  // or switch; the samples inside a step from the quintic Hermite interpolant of the phase that
  // held during it; the maxima of |q| located inside each step (§15.4).
  bool relative[2 * max_balls + 4];
  std::fill(relative, relative + dim, true);  // GSL's scaled control: rtol (scale_i + |y_i|)
  dense::Stepper<PhaseField<N>> dense(PhaseField<N>{&ph, o.rtol < 1e-9, 1.0 / (w_max + w_n)}, dim, o.rtol, scale,
                                      relative);
  const bool dense_on = o.record;
  const bool exact_dydt_out = stepper->gives_exact_dydt_out != 0;
  dense::SampleClock clock{every, o.t_end};
  double x_sample[2 * max_balls + 4];
  if (dense_on) {
    if (dense.start(t, y) != GSL_SUCCESS) fail("the right-hand side is not finite at the start");
    dense.peaks.add({std::hypot(y[0], y[1]), 0.0}, ph.omega_dot != 0);
  }
  while (!stop && !r.stopped_early && t < o.t_end) {
    double target = breaks[next_break];
    if (dense_on) target = dense.plan(t, h, clock.next(), target);
    const double t0 = t, h_before = h;
    std::copy(y, y + dim, y0);
    switching_functions(ph, t0, y0, g0);
    const int st = gsl_odeiv2_evolve_apply(evolve.get(), control.get(), step.get(), &sys, &t, target, &h, y);
    if (st != GSL_SUCCESS) {
      fail(fmt::format("{} [GSL {}]", st == GSL_EBADFUNC ? "the right-hand side is not finite" : gsl_strerror(st), st));
      break;
    }
    if (++r.stats.steps - dense.retaken > o.max_steps) {
      fail(fmt::format("more than {} steps (raise the tolerance or shorten the run)", o.max_steps));
      break;
    }
    if (o.interrupt && o.interrupt->load(std::memory_order_relaxed)) {
      r.status = SimulationStatus::interrupted;
      r.reason = fmt::format("interrupted at t = {:.9g} s", t);
      stop = true;
      break;
    }
    switching_functions(ph, t, y, g1);
    bool any = false;
    for (int i = 0; i < n; ++i) any = any || switched(ph.stuck[i], g0[i], g1[i]);
    if (any) {
      // Locate the first switch by bisection on the step length from (t0, y0): one step of the
      // same method per trial (its error below the accepted step's), to rounding of t.
      double lo = 0, hi = t - t0;
      std::copy(y, y + dim, yprobe);
      for (int it = 0; it < 200 && hi - lo > 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, t0 + hi);
           ++it) {
        const double mid = 0.5 * (lo + hi);
        double ym[2 * max_balls + 4];
        std::copy(y0, y0 + dim, ym);
        if (gsl_odeiv2_step_apply(probe.get(), t0, mid, ym, yerr, nullptr, nullptr, &sys) != GSL_SUCCESS) {
          lo = mid;  // cannot happen with a finite field; keep the bracket
          continue;
        }
        switching_functions(ph, t0 + mid, ym, g1);
        bool crossed = false;
        for (int i = 0; i < n; ++i) crossed = crossed || switched(ph.stuck[i], g0[i], g1[i]);
        if (crossed) {
          hi = mid;
          std::copy(ym, ym + dim, yprobe);
        } else {
          lo = mid;
        }
      }
      t = t0 + hi;
      std::copy(yprobe, yprobe + dim, y);
    } else if (t == target && h < h_before) {
      h = h_before;  // a step clamped to reach the target returns a small proposal; keep the previous one
    }
    if (dense_on) {
      // The step (cut at the switch, if any) in the phase that held during it.
      if (dense.finish(t, y, any || !exact_dydt_out ? nullptr : evolve->dydt_out) != GSL_SUCCESS) {
        fail("the right-hand side is not finite");
        break;
      }
      const dense::QPeak candidate = dense.candidate();
      // A step cut at a switch is shorter than the one planned: its interpolant is used as it is.
      if (!any && dense.retake(clock.next(), candidate)) {
        t = t0;
        std::copy(y0, y0 + dim, y);
        h = std::min(h, dense.h_limit);
        reset_evolve();
        continue;
      }
      const double t_part = dense.emit(
          clock, [&](double ts, const double* x) { return record(ts, x), r.stopped_early; }, candidate,
          ph.omega_dot != 0, x_sample);
      if (r.stopped_early) {  // the run ends at that sample
        t = t_part;
        std::copy(x_sample, x_sample + dim, y);
        break;
      }
      dense.advance();
    }
    if (any) {
      switching_functions(ph, t, y, g1);
      for (int i = 0; i < n; ++i)
        if (!ph.stuck[i] && switched(false, g0[i], g1[i])) y[d + 2 + i] = 0.0;  // reached rest relative to the race
      switch_modes(t);
      reset_evolve();
      gsl_odeiv2_step_reset(step.get());
      ++r.stats.restarts;
      at_one_instant = t - last_event <= 1e-12 * std::max(1.0, t) ? at_one_instant + 1 : 0;
      last_event = t;
      if (at_one_instant > max_events_at_one_instant) {
        fail(fmt::format("more than {} stick-slip switches at one instant (Zeno accumulation; model.md §14.6)",
                         max_events_at_one_instant));
        break;
      }
      h = std::max(h_before, 1e-6 / (w_max + w_n));
      if (dense_on && dense.start(t, y) != GSL_SUCCESS) fail("the right-hand side is not finite after a switch");
      continue;
    }
    if (t == breaks[next_break] && next_break + 1 < breaks.size()) {
      ++next_break;
      begin_segment(t);
      reset_evolve();
      switch_modes(t);  // omega' jumps: the force a stuck ball needs jumps too
      if (dense_on && dense.start(t, y) != GSL_SUCCESS) fail("the right-hand side is not finite after a breakpoint");
    }
  }
  if (stop && o.record && r.samples.back().t < t) record(t, y);
  r.stats.steps -= dense.retaken;  // counted above as accepted, then discarded
  r.stats.retaken = dense.retaken;
  r.stats.rejected = rejected + evolve->failed_steps + dense.retaken;
  r.stats.rhs_evaluations = ph.rhs;
  r.x_end = load<N>(y, dim);
  r.t_reached = t;
  r.stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  std::vector<int> stuck(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) stuck[std::size_t(i)] = ph.stuck[i] ? 1 : 0;
  out.end = stick_slip_end(p, speed.omega(t), r.x_end, stuck);
  if (o.record) {
    r.summary = summarize(p, speed, r.samples, o);
    dense.peaks.merge_into(r.summary);  // the maxima between the samples (model.md §15.4)
    if (r.summary.outcome == SimulationOutcome::rest && out.end.all_stuck)
      r.summary.note = fmt::format("every ball stuck (set-valued friction), max |s_i| = {:.4g} {} 1: {} the stick set "
                                   "(model.md §14.2)",
                                   out.end.max_abs_s, out.end.in_set ? "<=" : ">", out.end.in_set ? "inside" : "OUTSIDE");
  }
  return out;
}

#define ABU_INSTANTIATE_STICK_SLIP(N)                                                                              \
  template StickSlipResult<N> simulate_stick_slip<N>(const ParamsT<double, N>&, const SpeedProfile&,               \
                                                     const State<double, N>&, const SimulationOptions&);          \
  template StickSlipEnd stick_slip_end<N>(const ParamsT<double, N>&, double, const State<double, N>&,              \
                                          const std::vector<int>&);
ABU_INSTANTIATE_STICK_SLIP(2)
ABU_INSTANTIATE_STICK_SLIP(any_balls)
#undef ABU_INSTANTIATE_STICK_SLIP

}  // namespace abu
