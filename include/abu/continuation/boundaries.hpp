// Stability boundaries: the fold and Hopf points of a one-parameter continuation
// continued in a second parameter (two-parameter continuation), with the codimension-two
// points where these curves meet each other flagged: Bogdanov-Takens (a Hopf curve ends on
// a fold curve, its frequency going to 0), zero-Hopf (a Hopf curve crosses a fold curve),
// cusp (two fold curves meet), generalized Hopf (the Lyapunov coefficient changes sign).
//
// The unknowns are y = (z, p2) for folds and (z, p2, w) for Hopf points, z the scaled
// unknowns of static_equations.hpp; the equations are F = 0 plus the fold (one) or Hopf
// (two) condition of bifurcation.hpp, whose borders are refreshed at every accepted point.
// Pseudo-arclength continuation as for branches; Jacobians by central differences in
// long double, the residuals analytic.
//
//   auto run = abu::continue_branches(p, omega, 2000.0, options);
//   auto boundaries = abu::continue_boundaries(p, run, *abu::parse_param("d", 2), 1e-3, options);
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "abu/continuation/continuation.hpp"

namespace abu {

struct BoundaryPoint {
  long double parameter = 0, parameter2 = 0;
  Coordinates<long double, 2> position = Coordinates<long double, 2>::Zero();
  long double frequency = 0;  ///< Hopf curves: omega_H [rad/s]
  /// Hopf curves: the first Lyapunov coefficient l1 (< 0 supercritical, > 0 subcritical;
  /// its sign changes at GH; model.md (6.8)-(6.10)); nullopt on fold curves and at codimension-two points.
  std::optional<double> lyapunov;
  /// Hopf curves: the side of the curve on which the equilibrium is stable, in the first
  /// parameter (+1 larger, -1 smaller, 0 neither); nullopt on fold curves.
  std::optional<int> stable_side;
  /// GH points: located by a converged solve (false: interpolated, the corrector failed
  /// inside the segment; the CSV says so).
  bool located = true;
  Family family = Family::balanced;
  Label label = Label::none;  ///< EP at the ends, codimension-two labels where located
};

struct BoundaryCurve {
  Label kind = Label::LP;  ///< LP (fold curve) or HB (Hopf curve)
  int source_branch = 0;   ///< 1-based branch of the continuation run it started from
  std::vector<BoundaryPoint> points;   ///< along the curve, codimension-two points included
  std::array<StopReason, 2> stop{StopReason::end_of_range, StopReason::end_of_range};
  std::array<std::string, 2> stop_detail;
};

struct BoundaryRun {
  ParamRef param, param2;
  double from = 0, to = 0, from2 = 0, to2 = 0;
  std::vector<BoundaryCurve> curves;
  std::vector<std::string> notes;
};

/// Continues every fold and Hopf point of `run` in (run.param, param2) from the scene's
/// value of param2 to `to2`, within run's interval of the first parameter. Points that
/// are mirror images of one already continued (same label and parameter) are skipped.
BoundaryRun continue_boundaries(const Params& p, const ContinuationRun& run, ParamRef param2, double to2,
                                const ContinuationOptions& options);

}  // namespace abu
