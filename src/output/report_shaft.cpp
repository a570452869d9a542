// The reports of a flexible shaft's states (report_shaft.hpp).
#include "abu/output/report_shaft.hpp"

#include <fmt/format.h>

#include "abu/input/shaft_scene.hpp"
#include "abu/output/format.hpp"
#include "abu/output/provenance.hpp"

namespace abu {

namespace {

using cplx = std::complex<double>;

// The shift that found an eigenpair, for its nconv.
const ShiftRun* run_of(const SparseSpectrum& s, cplx shift) {
  for (const auto& r : s.shifts)
    if (r.shift == shift) return &r;
  return nullptr;
}

std::string pattern_text(const ShaftEquilibrium& e, int n) {
  if (e.family == Family::balanced || e.on_unround_race) return "";
  std::string s;
  for (int i = 0; i < n; ++i) s += (e.pattern >> i) & 1u ? '-' : '+';
  return s;
}

// "race" for an equilibrium of an unround race (model.md §18.18: member = its place by |q|).
std::string_view family_text(const ShaftEquilibrium& e) { return e.on_unround_race ? "race" : to_string(e.family); }

std::string spectrum_line(const SparseSpectrum& s) {
  int requested = 0, converged = 0;
  for (const auto& r : s.shifts) requested += r.requested, converged += r.converged;
  return fmt::format("{} eigenvalue(s); {} shift(s), nconv {} of {} asked, {} factorization(s); status {}{}",
                     s.eigenpairs.size(), s.shifts.size(), converged, requested, s.factorizations,
                     to_string(s.status.outcome), s.status.ok() ? "" : fmt::format(" ({})", s.status.reason));
}

}  // namespace

std::string shaft_line(const ShaftSystem& sys) {
  const auto x = node_positions(sys.spec);
  return fmt::format("{} nodes ({} elements, length {:.9g} m), {} shaft dofs + {} balls: {} states; balancer at node "
                     "{} (x = {:.9g} m); shaft and discs {:.9g} kg",
                     sys.nodes(), sys.spec.elements.size(), x.back(), sys.shaft_dofs(), sys.n_balls(),
                     sys.state_size(), sys.spec.balancer_node, x[std::size_t(sys.spec.balancer_node)],
                     shaft_mass(sys.spec));
}

std::string shaft_states_table(const ShaftStates& st, std::string_view file) {
  const ShaftSystem& sys = st.system;
  const std::vector<ShaftState>& pts = st.states;
  const ShaftSpectrumOptions& o = st.spectrum;
  const int n = sys.n_balls();
  std::string out = fmt::format("{}: flexible shaft (model.md §18): {}\n", file, shaft_line(sys));
  out += fmt::format("omega = {} rad/s, U = {} kg m; eigenvalues in the rotating frame [1/s], the {} rightmost with "
                     "|Im| <= {} 1/s (ARPACK shift-invert, model.md §19)\n",
                     sys.balancer.omega, sys.balancer.rotor.unbalance, o.eigenvalues, shaft_band(o, sys.balancer.omega));
  if (st.race)
    out += "the balls roll on an unround race (model.md §18.18): its equilibria, by |q| of the race on the equivalent "
           "rigid balancer\n" + describe_race(*st.race, "  ");
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ShaftState& pt = pts[i];
    const ShaftEquilibrium& e = pt.eq;
    std::string beta;
    for (int b = 0; b < n; ++b) beta += fmt::format("{}{:.9g}", b ? ", " : "", e.position[sys.ball_dof(b)]);
    out += fmt::format("\nequilibrium {}: {}{}{} member {}: {} (residual {:.3g}, {} Newton iterations)\n", i + 1,
                       family_text(e), pattern_text(e, n).empty() ? "" : " ", pattern_text(e, n), e.member,
                       to_string(e.status.outcome), e.residual, e.newton_iterations);
    out += fmt::format("  balancer node |q| = {:.6g} m; beta = ({}) rad; largest shaft deflection {:.6g} m at node {}\n",
                       pt.q_abs, beta, pt.max_deflection, pt.max_node);
    out += fmt::format("  spectrum: {}{}\n", spectrum_line(pt.spectrum),
                       pt.merged ? fmt::format("; {} copies found by a second shift merged", pt.merged) : "");
    out += "     #            Re [1/s]            Im [1/s]   residual   nconv  covered\n";
    for (std::size_t k = 0; k < pt.spectrum.eigenpairs.size(); ++k) {
      const auto& ep = pt.spectrum.eigenpairs[k];
      const ShiftRun* r = run_of(pt.spectrum, ep.shift);
      out += fmt::format("  {:4d} {:19.12g} {:19.12g} {:10.3g} {:4d}/{:<3d} {}{}\n", k + 1, ep.value.real(),
                         ep.value.imag(), ep.residual, r ? r->converged : 0, r ? r->requested : 0,
                         ep.covered ? "yes" : "no", pt.structural[k] ? "  (structural zero)" : "");
    }
    out += fmt::format("  verdict: {}\n", pt.verdict_text);
  }
  return out;
}

