// Internal to simulate() (simulation.cpp): the ODE system GSL integrates — the context that
// follows the speed profile (omega, omega' and the spin angle theta within a segment), the
// right-hand side and the analytic Jacobian with df/dt for model.md §3 and §9, the composed
// field of §20 (an unround race and/or an anisotropic support) and LuGre's 3n + 4 states
// (§12.7), the Jacobian cache the dense output shares (§15.1).
#pragma once

#include <gsl/gsl_errno.h>

#include <algorithm>
#include <cmath>

#include "abu/model/lugre.hpp"
#include "abu/model/machine_field.hpp"
#include "abu/model/model.hpp"
#include "dense_output.hpp"

namespace abu::sim_detail {

template <int N>
struct OdeContext {
  ParamsT<double, N> p;  // p.omega follows the profile
  // omega(t) = omega0 + omega_dot (t - t0), the spin angle theta(t) = theta0 + omega0 (t - t0) +
  // omega_dot (t - t0)^2 / 2 inside a segment of the profile.
  double segment_t0 = 0, segment_omega0 = 0, segment_theta0 = 0, omega_dot = 0;
  int dim = 0;
  unsigned long rhs = 0, jac = 0;
  ParamRef omega_ref{Quantity::omega, -1};
  // An unround race and/or an anisotropic support (model.md §15.6, §20), N = any_balls;
  // base(): model.md §3 and §9 by model.hpp.
  RigidMachine machine;
  MachineFieldValue value;  // the composed field's last evaluation (bounded: no allocation per step)
  void set_time(double t) { p.omega = segment_omega0 + omega_dot * (t - segment_t0); }
  double theta(double t) const {
    const double s = t - segment_t0;
    return segment_theta0 + s * (segment_omega0 + 0.5 * omega_dot * s);
  }
  // The last Jacobian evaluated and where: bsimp asks for J at the start of every step (again
  // after a rejection), the dense output at the end of every step, the same point (§15.1).
  bool jac_valid = false;
  double jac_t = 0;
  double jac_y[lugre_state_capacity] = {};
  double jac_dfdy[lugre_state_capacity * lugre_state_capacity] = {};  // row-major, dim x dim
  double jac_dfdt[lugre_state_capacity] = {};
};

template <int N>
State<double, N> load_state(const double y[], int dim) {
  State<double, N> x(dim);
  for (int i = 0; i < dim; ++i) x(i) = y[i];
  return x;
}

// LuGre (model.md §12.7): the (3n + 4) field of model/lugre.hpp; x holds the bristles last.
inline int lugre_rhs(const ParamsN& p, double omega_dot, const double y[], double dydt[], int dim) {
  const LugreState<double> f = lugre_vector_field(p, LugreState<double>(Eigen::Map<const Eigen::VectorXd>(y, dim)), omega_dot);
  for (int i = 0; i < dim; ++i) {
    if (!std::isfinite(f(i))) return GSL_EBADFUNC;
    dydt[i] = f(i);
  }
  return GSL_SUCCESS;
}

// A ball exactly at rest takes the forward one-sided slope (12.9); at z = 0 both agree.
inline int lugre_jac(const ParamsN& p, double omega_dot, const double y[], double* dfdy, double dfdt[], int dim) {
  const LugreState<double> x = Eigen::Map<const Eigen::VectorXd>(y, dim);
  const LugreMatrix<double> J = lugre_jacobian(p, x, RestSide::forward, omega_dot);
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) {
      if (!std::isfinite(J(i, j))) return GSL_EBADFUNC;
      dfdy[i * dim + j] = J(i, j);
    }
  if (omega_dot != 0) {
    const LugreState<double> dfw = lugre_omega_derivative(p, x);
    for (int i = 0; i < dim; ++i) dfdt[i] = omega_dot * dfw(i);
  } else {
    for (int i = 0; i < dim; ++i) dfdt[i] = 0.0;
  }
  return GSL_SUCCESS;
}

template <int N>
int ode_rhs(double t, const double y[], double dydt[], void* params) {
  auto& c = *static_cast<OdeContext<N>*>(params);
  ++c.rhs;
  c.set_time(t);
  if constexpr (N == any_balls)
    if (c.p.law == FrictionLaw::lugre) return lugre_rhs(c.p, c.omega_dot, y, dydt, c.dim);
  const State<double, N> x = load_state<N>(y, c.dim);
  if constexpr (N == any_balls)
    if (!c.machine.base()) {  // model.md (20.1): (11.3.4) with (15.6.1), and the support's force
      machine_field(c.p, c.machine, x, c.theta(t), c.omega_dot, c.value, false);
      for (int i = 0; i < c.dim; ++i) {
        if (!std::isfinite(c.value.field(i))) return GSL_EBADFUNC;
        dydt[i] = c.value.field(i);
      }
      return GSL_SUCCESS;
    }
  // model.md §3 at constant speed; §9 (Euler terms) while omega' != 0.
  const State<double, N> f = c.omega_dot == 0 ? vector_field(c.p, x) : vector_field(c.p, x, c.omega_dot);
  for (int i = 0; i < c.dim; ++i) {
    if (!std::isfinite(f(i))) return GSL_EBADFUNC;
    dydt[i] = f(i);
  }
  return GSL_SUCCESS;
}

