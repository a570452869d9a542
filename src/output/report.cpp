#include "abu/output/report.hpp"
#include "abu/core/widen_params.hpp"
#include "abu/output/report_stick_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "abu/output/format.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_views.hpp"
#include "equilibrium_text.hpp"
#include "abu/linear/kappa_sensitivity.hpp"

namespace abu {

using detail::pattern_of;
using detail::q_abs;
using detail::state_label;

namespace {

std::string num(double v, std::string_view what) { return format_number(v, what); }

template <int N>
std::string eigenvalue_cells(const SpectrumT<N>& sp) {
  std::string s;
  for (int k = 0; k < sp.count; ++k) {
    const auto& l = sp.eigenvalues[std::size_t(k)];
    s += fmt::format(",{},{}", num(l.real(), "eigenvalue"), num(l.imag(), "eigenvalue"));
  }
  return s;
}

std::string eigenvalue_header(int count) {
  std::string s;
  for (int k = 1; k <= count; ++k) s += fmt::format(",re{},im{}", k, k);
  return s;
}

std::string beta_header(int n_balls) {
  std::string s;
  for (int i = 1; i <= n_balls; ++i) s += fmt::format(",beta{}", i);
  return s;
}

template <int N>
std::string beta_cells(const EquilibriumT<N>& e) {
  std::string s;
  for (int i = 0; i < e.n_balls(); ++i) {
    s += ',';
    s += num(double(e.position(2 + i)), "beta");
  }
  return s;
}

// Notes on one equilibrium that a reader of the numbers must know.
template <int N>
std::vector<std::string> notes(const EquilibriumT<N>& e, const SpectrumT<N>& sp) {
  std::vector<std::string> out;
  if (e.is_set) out.push_back("representative of a circle of equilibria (U = 0)");
  if (!e.converged) out.push_back(fmt::format("Newton polish did not converge (residual {:.3g})", e.residual));
  if (!sp.converged) out.push_back("an eigenvalue refinement did not converge; its error estimate is the QR bound");
  if (sp.stability == Stability::marginal)
    out.push_back(fmt::format("marginal: {} eigenvalue(s) within the error band of the imaginary axis", sp.n_marginal));
  if (sp.certified_count > 0)
    out.push_back(fmt::format("{} eigenvalue(s) stayed within their error bands: the unstable count ({}) and the "
                              "abscissa are the characteristic polynomial's, certified (Routh, model.md §8)",
                              sp.certified_count, sp.n_unstable));
  if (sp.ill_conditioned) {
    double worst = 0;
    for (int k = 0; k < sp.count; ++k)
      if (!sp.structural[std::size_t(k)]) worst = std::max(worst, sp.condition[std::size_t(k)]);
    out.push_back(fmt::format("ill-conditioned spectrum: condition number up to {:.3g} (input rounding alone "
                              "moves an eigenvalue by > 1e-8 of its modulus)", worst));
  }
  return out;
}

template <class A>
int ball_count_of(const A& a, int fallback) {
  const auto points = a.equilibria.points();
  return points.empty() ? fallback : points.front().n_balls();
}

// The balanced set of n >= 3 balls as a whole: how many samples, how many normally stable,
// the extreme normal abscissae (model.md §13.4).
struct SetStatistics {
  int samples = 0, stable = 0;
  double min_abscissa = 0, max_abscissa = 0;
};
SetStatistics set_statistics(const AnalysisN& a) {
  SetStatistics st;
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].family != Family::balanced) continue;  // (two balls: the two mirror points)
    const double x = a.spectra[i].abscissa;
    st.min_abscissa = st.samples == 0 ? x : std::min(st.min_abscissa, x);
    st.max_abscissa = st.samples == 0 ? x : std::max(st.max_abscissa, x);
    ++st.samples;
    if (a.spectra[i].stability == Stability::stable) ++st.stable;
  }
  return st;
}