std::string shaft_header_lines(std::string_view command_line, std::string_view scene_file, const ShaftSystem& sys) {
  return fmt::format("# stability-scan {} (abu-stability)\n# command: {}\n# scene: {}\n# parameters (SI): {} (k, c, "
                     "M_r unused: the shaft's bearings and discs replace them)\n# shaft (model.md §18): {}\n",
                     ABU_VERSION, escaped(command_line), escaped(scene_file), describe_parameters(sys.balancer),
                     shaft_line(sys));
}

std::string shaft_states_csv(const ShaftStates& st, std::string_view command_line, std::string_view scene_file) {
  const ShaftSystem& sys = st.system;
  const std::vector<ShaftState>& pts = st.states;
  const ShaftSpectrumOptions& o = st.spectrum;
  const int n = sys.n_balls();
  std::string out = shaft_header_lines(command_line, scene_file, sys);
  if (st.race) out += describe_race(*st.race, "# ");  // family "race": its equilibria (model.md §18.18)
  out += fmt::format("# eigenvalues: rotating frame [1/s]; the {} rightmost with |Im| <= {} 1/s per equilibrium "
                     "(ARPACK shift-invert); q_abs, max_deflection [m], beta [rad]\n",
                     o.eigenvalues, shaft_band(o, sys.balancer.omega));
  out += "equilibrium,family,pattern,member,status,residual,q_abs,max_deflection,max_deflection_node";
  for (int b = 0; b < n; ++b) out += fmt::format(",beta{}", b + 1);
  out += ",verdict,spectrum_status,coverage_real_min,coverage_real_max,coverage_imag_max,rank,re,im,residual_eig,"
         "backward_error,shift_im,nconv,requested,covered,structural\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ShaftState& pt = pts[i];
    const ShaftEquilibrium& e = pt.eq;
    std::string front = fmt::format("{},{},{},{},{},{},{},{},{}", i + 1, family_text(e), pattern_text(e, n),
                                    e.member, to_string(e.status.outcome), format_number(e.residual, "residual"),
                                    format_number(pt.q_abs, "|q|"), format_number(pt.max_deflection, "deflection"),
                                    pt.max_node);
    for (int b = 0; b < n; ++b) front += fmt::format(",{}", format_number(e.position[sys.ball_dof(b)], "beta"));
    const SpectrumCoverage& c = pt.spectrum.coverage;
    front += fmt::format(",{},{},{},{},{}", pt.verdict, to_string(pt.spectrum.status.outcome),
                         c.empty() ? "" : format_number(c.real_min), c.empty() ? "" : format_number(c.real_max),
                         c.empty() ? "" : format_number(c.imag_max));
    if (pt.spectrum.eigenpairs.empty()) out += front + ",,,,,,,,,,\n";
    for (std::size_t k = 0; k < pt.spectrum.eigenpairs.size(); ++k) {
      const auto& ep = pt.spectrum.eigenpairs[k];
      const ShiftRun* r = run_of(pt.spectrum, ep.shift);
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", front, k + 1, format_number(ep.value.real(), "eigenvalue"),
                         format_number(ep.value.imag(), "eigenvalue"), format_number(ep.residual, "residual"),
                         format_number(ep.backward_error, "backward error"), format_number(ep.shift.imag(), "shift"),
                         r ? r->converged : 0, r ? r->requested : 0, ep.covered ? 1 : 0, int(pt.structural[k]));
    }
  }
  return out;
}