template <int N>
int evaluate_jacobian(OdeContext<N>& c, double t, const double y[], double* dfdy, double dfdt[]) {
  ++c.jac;
  c.set_time(t);
  if constexpr (N == any_balls)
    if (c.p.law == FrictionLaw::lugre) return lugre_jac(c.p, c.omega_dot, y, dfdy, dfdt, c.dim);
  const State<double, N> x = load_state<N>(y, c.dim);
  if constexpr (N == any_balls) {
    if (!c.machine.base()) {  // model.md §20: df/dt = omega' df/domega + omega df/dtheta
      machine_field(c.p, c.machine, x, c.theta(t), c.omega_dot, c.value, true);
      for (int i = 0; i < c.dim; ++i) {
        for (int j = 0; j < c.dim; ++j) {
          if (!std::isfinite(c.value.jacobian(i, j))) return GSL_EBADFUNC;
          dfdy[i * c.dim + j] = c.value.jacobian(i, j);  // GSL: row-major
        }
        dfdt[i] = c.omega_dot * c.value.omega_derivative(i) + c.p.omega * c.value.angle_derivative(i);
      }
      return GSL_SUCCESS;
    }
  }
  const StateMatrix<double, N> J = c.omega_dot == 0 ? jacobian(c.p, x) : jacobian(c.p, x, c.omega_dot);
  for (int i = 0; i < c.dim; ++i)
    for (int j = 0; j < c.dim; ++j) {
      if (!std::isfinite(J(i, j))) return GSL_EBADFUNC;
      dfdy[i * c.dim + j] = J(i, j);  // GSL: row-major
    }
  // df/dt = omega' df/domega (+ omega'' df/domega', zero inside a segment of the profile).
  if (c.omega_dot != 0) {
    const State<double, N> dfw = parameter_derivative(c.p, x, c.omega_ref);
    for (int i = 0; i < c.dim; ++i) dfdt[i] = c.omega_dot * dfw(i);
  } else {
    for (int i = 0; i < c.dim; ++i) dfdt[i] = 0.0;
  }
  return GSL_SUCCESS;
}

// J and df/dt at (t, y) in the context's cache, evaluated unless the cache holds that point.
template <int N>
int cached_jacobian(OdeContext<N>& c, double t, const double y[]) {
  if (c.jac_valid && t == c.jac_t && std::equal(y, y + c.dim, c.jac_y)) return GSL_SUCCESS;
  c.jac_valid = false;
  const int st = evaluate_jacobian(c, t, y, c.jac_dfdy, c.jac_dfdt);
  if (st != GSL_SUCCESS) return st;
  c.jac_valid = true;
  c.jac_t = t;
  std::copy(y, y + c.dim, c.jac_y);
  return GSL_SUCCESS;
}

template <int N>
int ode_jacobian(double t, const double y[], double* dfdy, double dfdt[], void* params) {
  auto& c = *static_cast<OdeContext<N>*>(params);
  const int st = cached_jacobian(c, t, y);
  if (st != GSL_SUCCESS) return st;
  std::copy(c.jac_dfdy, c.jac_dfdy + c.dim * c.dim, dfdy);
  std::copy(c.jac_dfdt, c.jac_dfdt + c.dim, dfdt);
  return GSL_SUCCESS;
}

// y'' = J f + df/dt at (t, y) with f = y' given (the dense output's second derivative, §15.1).
template <int N>
int second_derivative(OdeContext<N>& c, double t, const double y[], const double f[], double g[]) {
  const int st = cached_jacobian(c, t, y);
  if (st != GSL_SUCCESS) return st;
  for (int i = 0; i < c.dim; ++i) {
    double v = c.jac_dfdt[i];
    const double* row = c.jac_dfdy + i * c.dim;
    for (int j = 0; j < c.dim; ++j) v += row[j] * f[j];
    g[i] = v;
  }
  return GSL_SUCCESS;
}

// simulate()'s field for the dense output (model.md §15.1): f, and y'' = J f + f_t. With the
// steppers that evaluate J at every step's start (bsimp, rk4imp) from the analytic Jacobian,
// cached for the next step: it costs nothing more. With the others a Jacobian would cost about
// four evaluations of f: y'' by differences of f along (1, f) instead (dense_output.hpp).
template <int N>
struct OdeField {
  OdeContext<N>* ctx;
  bool analytic;
  bool central;       // the central difference (rtol < 1e-9), else the forward one
  double time_scale;  // 1 / (omega_max + omega_n)
  int rhs(double t, const double* y, double* f) const { return ode_rhs<N>(t, y, f, ctx); }
  int second(double t, const double* y, const double* f, double* g) const {
    if (analytic) return second_derivative(*ctx, t, y, f, g);
    const auto field = [this](double tt, const double* yy, double* ff) { return ode_rhs<N>(tt, yy, ff, ctx); };
    return dense::second_by_difference(field, ctx->dim, time_scale, central, t, y, f, g);
  }
};

}  // namespace abu::sim_detail
