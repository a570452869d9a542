// The scaled flow of the two-ball cycle shooting and its variational equations
// (docs/model.md §17.2, §17.4, §17.11): the context, GSL's right-hand side and Jacobian, the
// Radau step's field, and the integrator over one shooting interval (GSL's adaptive steppers
// or fixed Radau IIA steps). Internal to src/dynamics (periodic_orbits.cpp).
#pragma once

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <functional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "abu/core/params.hpp"
#include "abu/model/model.hpp"
#include "shooting_flow.hpp"
#include "stiff_cycles.hpp"

namespace abu::cycle_flow {

inline constexpr int kDim = 8;       // 2 n + 4, n = 2
inline constexpr int kColumns = 9;   // the transition matrix and the parameter sensitivity
inline constexpr int kAugmented = kDim * (1 + kColumns);
using State8 = State<double, 2>;
using Matrix8 = StateMatrix<double, 2>;

// The scaled flow y = D^-1 x (model.md §17.2) and its variational equations
// Phi' = J~ Phi, z' = J~ z + D^-1 f_p * span (z: dy/d(scaled parameter)).
struct FlowContext {
  Params p;
  ParamRef ref;
  Eigen::Matrix<double, kDim, 1> scale;  // D
  double span = 1;                       // d p / d (scaled parameter)
  bool variational = true;
  long evaluations = 0;
  double radau_step = 0;  // the stiff route's nominal Radau step [s] (model.md §17.11)
  State8 unscale(const double* y) const {
    State8 x;
    for (int i = 0; i < kDim; ++i) x(i) = scale(i) * y[i];
    return x;
  }
  Matrix8 scaled(const Matrix8& J) const { return scale.cwiseInverse().asDiagonal() * J * scale.asDiagonal(); }
  Matrix8 scaled_jacobian(const State8& x) const { return scaled(jacobian(p, x)); }
};

inline int flow_rhs(double, const double y[], double dydt[], void* params) {
  auto& c = *static_cast<FlowContext*>(params);
  ++c.evaluations;
  const State8 x = c.unscale(y);
  if (!c.variational) {
    const State8 f = vector_field(c.p, x);
    for (int i = 0; i < kDim; ++i) dydt[i] = f(i) / c.scale(i);
  } else {
    // f, J and f_p in one evaluation sharing the kinematics (model.md §17.9).
    const FieldDerivatives<double, 2> d = field_derivatives(c.p, x, c.ref);
    for (int i = 0; i < kDim; ++i) dydt[i] = d.field(i) / c.scale(i);
    const Matrix8 J = c.scaled(d.jacobian);
    const State8& fp = d.parameter_derivative;
    // All 9 columns in one fixed-size, unrolled product (Eigen's general matrix-vector
    // kernel, called per column, was a fifth of a branch's instructions). The upper half of
    // J~ is [0, D_s^-1 D_v] (positions' rates are the velocities, model.md (6.2)): those rows
    // are a diagonal scaling of the velocity rows, the same values the full product gives
    // (its other terms are zeros), at an eighth of its cost; the lower half is the product.
    constexpr int half = kDim / 2;
    const Eigen::Map<const Eigen::Matrix<double, kDim, kColumns>> cols(y + kDim);
    Eigen::Map<Eigen::Matrix<double, kDim, kColumns>> out(dydt + kDim);
    out.template topRows<half>() =
        J.template topRightCorner<half, half>().diagonal().asDiagonal() * cols.template bottomRows<half>();
    out.template bottomRows<half>().noalias() = J.template bottomRows<half>().lazyProduct(cols);
    for (int i = 0; i < kDim; ++i) out(i, kColumns - 1) += fp(i) * c.span / c.scale(i);
  }
  // x * 0 is 0 for every finite x and NaN for inf or NaN: one branch for all components
  // (a test per component was a fifth of this function's own time), summed in kDim
  // independent lanes (one chain of 80 dependent additions was a quarter of it).
  static_assert(kAugmented % kDim == 0);
  double lanes[kDim] = {};
  for (int i = 0; i < (c.variational ? kAugmented : kDim); i += kDim)
    for (int k = 0; k < kDim; ++k) lanes[k] += dydt[i + k] * 0.0;
  double nonfinite = 0;
  for (int k = 0; k < kDim; ++k) nonfinite += lanes[k];
  return nonfinite == 0 ? GSL_SUCCESS : GSL_EBADFUNC;
}

// For the implicit stepper: J~ on the state and on every variational column (the
// columns' dependence on the state, second derivatives of f, is left out: it changes
// the stepper's Newton-like stage solves, not the solution the error control accepts).
inline int flow_jacobian(double, const double y[], double* dfdy, double dfdt[], void* params) {
  auto& c = *static_cast<FlowContext*>(params);
  const int dim = c.variational ? kAugmented : kDim;
  const Matrix8 J = c.scaled_jacobian(c.unscale(y));
  std::fill(dfdy, dfdy + dim * dim, 0.0);
  for (int b = 0; b < dim / kDim; ++b)
    for (int i = 0; i < kDim; ++i)
      for (int j = 0; j < kDim; ++j) dfdy[(b * kDim + i) * dim + b * kDim + j] = J(i, j);
  std::fill(dfdt, dfdt + dim, 0.0);
  if (!J.allFinite()) return GSL_EBADFUNC;
  return GSL_SUCCESS;
}

// The Radau step's field(t, y, F, J, P) of the scaled system (model.md §17.11): F, J~ and,
// for the variational columns, D^-1 f_p * span.
struct RadauField {
  FlowContext& c;
  template <class F, class P>
  void operator()(double, const Eigen::VectorXd& y, F&& f, Eigen::MatrixXd& J, P&& par) {
    ++c.evaluations;
    const State8 x = c.unscale(y.data());
    if (!c.variational) {  // the state alone: no f_p to compute
      const State8 fx = vector_field(c.p, x);
      for (int i = 0; i < kDim; ++i) f(i) = fx(i) / c.scale(i);
      J = c.scaled_jacobian(x);
      par.setZero();
      return;
    }
    const FieldDerivatives<double, 2> d = field_derivatives(c.p, x, c.ref);
    for (int i = 0; i < kDim; ++i) f(i) = d.field(i) / c.scale(i);
    J = c.scaled(d.jacobian);
    for (int i = 0; i < kDim; ++i) par(i) = d.parameter_derivative(i) * c.span / c.scale(i);
  }
};

// The flow over [0, h] of the scaled system (stopping at every target in between): GSL's
// adaptive steppers, or on the stiff route (radau) fixed Radau IIA steps of the context's
// radau_step, whose summed increment y(h) - y(0) is kept apart (model.md §17.11).
class Integrator {
 public:
  Integrator(const gsl_odeiv2_step_type* type, int dim, double rtol, bool radau = false)
      : flow_(type, dim, rtol, "cycle continuation: integrating an interval"), dim_(dim), radau_(radau),
        step_(kDim), increment_(kDim) {
    step_.set_rounding_floor(1e-10);
  }
  bool run(FlowContext& c, double* y, double h, const std::vector<double>& targets,
           const std::function<void(const double*)>& at_target, std::string_view& why) {
    if (radau_) {
      RadauField field{c};
      return detail::radau_run(step_, field, kDim, dim_ == kAugmented ? kColumns : 0, y, c.radau_step, targets,
                               at_target, increment_, radau_steps_, why);
    }
    gsl_odeiv2_system sys{&flow_rhs, &flow_jacobian, std::size_t(flow_.dimension()), &c};
    return flow_.run(sys, 0.0, y, h, targets, at_target, why);
  }
  long steps() const { return radau_ ? radau_steps_ : flow_.steps(); }
  bool radau() const { return radau_; }
  /// Radau: the last run's y(h) - y(0), summed apart from the state.
  const Eigen::VectorXd& increment() const { return increment_; }

 private:
  detail::FlowIntegrator flow_;
  int dim_;
  bool radau_;
  detail::RadauStep step_;
  Eigen::VectorXd increment_;
  long radau_steps_ = 0;
};

}  // namespace abu::cycle_flow