std::string shaft_states_json(const ShaftStates& st, std::string_view command_line, std::string_view scene_file) {
  const ShaftSystem& sys = st.system;
  const std::vector<ShaftState>& pts = st.states;
  const ShaftSpectrumOptions& o = st.spectrum;
  const int n = sys.n_balls();
  const auto x = node_positions(sys.spec);
  std::string out = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                                ABU_VERSION, json_string(command_line), json_string(scene_file));
  out += fmt::format("  \"parameters\": {},\n  \"balls\": {},\n  \"frame\": \"rotating\",\n", json_string(describe_parameters(sys.balancer)), n);
  out += fmt::format("  \"units\": {},\n", json_string("q_abs, max_deflection [m], beta [rad], eigenvalues and coverage "
                                                       "[1/s] (rotating frame), residuals dimensionless"));
  out += fmt::format("  \"shaft\": {{\"nodes\": {}, \"elements\": {}, \"length\": {}, \"shaft_dofs\": {}, \"states\": "
                     "{}, \"balancer_node\": {}, \"mass\": {}}},\n",
                     sys.nodes(), sys.spec.elements.size(), format_number(x.back()), sys.shaft_dofs(), sys.state_size(),
                     sys.spec.balancer_node, format_number(shaft_mass(sys.spec)));
  out += fmt::format("  \"spectrum_request\": {{\"eigenvalues\": {}, \"band\": {}, \"method\": \"ARPACK shift-invert, "
                     "rightmost in the band (model.md §19)\"}},\n",
                     o.eigenvalues, format_number(shaft_band(o, sys.balancer.omega)));
  if (st.race) out += fmt::format("  \"race\": {},\n", json_string(describe_race(*st.race, "")));
  out += "  \"equilibria\": [";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ShaftState& pt = pts[i];
    const ShaftEquilibrium& e = pt.eq;
    out += i ? ",\n    {" : "\n    {";
    out += fmt::format("\"family\": \"{}\", \"pattern\": \"{}\", \"member\": {}, \"status\": \"{}\", \"residual\": {}, "
                       "\"q_abs\": {}, \"max_deflection\": {}, \"max_deflection_node\": {}, \"beta\": [",
                       family_text(e), pattern_text(e, n), e.member, to_string(e.status.outcome),
                       format_number(e.residual), format_number(pt.q_abs), format_number(pt.max_deflection),
                       pt.max_node);
    for (int b = 0; b < n; ++b) out += fmt::format("{}{}", b ? ", " : "", format_number(e.position[sys.ball_dof(b)]));
    const SparseSpectrum& s = pt.spectrum;
    const SpectrumCoverage& c = s.coverage;
    out += fmt::format("],\n     \"verdict\": \"{}\", \"verdict_text\": {},\n", pt.verdict, json_string(pt.verdict_text));
    out += fmt::format("     \"spectrum\": {{\"status\": \"{}\", \"reason\": {}, \"factorizations\": {}, "
                       "\"merged_copies\": {}, \"coverage\": ",
                       to_string(s.status.outcome), json_string(s.status.reason), s.factorizations, pt.merged);
    out += c.empty() ? std::string("null")
                     : fmt::format("{{\"real_min\": {}, \"real_max\": {}, \"imag_max\": {}, \"how\": {}}}",
                                   format_number(c.real_min), format_number(c.real_max), format_number(c.imag_max),
                                   json_string(c.how));
    out += ",\n      \"shifts\": [";
    for (std::size_t k = 0; k < s.shifts.size(); ++k) {
      const auto& r = s.shifts[k];
      out += fmt::format("{}{{\"re\": {}, \"im\": {}, \"requested\": {}, \"nconv\": {}, \"iterations\": {}, \"radius\": "
                         "{}, \"status\": \"{}\"}}",
                         k ? ", " : "", format_number(r.shift.real()), format_number(r.shift.imag()), r.requested,
                         r.converged, r.iterations, format_number(r.radius), to_string(r.status.outcome));
    }
    out += "],\n      \"eigenvalues\": [";
    for (std::size_t k = 0; k < s.eigenpairs.size(); ++k) {
      const auto& ep = s.eigenpairs[k];
      const ShiftRun* r = run_of(s, ep.shift);
      out += fmt::format("{}{{\"re\": {}, \"im\": {}, \"residual\": {}, \"backward_error\": {}, \"shift_im\": {}, "
                         "\"nconv\": {}, \"covered\": {}, \"structural\": {}}}",
                         k ? ",\n        " : "\n        ", format_number(ep.value.real()), format_number(ep.value.imag()),
                         format_number(ep.residual), format_number(ep.backward_error), format_number(ep.shift.imag()),
                         r ? r->converged : 0, ep.covered, bool(pt.structural[k]));
    }
    out += "]}}";
  }
  out += "\n  ]\n}\n";
  return out;
}

}  // namespace abu
