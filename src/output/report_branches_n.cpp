// Output formats of n-ball continuation runs (branches_n.hpp; declared in report.hpp).
// This file owns the three schemas branch_NAME.csv, special_NAME.csv and
// envelope_NAME.csv of `continue` on n >= 3 balls.
#include <fmt/format.h>

#include "abu/output/report_dry_along.hpp"

#include <cmath>

#include "abu/output/format.hpp"
#include "abu/output/report.hpp"

namespace abu {

namespace {

std::string num(double v, std::string_view what) { return format_number(v, what); }

// family,pattern,member of a branch.
std::string identity_cells(const BranchN& b, int n_balls) {
  return fmt::format("{},{},{}", to_string(b.family), b.family == Family::aligned ? pattern_string(b.pattern, n_balls) : "",
                     b.member);
}

// q1,q2,beta1..beta<n>,q_abs (angles wrapped to [0, 2 pi)). On the balanced family q = 0
// by construction (model.md §13): the corrector's rounding residue is printed as 0.
std::string position_cells(const Coordinates<long double, any_balls>& s, Family family) {
  const bool balanced = family == Family::balanced;
  const double q1 = balanced ? 0.0 : double(s(0)), q2 = balanced ? 0.0 : double(s(1));
  std::string out = fmt::format("{},{}", num(q1, "q1"), num(q2, "q2"));
  for (Eigen::Index i = 2; i < s.size(); ++i) out += fmt::format(",{}", num(double(wrap_angle(s(i))), "beta"));
  out += fmt::format(",{}", num(std::hypot(q1, q2), "|q|"));
  return out;
}

std::string position_header(int n_balls) {
  std::string out = "q1,q2";
  for (int i = 1; i <= n_balls; ++i) out += fmt::format(",beta{}", i);
  out += ",q_abs";
  return out;
}

bool failed(StopReason r) { return r == StopReason::step_underflow || r == StopReason::max_steps; }

std::string run_comments(const ContinuationRunN& run) {
  const auto& st = run.stats;
  std::string out = fmt::format("# run: {} points, {} steps retried, {} Newton iterations, {} spectra\n", st.steps,
                                st.rejected, st.newton_iterations, st.full_spectra);
  for (std::size_t k = 0; k < run.branches.size(); ++k) {
    const BranchN& b = run.branches[k];
    for (int end = 0; end < 2; ++end)
      out += fmt::format("# branch {} ({} {} {}) {}: {}{}{}\n", k + 1, to_string(b.family),
                         b.family == Family::aligned ? pattern_string(b.pattern, run.n_balls) : "sample", b.member,
                         end == 0 ? "start side" : "far side", to_string(b.stop[std::size_t(end)]),
                         b.stop_detail[std::size_t(end)].empty() ? "" : ": ", b.stop_detail[std::size_t(end)]);
  }
  for (const auto& n : run.notes) out += "# note: " + n + "\n";
  return out;
}

}  // namespace

std::string branch_csv(const ContinuationRunN& run, std::string_view header, const DryFiguresAlong* dry,
                       std::string_view dry_which) {
  const std::string name = to_string(run.param);
  const int n = run.n_balls, size = 2 * n + 4;
  std::string out(header);
  out += fmt::format(
      "# continuation of {} balls in {} [{}] from {} to {}; pseudo-arclength, points ordered along each branch "
      "(docs/model.md §13.7)\n"
      "# columns: branch (1-based), point (index along the branch), label (EP at the ends; special points are in "
      "special_{}.csv),\n"
      "#   family (aligned, or balanced: a sample of the balanced set followed with beta3..beta{} held), pattern "
      "(aligned: + / - per ball), member (aligned: root; balanced: sample),\n"
      "#   q1 q2 [m], beta_i [rad] in [0, 2 pi), q_abs [m] (also the fixed-frame whirl radius), residual (scaled "
      "static equations),\n"
      "#   spectral_abscissa [1/s] and stable (1/0): normal to the set on balanced branches, n_unstable, "
      "n_structural_zero (eigenvalues zero along the set),\n"
      "#   re_k im_k [1/s]: the {} eigenvalues sorted by real part descending (rotating frame), structural zeros "
      "exactly 0\n",
      n, name, unit(run.param.quantity), run.from, run.to, name, n, size);
  out += run_comments(run);
  if (dry) out += dry_columns_doc(dry_which);
  out += fmt::format("branch,point,label,{},family,pattern,member,{},residual,spectral_abscissa,stable,n_unstable,"
                     "n_structural_zero",
                     name, position_header(n));
  for (int k = 1; k <= size; ++k) out += fmt::format(",re{},im{}", k, k);
  if (dry) out += dry_columns();
  out += "\n";
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    const BranchN& branch = run.branches[b];
    for (std::size_t i = 0; i < branch.points.size(); ++i) {
      const BranchPointN& pt = branch.points[i];
      const SpectrumN& sp = pt.spectrum;
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}", b + 1, i, to_string(pt.label),
                         num(double(pt.parameter), name), identity_cells(branch, n),
                         position_cells(pt.position, branch.family),
                         num(pt.residual, "residual"), num(sp.abscissa, "spectral abscissa"),
                         sp.stability == Stability::stable ? 1 : 0, sp.n_unstable, sp.n_structural);
      for (int k = 0; k < sp.count; ++k) {
        const auto l = sp.structural[std::size_t(k)] ? std::complex<double>() : sp.eigenvalues[std::size_t(k)];
        out += fmt::format(",{},{}", num(l.real(), "eigenvalue"), num(l.imag(), "eigenvalue"));
      }
      if (dry) out += dry_cells(*dry, double(pt.parameter));
      out += "\n";
    }
  }
  return out;
}

