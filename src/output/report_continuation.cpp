// Output formats of continuation runs (declared in report.hpp).
#include <fmt/compile.h>
#include <fmt/format.h>

#include "abu/output/report_dry_along.hpp"

#include <cmath>
#include <iterator>
#include <numbers>

#include "abu/core/errors.hpp"
#include "abu/output/format.hpp"
#include "abu/output/report.hpp"

namespace abu {

namespace {

std::string num(double v, std::string_view what) { return format_number(v, what); }

long double wrap(long double beta) { return wrap_angle(beta); }

// q = 0 by construction on the balanced family (model.md §5): the corrector's rounding
// residue (|q| ~ 1e-44 m) is printed as the exact 0 it stands for.
std::string position_cells(const Coordinates<long double, 2>& s, Family family) {
  const bool balanced = family == Family::balanced;
  const double q1 = balanced ? 0.0 : double(s(0)), q2 = balanced ? 0.0 : double(s(1));
  return fmt::format("{},{},{},{},{}", num(q1, "q1"), num(q2, "q2"), num(double(wrap(s(2))), "beta1"),
                     num(double(wrap(s(3))), "beta2"), num(std::hypot(q1, q2), "|q|"));
}

std::string stop_line(const Branch& b, std::size_t k, int end) {
  const std::string_view side = end == 0 ? "start side" : "far side";
  return fmt::format("branch {} ({} {}) {}: {}{}{}", k + 1, to_string(b.family), b.member, side,
                     to_string(b.stop[std::size_t(end)]), b.stop_detail[std::size_t(end)].empty() ? "" : ": ",
                     b.stop_detail[std::size_t(end)]);
}

bool failed(StopReason r) { return r == StopReason::step_underflow || r == StopReason::max_steps; }

// A value that is not defined at a point (a Hopf frequency off Hopf points, a Lyapunov
// coefficient where no Hopf point was located) is an empty field, never a sentinel 0:
// 0 is a meaningful value of both (a Bogdanov-Takens end, a degenerate Hopf point).
std::string num_if(bool defined, double v, std::string_view what) { return defined ? num(v, what) : std::string(); }

std::string run_comments(const ContinuationRun& run) {
  const auto& st = run.stats;
  std::string out = fmt::format(
      "# run: {} points, {} steps retried, {} Newton iterations, {} spectra by eigenvalue continuation, {} computed "
      "afresh\n",
      st.steps, st.rejected, st.newton_iterations, st.tracked_spectra, st.full_spectra);
  for (std::size_t k = 0; k < run.branches.size(); ++k)
    for (int end = 0; end < 2; ++end) out += "# " + stop_line(run.branches[k], k, end) + "\n";
  for (const auto& n : run.notes) out += "# note: " + n + "\n";
  return out;
}

}  // namespace

std::string branch_csv(const ContinuationRun& run, std::string_view header, const DryFiguresAlong* dry,
                       std::string_view dry_which) {
  const std::string name = to_string(run.param);
  std::string out(header);
  out += fmt::format(
      "# continuation in {} [{}] from {} to {}; pseudo-arclength, points ordered along each branch\n"
      "# columns: branch (1-based), point (index along the branch), label (EP at the ends; LP, BP, HB: a special "
      "point of special_{}.csv\n#   at its located parameter, written twice where the stability changes there: "
      "first with the stable and n_unstable of the side\n#   before it, then of the side after it; its eigenvalues are "
      "those at the point),\n#   q1 q2 [m], beta1 beta2 [rad] in [0, 2 pi), q_abs [m], family of the point, stable (1/0), "
      "n_unstable,\n#   re_k im_k [1/s]: eigenvalue k (rotating frame; fixed frame: campbell_<param>.csv) in TRACKED order (matched from point to point: k stays the "
      "same mode along a branch)\n",
      name, unit(run.param.quantity), run.from, run.to, name);
  out += run_comments(run);
  if (dry) out += dry_columns_doc(dry_which);
  out += fmt::format("branch,point,label,{},q1,q2,beta1,beta2,q_abs,family,stable,n_unstable", name);
  for (int k = 1; k <= 8; ++k) out += fmt::format(",re{},im{}", k, k);
  if (dry) out += dry_columns();
  out += "\n";
  // The rows (some 20 numbers each, most of the file) formatted in place: the same text as
  // format_number's, without a string per number.
  const auto cell = [&out](double v, std::string_view what) {
    if (!std::isfinite(v)) throw NumericalError(fmt::format("non-finite {} ({}) would be written", what, v));
    fmt::format_to(std::back_inserter(out), FMT_COMPILE(",{}"), v);
  };
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    const auto& branch = run.branches[b];
    for (std::size_t i = 0; i < branch.points.size(); ++i) {
      const auto& pt = branch.points[i];
      const auto& s = pt.position;
      // q = 0 on balanced rows is printed as 0 (position_cells): the polish leaves ~1e-44.
      const bool balanced = pt.family == Family::balanced;
      const double q1 = balanced ? 0.0 : double(s(0)), q2 = balanced ? 0.0 : double(s(1));
      fmt::format_to(std::back_inserter(out), FMT_COMPILE("{},{},{}"), b + 1, i, to_string(pt.label));
      cell(double(pt.parameter), name);
      cell(q1, "q1");
      cell(q2, "q2");
      cell(double(wrap(s(2))), "beta1");
      cell(double(wrap(s(3))), "beta2");
      cell(std::hypot(q1, q2), "|q|");
      fmt::format_to(std::back_inserter(out), FMT_COMPILE(",{},{},{}"), to_string(pt.family),
                     pt.spectrum.stability == Stability::stable ? 1 : 0, pt.spectrum.n_unstable);
      for (const auto& l : pt.modes) cell(l.real(), "eigenvalue"), cell(l.imag(), "eigenvalue");
      if (dry) out += dry_cells(*dry, double(pt.parameter));
      out += '\n';
    }
  }
  return out;
}

