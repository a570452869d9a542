// `equilibria` and `sweep --param omega` on a flexible-shaft scene (shaft_commands.hpp).
//
// Per equilibrium (model.md §18.8) the rightmost eigenvalues of the sparse pencil
// a v = lambda b v of (18.7.3) come from ARPACK shift-invert (linear/sparse_spectrum.hpp,
// §19): the k of largest real part in the band |Im lambda| <= band, with the rectangle of
// the complex plane the search has covered. The verdict says what that covers: an
// eigenvalue found with Re > 0 is unstable whatever the coverage; "stable" means every
// eigenvalue in the covered rectangle is listed and all have Re < 0, and the rectangle is
// printed with it (eigenvalues outside it, above the band, are not excluded).
#include "shaft_commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/io/io.hpp"
#include "abu/io/shaft_scene.hpp"
#include "abu/linear/sparse_spectrum.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/scan/scan.hpp"
#include "abu/scan/shaft_crossings.hpp"
#include "abu/scan/shaft_map.hpp"

namespace abu::cli {

namespace {

using cplx = std::complex<double>;

// One analysed equilibrium.
struct ShaftPoint {
  ShaftEquilibrium eq;
  SparseSpectrum spectrum;
  double q_abs = 0.0;           // |q| at the balancer node [m]
  double max_deflection = 0.0;  // max_k |u_k| over the nodes [m]
  int max_node = 0;
  double rightmost = -std::numeric_limits<double>::infinity();  // max Re of the non-structural eigenvalues
  std::vector<char> structural;  // per eigenpair: one of the eq's structural zeros
  std::string verdict;           // stable / unstable / undetermined
  std::string verdict_text;      // the sentence
  int merged = 0;                // copies of one eigenvalue from overlapping shifts, dropped
};

ShaftSystem system_of(const Scene& scene) {
  const ParamsN p = params_of<any_balls>(scene);
  try {
    return make_shaft_system(shaft_spec_of(scene), p);
  } catch (const std::invalid_argument& e) {
    // The scene reader checks the model's rules with file and line (shaft_scene.hpp); one it
    // missed is still bad input, named here.
    throw InputError(scene.file, 0, "shaft", e.what());
  }
}

double band_of(const ShaftSpectrumOptions& o, double omega) { return o.band > 0 ? o.band : 10.0 * omega; }

// The shift that found an eigenpair, for its nconv.
const ShiftRun* run_of(const SparseSpectrum& s, cplx shift) {
  for (const auto& r : s.shifts)
    if (r.shift == shift) return &r;
  return nullptr;
}

ShaftPoint analyse(const ShaftSystem& sys, const ShaftEquilibrium& e, const ShaftSpectrumOptions& o, bool vectors) {
  ShaftPoint pt;
  pt.eq = e;
  const Eigen::VectorXd& s = e.position;
  const int b = sys.balancer_dof();
  pt.q_abs = std::hypot(s[b], s[b + 1]);
  for (int k = 0; k < sys.nodes(); ++k) {
    const double d = std::hypot(s[4 * k], s[4 * k + 1]);
    if (d > pt.max_deflection) pt.max_deflection = d, pt.max_node = k;
  }
  pt.spectrum = shaft_rightmost(sys, e.state(), o.eigenvalues, o.band, vectors, &pt.merged);
  // The verdict's rule and the structural zeros set aside: scan/shaft_map.hpp (shared with `map`).
  ShaftVerdict v = shaft_verdict(pt.spectrum, e.structural_zeros);
  pt.structural = std::move(v.structural);
  pt.rightmost = v.abscissa;
  const SpectrumCoverage& c = pt.spectrum.coverage;
  const std::string cover =
      c.empty() ? std::string("nothing covered")
                : fmt::format("covered: every eigenvalue with {:.6g} <= Re <= {:.6g} and |Im| <= {:.6g} 1/s is listed "
                              "({})",
                              c.real_min, c.real_max, c.imag_max, c.how);
  pt.verdict = v.verdict;
  if (v.verdict == "unstable") {
    pt.verdict_text = fmt::format("unstable: an eigenvalue with Re = {:.6g} 1/s > 0 was found", pt.rightmost);
  } else if (v.verdict == "stable") {
    pt.verdict_text = fmt::format(
        "stable as far as covered: every listed eigenvalue has Re < 0 (rightmost {:.6g} 1/s){}; {}. Eigenvalues with "
        "|Im| above the band or Re above {:.6g} 1/s are not excluded",
        pt.rightmost, e.structural_zeros ? fmt::format(", {} structural zero(s) set aside", e.structural_zeros) : "",
        cover, c.real_max);
  } else {
    pt.verdict_text = fmt::format(
        "undetermined: {}; {}",
        pt.spectrum.status.ok() ? std::string_view("the covered region does not reach Re >= 0")
                                : pt.spectrum.status.reason,
        cover);
  }
  return pt;
}

std::vector<ShaftPoint> analyse_all(const ShaftSystem& sys, const ShaftEquilibriumSet& set,
                                    const ShaftSpectrumOptions& o, std::string& warnings) {
  std::vector<ShaftPoint> out;
  for (const auto& e : set.list) {
    throw_if_stopped("equilibria (shaft)");
    if (!e.status.ok())
      warnings += fmt::format("warning: omega={}: a {} equilibrium's polish: {} (residual {:.3g})\n",
                              sys.balancer.omega, to_string(e.family), e.status.reason, e.residual);
    out.push_back(analyse(sys, e, o, false));
    const ShaftPoint& pt = out.back();
    if (!pt.spectrum.status.ok())
      warnings += fmt::format("warning: omega={}: {} equilibrium: ARPACK: {} ({} eigenvalue(s) found)\n",
                              sys.balancer.omega, to_string(e.family), pt.spectrum.status.reason,
                              pt.spectrum.eigenpairs.size());
  }
  if (!set.status.ok())
    warnings += fmt::format("warning: omega={}: shaft equilibria: {}\n", sys.balancer.omega, set.status.reason);
  return out;
}

std::string pattern_text(const ShaftEquilibrium& e, int n) {
  if (e.family == Family::balanced) return "";
  std::string s;
  for (int i = 0; i < n; ++i) s += (e.pattern >> i) & 1u ? '-' : '+';
  return s;
}

std::string shaft_line(const ShaftSystem& sys) {
  const auto x = node_positions(sys.spec);
  return fmt::format("{} nodes ({} elements, length {:.9g} m), {} shaft dofs + {} balls: {} states; balancer at node "
                     "{} (x = {:.9g} m); shaft and discs {:.9g} kg",
                     sys.nodes(), sys.spec.elements.size(), x.back(), sys.shaft_dofs(), sys.n_balls(),
                     sys.state_size(), sys.spec.balancer_node, x[std::size_t(sys.spec.balancer_node)],
                     shaft_mass(sys.spec));
}

std::string spectrum_line(const SparseSpectrum& s) {
  int requested = 0, converged = 0;
  for (const auto& r : s.shifts) requested += r.requested, converged += r.converged;
  return fmt::format("{} eigenvalue(s); {} shift(s), nconv {} of {} asked, {} factorization(s); status {}{}",
                     s.eigenpairs.size(), s.shifts.size(), converged, requested, s.factorizations,
                     to_string(s.status.outcome), s.status.ok() ? "" : fmt::format(" ({})", s.status.reason));
}

std::string table(const ShaftSystem& sys, const std::vector<ShaftPoint>& pts, const std::string& file,
                  const ShaftSpectrumOptions& o) {
  const int n = sys.n_balls();
  std::string out = fmt::format("{}: flexible shaft (model.md §18): {}\n", file, shaft_line(sys));
  out += fmt::format("omega = {} rad/s, U = {} kg m; eigenvalues in the rotating frame [1/s], the {} rightmost with "
                     "|Im| <= {} 1/s (ARPACK shift-invert, model.md §19)\n",
                     sys.balancer.omega, sys.balancer.rotor.unbalance, o.eigenvalues, band_of(o, sys.balancer.omega));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ShaftPoint& pt = pts[i];
    const ShaftEquilibrium& e = pt.eq;
    std::string beta;
    for (int b = 0; b < n; ++b) beta += fmt::format("{}{:.9g}", b ? ", " : "", e.position[sys.ball_dof(b)]);
    out += fmt::format("\nequilibrium {}: {}{}{} member {}: {} (residual {:.3g}, {} Newton iterations)\n", i + 1,
                       to_string(e.family), e.family == Family::balanced ? "" : " ", pattern_text(e, n), e.member,
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

std::string header_lines(const Scene& scene, const ShaftSystem& sys) {
  return fmt::format("# stability-scan {} (abu-stability)\n# command: {}\n# scene: {}\n# parameters (SI): {} (k, c, "
                     "M_r unused: the shaft's bearings and discs replace them)\n# shaft (model.md §18): {}\n",
                     ABU_VERSION, escaped(command_line()), escaped(scene.file), describe_parameters(sys.balancer),
                     shaft_line(sys));
}

std::string csv(const Scene& scene, const ShaftSystem& sys, const std::vector<ShaftPoint>& pts,
                const ShaftSpectrumOptions& o) {
  const int n = sys.n_balls();
  std::string out = header_lines(scene, sys);
  out += fmt::format("# eigenvalues: rotating frame [1/s]; the {} rightmost with |Im| <= {} 1/s per equilibrium "
                     "(ARPACK shift-invert); q_abs, max_deflection [m], beta [rad]\n",
                     o.eigenvalues, band_of(o, sys.balancer.omega));
  out += "equilibrium,family,pattern,member,status,residual,q_abs,max_deflection,max_deflection_node";
  for (int b = 0; b < n; ++b) out += fmt::format(",beta{}", b + 1);
  out += ",verdict,spectrum_status,coverage_real_min,coverage_real_max,coverage_imag_max,rank,re,im,residual_eig,"
         "backward_error,shift_im,nconv,requested,covered,structural\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ShaftPoint& pt = pts[i];
    const ShaftEquilibrium& e = pt.eq;
    std::string front = fmt::format("{},{},{},{},{},{},{},{},{}", i + 1, to_string(e.family), pattern_text(e, n),
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

std::string json(const Scene& scene, const ShaftSystem& sys, const std::vector<ShaftPoint>& pts,
                 const ShaftSpectrumOptions& o) {
  const int n = sys.n_balls();
  const auto x = node_positions(sys.spec);
  std::string out = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                                ABU_VERSION, json_string(command_line()), json_string(scene.file));
  out += fmt::format("  \"parameters\": {},\n  \"balls\": {},\n  \"frame\": \"rotating\",\n", json_string(describe_parameters(sys.balancer)), n);
  out += fmt::format("  \"units\": {},\n", json_string("q_abs, max_deflection [m], beta [rad], eigenvalues and coverage "
                                                       "[1/s] (rotating frame), residuals dimensionless"));
  out += fmt::format("  \"shaft\": {{\"nodes\": {}, \"elements\": {}, \"length\": {}, \"shaft_dofs\": {}, \"states\": "
                     "{}, \"balancer_node\": {}, \"mass\": {}}},\n",
                     sys.nodes(), sys.spec.elements.size(), format_number(x.back()), sys.shaft_dofs(), sys.state_size(),
                     sys.spec.balancer_node, format_number(shaft_mass(sys.spec)));
  out += fmt::format("  \"spectrum_request\": {{\"eigenvalues\": {}, \"band\": {}, \"method\": \"ARPACK shift-invert, "
                     "rightmost in the band (model.md §19)\"}},\n",
                     o.eigenvalues, format_number(band_of(o, sys.balancer.omega)));
  out += "  \"equilibria\": [";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ShaftPoint& pt = pts[i];
    const ShaftEquilibrium& e = pt.eq;
    out += i ? ",\n    {" : "\n    {";
    out += fmt::format("\"family\": \"{}\", \"pattern\": \"{}\", \"member\": {}, \"status\": \"{}\", \"residual\": {}, "
                       "\"q_abs\": {}, \"max_deflection\": {}, \"max_deflection_node\": {}, \"beta\": [",
                       to_string(e.family), pattern_text(e, n), e.member, to_string(e.status.outcome),
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

// The circular split of a mode (model.md (16.2.1)) over the shaft's nodes (translations and
// tilts, weighted by the diagonal of A) and the balls (absolute displacement
// dq + l_i (-sin beta_i, cos beta_i) dbeta_i, mass m_i): the forward share f+.
double forward_share(const ShaftSystem& sys, const Eigen::SparseMatrix<double>& mass, const Eigen::VectorXd& s,
                     const Eigen::VectorXcd& v) {
  double fwd = 0.0, all = 0.0;
  auto add = [&](double m, cplx a1, cplx a2) {
    const cplx wp = (a1 + cplx(0, 1) * a2) / 2.0;
    const cplx wm = (std::conj(a1) + cplx(0, 1) * std::conj(a2)) / 2.0;
    fwd += m * std::norm(wp);
    all += m * (std::norm(wp) + std::norm(wm));
  };
  // Translations and tilts of every node: both pairs turn with the frame (model.md §18.5), and
  // the diagonal of A weighs them by their kinetic energy (kg for u, kg m^2 for psi).
  for (int k = 0; k < sys.nodes(); ++k) {
    add(mass.coeff(4 * k, 4 * k), v[4 * k], v[4 * k + 1]);
    add(mass.coeff(4 * k + 2, 4 * k + 2), v[4 * k + 2], v[4 * k + 3]);
  }
  const int b = sys.balancer_dof();
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = sys.balancer.balls[std::size_t(i)];
    const double beta = s[sys.ball_dof(i)];
    const cplx db = v[sys.ball_dof(i)];
    add(ball.mass, v[b] - ball.race_radius * std::sin(beta) * db, v[b + 1] + ball.race_radius * std::cos(beta) * db);
  }
  return all > 0 ? fwd / all : 0.5;
}

}  // namespace

void add_shaft_spectrum_options(CLI::App& sub, ShaftSpectrumOptions& o) {
  sub.add_option("--eigenvalues", o.eigenvalues,
                 "Flexible shaft ([shaft]): the number of rightmost eigenvalues per equilibrium (ARPACK, model.md §19)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub.add_option("--band", o.band,
                 "Flexible shaft: search the rightmost eigenvalues in |Im lambda| <= BAND [1/s, rotating frame]; 0: "
                 "10 omega")
      ->check(CLI::Range(0.0, 1e12))
      ->capture_default_str();
}

std::string shaft_equilibria(const Scene& scene, const std::string& format, const BalancedSampling& sampling,
                             const ShaftSpectrumOptions& spectrum, std::string& warnings) {
  const ShaftSystem sys = system_of(scene);
  const ShaftEquilibriumSet set = find_shaft_equilibria(sys, sampling);
  const std::vector<ShaftPoint> pts = analyse_all(sys, set, spectrum, warnings);
  for (const auto& pt : pts)
    if (pt.spectrum.eigenpairs.empty())
      throw NumericalError(fmt::format("omega={}: ARPACK found no eigenvalue of a {} equilibrium: {}",
                                       sys.balancer.omega, to_string(pt.eq.family), pt.spectrum.status.reason));
  if (format == "csv") return csv(scene, sys, pts, spectrum);
  if (format == "json") return json(scene, sys, pts, spectrum);
  return table(sys, pts, scene.file, spectrum);
}

int shaft_campbell_sweep(const Scene& scene, const SceneOptions& options, double from, double to, int steps,
                         bool logarithmic, const ShaftSpectrumOptions& spectrum, bool chart,
                         const std::string& output_dir) {
  const std::vector<double> values = grid_values(from, to, steps, logarithmic);
  std::vector<Scene> scenes;
  for (double v : values) {  // every value checked before any work
    Scene s = scene;
    set_checked(s, {Quantity::omega, -1}, v, "--from/--to");
    scenes.push_back(std::move(s));
  }
  const SpeedUnit unit = options.speed_unit();
  std::string rows;
  std::size_t count = 0;
  const ShaftSystem first = system_of(scenes.front());
  std::string head = header_lines(scene, first);
  head += fmt::format("# Campbell diagram of the flexible shaft (model.md §16.1, §18): per speed the balanced state "
                      "(else the aligned state of least |q|), its {} rightmost eigenvalues with |Im| <= {} "
                      "(rotating frame, ARPACK); whirl = the signed fixed-frame frequency Omega = omega + Im lambda "
                      "(forward share f+ >= 1/2) or omega - Im lambda (model.md (16.2.1)), > 0 forward, < 0 backward, "
                      "[rad/s]; zeta = -Re lambda / |Re lambda + i Omega| (16.4.1)\n",
                      spectrum.eigenvalues, spectrum.band > 0 ? fmt::format("{} 1/s", spectrum.band) : "10 omega");
  head += "omega,family,q_abs,rank,re,im,whirl,direction,forward_share,zeta,residual,covered,spectrum_status,verdict\n";
  // Per speed: the chosen state's spectral abscissa, its eigenvalue and configuration, for the
  // stability changes of the balanced state (model.md §18.14) located after the sweep.
  struct Abscissa {
    bool balanced = false;
    double re = 0.0;
    cplx value;
    Eigen::VectorXd position;
  };
  std::vector<Abscissa> abscissas(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    throw_if_stopped("sweep (shaft)");
    const ShaftSystem sys = system_of(scenes[i]);
    const ShaftEquilibriumSet set = find_shaft_equilibria(sys);
    if (set.list.empty())
      throw NumericalError(fmt::format("omega={}: no equilibrium of the shaft: {}", values[i], set.status.reason));
    // The design state: balanced where it exists, else the aligned one of least |q|.
    const ShaftEquilibrium* chosen = nullptr;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& e : set.list) {
      const double q = std::hypot(e.position[sys.balancer_dof()], e.position[sys.balancer_dof() + 1]);
      const double key = e.family == Family::balanced ? -1.0 : q;
      if (key < best) best = key, chosen = &e;
    }
    const ShaftPoint pt = analyse(sys, *chosen, spectrum, true);
    if (pt.spectrum.eigenpairs.empty())
      throw NumericalError(fmt::format("omega={}: ARPACK found no eigenvalue: {}", values[i], pt.spectrum.status.reason));
    if (!pt.spectrum.status.ok())
      fmt::print(stderr, "stability-scan: warning: omega={}: ARPACK: {}\n", values[i], pt.spectrum.status.reason);
    abscissas[i].balanced = chosen->family == Family::balanced && std::isfinite(pt.rightmost);
    abscissas[i].re = pt.rightmost;
    abscissas[i].position = chosen->position;
    for (std::size_t k = 0; k < pt.spectrum.eigenpairs.size(); ++k)
      if (!pt.structural[k] && pt.spectrum.eigenpairs[k].value.real() == pt.rightmost) {
        abscissas[i].value = pt.spectrum.eigenpairs[k].value;
        break;
      }
    const ShaftLinearization lin = linearize_shaft(sys, chosen->state());
    for (std::size_t k = 0; k < pt.spectrum.eigenpairs.size(); ++k) {
      const auto& ep = pt.spectrum.eigenpairs[k];
      if (ep.value.imag() < 0 || pt.structural[k]) continue;  // one of each conjugate pair; no structural zero
      const double f = forward_share(sys, lin.mass, chosen->position, ep.vector.head(sys.configuration_size()));
      const double omega = values[i];
      const double whirl = f >= 0.5 ? omega + ep.value.imag() : omega - ep.value.imag();
      const double zeta = -ep.value.real() / std::abs(cplx(ep.value.real(), whirl));
      rows += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", format_number(omega), to_string(chosen->family),
                          format_number(pt.q_abs), k + 1, format_number(ep.value.real()),
                          format_number(ep.value.imag()), format_number(whirl),
                          whirl > 0 ? "forward" : whirl < 0 ? "backward" : "none", format_number(f),
                          format_number(zeta), format_number(ep.residual), ep.covered ? 1 : 0,
                          to_string(pt.spectrum.status.outcome), pt.verdict);
      ++count;
    }
  }
  // Where the balanced state loses or regains stability: between speeds whose spectral
  // abscissas have opposite signs, the crossing eigenvalue tracked and Re lambda = 0 solved.
  const auto system_at = [&scene](double omega) {
    Scene s = scene;
    set_checked(s, {Quantity::omega, -1}, omega, "--from/--to");
    return system_of(s);
  };
  std::string crossings = header_lines(scene, first);
  crossings += "# Stability changes of the balanced state along omega (model.md §18.14): between two speeds of the "
               "sweep (bracket_lo, bracket_hi) whose spectral abscissas have opposite signs, the crossing eigenvalue "
               "tracked by ARPACK shift-invert and Re lambda(omega) = 0 solved by Brent to 1e-12 relative. change = "
               "loses / regains (with increasing omega); im = Im lambda there [1/s, rotating frame]; whirl = the "
               "signed fixed-frame frequency omega +- Im lambda by the forward share (model.md (16.2.1)) [rad/s]; "
               "slope = d Re lambda / d omega over the bracket; status not_converged: the numbers are empty and the "
               "stderr line says why\n";
  crossings += "bracket_lo,bracket_hi,omega,change,re,im,whirl,direction,forward_share,slope,residual,evaluations,status\n";
  std::size_t n_crossings = 0;
  for (std::size_t i = 0; i + 1 < values.size(); ++i) {
    const Abscissa &a = abscissas[i], &b = abscissas[i + 1];
    if (!a.balanced || !b.balanced || !((a.re > 0) != (b.re > 0))) continue;
    throw_if_stopped("sweep (shaft): crossings");
    const bool from_a = a.re > 0;  // track the eigenvalue with Re > 0: it is the one that crosses
    const Abscissa& u = from_a ? a : b;
    const double w_u = values[from_a ? i : i + 1], w_s = values[from_a ? i + 1 : i];
    const ShaftCrossing c = refine_shaft_crossing(system_at, u.position, w_u, u.value, w_s);
    ++n_crossings;
    const double lo = std::min(w_u, w_s), hi = std::max(w_u, w_s);
    if (!c.status.ok()) {
      fmt::print(stderr, "stability-scan: warning: a stability change of the balanced state in omega = [{}, {}] rad/s "
                         "not located: {}\n", lo, hi, c.status.reason);
      crossings += fmt::format("{},{},,,,,,,,,,{},{}\n", format_number(lo), format_number(hi), c.evaluations,
                               to_string(c.status.outcome));
      continue;
    }
    const ShaftSystem sys = system_at(c.omega);
    const ShaftLinearization lin = linearize_shaft(sys, c.state);
    const double f = forward_share(sys, lin.mass, c.state.head(sys.configuration_size()),
                                   c.vector.head(sys.configuration_size()));
    const double whirl = f >= 0.5 ? c.omega + c.value.imag() : c.omega - c.value.imag();
    crossings += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", format_number(lo), format_number(hi),
                             format_number(c.omega), c.loses ? "loses" : "regains", format_number(c.value.real()),
                             format_number(c.value.imag()), format_number(whirl),
                             whirl > 0 ? "forward" : whirl < 0 ? "backward" : "none", format_number(f),
                             format_number(c.slope), format_number(c.residual), c.evaluations,
                             to_string(c.status.outcome));
    fmt::print(stderr, "balanced state {} stability at omega = {:.12g} rad/s: Im lambda = {:.9g} 1/s (rotating frame), "
                       "whirl {:.9g} rad/s (fixed frame, {})\n", c.loses ? "loses" : "regains", c.omega,
               c.value.imag(), whirl, whirl > 0 ? "forward" : whirl < 0 ? "backward" : "none");
  }
  const std::filesystem::path dir(output_dir);
  const auto crossings_path = dir / "crossings_shaft_omega.csv";
  const auto csv_path = dir / "campbell_shaft_omega.csv";
  const auto png_path = dir / "campbell_shaft_omega.png";
  OutputTransaction out;
  const auto staged = out.stage(csv_path, head + rows);
  out.stage(crossings_path, crossings);
  if (chart)
    run_gnuplot(plots_dir() / "campbell_shaft.gp",
                {{"csv", staged.string()},
                 {"png", out.reserve(png_path).string()},
                 {"unit", std::string(to_string(unit))},
                 {"scale", format_number(from_rad_per_s(1.0, unit))},
                 {"title", fmt::format("{}: Campbell diagram of the flexible shaft (fixed frame)", scene.file)}});
  out.commit();
  fmt::print(stderr, "wrote {} ({} rows){}, {} ({} stability change(s))\n", csv_path.string(), count,
             chart ? fmt::format(" and {}", png_path.string()) : std::string(), crossings_path.string(), n_crossings);
  return exit_ok;
}

}  // namespace abu::cli
