// Pseudo-arclength continuation (arclength.hpp) of equilibrium branches in one parameter, with the
// eigenvalues tracked along each branch and the special points where stability can
// change detected and located (AUTO-07p's labels: EP end point, LP fold, BP branch
// point, HB Hopf, MX no convergence).
//
// The unknowns are u = (s, p): the configuration s = (q1, q2, beta1, beta2) at rest and
// the parameter. Equilibria solve the four static equations F(u) = b(s, 0; p) = 0
// (model.md §5); with the pseudo-arclength condition t . (u - u_pred) = 0 the corrector
// is a square 5x5 Newton system using the analytic F_s = -K and F_p = db/dp. Internally
// u is scaled: q by the displacement scale, p by the length of the requested interval,
// each equation by its natural size. Angles are followed continuously (no jump at 2 pi)
// and wrapped only when reported.
//
// Test functions between consecutive points (sign changes):
//   LP  the parameter component of the tangent, t_p;
//   BP  det [F_u; t^T] (it keeps its sign through a fold, changes it at a branch point);
//   HB  the sign of prod_{i<j} (lambda_i + lambda_j) (bifurcation.hpp): it changes where a
//       complex pair crosses the axis, and at a neutral saddle (a real pair lambda,
//       -lambda), which the location tells apart and does not report.
// Each is then located by solving an augmented system (bifurcation.hpp), not on the grid.
//
//   abu::ContinuationRun run = abu::continue_branches(p, *abu::parse_param("omega", 2), 2000.0);
//   for (const auto& b : run.branches) for (const auto& sp : b.specials) ...
#pragma once

#include <array>
#include <complex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abu/continuation/arclength.hpp"  // ContinuationOptions
#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/spectrum.hpp"

namespace abu {

/// Codimension one: LP fold, BP branch point, HB Hopf; two (on fold and Hopf curves):
/// BT Bogdanov-Takens, ZH zero-Hopf, CP cusp, GH generalized Hopf (l1 = 0).
enum class Label { none, EP, LP, BP, HB, MX, BT, ZH, CP, GH };
std::string_view to_string(Label label);

/// One converged point of a branch.
struct BranchPoint {
  long double parameter = 0;
  Coordinates<long double, 2> position = Coordinates<long double, 2>::Zero();  ///< angles unwrapped
  Family family = Family::balanced;  ///< of this point (a branch can pass a branch point)
  Spectrum spectrum;  ///< sorted as spectrum.hpp says; `modes` gives the tracked order
  /// The eigenvalues in tracked order: modes[k] is the same mode at every point,
  /// matched by eigenvector overlap and distance to the extrapolated eigenvalue.
  std::array<std::complex<double>, 8> modes{};
  std::array<Eigen::Matrix<std::complex<double>, 4, 1>, 8> mode_vectors{};  ///< SI, unit norm
  double tangent_parameter = 0;  ///< t_p, the LP test function
  double branch_test = 0;        ///< det [F_u; t^T], the BP test function (sign matters)
  Label label = Label::none;     ///< EP at the ends; special points are listed separately
};

/// A located special point.
struct SpecialPoint {
  Label label = Label::none;
  long double parameter = 0;
  Coordinates<long double, 2> position = Coordinates<long double, 2>::Zero();
  Family family = Family::balanced;
  std::complex<double> eigenvalue{};  ///< the critical eigenvalue (HB: +i omega_H)
  double frequency = 0;               ///< HB: omega_H [rad/s]
  double lyapunov = 0;                ///< HB: first Lyapunov coefficient (state in SI)
  bool converged = false;             ///< the augmented system was solved
  int n_unstable_before = 0;          ///< along the branch's direction of travel
  int n_unstable_after = 0;
  long double bracket_from = 0, bracket_to = 0;  ///< parameters of the bracketing points
  std::string note;
};

enum class StopReason {
  end_of_range,       ///< reached the end of the parameter interval (EP)
  max_steps,          ///< ran out of steps
  step_underflow,     ///< the corrector failed at the minimum step (MX)
  invalid_parameter,  ///< the parameter left its physical range (mass <= 0, omega <= 0)
  closed_loop,        ///< came back to its start
};
std::string_view to_string(StopReason r);

/// A branch traced in both directions from its start, ordered along the arclength.
struct Branch {
  Family family = Family::balanced;  ///< of the start point
  int member = 1;
  std::vector<BranchPoint> points;
  std::vector<SpecialPoint> specials;  ///< ordered along the branch
  std::array<StopReason, 2> stop{StopReason::end_of_range, StopReason::end_of_range};  ///< at each end
  std::array<std::string, 2> stop_detail;
  long double start_parameter = 0;
};

/// What a run did, for benchmarks and the output's comments.
struct ContinuationStats {
  long steps = 0;              ///< accepted points
  long rejected = 0;           ///< predictor-corrector steps retried with a smaller step
  long newton_iterations = 0;  ///< corrector iterations, accepted and rejected steps alike
  long tracked_spectra = 0;    ///< spectra by eigenvalue continuation from the last point
  long full_spectra = 0;       ///< spectra computed afresh (starts, fallbacks, special points)
  ContinuationStats& operator+=(const ContinuationStats& o) {
    steps += o.steps, rejected += o.rejected, newton_iterations += o.newton_iterations;
    tracked_spectra += o.tracked_spectra, full_spectra += o.full_spectra;
    return *this;
  }
};

struct ContinuationRun {
  ContinuationStats stats;
  ParamRef param;
  double from = 0, to = 0;
  std::vector<Branch> branches;
  std::vector<std::string> notes;  ///< e.g. start equilibria already covered by a branch
  double memory_estimate = 0;  ///< what the branches could hold [bytes], checked before tracing (arclength.hpp)
};

/// Which equilibria start branches.
struct StartSelection {
  std::optional<Family> family;                       ///< only this family (nullopt: all)
  std::optional<Coordinates<long double, 2>> state;  ///< or a given configuration (polished first)
  /// The front end's name of `family`, for the refusal when it has no equilibrium.
  std::string_view family_option = "--from-equilibrium";
};

/// Continues every selected equilibrium of `p` (at its value of `param`) to `to`. Throws
/// InputError (start.family_option) when the selected family has no equilibrium at either
/// end of the interval: there is nothing to continue.
ContinuationRun continue_branches(const Params& p, ParamRef param, double to, const ContinuationOptions& options,
                                  const StartSelection& start = {});

/// Which family a configuration belongs to (q = 0: balanced; beta1 = beta2: together;
/// beta2 = beta1 + pi: opposite), within a relative tolerance of 1e-7.
Family classify(const Params& p, const Coordinates<long double, 2>& s);

}  // namespace abu