std::string special_points_csv(const ContinuationRun& run, std::string_view header) {
  const std::string name = to_string(run.param);
  std::string out(header);
  out += fmt::format(
      "# special points of the continuation in {} [{}]: LP fold, BP branch point, HB Hopf, MX a branch that ended "
      "in failure\n# columns: branch, label, {} (located by an augmented system to the rounding level), q1 q2 [m], "
      "beta1 beta2 [rad], q_abs [m], family,\n#   frequency [rad/s] (HB; empty otherwise), re im [1/s] the critical eigenvalue (both in the rotating frame), "
      "lyapunov = first Lyapunov coefficient (HB; < 0 supercritical, > 0 subcritical; state in SI, <q,q> = 1;\n"
      "#   empty off HB rows and where the Hopf system did not converge), converged (1/0), n_unstable before/after "
      "along the branch;\n#   MX rows: frequency, re, im, lyapunov and converged empty (no point was located)\n",
      name, unit(run.param.quantity), name);
  out += run_comments(run);
  out += fmt::format(
      "branch,label,{},q1,q2,beta1,beta2,q_abs,family,frequency,re,im,lyapunov,converged,n_unstable_before,"
      "n_unstable_after\n",
      name);
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    const auto& branch = run.branches[b];
    for (const auto& sp : branch.specials)
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", b + 1, to_string(sp.label),
                         num(double(sp.parameter), name), position_cells(sp.position, sp.family), to_string(sp.family),
                         num_if(sp.label == Label::HB, sp.frequency, "frequency"),
                         num(sp.eigenvalue.real(), "eigenvalue"), num(sp.eigenvalue.imag(), "eigenvalue"),
                         num_if(sp.label == Label::HB && sp.converged, sp.lyapunov, "lyapunov"), sp.converged ? 1 : 0,
                         sp.n_unstable_before, sp.n_unstable_after);
    for (int end = 0; end < 2; ++end) {
      if (!failed(branch.stop[std::size_t(end)])) continue;
      const auto& pt = end == 0 ? branch.points.front() : branch.points.back();
      // No special point was located here: frequency, eigenvalue, lyapunov and converged
      // are not defined (empty).
      out += fmt::format("{},MX,{},{},{},,,,,,{},{}\n", b + 1, num(double(pt.parameter), name),
                         position_cells(pt.position, branch.family), to_string(branch.family), pt.spectrum.n_unstable,
                         pt.spectrum.n_unstable);
    }
  }
  return out;
}

