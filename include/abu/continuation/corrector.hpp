// The scaled static equations (static_equations.hpp) as a System of the pseudo-arclength
// engine (bordered.hpp, arclength.hpp): F and the analytic F_u, the corrector's
// tolerances, and the distance between scaled points. Branches are traced on it, and
// their special points located on it (each test-function value, each bisection point is
// a corrector solve onto the branch).
#pragma once

#include "abu/continuation/bordered.hpp"
#include "abu/model/static_equations.hpp"

namespace abu {

struct EquilibriumSystem {
  using Vec = StaticEquations::Vec5;
  using Jacobian = StaticEquations::Mat45;
  const StaticEquations& eq;

  StaticEquations::Vec4 residual(const Vec& z) const { return eq.residual(z); }
  Jacobian jacobian(const Vec& z) const { return eq.jacobian(z); }
  /// F is scaled to O(1): rounding of double (1e-15) is reachable and asked for.
  long double residual_size(const Vec& z) const { return eq.residual(z).cwiseAbs().maxCoeff(); }
  static arclength::NewtonSettings newton() { return {}; }
};

using Corrected = arclength::Correction<EquilibriumSystem>;

/// Newton on [F(z); d . (z - z_pred)] = 0: the pseudo-arclength corrector (d the tangent),
/// or, with d = e_5, the equilibrium at a fixed parameter.
inline Corrected correct(const StaticEquations& eq, const StaticEquations::Vec5& z_pred,
                         const StaticEquations::Vec5& d) {
  return arclength::correct(EquilibriumSystem{eq}, z_pred, d);
}

/// Distance between two scaled points, the angles compared modulo 2 pi (max norm).
long double distance(const StaticEquations::Vec5& a, const StaticEquations::Vec5& b);

}  // namespace abu