template <class A>
std::string balanced_set_comment(const A& a) {
  if constexpr (std::is_same_v<A, AnalysisN>) {
    const auto& info = a.equilibria.balanced_set;
    if (info.dimension < 1) return {};
    if (!info.exists) return "# balanced set: does not exist (the polygon inequality fails)\n";
    const SetStatistics st = set_statistics(a);
    return fmt::format(
        "# balanced set: dimension {}, sampled on a grid of {} values per free angle (beta3..beta{}), both sheets: "
        "{} of {} grid points on the set; normally stable at {} of {} samples (fraction {}); normal spectral "
        "abscissa from {} to {} 1/s\n",
        info.dimension, info.grid, info.dimension + 2, info.samples, info.grid_points, st.stable, st.samples,
        st.samples ? num(double(st.stable) / st.samples, "fraction") : std::string("-"),
        st.samples ? num(st.min_abscissa, "abscissa") : std::string("-"),
        st.samples ? num(st.max_abscissa, "abscissa") : std::string("-"));
  } else {
    return {};
  }
}

}  // namespace


template <class A, int N>
std::string creep_lines(const A& a, const std::vector<KappaSensitivity<N>>& ks, std::string_view prefix) {
  std::string out;
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!ks[i].defined || ks[i].n_creep == 0) continue;
    std::string which;
    for (int k = 0; k < a.spectra[i].count; ++k)
      if (ks[i].creep[std::size_t(k)]) which += fmt::format("{}{}", which.empty() ? "" : ", ", k + 1);
    out += fmt::format("{}{} {}: creep modes (lambda ~ 1/kappa, d log|lambda| / d log kappa = -1 +- {}, model.md "
                       "(6.11)): eigenvalues {}; their sign is physics, their rate is set by kappa\n",
                       prefix, to_string(points[i].family), points[i].member, creep_tolerance, which);
  }
  return out;
}
template std::string creep_lines<Analysis, 2>(const Analysis&, const std::vector<KappaSensitivity<2>>&,
                                              std::string_view);
template std::string creep_lines<AnalysisN, any_balls>(const AnalysisN&,
                                                      const std::vector<KappaSensitivity<any_balls>>&,
                                                      std::string_view);

std::string_view equilibrium_columns_doc() {
  return "# columns: family = balanced|together|opposite (two balls) or balanced|aligned (n >= 3) (model.md §5, "
         "§13); pattern = sigma_i, '+' for a ball on the side of the line direction phi, '-' opposite "
         "(empty for balanced);\n"
         "#   member = root of the pattern's equation (1 or 2), or the balanced sample's index; q1, q2 [m] rotor "
         "centre in the rotating frame; beta_i [rad] ball angles from the unbalance, in [0, 2 pi);\n"
         "#   residual = max_i |b_i(s,0)| / scale_i, dimensionless (rounding level ~1e-16); "
         "spectral_abscissa = max Re lambda [1/s] over the eigenvalues that are not structural zeros;\n"
         "#   stable = 1 if every such eigenvalue lies left of its error band around the imaginary axis, else 0 "
         "(on the balanced set of n >= 3 balls: normal stability);\n"
         "#   n_structural_zero = eigenvalues zero by construction (the balanced set's tangent directions), printed "
         "as 0;\n"
         "#   re_k, im_k [1/s] eigenvalue k of the (2n+4)x(2n+4) Jacobian in the rotating frame (state order q1 q2 "
         "beta1..betan and their rates), sorted by real part descending, then imaginary part descending\n";
}

template <class A>
std::string equilibria_csv(const A& a, std::string_view header, int n_balls) {
  std::string out(header);
  out += equilibrium_columns_doc();
  for (const auto& line : describe_degeneracy(a.equilibria.degeneracy)) out += fmt::format("# degenerate: {}\n", line);
  out += balanced_set_comment(a);
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const auto& n : notes(points[i], a.spectra[i])) out += fmt::format("# {}: {}\n", state_label(points[i]), n);
  out += "family,pattern,member,q1,q2" + beta_header(n_balls) + ",residual,spectral_abscissa,stable,n_structural_zero" +
         eigenvalue_header(2 * n_balls + 4) + "\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const auto& sp = a.spectra[i];
    out += fmt::format("{},{},{},{},{}{},{},{},{},{}{}\n", to_string(e.family), pattern_of(e), e.member,
                       num(double(e.position(0)), "q1"), num(double(e.position(1)), "q2"), beta_cells(e),
                       num(e.residual, "residual"), num(sp.abscissa, "spectral abscissa"),
                       sp.stability == Stability::stable ? 1 : 0, sp.n_structural, eigenvalue_cells(sp));
  }
  return out;
}

