// Where a flexible rotor's balanced state loses or regains stability along omega
// (docs/model.md §18.14): between two speeds of a sweep whose spectral abscissas have opposite
// signs, the eigenvalue that crosses Re = 0 is tracked (ARPACK shift-invert, eigenvalues_near,
// at the previous eigenvalue as shift) and Re lambda(omega) = 0 solved by Brent (GSL) to
// 1e-12 relative in omega (the reported figure: 1e-10).
//
//   abu::ShaftCrossing c = abu::refine_shaft_crossing(system_at, reference, w_a, lambda_a, w_b);
//   if (c.status.ok()) ... c.omega, c.value (Re ~ 0, Im the rotating-frame frequency) ...
#pragma once

#include <complex>
#include <functional>

#include <Eigen/Core>

#include "abu/core/status.hpp"
#include "abu/model/shaft_system.hpp"

namespace abu {

struct ShaftCrossing {
  double omega = 0.0;                  ///< [rad/s]
  std::complex<double> value;          ///< lambda at omega [1/s, rotating frame], Im >= 0
  double slope = 0.0;                  ///< d Re lambda / d omega there (secant of the last bracket) [1/rad]
  bool loses = false;                  ///< Re lambda goes from < 0 to > 0 with increasing omega
  Eigen::VectorXcd vector;             ///< the eigenvector (unit 2-norm) at omega
  Eigen::VectorXd state;               ///< the balanced state x = (s, 0) at omega
  int evaluations = 0;                 ///< eigenvalue solves
  double residual = 0.0;               ///< of the final eigenpair (sparse_spectrum.hpp)
  Status status;                       ///< not converged with the reason if tracking or Brent failed
};

/// The crossing of the eigenvalue `lambda_a` (of the balanced state nearest `reference`, a
/// configuration s, at speed w_a) between w_a and w_b. `system_at(omega)` builds the system at
/// a speed (the balanced states do not depend on it, but the system does); the eigenvalue is
/// tracked from w_a to w_b in `steps` steps, and must have changed the sign of its real part.
ShaftCrossing refine_shaft_crossing(const std::function<ShaftSystem(double omega)>& system_at,
                                    const Eigen::VectorXd& reference, double w_a, std::complex<double> lambda_a,
                                    double w_b, int steps = 16);

}  // namespace abu
