// The equilibrium equations F(s, p) = b(s, 0; p) = 0 of model.md §5 as a function of
// the scaled unknowns z = (q1 / L, q2 / L, beta1, beta2, (p - p0) / P): L the
// displacement scale, P the length of the parameter interval. Every equation is divided
// by its natural size at z (model.hpp static_force_scale), so |F| ~ 1e-16 is rounding
// level and the Jacobian's entries are O(1). Continuation, the location of special
// points and the two-parameter curves all work on this one scaled system.
//
//   abu::StaticEquations eq(p, *abu::parse_param("omega", 2), 300.0, 1700.0);
//   abu::StaticEquations::Vec5 z = eq.scaled(s, 900.0L);
//   auto F = eq.residual(z);   auto DF = eq.jacobian(z);
#pragma once

#include <Eigen/Core>

#include "abu/model/model.hpp"

namespace abu {

class StaticEquations {
 public:
  using ld = long double;
  using Vec4 = Eigen::Matrix<ld, 4, 1>;
  using Vec5 = Eigen::Matrix<ld, 5, 1>;
  using Mat45 = Eigen::Matrix<ld, 4, 5>;

  /// `origin` is p0, `span` the parameter scale P (> 0).
  StaticEquations(const Params& base, ParamRef param, ld origin, ld span);

  Vec5 scaled(const Coordinates<ld, 2>& s, ld parameter) const;
  Coordinates<ld, 2> position(const Vec5& z) const;
  ld parameter(const Vec5& z) const { return origin_ + span_ * z(4); }
  /// The parameter set at z, in long double (and as given, in double).
  ParamsT<ld, 2> params_ld(const Vec5& z) const;
  Params params(const Vec5& z) const;

  /// F(z), each equation divided by its natural size at z.
  Vec4 residual(const Vec5& z) const;
  /// The natural sizes the equations are divided by at z.
  Vec4 residual_scale(const Vec5& z) const { return row_scale(z); }
  /// [dF/ds * diag(L, L, 1, 1), dF/dp * P] with the same row scaling as residual(z).
  Mat45 jacobian(const Vec5& z) const;
  /// The second-order linearization at z (for spectra and augmented systems).
  Linearization<ld, 2> linearization(const Vec5& z) const;

  ParamRef param() const { return param_; }
  ld length() const { return length_; }
  ld span() const { return span_; }
  const Params& base() const { return base_; }

 private:
  Vec4 row_scale(const Vec5& z) const;
  Params base_;
  ParamsT<ld, 2> base_ld_;
  ParamRef param_;
  ld origin_, span_, length_;
};

}  // namespace abu