std::string special_points_csv(const ContinuationRunN& run, std::string_view header) {
  const std::string name = to_string(run.param);
  const int n = run.n_balls;
  std::string out(header);
  out += fmt::format(
      "# special points of the continuation of {} balls in {} [{}]: LP fold, BP branch point, HB Hopf (normal to the "
      "balanced set on balanced branches), MX a branch that ended in failure\n"
      "# columns: branch, label, {} (located by Brent's method on the test function along the branch, to 1e-13 of "
      "the bracket), family, pattern, member, q1 q2 [m], beta_i [rad], q_abs [m],\n"
      "#   frequency [rad/s] (HB only: omega_H in the rotating frame; empty otherwise), re im [1/s] the critical "
      "eigenvalue (empty on MX rows), converged (1/0; empty on MX rows),\n"
      "#   n_unstable before/after along the branch, bracket_from bracket_to: the parameters of the points either "
      "side; note\n",
      n, name, unit(run.param.quantity), name);
  out += run_comments(run);
  out += fmt::format("branch,label,{},family,pattern,member,{},frequency,re,im,converged,n_unstable_before,"
                     "n_unstable_after,bracket_from,bracket_to,note\n",
                     name, position_header(n));
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    const BranchN& branch = run.branches[b];
    for (const SpecialPointN& sp : branch.specials)
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\"\n", b + 1, to_string(sp.label),
                         num(double(sp.parameter), name), identity_cells(branch, n),
                         position_cells(sp.position, branch.family),
                         sp.frequency ? num(*sp.frequency, "frequency") : "", num(sp.eigenvalue.real(), "eigenvalue"),
                         num(sp.eigenvalue.imag(), "eigenvalue"), sp.converged ? 1 : 0, sp.n_unstable_before,
                         sp.n_unstable_after, num(double(sp.bracket_from), name), num(double(sp.bracket_to), name),
                         sp.note);
    for (int end = 0; end < 2; ++end) {
      if (!failed(branch.stop[std::size_t(end)])) continue;
      const BranchPointN& pt = end == 0 ? branch.points.front() : branch.points.back();
      out += fmt::format("{},MX,{},{},{},,,,,{},{},,,\"{}\"\n", b + 1, num(double(pt.parameter), name),
                         identity_cells(branch, n), position_cells(pt.position, branch.family), pt.spectrum.n_unstable,
                         pt.spectrum.n_unstable, branch.stop_detail[std::size_t(end)]);
    }
  }
  return out;
}

