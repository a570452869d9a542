// Set-valued Coulomb friction (`coulomb-set`, model.md (4.6)): the set of ball
// arrangements in which every ball can stick, and the worst residual vibration over it
// (model.md §14).
//
//   E = { beta in T^n : |s_i(beta)| <= 1 for every ball i },
//   s_i = (q1 sin beta_i - q2 cos beta_i) / (mu_i l_i),   (K + iC) q = omega^2 W(beta)   (14.1)
//
// Two balls: the region of the torus is computed column by column (beta_1 fixed, the
// intervals in beta_2 found by sampling and bisection to rounding), its area by adaptive
// Simpson over beta_1, its boundary curves by tracing the level curves s_i = +-1
// (predictor-corrector, model.md §14.3), its components by linking overlapping intervals
// of neighbouring columns with the torus wrap in both angles. The maximum of |q| on each
// component is exact on every column (|W|^2 is a cosine in beta_2) and refined over
// beta_1 by golden section. n >= 3: a grid of G points per angle (the stated resolution).
//
//   abu::StickSet set = abu::stick_set(p);      // p.law == FrictionLaw::coulomb_set
//   fmt::print("{} {}\n", set.area, set.worst_q_abs);
#pragma once

#include <array>
#include <string>
#include <vector>

#include "abu/core/params.hpp"
#include "abu/core/status.hpp"

