// A branch of pi/omega-periodic orbits of a rigid rotor on an anisotropic support (with an
// unround race: the composed machine, docs/model.md §20.9) in a physical parameter lambda
// (omega, U, a ball's parameter, the race's unroundness factor), traced by the project's one
// pseudo-arclength engine (continuation/arclength.hpp) on the multiple-shooting equations of
// forced_orbits.hpp, with lambda an unknown (scaled to [0, 1] over the interval).
//
// Along it, two test functions: the tangent's lambda component (its sign change a fold, LP:
// a multiplier through +1 where the branch turns back, where a sweep loses the orbit) and
// ln max|rho| (a change of stability: +1 without a fold a branch point BP, -1 a flip PD, a
// complex pair a Neimark-Sacker point NS). Each is located by Brent's method on the chord
// between two branch points (core/bracketed_root.hpp), every trial point corrected onto the
// branch across the chord.
//
//   abu::ForcedBranch b = abu::continue_forced_orbit(support, family, 900, 1400, orbit, 1100);
//   for (const auto& pt : b.points) ... pt.value, pt.orbit.q_abs_max, pt.orbit.verdict ...
#pragma once

#include <array>
#include <complex>
#include <string>
#include <vector>

#include "abu/continuation/arclength.hpp"
#include "abu/core/status.hpp"
#include "abu/dynamics/forced_orbits.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu {

struct ForcedBranchPoint {
  double value = 0;   ///< lambda
  ForcedOrbit orbit;  ///< |q| over the period, the 2n + 4 multipliers, the verdict (forced_orbits.hpp)
};

/// A located special point (model.md §20.9).
struct ForcedSpecialPoint {
  /// "LP": the branch turns back in lambda (a multiplier through +1; a sweep loses the orbit
  /// there); "BP": a real multiplier through +1 where the branch goes on; "PD": a multiplier
  /// through -1 (period doubling); "NS": a complex pair through the unit circle (a torus).
  std::string kind;
  double value = 0;
  ForcedOrbit orbit;
  /// The critical multiplier there (rotating frame, over pi/omega): for LP and BP the real one
  /// nearest +1, for PD the one nearest -1, for NS the complex one of modulus nearest 1.
  std::complex<double> multiplier;
  /// false: the test changed sign between two branch points but Brent's search did not
  /// converge (a trial point on the chord failed); `value` and `orbit` are then the later
  /// branch point's, `bracket` the two values and `reason` why.
  bool located = true;
  std::array<double, 2> bracket{};
  std::string reason;
};

struct ForcedBranch {
  std::vector<ForcedBranchPoint> points;  ///< in arclength order
  std::vector<ForcedSpecialPoint> specials;
  std::string end_forward, end_backward;  ///< how each run ended (arclength::End); backward empty if not traced
  /// converged when both runs ended where they should (the interval's edges, a closed loop);
  /// otherwise the first run that did not, with where and why in `reason`. The points are kept.
  Status status;
  std::string reason;
};

struct ForcedBranchOptions {
  /// The shooting: the start orbit's intervals and steps per interval are kept along the
  /// branch; each point's multipliers carry their discretization error (forced_orbits.hpp).
  ForcedOrbitOptions orbit;
  /// In the scaled unknowns (lambda's interval 1 long, states O(1)): first step 0.02, steps of
  /// at most 0.05 (longer ones can land on a neighbouring orbit where two pass close), ds_min
  /// 1e-7, 2000 attempts each way.
  ContinuationOptions continuation{0.02, 1e-7, 0.05, 2000, 1};
};

/// The branch through `start` (an orbit of family(start_value), from forced_orbit or
/// forced_orbit_near) in lambda over [from, to] (from < to; start_value inside, usually an
/// end: the branch is then traced inwards, else both ways). `family` gives the machine at a
/// value with the mean support; `support` is the scene's. Throws only on cancellation.
ForcedBranch continue_forced_orbit(const AnisotropicSupport& support, const MachineFamily& family, double from,
                                   double to, const ForcedOrbit& start, double start_value,
                                   const ForcedBranchOptions& options = {});

}  // namespace abu
