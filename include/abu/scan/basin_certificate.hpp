// A region proven (up to a sampled bound, below) to lie in the basin of a stable
// equilibrium: the sublevel set of the quadratic Lyapunov function of its linearization,
// small enough that the field's second-order remainder cannot undo the decrease
// (model.md §15.8). `basin` counts a run as settled on an attractor only once the state is
// inside this region; inside, its fate is decided.
//
// In the scaled coordinates y = S^-1 (x - x*), S = (L, L, 1.., L w, L w, w..) (angles
// wrapped), g(y) = S^-1 f(x* + S y), A = Dg(0):
//   A^T P + P A = -I,   V(y) = y^T P y,
//   K2 >= |D^2 g(z)[u, u]| for |z| <= r, |u| = 1,   r = min(rho, 1 / (2 |P| K2)),
//   region { V < c },  c = lambda_min(P) r^2:   V' <= -|y|^2 / 2 there.
// K2 is the largest of the exact second-derivative tensors (Taylor jets, polarization,
// Frobenius bound per component) at sampled points of the ball, times 2.
//
//   abu::BasinRegion R = abu::certify_basin_region(p, position);   // p.omega the final speed
//   if (R.certified && abu::inside_region(R, x)) ...
#pragma once

#include <string>
#include <vector>

#include "abu/core/params.hpp"

namespace abu {

struct BasinRegion {
  bool certified = false;
  std::string reason;            ///< why not certified (empty when certified)
  int dim = 0;                   ///< 2n + 4
  std::vector<double> centre;    ///< x* (the equilibrium at rest) [SI]
  std::vector<double> scale;     ///< S: L, L, 1.., L w, L w, w..
  std::vector<double> P;         ///< dim x dim, row-major, scaled coordinates
  double radius = 0;             ///< r: V' <= -|y|^2 / 2 on the scaled ball |y| <= r
  double level = 0;              ///< c = lambda_min(P) r^2: the region is V < c
  double second_derivative_bound = 0;  ///< K2 on the ball |y| <= r (sampled, times 2)
  double p_norm = 0, p_min = 0;  ///< largest and smallest eigenvalue of P
  double lyapunov_residual = 0;  ///< |A^T P + P A + I|_max
  int sample_points = 0;         ///< points of the ball at which D^2 g was bounded (last radius)
};

/// The region of model.md §15.8 for the two-ball equilibrium at `position` (q1, q2, beta1,
/// beta2 [m, rad]) at the speed p.omega. Not certified (with the reason) when the
/// linearization is not Hurwitz or the Lyapunov equation cannot be solved accurately.
BasinRegion certify_basin_region(const Params& p, const std::vector<double>& position);

/// V(y) of a state x (2n + 4 values, SI), angles wrapped; no allocation.
double lyapunov_value(const BasinRegion& region, const double* x);
inline bool inside_region(const BasinRegion& region, const double* x) {
  return region.certified && lyapunov_value(region, x) < region.level;
}

/// |D^2 g(z)[u, u]| bounds at a scaled point z (dim values): the Frobenius bound
/// sqrt(sum_k |T_k|_F^2) of the second-derivative tensor, exact to rounding. Exposed for tests.
double second_derivative_bound_at(const Params& p, const BasinRegion& region, const double* z);

}  // namespace abu
