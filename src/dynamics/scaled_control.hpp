// Internal to the dynamics layer: what `simulate` (simulation.cpp) and `simulate` on a
// flexible shaft (shaft_simulation.cpp) share around GSL odeiv2 — the error control in the
// model's scaling (model.md §15.1), the steppers of IntegrationMethod, the tolerance factor
// of bsimp, the driver's deleter and GSL's error handler turned off.
#pragma once

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "abu/dynamics/simulation.hpp"

namespace abu::sim_detail {

// GSL's default handler aborts; the simulations report every return code instead.
inline void gsl_handler_off_once() {
  static std::once_flag flag;
  std::call_once(flag, [] { gsl_set_error_handler_off(); });
}

// The run's own stop rules after a step (model.md §15.1): beyond `max_steps` accepted steps it
// fails, on the interrupt flag (Ctrl-C) it is interrupted; either sets the status and the reason
// with the time, and says so.
inline bool stop_rule(unsigned long steps, const SimulationOptions& o, double t, SimulationStatus& status,
                      std::string& reason) {
  if (steps > o.max_steps) {
    status = SimulationStatus::failed;
    reason = fmt::format("at t = {:.9g} s: more than {} steps (raise the tolerance or shorten the run)", t, o.max_steps);
    return true;
  }
  if (o.interrupt && o.interrupt->load(std::memory_order_relaxed)) {
    status = SimulationStatus::interrupted;
    reason = fmt::format("interrupted at t = {:.9g} s", t);
    return true;
  }
  return false;
}

// ---- error control in the model's scaling (model.md §15.1) -------------------------------
// D_i = rtol (scale_i + relative_i |y_i|); a step is accepted when max_i |err_i| / D_i <= 1.1,
// the step adjusted as GSL's standard control does (safety 0.9, factors in [0.2, 5]).
// The scales are sized once per run (resize), never per step.
struct ScaledControlState {
  double rtol = 1e-8;
  std::size_t dim = 0;
  std::vector<double> scale;
  std::unique_ptr<bool[]> relative;
  void resize(std::size_t d) {
    dim = d;
    scale.assign(d, 0.0);
    relative = std::make_unique<bool[]>(d);
  }
};

// Start components nonzero but below 1e-3 of their absolute tolerance rtol * scale_i are set
// to 0 and counted (SimulationResult::start_below_resolution): below what the run resolves,
// and GSL's bsimp, which weighs a change by |y_i|, takes any change of one for a runaway.
inline int zero_below_resolution(double* y, int dim, const ScaledControlState& s, double rtol) {
  int zeroed = 0;
  for (int i = 0; i < dim; ++i)
    if (y[i] != 0.0 && std::abs(y[i]) < 1e-3 * rtol * s.scale[std::size_t(i)]) y[i] = 0.0, ++zeroed;
  return zeroed;
}

inline void* scaled_alloc() { return new (std::nothrow) ScaledControlState; }
inline int scaled_init(void* vs, double eps_abs, double, double, double) {
  static_cast<ScaledControlState*>(vs)->rtol = eps_abs;
  return GSL_SUCCESS;
}
inline double tolerance_of(const ScaledControlState& s, std::size_t i, double y) {
  return s.rtol * (s.scale[i] + (s.relative[i] ? std::abs(y) : 0.0));
}
inline int scaled_hadjust(void* vs, std::size_t dim, unsigned int ord, const double y[], const double yerr[],
                          const double*, double* h) {
  const auto& s = *static_cast<ScaledControlState*>(vs);
  double rmax = std::numeric_limits<double>::min();
  for (std::size_t i = 0; i < dim; ++i) rmax = std::max(rmax, std::abs(yerr[i]) / tolerance_of(s, i, y[i]));
  if (!std::isfinite(rmax)) rmax = 1e300;  // a non-finite error estimate: shrink as far as allowed
  const double h_old = *h;
  if (rmax > 1.1) {
    *h = h_old * std::max(0.9 * std::pow(rmax, -1.0 / ord), 0.2);
    return GSL_ODEIV_HADJ_DEC;
  }
  if (rmax < 0.5) {
    *h = h_old * std::clamp(0.9 * std::pow(rmax, -1.0 / (ord + 1.0)), 1.0, 5.0);
    return GSL_ODEIV_HADJ_INC;
  }
  return GSL_ODEIV_HADJ_NIL;
}
inline int scaled_errlevel(void* vs, const double y, const double, const double, const std::size_t ind,
                           double* errlev) {
  const auto& s = *static_cast<ScaledControlState*>(vs);
  *errlev = tolerance_of(s, ind, y);
  return *errlev > 0 ? GSL_SUCCESS : GSL_EINVAL;
}
inline int scaled_set_driver(void*, const gsl_odeiv2_driver*) { return GSL_SUCCESS; }
inline void scaled_free(void* vs) { delete static_cast<ScaledControlState*>(vs); }
inline const gsl_odeiv2_control_type kScaledControl = {"model-scaled", &scaled_alloc,      &scaled_init,
                                                       &scaled_hadjust, &scaled_errlevel, &scaled_set_driver,
                                                       &scaled_free};

inline const gsl_odeiv2_step_type* step_type(IntegrationMethod m) {
  switch (m) {
    case IntegrationMethod::rk8pd: return gsl_odeiv2_step_rk8pd;
    case IntegrationMethod::rk4imp: return gsl_odeiv2_step_rk4imp;
    case IntegrationMethod::bsimp: return gsl_odeiv2_step_bsimp;
    case IntegrationMethod::rkf45: return gsl_odeiv2_step_rkf45;
    default: return gsl_odeiv2_step_msbdf;
  }
}

// The error control's tolerance is rtol / factor, so that the global error the method achieves
// lies within a small factor of the requested rtol (model.md §15.1, measured by
// tests/benchmarks/bench_simulate): bsimp's local-error control accumulates to 35-420 times the
// tolerance over the benchmark problems, and handed rtol / 30 it ends at 0.4 to 8 times rtol;
// rk8pd's ends at 0.6 to 1.6 times rtol as it is (on the problem it is chosen for).
inline double tolerance_factor(IntegrationMethod m) { return m == IntegrationMethod::bsimp ? 30.0 : 1.0; }

struct DriverDeleter {
  void operator()(gsl_odeiv2_driver* d) const { gsl_odeiv2_driver_free(d); }
};

}  // namespace abu::sim_detail
