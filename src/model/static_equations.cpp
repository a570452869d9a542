#include "abu/model/static_equations.hpp"

namespace abu {

StaticEquations::StaticEquations(const Params& base, ParamRef param, ld origin, ld span)
    : base_(base), base_ld_(base.cast<ld>()), param_(param), origin_(origin), span_(span) {
  length_ = displacement_scale(base_ld_);
}

StaticEquations::Vec5 StaticEquations::scaled(const Coordinates<ld, 2>& s, ld parameter) const {
  Vec5 z;
  z << s(0) / length_, s(1) / length_, s(2), s(3), (parameter - origin_) / span_;
  return z;
}

Coordinates<long double, 2> StaticEquations::position(const Vec5& z) const {
  Coordinates<ld, 2> s;
  s << z(0) * length_, z(1) * length_, z(2), z(3);
  return s;
}

ParamsT<long double, 2> StaticEquations::params_ld(const Vec5& z) const {
  ParamsT<ld, 2> p = base_ld_;  // the long-double parameter keeps every digit of z
  set(p, param_, parameter(z));
  return p;
}

Params StaticEquations::params(const Vec5& z) const {
  Params p = base_;
  set(p, param_, double(parameter(z)));
  return p;
}

StaticEquations::Vec4 StaticEquations::row_scale(const Vec5& z) const {
  return static_force_scale(params_ld(z), position(z));
}

StaticEquations::Vec4 StaticEquations::residual(const Vec5& z) const {
  const auto p = params_ld(z);
  const Vec4 b = generalized_forces(p, at_rest<ld, 2>(position(z)));
  return b.cwiseQuotient(static_force_scale(p, position(z)));
}

StaticEquations::Mat45 StaticEquations::jacobian(const Vec5& z) const {
  const auto p = params_ld(z);
  const State<ld, 2> x = at_rest<ld, 2>(position(z));
  const Vec4 scale = static_force_scale(p, position(z));
  Mat45 D;
  // db/ds = -K at rest (K's (dA/ds) s'' part vanishes on the branch, where s'' = 0).
  D.leftCols<4>() = -linearize(p, x).stiffness * Eigen::DiagonalMatrix<ld, 4>(length_, length_, 1, 1);
  D.col(4) = generalized_force_derivative(p, x, param_) * span_;
  return scale.cwiseInverse().asDiagonal() * D;
}

Linearization<long double, 2> StaticEquations::linearization(const Vec5& z) const {
  return linearize(params_ld(z), at_rest<ld, 2>(position(z)));
}

}  // namespace abu
