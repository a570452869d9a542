// Continuation of the equilibria of n >= 3 balls in one parameter (model.md §13.7), on
// the pseudo-arclength engine of every branch (arclength.hpp), with LP, BP and HB located.
//
//  aligned   every isolated equilibrium (one per sign pattern and root, §13.2) starts a
//            branch in the n + 3 scaled unknowns z = (q / L, beta_1..beta_n, (p - p0) / P)
//            of the n + 2 static equations (static_equations.hpp, N = any_balls).
//  balanced  each sample of the balanced set (§13.5) starts a branch with its free angles
//            beta_3..beta_n held: the unknowns are (q / L, beta_1, beta_2, p), the
//            equations the rotor's two and those of balls 1 and 2, whose 4 x 4 Jacobian
//            is regular while balls 1 and 2 are not collinear (§13.7). The other balls'
//            equations hold on q = 0 by themselves. Along such a branch the stability is
//            the normal stability (spectrum.hpp compute_normal_spectrum).
//
// Test functions between consecutive points (sign changes), as for two balls:
//   LP  the parameter component of the tangent, t_p;
//   BP  det [F_u; t^T] (it keeps its sign through a fold, changes it at a branch point);
//   HB  the sign of prod_{i<j} (lambda_i + lambda_j) over the (normal) spectrum,
//       structural zeros left out (bifurcation.hpp hopf_test_sign).
// LP and BP are located by Brent's method (GSL) on their test function along the chord
// between the bracketing points, every value on the branch; HB by bisection until the
// crossing pair is complex at both ends, then Brent on its real part. The eigenvalues are
// computed afresh at every point (no mode tracking; the test functions are symmetric in
// the eigenvalues).
//
// The balanced set's stability boundary in the parameter is the envelope of its samples'
// Hopf points: BalancedEnvelope lists the sub-intervals of the parameter between
// consecutive Hopf points of any sample with how many samples are normally stable in each.
//
//   abu::ContinuationRunN run = abu::continue_branches(p, *abu::parse_param("omega", 3), 2000.0, {});
#pragma once

#include <array>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "abu/continuation/continuation.hpp"  // Label, StopReason, ContinuationStats
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/spectrum.hpp"

namespace abu {

/// One converged point of an n-ball branch.
struct BranchPointN {
  long double parameter = 0;
  Coordinates<long double, any_balls> position;  ///< SI, angles unwrapped along the branch
  /// The full spectrum (aligned branches) or the normal one with the structural zeros
  /// flagged (balanced samples), sorted as spectrum.hpp says.
  SpectrumN spectrum;
  double residual = 0;           ///< static_residual of all n + 2 equations at the point
  double tangent_parameter = 0;  ///< t_p, the LP test function
  double branch_test = 0;        ///< det [F_u; t^T], the BP test function (sign matters)
  Label label = Label::none;     ///< EP at the ends
};

/// A located special point of an n-ball branch.
struct SpecialPointN {
  Label label = Label::none;
  long double parameter = 0;
  Coordinates<long double, any_balls> position;
  std::complex<double> eigenvalue{};  ///< the critical eigenvalue (HB: +i omega_H)
  /// HB: omega_H [rad/s], in the rotating frame (the model's coordinates, model.md §3).
  std::optional<double> frequency;
  bool converged = false;  ///< the location converged (Brent to 1e-13 of the chord)
  int n_unstable_before = 0;  ///< along increasing arclength of the branch
  int n_unstable_after = 0;
  long double bracket_from = 0, bracket_to = 0;  ///< parameters of the bracketing points
  int next_point = 0;  ///< index in BranchN::points of the bracketing point after it
  std::string note;
};

/// A branch traced both ways from its start, ordered along the arclength.
struct BranchN {
  Family family = Family::aligned;  ///< aligned, or balanced (a sample, free angles held)
  unsigned pattern = 0;             ///< aligned: the sign pattern (equilibria.hpp)
  int member = 1;                   ///< aligned: the root; balanced: the sample (1-based)
  /// Equilibria at the start the branch also stands for: images under a permutation of
  /// balls with equal parameters (same spectra at the same parameter values; not traced
  /// again, see ContinuationRunN::notes). Balanced samples count with 1 + images in the
  /// envelope.
  int images = 0;
  std::vector<BranchPointN> points;
  std::vector<SpecialPointN> specials;  ///< ordered along the branch
  std::array<StopReason, 2> stop{StopReason::end_of_range, StopReason::end_of_range};
  std::array<std::string, 2> stop_detail;
  long double start_parameter = 0;
};

/// The balanced set's stability boundary in the parameter: between consecutive Hopf
/// points of any sample the number of normally stable samples is constant.
struct BalancedEnvelope {
  struct Interval {
    long double from = 0, to = 0;  ///< parameter values (from < to)
    int stable = 0;                ///< samples normally stable throughout
    int samples = 0;               ///< samples whose branch covers the whole interval
  };
  std::vector<Interval> intervals;  ///< by increasing parameter
  int samples = 0;                  ///< balanced-sample branches
  int samples_with_hopf = 0;        ///< of them, with at least one located HB
};

struct ContinuationRunN {
  ContinuationStats stats;
  ParamRef param;
  double from = 0, to = 0;
  int n_balls = 0;
  std::vector<BranchN> branches;  ///< balanced samples first, then aligned by pattern, member
  BalancedSetSummary balanced_set;  ///< at the start value
  BalancedEnvelope envelope;
  std::vector<std::string> notes;
  /// What one branch could hold [bytes], checked before tracing (arclength.hpp); the run holds
  /// at most this times its branches.
  double memory_estimate = 0;
};

/// Continues every aligned equilibrium and every balanced sample of `p` (n >= 3, at its
/// value of `param`) to `to`, one of each set of images under permutations of equal
/// balls (traced from its canonical image: each class's angles in ascending order); aligned equilibria at `to` that no branch reached start
/// branches too. Throws InputError for n < 3 (continuation.hpp is the two-ball path) and
/// for an end value outside the parameter's range.
ContinuationRunN continue_branches(const ParamsN& p, ParamRef param, double to, const ContinuationOptions& options,
                                   const BalancedSampling& sampling = {});

}  // namespace abu
