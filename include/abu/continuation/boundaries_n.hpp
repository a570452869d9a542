// Stability boundaries of n >= 3 balls: the fold points of the aligned branches and the
// Hopf points of the aligned branches and of the balanced samples (free angles held) of
// an n-ball continuation run (branches_n.hpp), continued in a second parameter on the
// pseudo-arclength engine (model.md §13.7). The balanced samples' Hopf curves together
// are the balanced set's stability boundary in the two parameters: between the first and
// the last of them part of the set is normally stable.
//
// The unknowns are y = (u, p2) for folds and (u, p2, w / w0) for Hopf points, u the
// branch's own unknowns (n + 3 aligned, 5 for a held sample); the equations its static
// equations plus the fold (one) or Hopf (two) condition of bifurcation.hpp on the n + 2
// static equations, borders refreshed at every accepted point; Jacobians by central
// differences in long double, residuals analytic — as for two balls (boundaries.hpp).
// Codimension-two points are not classified for n >= 3: a Hopf curve whose frequency
// falls to 0 ends there (a Bogdanov-Takens point), and says so.
//
//   auto run = abu::continue_branches(p, omega, 100.0, options);          // p: ParamsN
//   auto curves = abu::continue_boundaries(p, run, *abu::parse_param("mu", 3), 0.01, options);
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "abu/continuation/branches_n.hpp"

namespace abu {

struct BoundaryPointN {
  long double parameter = 0, parameter2 = 0;
  Coordinates<long double, any_balls> position;
  std::optional<double> frequency;  ///< Hopf curves: omega_H [rad/s], rotating frame
  Label label = Label::none;        ///< EP at the ends
};

struct BoundaryCurveN {
  Label kind = Label::LP;  ///< LP (fold curve) or HB (Hopf curve)
  int source_branch = 0;   ///< 1-based branch of the continuation run it started from
  Family family = Family::aligned;
  unsigned pattern = 0;
  int member = 1;  ///< aligned: root; balanced: sample
  std::vector<BoundaryPointN> points;
  std::array<StopReason, 2> stop{StopReason::end_of_range, StopReason::end_of_range};
  std::array<std::string, 2> stop_detail;
};

struct BoundaryRunN {
  ParamRef param, param2;
  double from = 0, to = 0, from2 = 0, to2 = 0;
  int n_balls = 0;
  std::vector<BoundaryCurveN> curves;
  std::vector<std::string> notes;
};

/// Continues every converged fold and Hopf point of `run` in (run.param, param2) from
/// the scene's value of param2 to `to2`, within run's interval of the first parameter.
/// Points that are images of one already continued under a permutation of equal balls
/// (same label, parameter, |q| and frequency to 1e-9) are skipped, with a note.
BoundaryRunN continue_boundaries(const ParamsN& p, const ContinuationRunN& run, ParamRef param2, double to2,
                                 const ContinuationOptions& options);

}  // namespace abu
