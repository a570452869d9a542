// A sweep of one parameter on an unround race with an anisotropic support (docs/model.md
// §20.6): at every value every state `equilibria` finds there (the race's equilibria on the
// mean support, each continued in the anisotropy delta to a pi/omega-periodic orbit, §20.4),
// each with |q| over the period and its 2n + 4 Floquet multipliers; the same orbit followed
// from value to value (an orbit's track: Newton from the previous value's orbit, matched to
// one of this value's orbits); where a track's largest |rho| crosses 1 between two values,
// the crossing located by bisection on the parameter (bisect_unit_circle, the anisotropic
// support's search) and classified: +1 fold, -1 flip, a complex pair Neimark-Sacker.
//
//   abu::ComposedAt at = [&](double v) { ... return abu::ComposedMachineAt{p_at_v, race_at_v}; };
//   abu::ComposedSweep s = abu::composed_sweep(*scene.support, at, values, {});
//   if (!s.status.ok()) ... s.status.reason ...;   // rows, losses, crossings: s.points, s.crossings
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "abu/analysis/floquet_sweep.hpp"
#include "abu/core/status.hpp"
#include "abu/dynamics/forced_orbits.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// The machine at one value of the swept parameter (dynamics/forced_orbits.hpp).
using ComposedMachineAt = MachineAtValue;
using ComposedAt = MachineFamily;

/// One orbit at one value.
struct ComposedOrbitRow {
  /// The orbit's number along the sweep (1, 2, ...: the same number at neighbouring values is
  /// the same orbit); 0 for an orbit that did not converge (no identity to follow).
  int track = 0;
  /// Its equilibrium of the race on the mean support at this value (1-based, in the search's
  /// order, §11.4); 0 on a lost row.
  int equilibrium = 0;
  /// A lost row: track's orbit at the previous value does not continue to this one among this
  /// value's orbits; orbit.status says not converged and orbit.reason where and why.
  bool lost = false;
  ForcedOrbit orbit;
};

struct ComposedSweepPoint {
  double value = 0.0;
  int equilibria = 0;       ///< of the race on the mean support
  std::string search_doubt;  ///< the search's doubt (§11.4); empty when it is complete
  std::vector<ComposedOrbitRow> rows;  ///< this value's orbits, then the lost ones
};

/// A sign change of a track's ln max|rho| between two values that bisection could not follow
/// (the orbit was lost inside the bracket).
struct ComposedUnlocated {
  int track = 0;
  double lower = 0.0, upper = 0.0;  ///< the grid bracket (sweep order)
  double lost_at = 0.0;             ///< where the bisection lost the orbit
  std::string reason;
};

struct ComposedSweep {
  std::vector<double> values;
  std::vector<ComposedSweepPoint> points;       ///< one per value
  std::vector<FloquetCrossing> crossings;       ///< member = the track
  std::vector<ComposedUnlocated> unlocated;
  int tracks = 0;  ///< orbits followed (the largest track number)
  /// converged: every orbit at every value converged, no track was lost and every sign change
  /// was located; otherwise the first problem (where and why). The rows are kept in any case.
  Status status;
};

struct ComposedSweepOptions {
  ForcedOrbitOptions orbit;  ///< the orbits' shooting and continuation in delta (forced_orbits.hpp)
  /// The crossings' bisection: bracket 1e-10 relative (the orbits' multipliers are accurate to
  /// ~1e-10, §10.18), at most 60 halvings.
  FloquetSweepOptions crossing = [] {
    FloquetSweepOptions o;
    o.bracket_tolerance = 1e-10;
    return o;
  }();
  /// Two orbits are one when their x(0) differ by at most this (scaled as the shooting's
  /// unknowns, ball angles modulo 2 pi); default 1e-6: converged orbits agree to ~1e-10, distinct
  /// ones differ by O(1).
  double match_tolerance = 1e-6;
};

/// The distance of two orbits' x(0) on the machine p, scaled as the shooting's unknowns
/// (model.md (10.14.3): q by L, ball angles in rad modulo 2 pi, velocities by L omega and omega).
double composed_orbit_distance(const ParamsN& p, const std::vector<double>& a, const std::vector<double>& b);

/// An orbit with a verdict: converged, its multipliers computed.
bool composed_orbit_usable(const ForcedOrbit& o);

/// The orbits at one value (what `equilibria` reports, §20.4): every equilibrium of the race on
/// the mean support continued in delta to a pi/omega-periodic orbit; rows with track 0 (no sweep
/// yet). Throws NumericalError where an equilibrium of the race has a residual above 1e-8.
ComposedSweepPoint composed_orbits_at(const AnisotropicSupport& support, const ComposedMachineAt& m, double value,
                                      const ForcedOrbitOptions& options = {});

/// The sweep over `values` (in sweep order). `at` gives the machine at a value (grid values and
/// the bisection's). Throws NumericalError where an equilibrium of the race has a residual
/// above 1e-8 (not an equilibrium: exit 3, as `equilibria`); every other failure is in the
/// result's statuses.
ComposedSweep composed_sweep(const AnisotropicSupport& support, const ComposedAt& at, const std::vector<double>& values,
                             const ComposedSweepOptions& options = {});

}  // namespace abu