std::string equilibria_csv(const Analysis& a, std::string_view header) { return equilibria_csv(a, header, 2); }
std::string equilibria_csv(const AnalysisN& a, std::string_view header, int n_balls) {
  return equilibria_csv<AnalysisN>(a, header, n_balls);
}

namespace {
// ", \"kappa_log_slope\": s, \"creep\": b" of eigenvalue k (model.md (6.11)); null / false where
// the law has no kappa or the eigenvalue is zero.
template <int N>
std::string kappa_json(const KappaSensitivity<N>& ks, std::size_t k) {
  if (!ks.defined || !ks.computed[k]) return ", \"kappa_log_slope\": null, \"creep\": false";
  return fmt::format(", \"kappa_log_slope\": {}, \"creep\": {}", num(ks.log_slope[k], "kappa sensitivity"), ks.creep[k]);
}
}  // namespace

template <class A, int N>
std::string equilibria_json(const A& a, std::string_view command_line, std::string_view scene_file,
                            const ParamsT<double, N>& p, const std::vector<KappaSensitivity<N>>& ks,
                            const DryFrictionVerdict& dry) {
  std::string out = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                                ABU_VERSION, json_string(command_line), json_string(scene_file));
  out += fmt::format("  \"parameters\": {},\n  \"balls\": {},\n  \"units\": {},\n", json_string(describe_parameters(p)),
                     p.n_balls(),
                     json_string("q [m], beta [rad] in [0, 2 pi), eigenvalues (rotating frame) and errors [1/s], "
                                 "residual and condition dimensionless"));
  // Rotordynamics views (docs/views.md): the frame of every eigenvalue, the parameters with
  // their units, the point's answer.
  out += fmt::format("  \"frame\": \"rotating\",\n  \"parameter_values\": {},\n  \"answer\": {},\n",
                     parameters_json(p), answer_json(point_answer(a, p)));
  out += "  \"degeneracies\": [";
  const auto deg = describe_degeneracy(a.equilibria.degeneracy);
  for (std::size_t i = 0; i < deg.size(); ++i) out += (i ? ", " : "") + json_string(deg[i]);
  out += "],\n";
  if constexpr (std::is_same_v<A, AnalysisN>) {
    const auto& info = a.equilibria.balanced_set;
    const SetStatistics st = set_statistics(a);
    out += fmt::format(
        "  \"balanced_set\": {{\"exists\": {}, \"dimension\": {}, \"grid\": {{\"free_angles\": {}, "
        "\"values_per_angle\": {}, \"spacing_rad\": {}, \"sheets\": 2, \"grid_points\": {}}}, \"samples\": {}, "
        "\"normally_stable\": {}, \"fraction_stable\": {}, \"normal_abscissa_min\": {}, "
        "\"normal_abscissa_max\": {}}},\n",
        info.exists, info.dimension, std::max(0, info.dimension), info.grid,
        info.grid > 0 ? num(2 * std::numbers::pi / info.grid, "spacing") : std::string("null"), info.grid_points,
        info.samples, st.stable, st.samples ? num(double(st.stable) / st.samples, "fraction") : std::string("null"),
        st.samples ? num(st.min_abscissa, "abscissa") : std::string("null"),
        st.samples ? num(st.max_abscissa, "abscissa") : std::string("null"));
  }
  out += dry_friction_json(dry);
  out += "  \"equilibria\": [";
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const auto& sp = a.spectra[i];
    out += i ? ",\n    {" : "\n    {";
    out += fmt::format("\"family\": \"{}\", \"pattern\": \"{}\", \"member\": {}, \"q1\": {}, \"q2\": {}, ",
                       to_string(e.family), pattern_of(e), e.member, num(double(e.position(0)), "q1"),
                       num(double(e.position(1)), "q2"));
    for (int b = 0; b < e.n_balls(); ++b)
      out += fmt::format("\"beta{}\": {}, ", b + 1, num(double(e.position(2 + b)), "beta"));
    out += fmt::format("\"q_abs\": {}, \"residual\": {}, \"newton_iterations\": {}, \"converged\": {}, "
                       "\"is_set\": {}, \"on_balanced_set\": {},\n     ",
                       num(q_abs(e), "|q|"), num(e.residual, "residual"), e.newton_iterations, e.converged,
                       e.is_set, e.on_balanced_set);
    out += fmt::format("\"stability\": \"{}\", \"spectral_abscissa\": {}, \"n_unstable\": {}, \"n_marginal\": {}, "
                       "\"n_structural_zero\": {}, \"ill_conditioned\": {}, \"spectrum_converged\": {}, \"n_creep\": {},\n     "
                       "\"eigenvalues\": [",
                       to_string(sp.stability), num(sp.abscissa, "abscissa"), sp.n_unstable, sp.n_marginal,
                       sp.n_structural, sp.ill_conditioned, sp.converged,
                       ks[i].defined ? std::to_string(ks[i].n_creep) : std::string("null"));
    const auto modes = mode_views(p, e.position, sp);
    const KappaSensitivity<N>& kappa = ks[i];
    const auto mode_of = mode_of_eigenvalue(modes, sp.count);
    for (std::size_t k = 0; k < std::size_t(sp.count); ++k) {
      out += fmt::format("{}{{\"re\": {}, \"im\": {}, \"error\": {}, \"condition\": {}, \"structural\": {}{}}}",
                         k ? ",\n       " : "", num(sp.eigenvalues[k].real(), "eigenvalue"),
                         num(sp.eigenvalues[k].imag(), "eigenvalue"), num(sp.error[k], "error"),
                         // A structural zero has no condition number (it is exact, not computed);
                         // an eigenvalue 0 has none either (cond divides by |lambda|): null.
                         std::isfinite(sp.condition[k]) && !sp.structural[k] ? num(sp.condition[k], "condition")
                                                                              : std::string("null"),
                         sp.structural[k], eigen_view_json(p, sp, int(k), modes, mode_of) + kappa_json(kappa, k));
    }
    out += "]}";
  }
  out += "\n  ]\n}\n";
  return out;
}