namespace abu {

struct RaceShape;  // model/unround_race.hpp

/// Options of the stick-set computation; the defaults give area to ~1e-9 relative and the
/// maxima to rounding on the scenes of tests/reference (model.md §14.3).
struct StickSetOptions {
  int columns = 512;           ///< uniform beta_1 columns (two balls), besides the dense ones at the seeds
  int samples = 1024;          ///< uniform beta_2 samples per column (two balls)
  double area_tolerance = 1e-10;  ///< absolute [rad^2] per unit beta_1, adaptive Simpson
  bool trace = true;           ///< trace the boundary curves (two balls)
  long grid_budget = 1L << 21;  ///< n >= 3: at most this many grid points, G = floor(budget^(1/n))
  /// Only what a verdict reads (area, area_fraction, whole_torus, the components,
  /// balanced_exists, V and V_E with where they are attained): E = T^n when the bound
  /// |G| (U + sum m_i l_i) <= min mu_i l_i proves it (any n, no scan); else, two balls,
  /// computed exactly as without it, the integrals of |q| (mean_q_abs, each component's
  /// q_abs_integral), the spreads and max_abs_s left 0 (model.md §14.10).
  bool verdict_only = false;
};

/// One traced piece of the boundary of E: a curve s_ball = sign on which the other
/// constraints hold, as points (beta_1, beta_2) in [0, 2 pi)^2 (a jump by 2 pi is a wrap).
struct StickBoundaryArc {
  int ball = 0;   ///< 0-based ball whose constraint is active
  int sign = 1;   ///< +1: s_ball = +1, -1: s_ball = -1
  bool closed = false;  ///< the whole level curve lies in E (a closed curve on the torus)
  std::vector<std::array<double, 2>> points;
};

/// One connected component of E.
struct StickComponent {
  double area = 0.0;          ///< [rad^n]; two balls: its own adaptive Simpson, in the panels of StickSet::area
  double q_abs_max = 0.0;     ///< max |q| on the component [m]
  std::vector<double> beta_at_max;  ///< where it is attained [rad]
  double q_abs_integral = 0.0;  ///< integral of |q| over the component [m rad^n]
  std::vector<int> balanced_points;  ///< indices into StickSet::seeds of the balanced points inside
  std::vector<int> seeds;            ///< indices of every smooth equilibrium inside
  std::vector<double> spread;        ///< per ball: length of the shortest arc holding the projection [rad]
  bool wraps = false;                ///< the component winds around the torus
};

/// A smooth equilibrium (tau = 0, model.md §5): always in E.
struct StickSeed {
  std::string family;           ///< balanced, together, opposite, aligned; "equilibrium K" on an unround race
  /// V is measured over the components holding an anchor: a balanced point, or on an unround
  /// race its stable equilibrium of least |q| (model.md §20.5).
  bool anchor = false;
  std::vector<double> beta;     ///< [rad]
  double q_abs = 0.0;           ///< [m]
  int component = -1;           ///< index into StickSet::components, -1 if not resolved
};

/// The stick set of one parameter point and its worst residual vibration.
struct StickSet {
  Status status;                ///< ok, or why a figure is not resolved
  int n_balls = 0;
  bool sampled = false;         ///< n >= 3: grid values (resolution below); 2: traced and refined
  double resolution = 0.0;      ///< grid step [rad] (n >= 3); smallest column step (2 balls)
  int grid_points_per_angle = 0;  ///< n >= 3
  double area = 0.0;            ///< [rad^n]
  double area_fraction = 0.0;   ///< area / (2 pi)^n
  bool whole_torus = false;     ///< every arrangement sticks
  double max_abs_s = 0.0;       ///< max over the torus of max_i |s_i| (sampled): E = T^n iff <= 1
  std::vector<StickComponent> components;
  /// Components that are a smooth equilibrium alone, its part of E narrower than the scan's
  /// resolution (small mu: the width shrinks with mu), area 0, |q| the equilibrium's.
  int point_components = 0;
  std::vector<StickSeed> seeds;
  /// What anchors V (StickSeed::anchor): "balanced point", or "least-|q| stable equilibrium of the
  /// race" on an unround race (model.md §20.5); the fields named balanced_* below mean the anchor.
  std::string anchor = "balanced point";
  bool unround_race = false;    ///< the balls stick on an unround race's paths (model.md §20.5)
  double worst_q_abs = 0.0;     ///< V: max |q| over the components holding a balanced point [m]
  std::vector<double> worst_beta;     ///< where V is attained
  bool balanced_exists = false;       ///< false: no balanced state, V is reported as 0 and status says so
  double worst_q_abs_any = 0.0;  ///< V_E: max |q| over E [m]
  std::vector<double> worst_beta_any;
  double mean_q_abs = 0.0;      ///< integral of |q| over E / area [m]
  std::vector<double> spread;   ///< per ball: the largest spread over the balanced components [rad]
  double bare_rotor_q_abs = 0.0;  ///< omega^2 U / |K + iC|, the rotor without balls [m]
  std::vector<StickBoundaryArc> boundary;  ///< two balls, when traced
};

/// q(beta) of (5.4) and the scaled friction demand s_i of (14.1) at one arrangement.
struct StickPoint {
  double q1 = 0.0, q2 = 0.0;
  std::vector<double> s;
};
StickPoint stick_point(const ParamsN& p, const std::vector<double>& beta);
/// The same on an unround race's paths (model.md (20.5)).
StickPoint stick_point(const ParamsN& p, const RaceShape& race, const std::vector<double>& beta);

/// The stick set of a `coulomb-set` scene (any law is accepted: its mu_i are used).
/// Throws NotSupportedError if some mu_i <= 0 (the set then has no interior) or
/// K = C = 0 (q undefined).
StickSet stick_set(const ParamsN& p, const StickSetOptions& options = {});

/// Throws what stick_set throws for p before it computes anything: NotSupportedError if some
/// mu_i <= 0 or K = C = 0.
void check_stick_set_defined(const ParamsN& p);

/// True when the bound (14.10.1) proves that every arrangement sticks (E = T^n): then the
/// verdict (StickSetOptions::verdict_only) costs nothing, otherwise it scans the torus. False
/// where the set is not defined.
bool whole_torus_by_bound(const ParamsN& p);

/// The same on an unround race (model.md §20.5) from given seeds, the race's equilibria
/// (§11.4): their angles, names and anchors (the stable one of least |q|); each seed's q_abs
/// is computed here. The grid method for every n (two balls too, at the stated resolution), V
/// over the components holding an anchor. Which equilibrium is stable takes their spectra:
/// linear/unround_stick_set.hpp's stick_set(p, race, options) finds the seeds and calls this.
StickSet stick_set_on_race(const ParamsN& p, const RaceShape& race, std::vector<StickSeed> seeds,
                           const StickSetOptions& options = {});

}  // namespace abu
