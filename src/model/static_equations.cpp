#include "abu/model/static_equations.hpp"

#include "abu/model/lugre.hpp"

namespace abu {

template <int N>
StaticEquationsT<N>::StaticEquationsT(const ParamsT<double, N>& base, ParamRef param, ld origin, ld span)
    : base_(base), base_ld_(base.template cast<ld>()), param_(param), origin_(origin), span_(span) {
  if (base.law == FrictionLaw::lugre) {  // model.md §12.8: the z = 0 branches solve b(s, 0) = 0 without friction
    lugre_ = true;
    base_.law = base_ld_.law = FrictionLaw::none;
  }
  length_ = displacement_scale(base_ld_);
  dofs_ = dofs_of<N>(ball_count(base) + 2);
}

template <int N>
typename StaticEquationsT<N>::Unknowns StaticEquationsT<N>::scaled(const Coordinates<ld, N>& s, ld parameter) const {
  Unknowns z(dofs_ + 1);
  z.template head<forces_size>(dofs_) = s;
  z(0) /= length_;
  z(1) /= length_;
  z(dofs_) = (parameter - origin_) / span_;
  return z;
}

template <int N>
Coordinates<long double, N> StaticEquationsT<N>::position(const Unknowns& z) const {
  Coordinates<ld, N> s = z.template head<forces_size>(dofs_);
  s(0) *= length_;
  s(1) *= length_;
  return s;
}

template <int N>
ParamsT<long double, N> StaticEquationsT<N>::params_ld(const Unknowns& z) const {
  ParamsT<ld, N> p = base_ld_;  // the long-double parameter keeps every digit of z
  set(p, param_, parameter(z));
  return p;
}

template <int N>
ParamsT<double, N> StaticEquationsT<N>::params(const Unknowns& z) const {
  ParamsT<double, N> p = base_;
  set(p, param_, double(parameter(z)));
  return p;
}

template <int N>
typename StaticEquationsT<N>::Forces StaticEquationsT<N>::row_scale(const Unknowns& z) const {
  return static_force_scale(params_ld(z), position(z));
}

template <int N>
typename StaticEquationsT<N>::Forces StaticEquationsT<N>::residual(const Unknowns& z) const {
  const auto p = params_ld(z);
  const Forces b = generalized_forces(p, at_rest<ld, N>(position(z)));
  return b.cwiseQuotient(static_force_scale(p, position(z)));
}

template <int N>
typename StaticEquationsT<N>::JacobianMatrix StaticEquationsT<N>::jacobian(const Unknowns& z) const {
  const auto p = params_ld(z);
  const State<ld, N> x = at_rest<ld, N>(position(z));
  const Forces scale = static_force_scale(p, position(z));
  JacobianMatrix D(dofs_, dofs_ + 1);
  // db/ds = -K at rest (K's (dA/ds) s'' part vanishes on the branch, where s'' = 0).
  D.template leftCols<forces_size>(dofs_) = -linearize(p, x).stiffness;
  D.col(0) *= length_;
  D.col(1) *= length_;
  D.col(dofs_) = generalized_force_derivative(p, x, param_) * span_;
  return scale.cwiseInverse().asDiagonal() * D;
}

template <int N>
Linearization<long double, N> StaticEquationsT<N>::linearization(const Unknowns& z) const {
  if constexpr (N == any_balls)
    if (lugre_) return lugre_rest_linearization(params_ld(z), position(z), RestSide::forward, true);
  return linearize(params_ld(z), at_rest<ld, N>(position(z)));
}

template class StaticEquationsT<2>;
template class StaticEquationsT<any_balls>;

}  // namespace abu