std::string equilibria_json(const Analysis& a, std::string_view command_line, std::string_view scene_file,
                            const Params& p, const std::vector<KappaSensitivity<2>>& kappa,
                            const DryFrictionVerdict& dry) {
  return equilibria_json<Analysis, 2>(a, command_line, scene_file, p, kappa, dry);
}
std::string equilibria_json(const AnalysisN& a, std::string_view command_line, std::string_view scene_file,
                            const ParamsN& p, const std::vector<KappaSensitivity<any_balls>>& kappa,
                            const DryFrictionVerdict& dry) {
  return equilibria_json<AnalysisN, any_balls>(a, command_line, scene_file, p, kappa, dry);
}

template <class A, int N>
std::string equilibria_table(const A& a, const ParamsT<double, N>& p) {
  const double omega_n = std::sqrt(p.rotor.stiffness / p.total_mass());
  std::string out = fmt::format("{} balls; omega = {} rad/s = {:.4f} omega_n (omega_n = {:.6g} rad/s), friction {}\n",
                                p.n_balls(), p.omega, p.omega / omega_n, omega_n, to_string(p.law));
  if (const std::string spec = describe_specification(p); !spec.empty())
    out += fmt::format("balls as specified (model.md §1.1): {}\n", spec);
  out += "eigenvalues in the rotating frame [1/s]\n";
  for (const auto& line : describe_degeneracy(a.equilibria.degeneracy)) out += fmt::format("degenerate: {}\n", line);
  const std::string set_line = balanced_set_comment(a);
  if (!set_line.empty()) out += set_line.substr(2);
  const auto points = a.equilibria.points();
  if (points.empty()) out += "no equilibria\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const auto& sp = a.spectra[i];
    std::string betas;
    for (int b = 0; b < e.n_balls(); ++b) betas += fmt::format("{}{:.12g}", b ? ", " : "", double(e.position(2 + b)));
    out += fmt::format("\n{:<11} q = ({:.9g}, {:.9g}) m, |q| = {:.6g} m, beta = ({}) rad\n", state_label(e),
                       double(e.position(0)), double(e.position(1)), q_abs(e), betas);
    out += fmt::format("{:<11} residual {:.2g}, {} Newton steps; {}{}, spectral abscissa {:.9g} 1/s, {} unstable\n", "",
                       e.residual, e.newton_iterations, e.on_balanced_set ? "normally " : "", to_string(sp.stability),
                       sp.abscissa, sp.n_unstable);
    out += fmt::format("{:<11} {:>24} {:>24} {:>10} {:>10}\n", "", "Re lambda [1/s]", "Im lambda [1/s]", "cond",
                       "error");
    for (std::size_t k = 0; k < std::size_t(sp.count); ++k) {
      if (sp.structural[k]) {
        out += fmt::format("{:<11} {:>24} {:>24} {:>10} {:>10}\n", "", "0", "0", "structural", "zero");
        continue;
      }
      out += fmt::format("{:<11} {:>24.15g} {:>24.15g} {:>10.3g} {:>10.2g}\n", "", sp.eigenvalues[k].real(),
                         sp.eigenvalues[k].imag(), sp.condition[k], sp.error[k]);
    }
    for (const auto& n : notes(e, sp)) out += fmt::format("{:<11} note: {}\n", "", n);
  }
  return out;
}