std::string boundary_csv(const BoundaryRun& run, std::string_view header) {
  const std::string n1 = to_string(run.param), n2 = to_string(run.param2);
  std::string out(header);
  out += fmt::format(
      "# two-parameter continuation of the fold (LP) and Hopf (HB) points in ({} [{}], {} [{}]) over {} .. {} x {} .. "
      "{}\n# columns: curve, kind (LP fold curve, HB Hopf curve), point (index along the curve), label (EP end, BT "
      "Bogdanov-Takens,\n#   ZH zero-Hopf, CP cusp: where the curve meets them, located by interpolating their test functions;\n"
      "#   GH generalized Hopf: the zero of l1 along the Hopf curve, located by regula falsi on the curve), the two\n#   parameters, q1 q2 [m], beta1 beta2 [rad], q_abs [m], family, "
      "lyapunov = first Lyapunov coefficient l1 (Hopf curves:\n"
      "#   < 0 supercritical, > 0 subcritical; empty on fold curves and at codimension-two points), stable_side (Hopf\n"
      "#   curves: 1 the equilibrium is stable just above the curve in the first parameter, -1 just below, 0 on neither side; empty on\n"
      "#   fold curves and at codimension-two points), frequency [rad/s] (Hopf curves, rotating frame; empty on fold curves)\n",
      n1, unit(run.param.quantity), n2, unit(run.param2.quantity), run.from, run.to, run.from2, run.to2);
  for (std::size_t c = 0; c < run.curves.size(); ++c)
    for (int end = 0; end < 2; ++end) {
      const auto& curve = run.curves[c];
      out += fmt::format("# curve {} ({} from branch {}) {} end: {}{}{}\n", c + 1, to_string(curve.kind),
                         curve.source_branch, end == 0 ? "first" : "last", to_string(curve.stop[std::size_t(end)]),
                         curve.stop_detail[std::size_t(end)].empty() ? "" : ": ", curve.stop_detail[std::size_t(end)]);
    }
  for (const auto& n : run.notes) out += "# note: " + n + "\n";
  for (std::size_t c = 0; c < run.curves.size(); ++c)
    for (const auto& pt : run.curves[c].points)
      if (pt.label == Label::GH && !pt.located)
        out += fmt::format("# note: curve {}: the GH point at ({:.17g}, {:.17g}) is interpolated, not located (the "
                           "corrector failed inside its segment)\n",
                           c + 1, double(pt.parameter), double(pt.parameter2));
  // frequency stays last: gnuplot 5.4 misreads an empty *last* field (strcol returns an
  // earlier one), and only frequency's emptiness (fold curves) is old news to readers.
  out += fmt::format("curve,kind,point,label,{},{},q1,q2,beta1,beta2,q_abs,family,lyapunov,stable_side,frequency\n", n1,
                     n2);
  for (std::size_t c = 0; c < run.curves.size(); ++c) {
    const auto& curve = run.curves[c];
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
      const auto& pt = curve.points[i];
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", c + 1, to_string(curve.kind), i, to_string(pt.label),
                         num(double(pt.parameter), n1), num(double(pt.parameter2), n2),
                         position_cells(pt.position, pt.family),
                         to_string(pt.family), num_if(pt.lyapunov.has_value(), pt.lyapunov.value_or(0.0), "lyapunov"),
                         pt.stable_side ? fmt::format("{}", *pt.stable_side) : std::string(),
                         num_if(curve.kind == Label::HB, double(pt.frequency), "frequency"));
    }
  }
  return out;
}

std::string continuation_warnings(const ContinuationRun& run) {
  std::string out;
  for (std::size_t k = 0; k < run.branches.size(); ++k) {
    const auto& b = run.branches[k];
    for (int end = 0; end < 2; ++end)
      if (b.stop[std::size_t(end)] != StopReason::end_of_range && b.stop[std::size_t(end)] != StopReason::closed_loop)
        out += "warning: " + stop_line(b, k, end) + "\n";
    for (const auto& sp : b.specials)
      if (!sp.converged || (!sp.note.empty() && sp.note.rfind("located on branch", 0) != 0))
        out += fmt::format("warning: branch {}: {} at {}={:.17g}: {}\n", k + 1, to_string(sp.label),
                           to_string(run.param), double(sp.parameter), sp.note.empty() ? "not converged" : sp.note);
  }
  return out;
}

}  // namespace abu
