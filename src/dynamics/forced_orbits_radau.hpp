// One step of the three-stage Radau IIA collocation method (order 5, L-stable, stiffly
// accurate) as a map y_n -> y_n + Z_3 with its exact derivatives: the discretization of the
// forced orbits' shooting intervals (docs/model.md §10.18). Internal to src/dynamics
// (forced_orbits.cpp).
//
// Why not GSL's steppers: the shooting equations need (a) the increment y_{n+1} - y_n summed
// apart from the state, because a stuck coulomb ball's angle is nearly neutral (multiplier
// 1 - 1e-9) and an absolute error control of 1e-13 on the angle moves the orbit by 1e-4 rad
// (the reason 3 of 4 orbits stalled, §10.18), and (b) the derivative of the *discrete* map,
// so that Newton converges quadratically to rounding instead of to the integrator's noise.
// Neither is exposed by gsl_odeiv2; the step below is the textbook one (Hairer & Wanner,
// Solving ODEs II, §IV.5, the coefficients of Table 5.6).
//
//   RadauStep step(dim);
//   if (!step.advance(field, t, y, h, true, why)) ...;   // field(t, y, F, J, P): F, dF/dy, dF/dp
//   y_next = y + step.increment();  Phi_step = I + step.state_derivative();
#pragma once

#include <cmath>
#include <limits>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/LU>

namespace abu::detail {

class RadauStep {
 public:
  explicit RadauStep(int dim)
      : d_(dim), z_(Eigen::VectorXd::Zero(3 * dim)), dz_(3 * dim), f_(3 * dim), p_(3 * dim), g_(3 * dim),
        stage_(dim), k_(3 * dim, 3 * dim), lu_(3 * dim), rhs_(3 * dim, dim + 1), sol_(3 * dim, dim + 1),
        increment_(dim), state_derivative_(dim, dim), parameter_derivative_(dim) {
    for (auto& j : j_) j.resize(dim, dim);
  }

  /// The step from (t, y) of length h. field(t, y, F, J, P) writes the field F, its Jacobian J
  /// and its parameter derivative P at (t, y) (all preallocated); a field with
  /// deferred_parameter() true writes P in field.parameter(t, y, P) instead, called once per
  /// stage at the converged stages when `derivatives`. With `derivatives`, also
  /// d(increment)/dy and d(increment)/dp. False (with why) if the stage equations' Newton
  /// iteration fails: a step too long for the field's nonlinearity, or a non-finite value.
  template <class Field>
  bool advance(Field& field, double t, const Eigen::VectorXd& y, double h, bool derivatives, std::string_view& why) {
    const int d = d_;
    h_ = h;
    z_.setZero();
    double last = std::numeric_limits<double>::infinity();
    bool converged = false;
    // Full Newton on Z_i - h sum_j a_ij F(t + c_j h, y + Z_j) = 0 from Z = 0, with the stage
    // Jacobians of the current iterate; stopped when a correction no longer halves (rounding
    // reached) or is below 1e-16 of Z, then the stages are evaluated once more so that the
    // Jacobians the derivatives use are those of the converged stages.
    for (int it = 0; it < 20; ++it) {
      for (int i = 0; i < 3; ++i) {
        stage_ = y + z_.segment(i * d, d);
        auto fi = f_.segment(i * d, d);
        auto pi = p_.segment(i * d, d);
        field(t + kC[i] * h, stage_, fi, j_[i], pi);
      }
      if (!f_.allFinite()) {
        why = "the field was not finite at a Radau stage";
        return false;
      }
      if (converged) break;
      assemble();
      lu_.compute(k_);
      for (int i = 0; i < 3; ++i)
        g_.segment(i * d, d) = -z_.segment(i * d, d) + h * (kA[i][0] * f_.segment(0, d) + kA[i][1] * f_.segment(d, d) +
                                                            kA[i][2] * f_.segment(2 * d, d));
      dz_.noalias() = lu_.solve(g_);
      if (!dz_.allFinite()) {
        why = "a Radau stage correction was not finite (singular stage matrix)";
        return false;
      }
      z_ += dz_;
      const double size = dz_.cwiseAbs().maxCoeff(), scale = z_.cwiseAbs().maxCoeff();
      if (size <= 1e-16 * scale || (it >= 2 && size > last / 2)) {
        if (size > 1e-10 * (scale + 1e-300) && size > 1e-14 && size > rounding_floor_ * y.cwiseAbs().maxCoeff()) {
          why = "the Radau stage equations stopped converging (a step too long for the field's nonlinearity)";
          return false;
        }
        converged = true;  // evaluate the stages once more, then stop
      }
      last = size;
    }
    if (!converged) {
      why = "the Radau stage equations did not converge in 20 iterations";
      return false;
    }
    increment_ = z_.segment(2 * d, d);  // stiffly accurate: y_{n+1} = y_n + Z_3
    if (!derivatives) return true;
    // A field whose parameter derivative costs more than its value (a difference quotient)
    // writes P only here, at the converged stages, instead of at every stage iteration.
    if constexpr (requires { field.parameter(t, stage_, p_.segment(0, d)); }) {
      if (field.deferred_parameter())
        for (int i = 0; i < 3; ++i) {
          stage_ = y + z_.segment(i * d, d);
          auto pi = p_.segment(i * d, d);
          field.parameter(t + kC[i] * h, stage_, pi);
        }
    }
    // dZ/dy and dZ/dp from the converged stage equations: K dZ = h (A (x) I) blkdiag(J) (1 (x) dy)
    // + h (A (x) I) P dp, K = I - h (A (x) I) blkdiag(J) at the converged stages.
    assemble();
    lu_.compute(k_);
    for (int i = 0; i < 3; ++i) {
      rhs_.block(i * d, 0, d, d) = h * (kA[i][0] * j_[0] + kA[i][1] * j_[1] + kA[i][2] * j_[2]);
      rhs_.block(i * d, d, d, 1) = h * (kA[i][0] * p_.segment(0, d) + kA[i][1] * p_.segment(d, d) +
                                        kA[i][2] * p_.segment(2 * d, d));
    }
    sol_.noalias() = lu_.solve(rhs_);
    state_derivative_ = sol_.block(2 * d, 0, d, d);
    parameter_derivative_ = sol_.block(2 * d, d, d, 1);
    return true;
  }

