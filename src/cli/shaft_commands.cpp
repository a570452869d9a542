// `sweep --param omega` on a flexible-shaft scene (shaft_commands.hpp); its states and their
// spectra are analysis/shaft_states.hpp's.
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
#include "abu/analysis/shaft_race_sweep.hpp"
#include "abu/analysis/shaft_states.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/report_shaft.hpp"
#include "abu/output/report_shaft_race_sweep.hpp"
#include "abu/output/format.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/input/shaft_scene.hpp"
#include "abu/linear/sparse_spectrum.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/scan/scan.hpp"
#include "abu/scan/shaft_crossings.hpp"
#include "abu/scan/shaft_map.hpp"
#include "unround_commands.hpp"

namespace abu::cli {

namespace {
using cplx = std::complex<double>;
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
  const ShaftSystem first = shaft_system_of(scenes.front());
  std::string head = shaft_header_lines(command_line(), scene.file, first);
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
    const ShaftSystem sys = shaft_system_of(scenes[i]);
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
    const ShaftState pt = analyze_shaft_state(sys, *chosen, spectrum, true);
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
      const double f = shaft_forward_share(sys, lin.mass, chosen->position, ep.vector.head(sys.configuration_size()));
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
    return shaft_system_of(s);
  };
  std::string crossings = shaft_header_lines(command_line(), scene.file, first);
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
    const double f = shaft_forward_share(sys, lin.mass, c.state.head(sys.configuration_size()),
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

int sweep_shaft_race(const Scene& scene, const SceneOptions& options, const UnroundGrid& g,
                     const ShaftSpectrumOptions& spectrum) {
  // k, c and M_r are refused by set_checked: a shaft scene has none (model.md §18.10).
  const UnroundValues grid = unround_values(scene, g);
  const ShaftRaceSweep sweep = sweep_shaft_race(grid.scenes, grid.races, grid.values, spectrum);
  for (const auto& pt : sweep.points)
    if (!pt.warnings.empty()) fmt::print(stderr, "at {}={}:\n{}", grid.name, pt.value, pt.warnings);
  const ShaftSystem first = shaft_system_of(grid.scenes.front());
  const std::string header = shaft_header_lines(command_line(), scene.file, first) + describe_race(grid.races.front(), "# ");
  const auto [csv_path, summary_path, png_path] = sweep_paths(g.output_dir, grid.name);
  OutputTransaction out;
  const auto staged_all = out.stage(csv_path, shaft_race_sweep_csv(sweep, grid.name, grid.unit, header));
  const auto staged_summary =
      out.stage(summary_path, shaft_race_sweep_summary_csv(sweep, grid.name, grid.unit, header));
  if (g.chart)
    run_gnuplot(plots_dir() / "unround_sweep.gp",
                {{"csv", staged_all.string()},
                 {"summary", staged_summary.string()},
                 {"png", out.reserve(png_path).string()},
                 {"param", grid.name},
                 {"unit", grid.unit},
                 {"logx", g.logarithmic ? "1" : "0"},
                 {"first_order", "0"},
                 {"bare", "balls held at the balancer node"},
                 {"open", "unstable or undetermined equilibrium"},
                 {"title", fmt::format("{}: unround race on a flexible shaft, sweep of {}", scene.file, grid.name)},
                 {"subtitle", chart_subtitle(scene, options.overrides,
                                              {{grid.name, grid.values.front(), grid.values.back(), grid.unit}})}});
  out.commit();
  std::size_t rows = 0;
  for (const auto& pt : sweep.points) rows += pt.states.size();
  fmt::print(stderr, "wrote {} ({} rows) and {}{}\n", csv_path.string(), rows, summary_path.string(),
             g.chart ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}

}  // namespace abu::cli
