// The equilibrium equations F(s, p) = b(s, 0; p) = 0 of model.md §5 as a function of
// the scaled unknowns z = (q1 / L, q2 / L, beta_1 .. beta_n, (p - p0) / P): L the
// displacement scale, P the length of the parameter interval. Every equation is divided
// by its natural size at z (model.hpp static_force_scale), so |F| ~ 1e-16 is rounding
// level and the Jacobian's entries are O(1). Continuation, the location of special
// points and the two-parameter curves all work on this one scaled system.
//
// N = 2 is the two-ball system (fixed-size: Vec5 unknowns, Mat45 Jacobian); N =
// any_balls takes the ball count from the parameters at run time, in bounded storage
// (n + 3 <= max_balls + 3 unknowns, no heap allocation).
//
//   abu::StaticEquations eq(p, *abu::parse_param("omega", 2), 300.0, 1700.0);
//   abu::StaticEquations::Vec5 z = eq.scaled(s, 900.0L);
//   auto F = eq.residual(z);   auto DF = eq.jacobian(z);
#pragma once

#include <Eigen/Core>

#include "abu/model/model.hpp"

namespace abu {

template <int N>
class StaticEquationsT {
 public:
  using ld = long double;
  static constexpr int forces_size = dof_size<N>;  ///< n + 2 equations
  static constexpr int unknowns_size = N == any_balls ? Eigen::Dynamic : N + 3;
  using Forces = Coordinates<ld, N>;
  using Unknowns = Eigen::Matrix<ld, unknowns_size, 1, Eigen::ColMajor, dof_capacity<N> + 1, 1>;
  using JacobianMatrix =
      Eigen::Matrix<ld, forces_size, unknowns_size, Eigen::ColMajor, dof_capacity<N>, dof_capacity<N> + 1>;
  // The two-ball names.
  using Vec4 = Forces;
  using Vec5 = Unknowns;
  using Mat45 = JacobianMatrix;

  /// `origin` is p0, `span` the parameter scale P (> 0).
  StaticEquationsT(const ParamsT<double, N>& base, ParamRef param, ld origin, ld span);

  /// n + 2, the number of equations (the parameter is unknown n + 3).
  Eigen::Index dofs() const { return dofs_; }
  Unknowns scaled(const Coordinates<ld, N>& s, ld parameter) const;
  Coordinates<ld, N> position(const Unknowns& z) const;
  ld parameter(const Unknowns& z) const { return origin_ + span_ * z(dofs_); }
  /// The parameter set at z, in long double (and as given, in double).
  ParamsT<ld, N> params_ld(const Unknowns& z) const;
  ParamsT<double, N> params(const Unknowns& z) const;

  /// F(z), each equation divided by its natural size at z.
  Forces residual(const Unknowns& z) const;
  /// The natural sizes the equations are divided by at z.
  Forces residual_scale(const Unknowns& z) const { return row_scale(z); }
  /// [dF/ds * diag(L, L, 1, .., 1), dF/dp * P] with the same row scaling as residual(z).
  JacobianMatrix jacobian(const Unknowns& z) const;
  /// The second-order linearization at z (for spectra and augmented systems). LuGre
  /// (model.md §12.8): the equations are the frictionless model's (its z = 0 equilibria),
  /// the linearization the spring-dashpot one of (12.10) with c = 1.
  Linearization<ld, N> linearization(const Unknowns& z) const;
  /// The base parameters had friction law `lugre` (params() then gives law `none`).
  bool lugre() const { return lugre_; }

  ParamRef param() const { return param_; }
  ld length() const { return length_; }
  ld span() const { return span_; }
  const ParamsT<double, N>& base() const { return base_; }

 private:
  Forces row_scale(const Unknowns& z) const;
  ParamsT<double, N> base_;
  ParamsT<ld, N> base_ld_;
  ParamRef param_;
  ld origin_, span_, length_;
  Eigen::Index dofs_;
  bool lugre_ = false;
};

using StaticEquations = StaticEquationsT<2>;
using StaticEquationsN = StaticEquationsT<any_balls>;

}  // namespace abu
