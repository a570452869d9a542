// The componentwise residual of T(lambda) x = (lambda^2 A + lambda D + E) x (model.md (6.7)) at a
// linearization: max_i |(T x)_i| over max_i ((|lambda|^2 |A| + |lambda| |D| + |E|) |x|)_i, the
// backward error of (lambda, x) relative to the entries it sums. Shared by the tests of the
// equal-ball reductions (model.md §13.9, §13.10).
#pragma once

#include <complex>

#include "abu/model/model.hpp"

namespace abu::test {

template <class Vector>
long double qep_residual(const Linearization<long double, any_balls>& lin, std::complex<double> eigenvalue,
                         const Vector& vector) {
  using C = std::complex<long double>;
  const C l(eigenvalue.real(), eigenvalue.imag());
  const auto x = vector.template cast<C>().eval();
  const auto T =
      (l * l * lin.mass.cast<C>() + l * lin.damping.cast<C>() + lin.stiffness.cast<C>()).eval();
  const long double al = std::abs(l);
  const long double size =
      ((al * al * lin.mass.cwiseAbs() + al * lin.damping.cwiseAbs() + lin.stiffness.cwiseAbs()) * x.cwiseAbs())
          .maxCoeff();
  return (T * x).cwiseAbs().maxCoeff() / size;
}

}  // namespace abu::test
