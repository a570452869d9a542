// The monodromy Phi(pi/omega) of x' = J(t) x (docs/model.md §10.6) from short-interval
// transition matrices: fourth-order Magnus (two Gauss-Legendre points per step),
//   Omega = h/2 (A1 + A2) + sqrt(3)/12 h^2 [A2, A1],  Phi <- exp(Omega) Phi.
// An exponential step is exact for the constant part of J, so the stiff ball rates of the
// coulomb laws (1e8 1/s) decay as they should (an A-stable but not L-stable Gauss-Legendre
// step would map them to multipliers of modulus ~1). Its error comes from the commutator
// terms, which carry the stiff rates; §10.6 states the accuracy this gives. It is the
// cross-check of Hill's method (floquet_hill.hpp), not the primary route.
//
//   Eigen::MatrixXd Phi = abu::magnus_monodromy(J, 256);
#pragma once

#include <complex>
#include <vector>

#include "abu/model/anisotropic_support.hpp"

namespace abu {

/// Phi(pi/omega) with `steps` equal Magnus-4 steps (default 256 per period). Throws
/// std::invalid_argument for steps < 1.
Eigen::MatrixXd magnus_monodromy(const PeriodicJacobian& J, int steps = 256);

/// The eigenvalues of a monodromy, in floquet_order.
std::vector<std::complex<double>> monodromy_multipliers(const Eigen::MatrixXd& monodromy);

}  // namespace abu
