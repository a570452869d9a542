// `stability-scan equilibria SCENE`: every equilibrium of one parameter point with its
// spectrum, as a table, CSV or JSON.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string_view>
#include <vector>

#include "cli.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/io/io.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/io/report.hpp"
#include "abu/io/report_floquet.hpp"
#include "abu/io/report_forced_orbits.hpp"
#include "abu/io/report_lugre.hpp"
#include "abu/io/report_stick_set.hpp"
#include "abu/io/report_unround.hpp"
#include "abu/io/report_views.hpp"
#include "abu/scan/scan.hpp"
#include "commands.hpp"
#include "shaft_commands.hpp"
#include "stick_options.hpp"

namespace abu::cli {

namespace {
struct EquilibriaOptions {
  SceneOptions scene;
  std::string format = "table";
  std::string output;
  BalancedSampling sampling;
  bool chart = true;  // no chart to draw: --no-chart is accepted like everywhere
  std::string mode_shapes;  // --mode-shapes DIR
  std::string at_balls;     // --at-balls b1,..,bn: a LuGre stuck state [rad]
  std::string stick_dir;    // --stick-set DIR (coulomb-set scenes)
  StickSetOptions stick;
  bool periodic_orbits = true;  // anisotropic support: the other states' orbits (model.md §10.14)
  ShaftSpectrumOptions shaft;   // a flexible shaft: the rightmost eigenvalues (model.md §18, §19)
};

// --at-balls "b1,b2,..": one finite angle [rad] per ball.
std::vector<double> parse_ball_angles(const std::string& text, int n) {
  std::vector<double> out = parse_real_list(text, "--at-balls");
  if (int(out.size()) != n)
    throw InputError("--at-balls", 0, "",
                     fmt::format("the scene has {} balls: give {} angles beta_1..beta_{} [rad] (got {})", n, n, n,
                                 out.size()));
  return out;
}

// A LuGre scene (model.md §12): the z = 0 equilibria of §5 / §13 (found with the friction
// left out: they do not depend on it) and the stuck state of --at-balls, each with both
// one-sided normal spectra.
std::string render_lugre(const Scene& scene, const EquilibriaOptions& o, std::string& warnings) {
  const ParamsN p = params_of<any_balls>(scene);
  const int n = p.n_balls();
  throw_if_stopped("equilibria (lugre)");
  std::vector<LugreRow> rows = lugre_zero_bristle_rows(p, o.sampling);
  if (!o.at_balls.empty())
    rows.push_back({"stuck", "", 1, analyze_lugre_rest(p, lugre_configuration(p, parse_ball_angles(o.at_balls, n)),
                                                       false)});
  warnings = lugre_warnings(rows);
  if (o.format == "csv") return lugre_equilibria_csv(rows, p, provenance_header(command_line(), scene.file, p));
  if (o.format == "json") return lugre_equilibria_json(rows, p, command_line(), scene.file);
  return lugre_equilibria_table(rows, p);
}

// `coulomb-set` (model.md §14): the stick set instead of isolated equilibria; with
// --stick-set DIR also DIR/stick_boundary.csv (traced curves) and DIR/stick_set.png.
std::string render_stick_set(const Scene& scene, const EquilibriaOptions& o, OutputTransaction& out) {
  const ParamsN p = params_of<any_balls>(scene);
  const StickSet s = stick_set(p, stick_resolution(o.stick));
  const std::string header = provenance_header(command_line(), scene.file, p);
  if (!o.stick_dir.empty()) {
    const std::filesystem::path d(o.stick_dir);
    const auto csv = out.stage(d / "stick_set.csv", stick_set_csv(s, header));
    if (s.n_balls == 2) {
      const auto boundary = out.stage(d / "stick_boundary.csv", stick_boundary_csv(s, header));
      const auto raster = out.stage(d / "stick_raster.dat", stick_raster_dat(p, 240));
      if (o.chart) {
        std::string marks = "# smooth equilibria (tau = 0): beta1 beta2 kind (1 balanced, 2 other)\n";
        for (const auto& sd : s.seeds)
          marks += fmt::format("{},{},{}\n", sd.beta[0], sd.beta[1], sd.family == "balanced" ? 1 : 2);
        const auto seeds = out.stage(d / "stick_seeds.dat", marks);
        run_gnuplot(plots_dir() / "stick_set.gp",
                    {{"csv", boundary.string()},
                     {"raster", raster.string()},
                     {"seeds", seeds.string()},
                     {"png", out.reserve(d / "stick_set.png").string()},
                     {"worst1", fmt::format("{}", s.worst_beta.empty() ? -10.0 : s.worst_beta[0])},
                     {"worst2", fmt::format("{}", s.worst_beta.empty() ? -10.0 : s.worst_beta[1])},
                     {"title", fmt::format("{}: stick set of coulomb-set friction at omega = {} rad/s", scene.file,
                                           p.omega)},
                     {"subtitle", fmt::format("area {:.4g} rad^2 ({:.3g} of the torus), {} component(s), "
                                              "V = {:.4g} m (balanced comp.), V_E = {:.4g} m",
                                              s.area, s.area_fraction, s.components.size(), s.worst_q_abs,
                                              s.worst_q_abs_any)}});
      }
    }
  }
  if (o.format == "csv") return stick_set_csv(s, header);
  if (o.format == "json") return stick_set_json(s, command_line(), scene.file, p);
  return stick_set_table(s, p);
}

// A row must be an equilibrium: a point whose Newton polish left a residual above 1e-8
// (rounding level is 1e-16) is a numerical failure, exit 3, not a row (issue 12).
template <class A>
void check_equilibria(const A& a, double omega) {
  for (const auto& e : a.equilibria.points())
    if (!e.converged && !(e.residual <= 1e-8))
      throw NumericalError(fmt::format("omega={}: the Newton polish of a {} point did not converge (residual {:.3g}): "
                                       "it is not an equilibrium",
                                       omega, to_string(e.family), e.residual));
}

// `--mode-shapes DIR`: DIR/modes.csv (every equilibrium's modes) and DIR/modes.png (the
// best stable state's, else the first equilibrium's), docs/views.md.
template <class A, int N>
void stage_mode_shapes(OutputTransaction& out, const std::string& dir, const A& a, const ParamsT<double, N>& p,
                       const Scene& scene, bool draw) {
  const std::filesystem::path d(dir);
  const auto csv = out.stage(d / "modes.csv",
                             mode_shapes_csv(a, p, provenance_header(command_line(), scene.file, p)));
  const ModeChart chart = mode_chart(a, p);
  if (chart.titles.empty() || !draw) return;
  std::vector<std::pair<std::string, std::string>> vars{
      {"csv", csv.string()},
      {"png", out.reserve(d / "modes.png").string()},
      {"equilibrium", std::to_string(chart.equilibrium + 1)},
      {"count", std::to_string(chart.titles.size())},
      {"title", fmt::format("{}: mode shapes of {} at omega = {} rad/s (rotating frame)", scene.file, chart.label,
                            p.omega)}};
  for (std::size_t k = 0; k < chart.titles.size(); ++k) vars.emplace_back(fmt::format("t{}", k + 1), chart.titles[k]);
  run_gnuplot(plots_dir() / "modes.gp", vars);
}

// Two balls take the fixed-size path (closed forms of model.md §5), any other count the
// general one (§13); both write the same formats.
// An unround race (model.md §11): every equilibrium of §11.4 on the torus, its own report.
std::string render_unround(const Scene& scene, const EquilibriaOptions& o, std::string& warnings) {
  if (!o.mode_shapes.empty())
    throw NotSupportedError("--mode-shapes on an unround race (model.md §11): not supported yet");
  const ParamsN p = params_of<any_balls>(scene);
  const RaceShape race = race_shape(scene);
  const UnroundResult r = find_unround_equilibria(p, race);
  for (const auto& e : r.list)
    if (!(e.residual <= 1e-8))
      throw NumericalError(fmt::format("omega={}: an equilibrium of the unround race has residual {:.3g}: it is not "
                                       "an equilibrium",
                                       p.omega, e.residual));
  // An incomplete search is said on stderr as well as in the output's search line.
  if (!r.doubt.empty()) warnings = fmt::format("warning: omega={}: unround race: {}\n", p.omega, r.doubt);
  if (o.format == "csv") return unround_csv(r, p, race, provenance_header(command_line(), scene.file, p));
  if (o.format == "json") return unround_json(r, p, race, command_line(), scene.file);
  return unround_table(r, p, race, scene.file);
}

std::string render(const Scene& scene, const EquilibriaOptions& o, std::string& warnings, OutputTransaction& out) {
  refuse_combined_extensions(scene);
  if (scene.shaft) {  // a flexible shaft (model.md §18): its equilibria and rightmost eigenvalues
    if (!o.mode_shapes.empty()) throw NotSupportedError("--mode-shapes on a flexible shaft ([shaft], model.md §18)");
    return shaft_equilibria(scene, o.format, o.sampling, o.shaft, warnings);
  }
  if (!scene.race.round()) return render_unround(scene, o, warnings);
  if (scene.support) {  // anisotropic support: Floquet verdicts of the balanced states (model.md §10)
    if (!o.mode_shapes.empty())
      throw NotSupportedError("--mode-shapes on an anisotropic support (the modes are Floquet modes, model.md §10)");
    const ParamsN p = params_of<any_balls>(scene);
    FloquetAnalysis a = analyze_floquet(p, *scene.support, o.sampling);
    // The other states: periodic orbits continued from the mean system's (model.md §10.14).
    // They cost seconds to minutes on stiff coulomb balls; --no-periodic-orbits skips them.
    const ForcedOrbitAnalysis orbits =
        o.periodic_orbits ? analyze_forced_orbits(p, *scene.support, a.mean_equilibria) : ForcedOrbitAnalysis{};
    if (o.periodic_orbits) a.periodic_orbits_not_computed = 0;
    if (o.format == "csv")
      return floquet_csv(a, p, provenance_header(command_line(), scene.file, p)) +
             (o.periodic_orbits ? forced_orbits_csv(orbits, p) : "");
    if (o.format == "json")
      return floquet_json(a, p, *scene.support, command_line(), scene.file,
                          o.periodic_orbits ? forced_orbits_json(orbits) : "");
    return floquet_table(a, p, *scene.support) + (o.periodic_orbits ? forced_orbits_table(orbits, p) : "");
  }
  const SpeedUnit unit = o.scene.speed_unit();
  if (scene.law == FrictionLaw::coulomb_set) return render_stick_set(scene, o, out);
  if (scene.law == FrictionLaw::lugre) {
    if (!o.mode_shapes.empty())
      throw InputError("--mode-shapes", 0, "", "not available for friction law 'lugre' yet (model.md §12)");
    return render_lugre(scene, o, warnings);
  }
  if (!o.at_balls.empty())
    throw InputError("--at-balls", 0, "",
                     fmt::format("a stuck state is an equilibrium only with friction law 'lugre' (model.md §12.3); "
                                 "this scene's law is '{}'",
                                 to_string(scene.law)));
  if (scene.balls.size() == 2) {
    const Params p = params_of<2>(scene);
    const Analysis a = analyze(p);
    check_equilibria(a, p.omega);
    if (!o.mode_shapes.empty()) stage_mode_shapes(out, o.mode_shapes, a, p, scene, o.chart);
    warnings = analysis_warnings(a, fmt::format("omega={}", p.omega));
    const PointAnswer answer = point_answer(a, p);
    const ParamsN pn = params_of<any_balls>(scene);
    if (o.format == "csv")
      return equilibria_csv(a, provenance_header(command_line(), scene.file, p) + answer_lines(answer, unit, "# ") +
                                   creep_lines(a, p, "# ") + stick_verdict_lines(pn, StickSetOptions{}, "# "));
    if (o.format == "json") return equilibria_json(a, command_line(), scene.file, p);
    return equilibria_report(a, p, unit);  // ends with the dry-friction verdict
  }
  const ParamsN p = params_of<any_balls>(scene);
  const AnalysisN a = analyze(p, o.sampling);
  check_equilibria(a, p.omega);
  if (!o.mode_shapes.empty()) stage_mode_shapes(out, o.mode_shapes, a, p, scene, o.chart);
  warnings = analysis_warnings(a, fmt::format("omega={}", p.omega));
  const PointAnswer answer = point_answer(a, p);
  if (o.format == "csv")
    return equilibria_csv(a,
                          provenance_header(command_line(), scene.file, p) + answer_lines(answer, unit, "# ") +
                              creep_lines(a, p, "# ") + stick_verdict_lines(p, StickSetOptions{}, "# "),
                          p.n_balls());
  if (o.format == "json") return equilibria_json(a, command_line(), scene.file, p);
  return equilibria_report(a, p, unit);  // ends with the dry-friction verdict
}
}  // namespace

Action add_equilibria_command(CLI::App& app) {
  auto options = std::make_shared<EquilibriaOptions>();
  CLI::App* sub = app.add_subcommand(
      "equilibria",
      "All real equilibria (model.md §5, §13: balanced, and every aligned ball pattern; for n >= 3 balls the "
      "balanced set by samples) with residuals, eigenvalues [1/s, rotating frame] sorted by real part, condition "
      "numbers and stability.");
  add_scene_options(*sub, options->scene);
  sub->add_option("--format", options->format, "Output format")
      ->check(CLI::IsMember({"table", "csv", "json"}))
      ->capture_default_str();
  sub->add_option("-o,--output", options->output, "Write to FILE (atomically) instead of standard output")
      ->type_name("FILE");
  sub->add_option("--set-samples", options->sampling.samples_per_sheet,
                  "Samples per sheet of the balanced set (n >= 3): G = max(2, round(S^(1/(n-2)))) values per free "
                  "angle")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--at-balls", options->at_balls,
                  "LuGre scenes (model.md §12): also analyse the stuck state with these ball angles "
                  "beta_1,..,beta_n [rad] (q from (5.4), z from (12.5)), both one-sided spectra")
      ->type_name("B1,..,BN");
  sub->add_flag("!--no-periodic-orbits", options->periodic_orbits,
                "Anisotropic support: do not compute the other states' pi/omega-periodic orbits (model.md §10.14; "
                "seconds to minutes with stiff coulomb balls); the balanced states' Floquet verdicts only");
  sub->add_flag("!--no-chart", options->chart,
                "Do not draw the --mode-shapes chart (its CSV is still written)");
  sub->add_option("--mode-shapes", options->mode_shapes,
                  "Also write DIR/modes.csv (every mode of every equilibrium: rotor and ball motion over one cycle) and "
                  "DIR/modes.png")
      ->type_name("DIR");
  sub->add_option("--stick-set", options->stick_dir,
                  "coulomb-set scenes: also write DIR/stick_set.csv, and for two balls DIR/stick_boundary.csv (the "
                  "traced boundary curves), DIR/stick_raster.dat and DIR/stick_set.png (model.md §14)")
      ->type_name("DIR");
  add_stick_resolution_options(*sub, options->stick);
  add_shaft_spectrum_options(*sub, options->shaft);
  return [options]() -> int {
    const Scene scene = load(options->scene);
    if (!options->output.empty()) check_output_target(options->output);  // refused before any work
    std::string warnings;
    OutputTransaction out;
    const std::string text = render(scene, *options, warnings, out);
    fmt::print(stderr, "{}", warnings);
    if (options->output.empty()) {
      out.commit();
      fmt::print("{}", text);
    } else {
      out.stage(options->output, text);
      out.commit();
    }
    return exit_ok;
  };
}

}  // namespace abu::cli
