// The Newton matrix of a cycle's multiple shooting carried to another period before it is
// extrapolated along the branch (docs/model.md §17.7). Interval j's blocks (Phi_j / w_j, the
// period column f(phi_j) T_H (theta_{j+1} - theta_j) and the parameter column z_j) depend on
// its length h_j through the fast modes' rotation exp(i omega_f h_j): the rotor's modes at
// omega +- omega_n (~530 rad/s in the rotating frame) turn by omega_f dh when the period
// changes, about 0.5 rad per step where the period grows fastest, so that a Lagrange
// extrapolation in the arclength alone is off by tens of percent there. The blocks of each
// kept orbit are first moved to the predicted orbit's interval lengths by the flow near the
// interval's end, linearized: exp([J~ g; 0 0] dh) = [E w; 0 1] (J~ the scaled Jacobian, g the
// parameter column's forcing D^-1 f_p span, both at the interval's end y_{j+1}), so that
// Phi -> E Phi, f(phi) -> E f(phi) (f' = J f along the flow) and z -> E z + w. What remains to
// extrapolate is smooth in the arclength. Internal to src/dynamics (cycle_problem.hpp).
#pragma once

#include <Eigen/Core>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "cycle_flow.hpp"
#include "cyclic_jacobian.hpp"

namespace abu::cycle_problem {

using cycle_flow::kDim;
using Generator = Eigen::Matrix<double, kDim + 1, kDim + 1>;

/// The generator [J~ g; 0 0] at the scaled state y (the context's parameter set).
inline Generator period_shift_generator(const cycle_flow::FlowContext& ctx, const Eigen::Matrix<double, kDim, 1>& y) {
  const auto d = field_derivatives(ctx.p, ctx.unscale(y.data()), ctx.ref);
  Generator a = Generator::Zero();
  a.topLeftCorner<kDim, kDim>() = ctx.scaled(d.jacobian);
  for (int i = 0; i < kDim; ++i) a(i, kDim) = d.parameter_derivative(i) * ctx.span / ctx.scale(i);
  return a;
}

/// J's interval blocks moved by dh[j] along the flow (the generators at the intervals' ends).
inline detail::CyclicJacobian<kDim> shift_periods(const detail::CyclicJacobian<kDim>& J,
                                                  const std::vector<Generator>& generators,
                                                  const std::vector<double>& dh) {
  detail::CyclicJacobian<kDim> out = J;
  for (std::size_t j = 0; j < J.diag.size(); ++j) {
    if (dh[j] == 0) continue;
    const Generator e = Generator(generators[j] * dh[j]).exp();
    const auto E = e.topLeftCorner<kDim, kDim>();
    out.diag[j] = E * J.diag[j];
    out.border[j] = E * J.border[j];
    out.border[j].col(1) += e.topRightCorner<kDim, 1>();
  }
  return out;
}

}  // namespace abu::cycle_problem