std::string envelope_csv(const ContinuationRunN& run, std::string_view header) {
  const std::string name = to_string(run.param);
  const BalancedEnvelope& env = run.envelope;
  std::string out(header);
  out += fmt::format(
      "# the balanced set's stability boundary in {} [{}] (docs/model.md §13.7): the envelope of the Hopf points of "
      "its {} samples ({} with a Hopf point),\n"
      "# each sample continued with its free angles held. Columns: from, to (a piece of the interval between "
      "consecutive special points of any sample),\n"
      "#   samples (whose branch covers the piece), normally_stable (of them, stable normal to the set throughout), "
      "fraction_stable (empty where no sample covers the piece)\n",
      name, unit(run.param.quantity), env.samples, env.samples_with_hopf);
  out += "from,to,samples,normally_stable,fraction_stable\n";
  for (const auto& iv : env.intervals)
    out += fmt::format("{},{},{},{},{}\n", num(double(iv.from), name), num(double(iv.to), name), iv.samples, iv.stable,
                       iv.samples > 0 ? num(double(iv.stable) / iv.samples, "fraction") : "");
  return out;
}

std::string boundary_csv(const BoundaryRunN& run, std::string_view header) {
  const std::string n1 = to_string(run.param), n2 = to_string(run.param2);
  const int n = run.n_balls;
  std::string out(header);
  out += fmt::format(
      "# stability boundaries of {} balls in ({} [{}], {} [{}]): the folds of the aligned branches and the Hopf "
      "points of the aligned branches and of the balanced samples (free angles held), continued in {} from {} to {} "
      "(docs/model.md §13.7)\n"
      "# columns: curve (1-based), kind (LP fold curve, HB Hopf curve), family, pattern, member (aligned: root; "
      "balanced: sample), source_branch (of branch_{}.csv), point, label (EP end, BT where a Hopf frequency reached 0),\n"
      "#   {} {}, q1 q2 [m], beta_i [rad], q_abs [m], frequency [rad/s] (Hopf curves: omega_H, rotating frame; empty "
      "on fold curves)\n",
      n, n1, unit(run.param.quantity), n2, unit(run.param2.quantity), n2, run.from2, run.to2, n1, n1, n2);
  for (std::size_t k = 0; k < run.curves.size(); ++k)
    for (int end = 0; end < 2; ++end)
      out += fmt::format("# curve {} {}: {}{}{}\n", k + 1, end == 0 ? "start side" : "far side",
                         to_string(run.curves[k].stop[std::size_t(end)]),
                         run.curves[k].stop_detail[std::size_t(end)].empty() ? "" : ": ",
                         run.curves[k].stop_detail[std::size_t(end)]);
  for (const auto& note : run.notes) out += "# note: " + note + "\n";
  out += fmt::format("curve,kind,family,pattern,member,source_branch,point,label,{},{},{},frequency\n", n1, n2,
                     position_header(n));
  for (std::size_t k = 0; k < run.curves.size(); ++k) {
    const BoundaryCurveN& c = run.curves[k];
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const BoundaryPointN& pt = c.points[i];
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", k + 1, to_string(c.kind), to_string(c.family),
                         c.family == Family::aligned ? pattern_string(c.pattern, n) : "", c.member, c.source_branch, i,
                         to_string(pt.label), num(double(pt.parameter), n1), num(double(pt.parameter2), n2),
                         position_cells(pt.position, c.family), pt.frequency ? num(*pt.frequency, "frequency") : "");
    }
  }
  return out;
}

std::string continuation_warnings(const ContinuationRunN& run) {
  std::string out;
  for (std::size_t k = 0; k < run.branches.size(); ++k)
    for (int end = 0; end < 2; ++end)
      if (failed(run.branches[k].stop[std::size_t(end)]))
        out += fmt::format("warning: branch {}: {}\n", k + 1, run.branches[k].stop_detail[std::size_t(end)]);
  return out;
}

}  // namespace abu