  const Eigen::VectorXd& increment() const { return increment_; }
  /// A stalled stage iteration is also accepted when its correction is below this times
  /// |y|_inf (default 0: not). The stiff cycles (stiff_cycles.hpp, model.md §17.11) set it:
  /// there the stages are tiny against y (Z ~ 1e-4, y ~ 3 rad) and the ball modes' rounding
  /// in h F (eps h |lambda| |y| ~ 1e-10) stalls the corrections near 1e-13 |y|.
  void set_rounding_floor(double relative) { rounding_floor_ = relative; }
  /// d(increment)/dy_n: the step's transition matrix is I + this.
  const Eigen::MatrixXd& state_derivative() const { return state_derivative_; }
  const Eigen::VectorXd& parameter_derivative() const { return parameter_derivative_; }

 private:
  // K = I - h (A (x) I) blkdiag(J_1, J_2, J_3) at the current stages.
  void assemble() {
    const int d = d_;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) k_.block(i * d, j * d, d, d) = -(h_ * kA[i][j]) * j_[j];
    k_.diagonal().array() += 1.0;
  }

  // Radau IIA, s = 3: nodes c = (4 - sqrt6)/10, (4 + sqrt6)/10, 1 and the matrix A (b = last row).
  static constexpr double kS6 = 2.449489742783178098197284;
  static constexpr double kC[3] = {(4.0 - kS6) / 10.0, (4.0 + kS6) / 10.0, 1.0};
  static constexpr double kA[3][3] = {
      {(88.0 - 7.0 * kS6) / 360.0, (296.0 - 169.0 * kS6) / 1800.0, (-2.0 + 3.0 * kS6) / 225.0},
      {(296.0 + 169.0 * kS6) / 1800.0, (88.0 + 7.0 * kS6) / 360.0, (-2.0 - 3.0 * kS6) / 225.0},
      {(16.0 - kS6) / 36.0, (16.0 + kS6) / 36.0, 1.0 / 9.0}};

  int d_;
  double h_ = 0;
  double rounding_floor_ = 0;
  Eigen::VectorXd z_, dz_, f_, p_, g_, stage_;
  Eigen::MatrixXd j_[3];
  Eigen::MatrixXd k_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  Eigen::MatrixXd rhs_, sol_;
  Eigen::VectorXd increment_;
  Eigen::MatrixXd state_derivative_;
  Eigen::VectorXd parameter_derivative_;
};

}  // namespace abu::detail
