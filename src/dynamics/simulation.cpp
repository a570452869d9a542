// Trajectories of model.md §3 / §9 with GSL odeiv2 (see simulation.hpp, model.md §15).
#include "abu/dynamics/simulation.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>

#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "abu/model/lugre.hpp"
#include "dense_output.hpp"
#include "scaled_control.hpp"
#include "simulation_field.hpp"

namespace abu {

std::string_view to_string(IntegrationMethod m) {
  switch (m) {
    case IntegrationMethod::automatic: return "auto";
    case IntegrationMethod::bdf: return "bdf";
    case IntegrationMethod::rk8pd: return "rk8pd";
    case IntegrationMethod::rk4imp: return "rk4imp";
    case IntegrationMethod::bsimp: return "bsimp";
    case IntegrationMethod::rkf45: return "rkf45";
  }
  return "?";
}

std::optional<IntegrationMethod> integration_method_from_string(std::string_view name) {
  for (auto m : {IntegrationMethod::automatic, IntegrationMethod::bdf, IntegrationMethod::rk8pd, IntegrationMethod::rk4imp,
                 IntegrationMethod::bsimp, IntegrationMethod::rkf45})
    if (to_string(m) == name) return m;
  return std::nullopt;
}

std::string_view to_string(SimulationStatus s) {
  switch (s) {
    case SimulationStatus::completed: return "completed";
    case SimulationStatus::interrupted: return "interrupted";
    case SimulationStatus::failed: return "failed";
  }
  return "?";
}

std::string_view to_string(SimulationOutcome o) {
  switch (o) {
    case SimulationOutcome::balanced: return "balanced";
    case SimulationOutcome::aligned: return "aligned";
    case SimulationOutcome::rest: return "stuck";
    case SimulationOutcome::periodic: return "periodic";
    case SimulationOutcome::not_settled: return "not_settled";
    case SimulationOutcome::equilibrium: return "equilibrium";
    case SimulationOutcome::orbit: return "orbit";
  }
  return "?";
}

using namespace sim_detail;  // the ODE system (simulation_field.hpp), the GSL parts (scaled_control.hpp)

namespace {

double natural_frequency(double k, double M) { return std::sqrt(k / M); }

}  // namespace

double simulation_memory_estimate(const SimulationOptions& o, int balls, bool with_text) {
  if (!o.record) return 0;
  const double every = o.every > 0 ? std::min(o.every, o.t_end) : o.t_end / 2000;
  const double samples = std::ceil(o.t_end / every) + 2;
  const double columns = 3.0 * balls + 9;
  const double per_sample = double(sizeof(TrajectorySample<any_balls>)) + 8.0 * balls + (with_text ? 2 * 24 * columns : 0);
  return samples * per_sample;
}

void check_simulation_input(const SimulationOptions& o, int dim, const double* x0, int size, int balls) {
  if (!(std::isfinite(o.t_end) && o.t_end > 0))
    throw InputError("--t-end", 0, "", fmt::format("the end time must be > 0 s (got {})", o.t_end));
  if (!(o.every >= 0 && std::isfinite(o.every)))
    throw InputError("--every", 0, "", fmt::format("the output interval must be > 0 s (got {})", o.every));
  const double every = o.every > 0 ? std::min(o.every, o.t_end) : o.t_end / 2000;
  if (o.record && o.t_end / every > 2e7)
    throw InputError("--every", 0, "", fmt::format("more than 2e7 samples (t_end / every = {:.3g})", o.t_end / every));
  if (o.record) {
    const double need = simulation_memory_estimate(o, balls);
    const auto available = available_memory();
    require_memory(need, "--every", "the run",
                   fmt::format("{:.3g} samples of {} balls: the samples and the CSV text", o.t_end / every, balls),
                   fmt::format("use --every >= {:.3g} s or a shorter --t-end",
                               every * need / (kUsableMemoryShare * available.value_or(need))));
  }
  if (!(o.rtol >= 1e-14 && o.rtol < 0.1))
    throw InputError("--rtol", 0, "", fmt::format("the tolerance must lie in [1e-14, 0.1): below 1e-14 no double-precision step meets it (unit roundoff 1.1e-16) (got {})", o.rtol));
  if (size != dim)
    throw InputError("--from-state", 0, "", fmt::format("a state has 2n + 4 = {} values, got {}", dim, size));
  for (int i = 0; i < dim; ++i)
    if (!std::isfinite(x0[i])) throw InputError("--from-state", 0, "", "the initial state must be finite");
}

template <int N>
State<double, N> start_at_rest(const ParamsT<double, N>& p, const std::vector<double>& beta) {
  const int n = ball_count(p);
  if (int(beta.size()) != n)
    throw InputError("--balls", 0, "", fmt::format("expected {} ball angles (one per ball), got {}", n, beta.size()));
  State<double, N> x = State<double, N>::Zero(2 * n + 4);
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(beta[std::size_t(i)])) throw InputError("--balls", 0, "", "ball angles must be finite");
    x(2 + i) = beta[std::size_t(i)];
  }
  return x;
}