std::string equilibria_table(const Analysis& a, const Params& p) { return equilibria_table<Analysis, 2>(a, p); }
std::string equilibria_table(const AnalysisN& a, const ParamsN& p) { return equilibria_table<AnalysisN, any_balls>(a, p); }

std::string sweep_head(ParamRef param, std::size_t values, std::string_view header) {
  std::string out(header);
  out += fmt::format("# sweep of {} [{}] over {} values; step = index of the value\n", to_string(param),
                     unit(param.quantity), values);
  out += equilibrium_columns_doc();
  out += "#   q_abs = |q| [m]; n_unstable = eigenvalues right of their error band\n";
  return out;
}

std::string sweep_value_comments(ParamRef param, double value, const Analysis& a) {
  const std::string name = to_string(param);
  std::string out;
  for (const auto& line : describe_degeneracy(a.equilibria.degeneracy))
    out += fmt::format("# at {}={}: degenerate: {}\n", name, value, line);
  const auto points = a.equilibria.points();
  for (std::size_t k = 0; k < points.size(); ++k)
    for (const auto& n : notes(points[k], a.spectra[k]))
      out += fmt::format("# at {}={}: {}: {}\n", name, value, state_label(points[k]), n);
  return out;
}

std::string sweep_columns(ParamRef param) {
  return fmt::format("step,{},family,pattern,member,q1,q2{},q_abs,residual,spectral_abscissa,stable,n_unstable,"
                     "n_structural_zero{}\n",
                     to_string(param), beta_header(2), eigenvalue_header(Spectrum::capacity));
}

std::string sweep_row(std::size_t step, ParamRef param, double value, const Equilibrium& e, const Spectrum& sp) {
  return fmt::format("{},{},{},{},{},{},{}{},{},{},{},{},{},{}{}\n", step, num(value, to_string(param)),
                     to_string(e.family), pattern_of(e), e.member, num(double(e.position(0)), "q1"),
                     num(double(e.position(1)), "q2"), beta_cells(e), num(q_abs(e), "|q|"), num(e.residual, "residual"),
                     num(sp.abscissa, "spectral abscissa"), sp.stability == Stability::stable ? 1 : 0, sp.n_unstable,
                     sp.n_structural, eigenvalue_cells(sp));
}

