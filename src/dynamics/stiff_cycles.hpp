// Limit cycles of very stiff scenes (coulomb balls: a Hopf orbit of 37 min beside ball modes
// of -5.7e4 1/s and a rotor pair of -8.33 +- 499.7i 1/s; docs/model.md §17.11-§17.15):
// each shooting interval is a fixed number of three-stage Radau IIA steps (L-stable: the fast
// modes are damped at steps of seconds without being resolved, and on the slow manifold they
// are not excited), the increments summed apart from the state and the transition matrices
// the exact derivatives of the discrete map, as for the forced orbits (forced_orbits_radau.hpp,
// model.md §10.18). The multipliers no transition matrix represents (the discrete map damps
// them by R(h lambda), not e^{h lambda}) come from the frozen spectra along the orbit
// (model.md §17.13). Internal to src/dynamics (periodic_orbits.cpp).
#pragma once

#include <cmath>
#include <complex>
#include <functional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "abu/core/cancel.hpp"
#include "abu/core/params.hpp"
#include "forced_orbits_radau.hpp"

namespace abu::detail {

// A Hopf point is "very stiff" for the cycle code when its fastest mode is this many times
// faster than its frequency (the viscous scenes: 1e1 - 1e5, kept on GSL's adaptive steppers;
// the default scene's coulomb Hopf point: 2e7).
inline constexpr double kRadauStiffness = 1e6;

// One run of fixed Radau IIA steps over [0, targets.back()] of the d-dimensional state y[0..d) and, when
// `columns` > 0, the variational columns y[d .. d + d * columns) (column-major d x columns:
// the first d columns the transition matrix, the last the parameter sensitivity, updated as
// C <- (I + dZ/dy) C + [0 | dZ/dp]). The steps have the nominal length `step`: each segment
// between two targets gets max(1, round(length / step)) equal steps, so a run over one
// shooting interval always takes the same count (no jump of the discretization as the period
// moves). `acc` gets y(h) - y(0), summed apart from the state; at_target sees y at each target.
template <class Field>
bool radau_run(RadauStep& radau, Field& field, int d, int columns, double* y, double step,
               const std::vector<double>& targets, const std::function<void(const double*)>& at_target,
               Eigen::VectorXd& acc, long& steps, std::string_view& why) {
  const Eigen::Map<const Eigen::VectorXd> y0_map(y, d);
  const Eigen::VectorXd y0 = y0_map;
  Eigen::VectorXd state = y0;
  acc.setZero(d);
  Eigen::Map<Eigen::MatrixXd> cols(y + d, d, columns);
  Eigen::MatrixXd next(d, columns);
  double t = 0;
  for (double target : targets) {
    const double length = target - t;
    const long n = std::max(1L, std::lround(length / step));
    const double hs = length / double(n);
    for (long k = 0; k < n; ++k) {
      if ((++steps & 63) == 0) throw_if_stopped("cycle continuation (Radau steps)");
      if (!radau.advance(field, t + double(k) * hs, state, hs, columns > 0, why)) return false;
      acc += radau.increment();
      state = y0 + acc;
      if (columns > 0) {
        next.noalias() = radau.state_derivative() * cols;
        cols += next;
        cols.col(columns - 1) += radau.parameter_derivative();
      }
    }
    t = target;
    Eigen::Map<Eigen::VectorXd>(y, d) = state;
    if (at_target) at_target(y);
  }
  return true;
}

// The multipliers an orbit's factors cannot represent, from the frozen spectra (model.md
// §17.13): `samples` are the SI states at N uniform times over the period T. Of the product's
// multipliers (values, log_moduli: descending), those whose frozen exponent per step of the
// discrete map (T / total_steps) is below -1/2 are replaced by exp of the period integral of
// the matching fast eigenvalue (eigenvalues sorted by real part); returns how many (-1: an
// eigenvalue solver failed), and sets `liouville` to |sum ln|mu| - integral of trace J| /
// |integral| (Liouville's formula, which holds for the exact flow).
int replace_unresolved_multipliers(const Params& p, const std::vector<Eigen::VectorXd>& samples, double period,
                                   long total_steps, std::vector<std::complex<double>>& values,
                                   std::vector<double>& log_moduli, double& liouville);

}  // namespace abu::detail
