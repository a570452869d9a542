// Trajectories of the flexible rotor with GSL odeiv2 (shaft_simulation.hpp, model.md §18.16).
#include "abu/dynamics/shaft_simulation.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "abu/core/errors.hpp"
#include "abu/model/unround_race.hpp"
#include "dense_output.hpp"
#include "scaled_control.hpp"
#include "shaft_field.hpp"

namespace abu {

using namespace sim_detail;  // the GSL parts shared with simulate() (scaled_control.hpp)

namespace {

// omega(t) = omega0 + omega' (t - t0) within a segment of the speed profile, and the spin angle
// theta(t) = theta0 + omega0 (t - t0) + omega' (t - t0)^2 / 2 that turns anisotropic bearings (§18.19).
struct Context {
  shaft_detail::ShaftOde* ode;
  double t0 = 0, omega0 = 0, omega_dot = 0, theta0 = 0;
  void at(double t) const {
    const double s = t - t0;
    ode->set_speed(omega0 + omega_dot * s, omega_dot);
    ode->set_angle(theta0 + s * (omega0 + 0.5 * omega_dot * s));
  }
};

int field_rhs(double t, const double y[], double f[], void* params) {
  const auto& c = *static_cast<Context*>(params);
  c.at(t);
  return c.ode->field(y, f) ? GSL_SUCCESS : GSL_EBADFUNC;
}

int field_jacobian(double t, const double y[], double* dfdy, double dfdt[], void* params) {
  const auto& c = *static_cast<Context*>(params);
  c.at(t);
  try {
    return c.ode->jacobian(y, dfdy, dfdt) ? GSL_SUCCESS : GSL_EBADFUNC;
  } catch (const std::exception&) {  // linearize_shaft's factorization: reported as a bad function
    return GSL_EBADFUNC;
  }
}

// The field for the dense output (model.md §15.1, §18.16): f, and y'' by differences of f along
// (1, f) on the time scale of the fastest motion followed (dense_output.hpp).
struct DenseField {
  Context* ctx;
  bool central;  // rtol < 1e-9: the central difference
  double time_scale;
  int dim;
  int rhs(double t, const double* y, double* f) const { return field_rhs(t, y, f, ctx); }
  int second(double t, const double* y, const double* f, double* g) const {
    const auto field = [this](double tt, const double* yy, double* ff) { return rhs(tt, yy, ff); };
    return dense::second_by_difference<shaft_simulation_max_states>(field, dim, time_scale, central, t, y, f, g);
  }
};

// The largest |(y_pos, y_pos+1)| on the step's quintic Hermite interpolant from the values, rates
// (y_vel) and accelerations (f_vel) at both ends (model.md (15.1.3)); `s` is reused storage.
dense::QPeak pair_peak(dense::StepN<2>& s, double t0, double t1, const double* y0, const double* f0, const double* y1,
                       const double* f1, int pos, int vel, double floor) {
  s.dim = 2;
  s.t0 = t0;
  s.t1 = t1;
  for (int i = 0; i < 2; ++i) {
    s.y0[i] = y0[pos + i], s.f0[i] = y0[vel + i], s.g0[i] = f0[vel + i];
    s.y1[i] = y1[pos + i], s.f1[i] = y1[vel + i], s.g1[i] = f1[vel + i];
  }
  return s.q_peak(t0, t1, s.y0, s.y1, floor);
}

double shaft_length(const ShaftSpec& spec) {
  double length = 0;
  for (const auto& e : spec.elements) length += e.length;
  return length;
}

std::string failure_text(int st) {
  const char* why = st == GSL_EBADFUNC ? "the right-hand side or Jacobian is not finite"
                    : st == GSL_FAILURE ? "the step size fell below the rounding level of t (the tolerance cannot be met)"
                                        : gsl_strerror(st);
  return fmt::format("{} [GSL {}: {}]", why, st, gsl_strerror(st));
}

// The checks of simulate_shaft before any work (InputError naming the option and the rule).
void check_shaft_input(const ShaftSystem& sys, const Eigen::VectorXd& x0, const SimulationOptions& o) {
  if (o.support || !o.bristle_start.empty())
    throw std::invalid_argument("simulate_shaft: a rigid support or bristles are other routes");
  if (o.race && !o.race->round() && has_anisotropic_bearings(sys.spec))
    throw std::invalid_argument("simulate_shaft: anisotropic bearings with an unround race are not modelled (model.md "
                                "§18.19, §18.20)");
  const int n = sys.n_balls(), dim = sys.state_size();
  if (dim > shaft_simulation_max_states)
    throw InputError("[shaft]", 0, "",
                     fmt::format("the shaft's state has 2 (4 N_nodes + n) = 2 (4 x {} + {}) = {} values; simulate takes "
                                 "at most {} (its implicit steppers factor dense Jacobians: about {:.0f} MB at this "
                                 "size); use fewer elements (segments)",
                                 sys.nodes(), n, dim, shaft_simulation_max_states, 10.0 * 8.0 * dim * dim / 1e6));
  if (int(x0.size()) != dim)
    throw InputError("--from-state", 0, "",
                     fmt::format("a state of this shaft has 2 (4 N_nodes + n) = 2 (4 x {} + {}) = {} values (u1,u2,psi1,"
                                 "psi2 per node, beta1..beta{}, then their rates), got {}",
                                 sys.nodes(), n, dim, n, x0.size()));
  check_simulation_input(o, dim, x0.data(), dim, n);
}

// The stiffness probe (model.md §15.1, (18.16.5)): J at x0 with the balls at rest relative to the
// rotor and omega = omega_max. Sets the run's spectral_radius (the fastest decay) and
// stiffness_ratio; returns the fastest motion every stepper follows [1/s].
double probe_stiffness(shaft_detail::ShaftOde& ode, const ShaftSystem& sys, const Eigen::VectorXd& x0, double w_max,
                       double w_n, SimulationResult<any_balls>& run) {
  std::vector<double> xs(x0.data(), x0.data() + x0.size());
  for (int i = 0; i < sys.n_balls(); ++i) xs[std::size_t(sys.configuration_size() + sys.ball_dof(i))] = 0.0;
  ode.set_speed(w_max, 0.0);
  ode.set_angle(0.0);
  const shaft_detail::StiffnessProbe probe = ode.probe(xs.data());
  if (!std::isfinite(probe.decay) || probe.decay > 1e150)
    throw NumericalError(fmt::format("simulate: the stiffness probe's Jacobian at omega_max = {:g} rad/s is not finite "
                                     "(an overflow of the model at these parameters)",
                                     w_max));
  // The spin and omega_n as on the rigid rotor, or the shaft's fastest underdamped mode.
  const double follow = std::max(w_max + w_n, probe.oscillation);
  run.spectral_radius = probe.decay;
  run.stiffness_ratio = probe.decay / follow;
  return follow;
}

// The scales of the error control (model.md §18.16): translations in L, tilts in L over the
// shaft's length (or the race radius if larger), angles absolutely in rad; rates times omega_max.
void set_scales(ScaledControlState& cs, const ShaftSystem& sys, double L, double w_max) {
  const int d = sys.configuration_size(), ns = sys.shaft_dofs();
  double reach = shaft_length(sys.spec);
  for (const auto& ball : sys.balancer.balls) reach = std::max(reach, ball.race_radius);
  cs.resize(std::size_t(2 * d));
  for (int i = 0; i < 2 * d; ++i) {
    const int c = i % d;
    const bool angle = c >= ns;
    const double size = angle ? 1.0 : (c % 4 < 2 ? L : L / reach);
    cs.scale[std::size_t(i)] = size * (i >= d ? w_max : 1.0);
    cs.relative[std::size_t(i)] = !(angle && i < d);
  }
}

}  // namespace

State<double, any_balls> balancer_view(const ShaftSystem& sys, const double* x) {
  const int n = sys.n_balls(), ns = sys.shaft_dofs(), d = sys.configuration_size(), b = sys.balancer_dof();
  State<double, any_balls> v = State<double, any_balls>::Zero(2 * n + 4);
  for (int k = 0; k < 2; ++k) v(k) = x[b + k], v(n + 2 + k) = x[d + b + k];
  for (int i = 0; i < n; ++i) v(2 + i) = x[ns + i], v(n + 4 + i) = x[d + ns + i];
  return v;
}

Eigen::VectorXd shaft_start_at_rest(const ShaftSystem& sys, const std::vector<double>& beta) {
  const int n = sys.n_balls();
  if (int(beta.size()) != n)
    throw InputError("--balls", 0, "", fmt::format("expected {} ball angles (one per ball), got {}", n, beta.size()));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(sys.state_size());
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(beta[std::size_t(i)])) throw InputError("--balls", 0, "", "ball angles must be finite");
    x(sys.ball_dof(i)) = beta[std::size_t(i)];
  }
  return x;
}

