// The derivative of the mass matrix A(beta) of model.md (3.8) along the configuration:
// (dA/ds) z, as an (n+2)x(n+2) matrix whose column 2+i is (dA/dbeta_i) z (columns 0, 1
// zero: A does not depend on q). Off an equilibrium the linearization carries it for the
// acceleration, K += (dA/ds) s'' (model.md §6); the anisotropic field (10.14.2) for its
// extra acceleration. Defined in model.cpp, next to linearize, which uses it.
//
//   abu::DofMatrix<double, abu::any_balls> D = abu::mass_derivative_times(p, s, accel);
#pragma once

#include "abu/model/model.hpp"

namespace abu {

template <class T, int N>
DofMatrix<T, N> mass_derivative_times(const ParamsT<T, N>& p, const Coordinates<T, N>& s, const Coordinates<T, N>& z);

}  // namespace abu