std::string sweep_csv(const SweepResult& s, std::string_view header) {
  std::string out = sweep_head(s.param, s.values.size(), header);
  for (std::size_t i = 0; i < s.points.size(); ++i) out += sweep_value_comments(s.param, s.values[i], s.points[i]);
  out += sweep_columns(s.param);
  // By family and member, then value: each equilibrium's rows contiguous (a chart's line).
  for (auto family : {Family::balanced, Family::together, Family::opposite})
    for (int member = 1; member <= 2; ++member)
      for (std::size_t i = 0; i < s.points.size(); ++i) {
        const auto points = s.points[i].equilibria.points();
        for (std::size_t k = 0; k < points.size(); ++k)
          if (points[k].family == family && points[k].member == member)
            out += sweep_row(i, s.param, s.values[i], points[k], s.points[i].spectra[k]);
      }
  return out;
}

std::string sweep_head(const std::string& name, const std::string& unit, std::size_t values, std::string_view header) {
  std::string out(header);
  out += fmt::format("# sweep of {} [{}] over {} values; step = index of the value\n", name, unit, values);
  out += equilibrium_columns_doc();
  out += "#   q_abs = |q| [m]; n_unstable = eigenvalues right of their error band; columns of balls or eigenvalues a "
         "row does not have are empty\n";
  return out;
}

std::string sweep_value_comments(const std::string& name, double value, const AnalysisN& a) {
  std::string out;
  const std::string set_line = balanced_set_comment(a);
  if (!set_line.empty()) out += fmt::format("# at {}={}: {}", name, value, set_line.substr(2));
  for (const auto& line : describe_degeneracy(a.equilibria.degeneracy))
    out += fmt::format("# at {}={}: degenerate: {}\n", name, value, line);
  return out;
}

std::string sweep_columns(const std::string& name, int n_max) {
  return fmt::format("step,{},family,pattern,member,q1,q2{},q_abs,residual,spectral_abscissa,stable,n_unstable,"
                     "n_structural_zero{}\n",
                     name, beta_header(n_max), eigenvalue_header(2 * n_max + 4));
}

std::string sweep_value_rows(std::size_t step, const std::string& name, double value, const AnalysisN& a, int n_max) {
  std::string out;
  const auto points = a.equilibria.points();
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& e = points[k];
    const auto& sp = a.spectra[k];
    out += fmt::format("{},{},{},{},{},{},{}{}{}", step, num(value, name), to_string(e.family), pattern_of(e), e.member,
                       num(double(e.position(0)), "q1"), num(double(e.position(1)), "q2"), beta_cells(e),
                       std::string(std::size_t(n_max - e.n_balls()), ','));
    out += fmt::format(",{},{},{},{},{},{}{}{}\n", num(q_abs(e), "|q|"), num(e.residual, "residual"),
                       num(sp.abscissa, "spectral abscissa"), sp.stability == Stability::stable ? 1 : 0,
                       sp.n_unstable, sp.n_structural, eigenvalue_cells(sp),
                       std::string(std::size_t(2 * (2 * n_max + 4 - sp.count)), ','));
  }
  return out;
}

std::string sweep_csv(const SweepResultN& s, std::string_view header) {
  int n_max = 2;
  for (const auto& a : s.points)
    for (const auto& e : a.equilibria.points()) n_max = std::max(n_max, e.n_balls());
  std::string out = sweep_head(s.name, s.unit, s.values.size(), header);
  for (std::size_t i = 0; i < s.points.size(); ++i) out += sweep_value_comments(s.name, s.values[i], s.points[i]);
  out += sweep_columns(s.name, n_max);
  for (std::size_t i = 0; i < s.points.size(); ++i) out += sweep_value_rows(i, s.name, s.values[i], s.points[i], n_max);
  return out;
}

