// The predictor-corrector primitives of pseudo-arclength continuation on the scaled
// static equations (static_equations.hpp): the Newton corrector, the unit tangent, the
// branch-point test function and the distance between scaled points.
#pragma once

#include "abu/model/static_equations.hpp"

namespace abu {

/// The result of a corrector run.
struct Corrected {
  StaticEquations::Vec5 z;
  bool converged = false;
  int iterations = 0;
  /// F_u at the last iterate: within rounding of its value at z (reused for the tangent).
  StaticEquations::Mat45 jacobian = StaticEquations::Mat45::Zero();
};

/// Newton on [F(z); d . (z - z_pred)] = 0: the pseudo-arclength corrector (d the tangent),
/// or, with d = e_5, the equilibrium at a fixed parameter. Converged when the steps reach
/// the rounding level and F is at the rounding level of double or below.
Corrected correct(const StaticEquations& eq, const StaticEquations::Vec5& z_pred, const StaticEquations::Vec5& d);

/// Unit tangent: the null vector of F_u, oriented along `previous`.
StaticEquations::Vec5 tangent(const StaticEquations::Mat45& DF, const StaticEquations::Vec5& previous);

/// det [F_u; t^T]: changes sign at a branch point, not at a fold.
long double branch_test(const StaticEquations::Mat45& DF, const StaticEquations::Vec5& t);

/// Distance between two scaled points, the angles compared modulo 2 pi (max norm).
long double distance(const StaticEquations::Vec5& a, const StaticEquations::Vec5& b);

}  // namespace abu