template <int N>
State<double, N> perturbed_equilibrium(const ParamsT<double, N>& p, const Coordinates<double, N>& position,
                                       std::complex<double> lambda, const ModeVector<N>& mode, double eps) {
  const int d = int(position.size());
  const double L = displacement_scale(p);
  const double rate = std::max(std::abs(lambda), 1e-300);
  State<double, N> dir(2 * d);
  for (int i = 0; i < d; ++i) {
    dir(i) = mode(i).real();
    dir(d + i) = (lambda * mode(i)).real();
  }
  if (dir.head(d).isZero(0)) {  // a purely imaginary mode shape: take its imaginary part
    for (int i = 0; i < d; ++i) {
      dir(i) = mode(i).imag();
      dir(d + i) = (lambda * mode(i)).imag();
    }
  }
  double size = 0;
  for (int i = 0; i < d; ++i) {
    const double s = i < 2 ? L : 1.0;
    size = std::max({size, std::abs(dir(i)) / s, std::abs(dir(d + i)) / (s * rate)});
  }
  if (!(size > 0)) throw NumericalError("perturbed_equilibrium: the eigenmode is zero");
  State<double, N> x = at_rest<double, N>(position);
  x += (eps / size) * dir;
  return x;
}

template <int N>
SimulationResult<N> simulate(const ParamsT<double, N>& p, const SpeedProfile& speed, const State<double, N>& x0,
                             const SimulationOptions& o) {
  gsl_handler_off_once();
  const bool lugre = p.law == FrictionLaw::lugre;  // 3n + 4 states, the bristles last (model.md §12.7)
  if (lugre && N != any_balls) throw std::invalid_argument("simulate: a LuGre scene runs with N = any_balls");
  if (!RigidMachine{o.race, o.support}.base() && (N != any_balls || lugre))
    throw std::invalid_argument("simulate: an unround race or an anisotropic support runs with N = any_balls and a smooth law");
  const int n = ball_count(p), mech = 2 * n + 4, dim = lugre ? 3 * n + 4 : mech;
  check_simulation_input(o, mech, x0.data(), int(x0.size()), n);
  const double every = o.every > 0 ? std::min(o.every, o.t_end) : o.t_end / 2000;
  if (!o.bristle_start.empty() && (!lugre || int(o.bristle_start.size()) != n))
    throw InputError("--from-state", 0, "", fmt::format("bristle states z(0) go with friction law 'lugre', one per ball ({})", n));

  SimulationResult<N> r;
  r.memory_estimate = simulation_memory_estimate(o, n);
  const auto wall0 = std::chrono::steady_clock::now();
  const double L = displacement_scale(p);
  const double w_max = speed.max_omega();
  const double w_n = natural_frequency(p.rotor.stiffness, p.total_mass());
  r.displacement_scale = L;

  // Stiffness probe (model.md §15.1): J at the start with the balls at rest relative to the
  // rotor (the friction slope is largest at beta' = 0) and omega = omega_max (N_i largest).
  {
    ParamsT<double, N> pp = p;
    pp.omega = w_max;
    State<double, N> xs = x0;
    xs.tail(n).setZero();
    // A Jacobian that overflowed would give a NaN stiffness ratio (and so a silent choice
    // of the explicit method) or a DBL_MAX spectral radius in the summary: fail here.
    const auto spectral_radius = [&](const auto& J) {
      if (!J.allFinite() || !(J.cwiseAbs().maxCoeff() <= 1e150))
        throw NumericalError(fmt::format(
            "simulate: the stiffness probe's Jacobian at omega_max = {:g} rad/s is not finite or beyond 1e150 "
            "(an overflow of the model at these parameters)",
            w_max));
      Eigen::EigenSolver<std::decay_t<decltype(J)>> es(J, false);
      if (es.info() == Eigen::Success && es.eigenvalues().allFinite()) return double(es.eigenvalues().cwiseAbs().maxCoeff());
      return double(J.cwiseAbs().rowwise().sum().maxCoeff());  // the infinity norm bounds it
    };
    double rho = 0;
    if constexpr (N == any_balls) {
      if (lugre) {  // bristles at z = 0: the stiffest slope c = 1 of (12.9) at rest
        LugreState<double> xl = LugreState<double>::Zero(dim);
        xl.head(mech) = xs;
        rho = spectral_radius(lugre_jacobian(pp, xl, RestSide::forward));
      } else if (const RigidMachine m{o.race, o.support}; !m.base()) {
        MachineFieldValue v;
        machine_field(pp, m, xs, 0.0, 0.0, v, true);
        rho = spectral_radius(v.jacobian);
      } else {
        rho = spectral_radius(jacobian(pp, xs));
      }
    } else {
      rho = spectral_radius(jacobian(pp, xs));
    }
    r.spectral_radius = rho;
    r.stiffness_ratio = rho / (w_max + w_n);
  }
  r.method = o.method;
  if (o.method == IntegrationMethod::automatic)
    r.method = r.stiffness_ratio > o.stiffness_threshold ? IntegrationMethod::bsimp : IntegrationMethod::rk8pd;

  OdeContext<N> ctx;
  ctx.p = p;
  ctx.dim = dim;
  if constexpr (N == any_balls) ctx.machine = RigidMachine{o.race, o.support};
  r.unround_race = ctx.machine.unround();
  r.anisotropic_support = ctx.machine.anisotropic();
  gsl_odeiv2_system sys{&ode_rhs<N>, &ode_jacobian<N>, std::size_t(dim), &ctx};
  const double h0 = std::min(1e-3 / (w_max + w_n), 1e-2 * o.t_end);
  // The driver allocates the stepper, a control and the evolve object once; its control is
  // replaced by the model-scaled one.
  std::unique_ptr<gsl_odeiv2_driver, DriverDeleter> drv(
      gsl_odeiv2_driver_alloc_y_new(&sys, step_type(r.method), h0, o.rtol, o.rtol));
  if (!drv) throw NumericalError("simulate: GSL could not allocate the integrator");
  gsl_odeiv2_control_free(drv->c);
  drv->c = gsl_odeiv2_control_alloc(&kScaledControl);
  if (!drv->c) throw NumericalError("simulate: GSL could not allocate the error control");
  auto* cs = static_cast<ScaledControlState*>(drv->c->state);
  cs->resize(std::size_t(dim));
  for (int i = 0; i < dim; ++i) {
    const bool angle = i >= 2 && i < n + 2;
    const bool velocity = i >= n + 2;
    const bool rotor = i < 2 || (i >= n + 2 && i < n + 4);
    cs->scale[i] = angle ? 1.0 : (rotor ? L : 1.0) * (velocity ? w_max : 1.0);
    cs->relative[i] = !angle;
  }
  for (int i = 0; i < dim - mech; ++i) {  // z_i in its natural size mu_s / sigma0 (the invariant bound, §12.1)
    const auto& b = p.balls[std::size_t(i)];
    cs->scale[mech + i] = b.mu_s / b.sigma0;
    cs->relative[mech + i] = true;
  }
  const double gsl_rtol = o.rtol / tolerance_factor(r.method);
  if (int st = gsl_odeiv2_control_init(drv->c, gsl_rtol, gsl_rtol, 1.0, 0.0); st != GSL_SUCCESS)
    throw NumericalError(fmt::format("simulate: GSL control init: {}", gsl_strerror(st)));
  if (int st = gsl_odeiv2_control_set_driver(drv->c, drv.get()); st != GSL_SUCCESS)
    throw NumericalError(fmt::format("simulate: GSL control: {}", gsl_strerror(st)));

  double y[lugre_state_capacity];
  for (int i = 0; i < mech; ++i) y[i] = x0(i);
  for (int i = mech; i < dim; ++i) y[i] = o.bristle_start.empty() ? 0.0 : o.bristle_start[std::size_t(i - mech)];
  r.start_below_resolution = zero_below_resolution(y, dim, *cs, o.rtol);
  r.bristle_count = dim - mech;
  double t = 0, h = h0;
  const auto record = [&](double time, const double* x) {
    if (!o.record) return;
    TrajectorySample<N> s;
    s.t = time;
    s.omega = speed.omega(time);
    s.x = load_state<N>(x, mech);
    r.samples.push_back(s);
    r.bristle.insert(r.bristle.end(), x + mech, x + dim);
    if (o.progress) o.progress(time);
    if (o.stop_at_sample && o.stop_at_sample(time, x)) r.stopped_early = true;
  };
  if (o.record) r.samples.reserve(std::size_t(std::ceil(o.t_end / every)) + 2);
  if (o.record) r.bristle.reserve(std::size_t(dim - mech) * (std::size_t(std::ceil(o.t_end / every)) + 2));
  record(0.0, y);

  std::vector<double> breaks = speed.breakpoints(0.0, o.t_end);
  breaks.push_back(o.t_end);
  std::size_t next_break = 0;
  const auto begin_segment = [&](double at) {
    ctx.segment_t0 = at;
    ctx.segment_omega0 = speed.omega(at);
    ctx.segment_theta0 = speed.angle(at);
    ctx.omega_dot = speed.omega_dot(at);
    ctx.jac_valid = false;  // J and df/dt depend on omega'
  };
  begin_segment(0.0);
  const auto accumulate = [&] {
    r.stats.steps += drv->e->count;
    r.stats.rejected += drv->e->failed_steps;
  };
  bool stop = false;
  const auto fail = [&](int st) {
    r.status = SimulationStatus::failed;
    const char* why = st == GSL_EBADFUNC ? "the right-hand side or Jacobian is not finite"
                      : st == GSL_FAILURE ? "the step size fell below the rounding level of t (the tolerance cannot be met)"
                                          : gsl_strerror(st);
    r.reason = fmt::format("at t = {:.9g} s (omega = {:.9g} rad/s, step {:.3g} s, {} steps): {} [GSL {}: {}]", t,
                           speed.omega(t), h, r.stats.steps + drv->e->count, why, st, gsl_strerror(st));
    stop = true;
  };

  // Dense output (model.md §15.1): the stepper runs freely to the next breakpoint; after every
  // accepted step the samples inside it come from the quintic Hermite interpolant and the
  // maxima of |q| inside it are located (§15.4). Slot 0 of `step` is the current point.
  const bool jacobian_each_step = r.method == IntegrationMethod::bsimp || r.method == IntegrationMethod::rk4imp;
  const OdeField<N> field{&ctx, jacobian_each_step, o.rtol < 1e-9, 1.0 / (w_max + w_n)};
  dense::Stepper<OdeField<N>> dense(field, dim, o.rtol, cs->scale.data(), cs->relative.get());
  const bool dense_on = o.record;
  const bool retake_allowed = r.method != IntegrationMethod::bdf;  // msbdf keeps a history
  const bool exact_dydt_out = drv->s->type->gives_exact_dydt_out != 0;
  dense::SampleClock clock{every, o.t_end};
  double x_sample[dense::capacity];
  if (dense_on) {
    if (int st = dense.start(t, y); st != GSL_SUCCESS) fail(st);
    dense.peaks.add({std::hypot(y[0], y[1]), 0.0}, ctx.omega_dot != 0);
  }
  while (!stop && !r.stopped_early && t < o.t_end) {
    double target = breaks[next_break];
    if (dense_on) target = dense.plan(t, h, clock.next(), target);
    const double h_before = h;
    const int st = gsl_odeiv2_evolve_apply(drv->e, drv->c, drv->s, &sys, &t, target, &h, y);
    if (st != GSL_SUCCESS) {
      fail(st);
      break;
    }
    // A step clamped to reach the target returns a small proposal; keep the previous one.
    if (t == target && h < h_before) h = h_before;
    if (dense_on) {
      const int fs = dense.finish(t, y, exact_dydt_out ? drv->e->dydt_out : nullptr);
      if (fs != GSL_SUCCESS) {
        fail(fs);
        break;
      }
      const dense::QPeak candidate = dense.candidate();
      if (retake_allowed && dense.retake(clock.next(), candidate)) {  // the interpolant misses: again, shorter
        t = dense.step.t0;
        std::copy(dense.step.y0, dense.step.y0 + dim, y);
        h = std::min(h, dense.h_limit);
        // GSL's evolve takes the last step's end field as the next step's start field: reset it
        // (its counts are kept first), so that it evaluates f(t0, y0) again.
        accumulate();
        gsl_odeiv2_evolve_reset(drv->e);
        continue;
      }
      // The samples in (t0, t]: interpolated, the step's end exactly.
      const double t_part = dense.emit(
          clock, [&](double ts, const double* x) { return record(ts, x), r.stopped_early; }, candidate,
          ctx.omega_dot != 0, x_sample);
      if (r.stopped_early) {  // the run ends at that sample
        t = t_part;
        std::copy(x_sample, x_sample + dim, y);
        break;
      }
      dense.advance();
    }
    if (stop_rule(r.stats.steps + drv->e->count - dense.retaken, o, t, r.status, r.reason)) {
      stop = true;
      break;
    }
    if (t == breaks[next_break] && next_break + 1 < breaks.size()) {
      // omega' jumps here (model.md §9): restart the stepper on the new segment.
      accumulate();
      if (int rs = gsl_odeiv2_driver_reset(drv.get()); rs != GSL_SUCCESS)
        throw NumericalError(fmt::format("simulate: GSL reset at t = {}: {}", t, gsl_strerror(rs)));
      ++r.stats.restarts;
      ++next_break;
      begin_segment(t);
      if (dense_on)
        if (int ds = dense.start(t, y); ds != GSL_SUCCESS) fail(ds);
    }
  }
  if (stop && o.record && r.samples.back().t < t) record(t, y);
  accumulate();
  r.stats.steps -= dense.retaken;  // counted by GSL as accepted, then discarded
  r.stats.rejected += dense.retaken;
  r.stats.retaken = dense.retaken;
  r.stats.rhs_evaluations = ctx.rhs;
  r.stats.jacobian_evaluations = ctx.jac;
  r.x_end = load_state<N>(y, mech);
  r.bristle_end.assign(y + mech, y + dim);
  r.t_reached = t;
  r.stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (o.record) {
    r.summary = summarize(p, speed, r.samples, o);
    dense.peaks.merge_into(r.summary);  // the maxima between the samples (model.md §15.4)
  }
  return r;
}

#define ABU_INSTANTIATE_SIMULATION(N)                                                                               \
  template State<double, N> start_at_rest<N>(const ParamsT<double, N>&, const std::vector<double>&);                  \
  template State<double, N> perturbed_equilibrium<N>(const ParamsT<double, N>&, const Coordinates<double, N>&,       \
                                                     std::complex<double>, const ModeVector<N>&, double);            \
  template SimulationResult<N> simulate<N>(const ParamsT<double, N>&, const SpeedProfile&, const State<double, N>&, \
                                           const SimulationOptions&);
ABU_INSTANTIATE_SIMULATION(2)
ABU_INSTANTIATE_SIMULATION(any_balls)
#undef ABU_INSTANTIATE_SIMULATION

}  // namespace abu