ParamsN shaft_summary_params(const ShaftSystem& sys) {
  ParamsN p = sys.balancer;
  for (const auto& disc : sys.spec.discs)
    if (disc.node == sys.spec.balancer_node) p.rotor.mass = disc.mass;
  // The static stiffness at the balancer node: 1 / (K^-1)_bb (K is positive definite: the
  // bearings hold the shaft, model.md §18.11).
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(sys.fixed.stiffness);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(sys.shaft_dofs());
  e(sys.balancer_dof()) = 1.0;
  const Eigen::VectorXd h = ldlt.solve(e);
  if (ldlt.info() != Eigen::Success || !(h(sys.balancer_dof()) > 0))
    throw NumericalError("simulate: the shaft's stiffness matrix is not positive definite (model.md §18.11)");
  p.rotor.stiffness = 1.0 / h(sys.balancer_dof());
  p.rotor.damping = 0.0;
  return p;
}

ShaftSimulationResult simulate_shaft(const ShaftSystem& sys, const SpeedProfile& speed, const Eigen::VectorXd& x0,
                                     const SimulationOptions& o) {
  gsl_handler_off_once();
  check_shaft_input(sys, x0, o);
  const int d = sys.configuration_size(), b = sys.balancer_dof();
  const int dim = sys.state_size();
  const double every = o.every > 0 ? std::min(o.every, o.t_end) : o.t_end / 2000;

  ShaftSimulationResult r;
  const auto wall0 = std::chrono::steady_clock::now();
  r.view = shaft_summary_params(sys);
  r.nodes = sys.nodes();
  r.state_size = dim;
  SimulationResult<any_balls>& run = r.run;
  const double L = displacement_scale(r.view);
  const double w_max = speed.max_omega(), w_n = std::sqrt(r.view.rotor.stiffness / r.view.total_mass());
  run.displacement_scale = L;

  shaft_detail::ShaftOde ode(sys, o.race);  // an unround race: the balls on its paths (model.md §18.20)
  run.unround_race = ode.unround();
  const double follow = probe_stiffness(ode, sys, x0, w_max, w_n, run);
  run.method = o.method;
  run.memory_estimate = simulation_memory_estimate(o, sys.n_balls());
  if (o.method == IntegrationMethod::automatic)
    run.method = run.stiffness_ratio > o.stiffness_threshold ? IntegrationMethod::bsimp : IntegrationMethod::rk8pd;

  Context ctx{&ode};
  gsl_odeiv2_system system{&field_rhs, &field_jacobian, std::size_t(dim), &ctx};
  const double h0 = std::min(1e-3 / (w_max + w_n), 1e-2 * o.t_end);
  std::unique_ptr<gsl_odeiv2_driver, DriverDeleter> drv(
      gsl_odeiv2_driver_alloc_y_new(&system, step_type(run.method), h0, o.rtol, o.rtol));
  if (!drv) throw NumericalError("simulate: GSL could not allocate the integrator");
  gsl_odeiv2_control_free(drv->c);
  drv->c = gsl_odeiv2_control_alloc(&kScaledControl);
  if (!drv->c) throw NumericalError("simulate: GSL could not allocate the error control");
  auto* cs = static_cast<ScaledControlState*>(drv->c->state);
  set_scales(*cs, sys, L, w_max);
  const double gsl_rtol = o.rtol / tolerance_factor(run.method);
  if (int st = gsl_odeiv2_control_init(drv->c, gsl_rtol, gsl_rtol, 1.0, 0.0); st != GSL_SUCCESS)
    throw NumericalError(fmt::format("simulate: GSL control init: {}", gsl_strerror(st)));

  std::vector<double> y(x0.data(), x0.data() + dim), x_sample(y.size());
  run.start_below_resolution = zero_below_resolution(y.data(), dim, *cs, o.rtol);
  double t = 0, h = h0;
  const auto record = [&](double time, const double* x) {
    if (!o.record) return;
    TrajectorySample<any_balls> s;
    s.t = time;
    s.omega = speed.omega(time);
    s.x = balancer_view(sys, x);
    run.samples.push_back(s);
    if (o.stop_at_sample && o.stop_at_sample(time, s.x.data())) run.stopped_early = true;
    double worst = -1;
    int node = 0;
    for (int k = 0; k < sys.nodes(); ++k)
      if (const double v = std::hypot(x[4 * k], x[4 * k + 1]); v > worst) worst = v, node = k;
    r.deflection.push_back(worst);
    r.deflection_node.push_back(node);
    if (o.progress) o.progress(time);
  };
  if (o.record) {
    const std::size_t count = std::size_t(std::ceil(o.t_end / every)) + 2;
    run.samples.reserve(count);
    r.deflection.reserve(count);
    r.deflection_node.reserve(count);
  }
  record(0.0, y.data());
  if (o.record) r.max_deflection = r.deflection[0], r.max_deflection_node = r.deflection_node[0];

  std::vector<double> breaks = speed.breakpoints(0.0, o.t_end);
  breaks.push_back(o.t_end);
  std::size_t next_break = 0;
  bool stop = false;
  const auto fail = [&](const std::string& why) {
    run.status = SimulationStatus::failed;
    run.reason = fmt::format("at t = {:.9g} s (omega = {:.9g} rad/s, step {:.3g} s, {} steps): {}", t, speed.omega(t),
                             h, run.stats.steps + drv->e->count, why);
    stop = true;
  };
  const auto begin_segment = [&](double at) {
    ctx.t0 = at;
    ctx.omega0 = speed.omega(at);
    ctx.omega_dot = speed.omega_dot(at);
    ctx.theta0 = speed.angle(at);
  };
  begin_segment(0.0);
  const auto accumulate = [&] {
    run.stats.steps += drv->e->count;
    run.stats.rejected += drv->e->failed_steps;
  };
  // Dense output as the rigid route's (model.md §15.1): the stepper runs freely to the next
  // breakpoint; the samples come from each step's quintic Hermite interpolant, a step whose
  // interpolant misses rtol where it is used is taken again shorter; the largest |q| of the
  // balancer node and the largest node deflection are located on it (§15.4, §18.16). The
  // stepper's arrays hold shaft_simulation_max_states values: on the heap, once per run.
  auto dense = std::make_unique<dense::Stepper<DenseField, shaft_simulation_max_states>>(
      DenseField{&ctx, o.rtol < 1e-9, 1.0 / follow, dim}, dim, o.rtol, cs->scale.data(), cs->relative.get());
  const bool dense_on = o.record;
  const bool retake_allowed = run.method != IntegrationMethod::bdf;  // msbdf keeps a history
  const bool exact_dydt_out = drv->s->type->gives_exact_dydt_out != 0;
  dense::StepN<2> pair;  // one node's (u1, u2) interpolant
  dense::SampleClock clock{every, o.t_end};
  if (dense_on) {
    if (int st = dense->start(t, y.data()); st != GSL_SUCCESS) fail(failure_text(st));
    dense->peaks.add({std::hypot(y[std::size_t(b)], y[std::size_t(b + 1)]), 0.0}, ctx.omega_dot != 0);
  }
  while (!stop && !run.stopped_early && t < o.t_end) {
    double target = breaks[next_break];
    if (dense_on) target = dense->plan(t, h, clock.next(), target);
    const double h_before = h;
    if (int st = gsl_odeiv2_evolve_apply(drv->e, drv->c, drv->s, &system, &t, target, &h, y.data()); st != GSL_SUCCESS) {
      fail(failure_text(st));
      break;
    }
    if (t == target && h < h_before) h = h_before;  // a step clamped to reach the target
    if (dense_on) {
      if (int st = dense->finish(t, y.data(), exact_dydt_out ? drv->e->dydt_out : nullptr); st != GSL_SUCCESS) {
        fail(failure_text(st));
        break;
      }
      const auto& s = dense->step;
      const dense::QPeak candidate = pair_peak(pair, s.t0, s.t1, s.y0, s.f0, s.y1, s.f1, b, d + b, dense->peaks.all.q_abs);
      if (retake_allowed && dense->retake(clock.next(), candidate)) {  // the interpolant misses: again, shorter
        t = s.t0;
        std::copy(s.y0, s.y0 + dim, y.begin());
        h = std::min(h, dense->h_limit);
        accumulate();  // GSL's evolve keeps the end field of the step it returned: reset it
        gsl_odeiv2_evolve_reset(drv->e);
        continue;
      }
      for (int k = 0; k < sys.nodes(); ++k) {
        const dense::QPeak pk = pair_peak(pair, s.t0, s.t1, s.y0, s.f0, s.y1, s.f1, 4 * k, d + 4 * k, r.max_deflection);
        if (pk.q_abs > r.max_deflection) r.max_deflection = pk.q_abs, r.t_max_deflection = pk.t, r.max_deflection_node = k;
      }
      const double t_part = dense->emit(
          clock, [&](double ts, const double* x) { return record(ts, x), run.stopped_early; }, candidate,
          ctx.omega_dot != 0, x_sample.data());
      if (run.stopped_early) {  // the run ends at that sample
        t = t_part;
        std::copy(x_sample.begin(), x_sample.end(), y.begin());
        break;
      }
      dense->advance();
    }
    if (stop_rule(run.stats.steps + drv->e->count - dense->retaken, o, t, run.status, run.reason)) {
      stop = true;
      break;
    }
    if (t == breaks[next_break] && next_break + 1 < breaks.size()) {
      // omega' jumps here (model.md §9): restart the stepper on the new segment.
      accumulate();
      if (int rs = gsl_odeiv2_driver_reset(drv.get()); rs != GSL_SUCCESS)
        throw NumericalError(fmt::format("simulate: GSL reset at t = {}: {}", t, gsl_strerror(rs)));
      ++run.stats.restarts;
      ++next_break;
      begin_segment(t);
      if (dense_on)
        if (int st = dense->start(t, y.data()); st != GSL_SUCCESS) fail(failure_text(st));
    }
  }
  if (stop && o.record && run.samples.back().t < t) record(t, y.data());
  accumulate();
  run.stats.steps -= dense->retaken;  // counted by GSL as accepted, then discarded
  run.stats.rejected += dense->retaken;
  run.stats.retaken = dense->retaken;
  run.stats.rhs_evaluations = ode.rhs_count;
  run.stats.jacobian_evaluations = ode.jacobian_count;
  r.x_end = Eigen::Map<const Eigen::VectorXd>(y.data(), dim);
  run.x_end = balancer_view(sys, y.data());
  run.t_reached = t;
  run.stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (o.record) {
    run.summary = summarize(r.view, speed, run.samples, o);
    dense->peaks.merge_into(run.summary);
    // omega_n of the rigid view is the stall test's estimate, not a critical speed of the shaft:
    // no passages through it are listed (model.md §18.16).
    run.summary.t_omega_n.clear();
    // Nor is the rigid rotor's whirl a reference for a shaft (model.md §21.1: rigid rotors).
    run.summary.bare_rotor_q_abs = run.summary.balls_held_q_abs = 0;
  }
  return r;
}

}  // namespace abu