std::string sweep_summary_head(const std::string& name, const std::string& unit, std::string_view header) {
  std::string out(header);
  out += fmt::format("# per value of {} [{}]: balls = number of balls; capacity = sum m_i l_i [kg m] against U [kg m];\n"
                     "#   balanced_exists = the balanced set exists (polygon inequality, model.md §13.4); "
                     "balanced_samples, fraction_stable = its samples and the fraction normally stable;\n"
                     "#   normal_abscissa_max [1/s] = the least stable sample's normal spectral abscissa;\n"
                     "#   aligned = isolated equilibria with q != 0 (model.md §13.2), aligned_stable = how many are "
                     "stable;\n#   best_* = the stable state of least |q| [m] (empty: no stable state at this value)\n",
                     name, unit);
  out += fmt::format("step,{},balls,capacity,U,balanced_exists,balanced_samples,fraction_stable,normal_abscissa_max,aligned,"
                     "aligned_stable,best_family,best_pattern,best_q_abs\n",
                     name);
  return out;
}

std::string sweep_summary_row(std::size_t step, const std::string& name, double value, const AnalysisN& a) {
  const auto points = a.equilibria.points();
  const auto& info = a.equilibria.balanced_set;
  const SetStatistics st = set_statistics(a);
  int aligned = 0, aligned_stable = 0;
  const EquilibriumN* best = nullptr;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const bool stable = a.spectra[k].stability == Stability::stable;
    if (!points[k].on_balanced_set && points[k].family != Family::balanced) {
      ++aligned;
      aligned_stable += stable;
    }
    if (stable && (!best || q_abs(points[k]) < q_abs(*best))) best = &points[k];
  }
  const int n = points.empty() ? 0 : points.front().n_balls();
  std::string out = fmt::format("{},{},{},", step, num(value, name), n);
  out += fmt::format("{},{},{},{},{},{},{},{},", num(a.capacity, "capacity"), num(a.unbalance, "U"),
                     info.exists ? 1 : 0, info.samples,
                     st.samples ? num(double(st.stable) / st.samples, "fraction") : std::string(),
                     st.samples ? num(st.max_abscissa, "abscissa") : std::string(), aligned, aligned_stable);
  out += best ? fmt::format("{},{},{}\n", to_string(best->family), pattern_of(*best), num(q_abs(*best), "|q|"))
              : std::string(",,\n");
  return out;
}

std::string sweep_summary_csv(const SweepResultN& s, std::string_view header) {
  std::string out = sweep_summary_head(s.name, s.unit, header);
  for (std::size_t i = 0; i < s.points.size(); ++i) out += sweep_summary_row(i, s.name, s.values[i], s.points[i]);
  return out;
}

template <class A>
std::string analysis_warnings(const A& a, std::string_view where) {
  std::string out;
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    if (!e.converged)
      out += fmt::format("warning: {}: {}: Newton polish did not converge (residual {:.3g})\n", where, state_label(e),
                         e.residual);
    if (!a.spectra[i].converged)
      out += fmt::format("warning: {}: {}: eigenvalue refinement did not converge\n", where, state_label(e));
  }
  return out;
}

std::string analysis_warnings(const Analysis& a, std::string_view where) { return analysis_warnings<Analysis>(a, where); }
std::string analysis_warnings(const AnalysisN& a, std::string_view where) {
  return analysis_warnings<AnalysisN>(a, where);
}

// For the smooth coulomb and stribeck laws the dry-friction verdict comes first
// (report_stick_set.hpp, model.md §14.10).
std::string equilibria_report(const Analysis& a, const Params& p, SpeedUnit unit,
                              const std::vector<KappaSensitivity<2>>& kappa, const DryFrictionVerdict& dry) {
  return dry_first(dry, answer_lines(point_answer(a, p), unit, "") + "\n" + equilibria_table(a, p) +
                            modes_table(a, p, unit) + creep_lines(a, kappa, ""), "");
}
std::string equilibria_report(const AnalysisN& a, const ParamsN& p, SpeedUnit unit,
                              const std::vector<KappaSensitivity<any_balls>>& kappa, const DryFrictionVerdict& dry) {
  return dry_first(dry, answer_lines(point_answer(a, p), unit, "") + "\n" + equilibria_table(a, p) +
                            modes_table(a, p, unit) + creep_lines(a, kappa, ""), "");
}

}  // namespace abu
