// The output formats of an analysis: the equilibria CSV / JSON / table and the sweep
// CSV. Every file starts with the provenance header (provenance.hpp) and documents its columns
// in comment lines; numbers are in shortest round-trip form, states in SI in the state
// order of model.md §2, eigenvalues in 1/s.
#pragma once

#include <string>
#include <string_view>

#include "abu/analysis/dry_friction.hpp"
#include "abu/continuation/boundaries.hpp"
#include "abu/core/speed_units.hpp"
#include "abu/continuation/boundaries_n.hpp"
#include "abu/continuation/branches_n.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/linear/kappa_sensitivity.hpp"
#include "abu/scan/scan.hpp"

namespace abu {

/// Column documentation shared by the CSV files.
std::string_view equilibrium_columns_doc();

/// `family,pattern,member,q1,q2,beta1..beta<n>,residual,spectral_abscissa,stable,n_structural_zero,
/// re1,im1,...,re<2n+4>,im<2n+4>` (readers go by the header's names).
std::string equilibria_csv(const Analysis& a, std::string_view header);
std::string equilibria_csv(const AnalysisN& a, std::string_view header, int n_balls);
/// JSON; for n >= 3 balls with a `balanced_set` object (dimension, grid, samples,
/// fraction normally stable, extreme normal abscissae).
/// What `equilibria --format table` prints: the stated answer (report_views.hpp), the
/// equilibria with their rotating-frame eigenvalues, the fixed-frame modes and the creep
/// modes. The Python module's table is this text too.
std::string equilibria_report(const Analysis& a, const Params& p, SpeedUnit unit,
                              const std::vector<KappaSensitivity<2>>& kappa, const DryFrictionVerdict& dry);
std::string equilibria_report(const AnalysisN& a, const ParamsN& p, SpeedUnit unit,
                              const std::vector<KappaSensitivity<any_balls>>& kappa, const DryFrictionVerdict& dry);

/// Comment lines (each starting with `prefix`) naming, per equilibrium, the creep modes of
/// a coulomb or stribeck law: eigenvalues with d log|lambda| / d log kappa = -1 within
/// creep_tolerance (model.md (6.11), linear/kappa_sensitivity.hpp). Empty for other laws.
template <class A, int N>
std::string creep_lines(const A& a, const std::vector<KappaSensitivity<N>>& kappa, std::string_view prefix);

/// The JSON form; kappa: per equilibrium, as analyze_equilibria computed it; `dry` the
/// dry-friction verdict as the table and the CSV carry it (dry_friction_json).
std::string equilibria_json(const Analysis& a, std::string_view command_line, std::string_view scene_file,
                            const Params& p, const std::vector<KappaSensitivity<2>>& kappa,
                            const DryFrictionVerdict& dry = {});
std::string equilibria_json(const AnalysisN& a, std::string_view command_line, std::string_view scene_file,
                            const ParamsN& p, const std::vector<KappaSensitivity<any_balls>>& kappa,
                            const DryFrictionVerdict& dry = {});
std::string equilibria_table(const Analysis& a, const Params& p);
std::string equilibria_table(const AnalysisN& a, const ParamsN& p);

/// Long format, one row per equilibrium per value, ordered by family, member, value so
/// that each member of a family is one contiguous series:
/// `step,<param>,family,pattern,member,q1,q2,beta1,beta2,q_abs,residual,spectral_abscissa,stable,n_unstable,
/// n_structural_zero,re1,...,im8`.
std::string sweep_csv(const SweepResult& s, std::string_view header);
/// The same in pieces, for a sweep written as its values come (output/sweep_stream.hpp):
/// sweep_head + every value's comments + sweep_columns + every row, ordered by family and
/// member, then value.
std::string sweep_head(ParamRef param, std::size_t values, std::string_view header);
std::string sweep_value_comments(ParamRef param, double value, const Analysis& a);
std::string sweep_columns(ParamRef param);
std::string sweep_row(std::size_t step, ParamRef param, double value, const Equilibrium& e, const Spectrum& sp);

/// A sweep of any ball count (also over the ball count itself, `n`): the analysis at each
/// value. `values[i]` is the swept value, `points[i]` its analysis.
struct SweepResultN {
  std::string name;  ///< the parameter's symbol, or "n"
  std::string unit;
  std::vector<double> values;
  std::vector<AnalysisN> points;
};
/// Long format as sweep_csv, the columns for the largest ball count of the sweep (beta_i
/// and eigenvalue columns a row's equilibrium does not have are empty).
std::string sweep_csv(const SweepResultN& s, std::string_view header);
/// One row per value, what a designer reads off (model.md §13):
/// `step,<param>,n,capacity,U,balanced_exists,balanced_samples,fraction_stable,normal_abscissa_max,
///  aligned,aligned_stable,best_family,best_pattern,best_q_abs` (best: the stable state of least
/// |q|, empty when nothing is stable).
std::string sweep_summary_csv(const SweepResultN& s, std::string_view header);
/// The same two files in pieces, for a sweep written as its values come (output/sweep_stream.hpp):
/// sweep_csv = sweep_head + every value's comments + sweep_columns + every value's rows;
/// sweep_summary_csv = sweep_summary_head + every value's row.
std::string sweep_head(const std::string& name, const std::string& unit, std::size_t values, std::string_view header);
std::string sweep_value_comments(const std::string& name, double value, const AnalysisN& a);
std::string sweep_columns(const std::string& name, int n_max);
std::string sweep_value_rows(std::size_t step, const std::string& name, double value, const AnalysisN& a, int n_max);
std::string sweep_summary_head(const std::string& name, const std::string& unit, std::string_view header);
std::string sweep_summary_row(std::size_t step, const std::string& name, double value, const AnalysisN& a);

/// Continuation: one row per branch point,
/// `branch,point,label,<param>,q1,q2,beta1,beta2,q_abs,family,stable,n_unstable,re1,im1,...,re8,im8`
/// with the eigenvalues in tracked order (eigenvalue k is the same mode along a branch); with
/// `dry` (a coulomb / stribeck scene) every row also carries the dry_* columns of its parameter
/// value (output/report_dry_along.hpp), `dry_which` the resting law's coefficients.
std::string branch_csv(const ContinuationRun& run, std::string_view header, const DryFiguresAlong* dry = nullptr,
                       std::string_view dry_which = {});
/// One row per special point (and an MX row where a branch ended in failure):
/// `branch,label,<param>,q1,q2,beta1,beta2,q_abs,family,frequency,re,im,lyapunov,converged,n_unstable_before,n_unstable_after`.
std::string special_points_csv(const ContinuationRun& run, std::string_view header);
/// Two-parameter curves, one row per curve point (codimension-two points included, by
/// label): `curve,kind,point,label,<param>,<param2>,q1,q2,beta1,beta2,q_abs,family,frequency`.
std::string boundary_csv(const BoundaryRun& run, std::string_view header);

/// How each branch ended, one line per end that is not the end of the interval (stderr).
std::string continuation_warnings(const ContinuationRun& run);

/// Continuation of n >= 3 balls (report_branches_n.cpp): one row per branch point,
/// `branch,point,label,<param>,family,pattern,member,q1,q2,beta1..beta<n>,q_abs,residual,
/// spectral_abscissa,stable,n_unstable,n_structural_zero,re1,im1,...,re<2n+4>,im<2n+4>`
/// (eigenvalues sorted, normal stability on balanced samples); `dry` as for two balls.
std::string branch_csv(const ContinuationRunN& run, std::string_view header, const DryFiguresAlong* dry = nullptr,
                       std::string_view dry_which = {});
/// `branch,label,<param>,family,pattern,member,q1,..,q_abs,frequency,re,im,converged,
/// n_unstable_before,n_unstable_after,bracket_from,bracket_to,note` (frequency empty off HB).
std::string special_points_csv(const ContinuationRunN& run, std::string_view header);
/// The balanced set's stability boundary: `from,to,samples,normally_stable,fraction_stable`.
std::string envelope_csv(const ContinuationRunN& run, std::string_view header);
std::string continuation_warnings(const ContinuationRunN& run);
/// n >= 3 balls' stability boundaries: `curve,kind,family,pattern,member,source_branch,point,
/// label,<param>,<param2>,q1,q2,beta1..beta<n>,q_abs,frequency` (frequency empty on fold curves).
std::string boundary_csv(const BoundaryRunN& run, std::string_view header);

/// Warnings for the user (stderr): equilibria whose polish or spectrum did not
/// converge, ill-conditioned spectra; `where` says at which parameter value.
std::string analysis_warnings(const Analysis& a, std::string_view where);
std::string analysis_warnings(const AnalysisN& a, std::string_view where);

}  // namespace abu
