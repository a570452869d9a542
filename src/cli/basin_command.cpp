// `stability-scan basin SCENE`: basins of attraction (model.md §15.5). A grid of initial
// ball positions (rotor at rest), each integrated until it enters the neighbourhood of a
// stable equilibrium of the final speed (or to t_end) and classified; tiles through the
// map's TileStore (threads, --resume, --fresh, Ctrl-C keeps finished tiles); the long CSV,
// the fraction per attractor (CSV and JSON) and the classification map (PNG).
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli.hpp"
#include "abu/analysis/basin_targets.hpp"
#include "abu/analysis/outcomes.hpp"
#include "abu/core/sampling.hpp"
#include "abu/output/report_outcomes.hpp"
#include "abu/analysis/shaft_states.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/core/resources.hpp"
#include "abu/dynamics/stick_slip.hpp"
#include "abu/output/format.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/scan/basin.hpp"
#include "commands.hpp"
#include "tiled_run.hpp"

namespace abu::cli {

namespace {

struct BasinOptions {
  SceneOptions scene;
  std::string ramp, profile_file, grid = "24", fixed, others = "sobol";
  SimulationOptions sim;
  std::string method = "auto";
  double settle_radius = 1e-2;
  int settle_samples = 5;
  std::string output = "out/basin";
  int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  bool resume = false, fresh = false, chart = true, progress = false, quiet = false;
};

// The fraction table: balanced first, then the aligned patterns and the unround race's states
// (equilibria, orbits), periodic, stuck, not settled.
int label_rank(const std::string& label) {
  if (label == "balanced") return 0;
  if (label.rfind("aligned:", 0) == 0 || label == "equilibrium" || label == "orbit") return 1;
  if (label == "periodic") return 2;
  if (label == "stuck") return 3;
  return 4;
}

}  // namespace

Action add_basin_command(CLI::App& app) {
  auto o = std::make_shared<BasinOptions>();
  CLI::App* sub = app.add_subcommand(
      "basin",
      "Basins of attraction: from a grid of initial ball positions (rotor at rest) integrate to a settle criterion and "
      "classify (balanced, aligned pattern, periodic, stuck, not settled); fraction per attractor, classification map "
      "(model.md §15.5). Threads, resumable (--resume) like maps.");
  add_scene_options(*sub, o->scene);
  sub->add_option("--grid", o->grid, "Cells per axis of beta1 x beta2 over [0, 2 pi)^2: N or N1xN2")
      ->capture_default_str();
  sub->add_option("--fixed", o->fixed,
                  "n >= 3 balls: start angles of balls 3..n [rad], the same in every cell (default: --others)")
      ->type_name("B3,B4,...");
  sub->add_option("--others", o->others,
                  "n >= 3: how balls 3..n start: 'sobol' (default: each cell its own point of a Sobol sequence, "
                  "every ball's angle sampled) or 'symmetric' (every cell at 2 pi (i - 1) / n)")
      ->check(CLI::IsMember({"sobol", "symmetric"}));
  sub->add_option("--t-end", o->sim.t_end, "Longest integration per cell [s] (default 10, or the scene's t_end)");
  auto* ramp = sub->add_option("--ramp", o->ramp, "Run-up OMEGA0:OMEGA1:ALPHA (as simulate; default: the scene's "
                                                  "[simulate] run-up, else the constant [speed])")
                   ->type_name("W0:W1:ALPHA");
  auto* prof = sub->add_option("--speed-profile", o->profile_file, "Speed profile FILE (as simulate)")->type_name("FILE");
  ramp->excludes(prof);
  sub->add_option("--every", o->sim.every, "Sample interval [s]: the settle test looks at every sample (default "
                                            "t_end / 2000)")
      ->type_name("DT");
  sub->add_option("--rtol", o->sim.rtol, "Integration tolerance (model.md §15.1)")->capture_default_str();
  sub->add_option("--method", o->method, "Integrator (auto: by the stiffness ratio, model.md §15.1)")
      ->check(CLI::IsMember({"auto", "bdf", "rk8pd", "rk4imp", "bsimp", "rkf45"}))
      ->capture_default_str();
  sub->add_option("--settle-radius", o->settle_radius,
                  "Scaled distance to a stable equilibrium that counts as arrived (model.md §15.5)")
      ->capture_default_str();
  sub->add_option("--settle-samples", o->settle_samples, "Consecutive samples inside the settle radius")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--settle-tol", o->sim.settle_tolerance, "Scaled distance for 'settled' at t_end (model.md §15.2)")
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "Worker threads (the output does not depend on it)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  auto* resume = sub->add_flag("--resume", o->resume, "Continue an interrupted basin from its tiles");
  auto* fresh = sub->add_flag("--fresh", o->fresh, "Discard the tiles of an interrupted basin and start over");
  resume->excludes(fresh);
  sub->add_option("-o,--output", o->output, "Output directory: basin.csv, basin_fractions.csv, basin.json, basin.png")
      ->capture_default_str();
  sub->add_flag("--no-chart", [o](std::int64_t) { o->chart = false; }, "Do not draw the map");
  auto* progress = sub->add_flag("--progress", o->progress, "Progress on stderr even if not a terminal");
  auto* quiet = sub->add_flag("--quiet", o->quiet, "No progress and no summary on stderr");
  progress->excludes(quiet);
  return [o, sub]() -> int {
    // Everything is checked before any work (exit 2, nothing written).
    const Scene scene = load(o->scene);
    // It integrates the base model's field (model.md §3), LuGre's 3n + 4 (§12.7) or the
    // stick-slip dynamics of coulomb-set (§14.8).
    refuse_unmodelled(scene, "basin", handles_of("basin"));
    check_output_directory(o->output);
    BasinOptions b = *o;
    b.sim.t_end = 10.0;
    if (scene.simulate) {  // the scene's [simulate] keys where no flag is given
      const SimulateSettings& s = *scene.simulate;
      if (s.t_end) b.sim.t_end = *s.t_end;
      if (s.every && sub->count("--every") == 0) b.sim.every = *s.every;
      if (s.rtol && sub->count("--rtol") == 0) b.sim.rtol = *s.rtol;
      if (s.method && sub->count("--method") == 0) b.method = *s.method;
    }
    if (sub->count("--t-end") > 0) b.sim.t_end = o->sim.t_end;
    if (!(std::isfinite(b.sim.t_end) && b.sim.t_end > 0))
      throw InputError("--t-end", 0, "", fmt::format("the end time must be > 0 s (got {})", b.sim.t_end));
    if (!(b.sim.every >= 0 && std::isfinite(b.sim.every)))
      throw InputError("--every", 0, "", "the sample interval must be > 0 s");
    if (!(b.sim.rtol >= 1e-14 && b.sim.rtol < 0.1))
      throw InputError("--rtol", 0, "", fmt::format("the tolerance must lie in [1e-14, 0.1): below 1e-14 no double-precision step meets it (unit roundoff 1.1e-16) (got {})", b.sim.rtol));
    if (!(b.settle_radius > 0 && b.settle_radius < 1)) throw InputError("--settle-radius", 0, "", "must lie in (0, 1)");
    if (!(b.sim.settle_tolerance > 0 && b.sim.settle_tolerance < 1))
      throw InputError("--settle-tol", 0, "", "must lie in (0, 1)");
    const int n = int(scene.balls.size());
    BasinJob job;
    job.speed = run_speed(o->scene, o->ramp, o->profile_file, scene);
    const auto [c1, c2] = parse_cell_grid(b.grid, "--grid");
    job.cells1 = c1;
    job.cells2 = c2;
    if (!b.fixed.empty()) {
      if (n == 2) throw InputError("--fixed", 0, "", "a scene of two balls has no fixed balls (both are gridded)");
      job.fixed = parse_real_list(b.fixed, "--fixed");
      if (int(job.fixed.size()) != n - 2)
        throw InputError("--fixed", 0, "", fmt::format("give balls 3..{}: {} angles, got {}", n, n - 2, job.fixed.size()));
    } else if (b.others == "symmetric") {
      for (int i = 3; i <= n; ++i) job.fixed.push_back(2 * M_PI * (i - 1) / n);
    }
    job.sim = b.sim;
    job.sim.method = *integration_method_from_string(b.method);
    job.settle_radius = b.settle_radius;
    job.settle_samples = b.settle_samples;
    const RaceShape race = race_shape(scene);  // an unround race: its paths and equilibria (model.md §15.7)
    // LuGre: bounded 3n + 4 storage; an unround race: the bounded storage of its field.
    // An anisotropic support: the composed field's storage too (model.md §20).
    job.any_balls = !two_ball_storage(scene);
    job.support = scene.support;
    if (scene.shaft) job.shaft = std::make_shared<const ShaftSystem>(shaft_system_of(scene));  // model.md §18.21
    std::string line = fmt::format("stability-scan basin {} --grid {}x{}", o->scene.scene, c1, c2);
    for (const auto& s : o->scene.overrides) line += " --set " + s;
    line += fmt::format(" ({}, t_end {} s, rtol {}, method {}, settle radius {} for {} samples)", job.speed.describe(),
                        job.sim.t_end, job.sim.rtol, b.method, job.settle_radius, job.settle_samples);
    if (job.shaft) {  // the balancer's view: the settle test's scales; the shaft itself in the header
      job.params_n = shaft_summary_params(*job.shaft);
      job.params_n.omega = job.speed.omega(0.0);
      job.provenance = provenance_header(line, scene.file, job.shaft->balancer) + describe_shaft(job.shaft->spec, "# ");
    } else if (job.any_balls) {
      job.params_n = params_of<any_balls>(scene);
      job.params_n.omega = job.speed.omega(0.0);
      job.provenance = provenance_header(line, scene.file, job.params_n);
    } else {
      job.params = params_of<2>(scene);
      job.params.omega = job.speed.omega(0.0);
      job.provenance = provenance_header(line, scene.file, job.params);
    }
    set_basin_race(job, race);  // after params_n and the speed: the equilibria at the final speed
    set_sobol_starts(job);      // n >= 3 without fixed angles: every ball's start angle sampled
    if (!job.race.round()) job.provenance += describe_race(job.race, "# ");
    if (const auto& k = job.support)  // the mean is the scene's k and c (provenance); the whole matrices here
      job.provenance += fmt::format("# anisotropic support (model.md §10, §20): fixed frame K_f = [[{:.17g}, {:.17g}], "
                                    "[{:.17g}, {:.17g}]] N/m, C_f = [[{:.17g}, {:.17g}], [{:.17g}, {:.17g}]] N s/m\n",
                                    k->k_x, k->k_xy, k->k_xy, k->k_y, k->c_x, k->c_xy, k->c_xy, k->c_y);
    job.provenance += fmt::format("# grid: beta1 x beta2 over [0, 2 pi)^2, {} x {} cells; rotor at rest, balls at rest "
                                  "in the rotor frame\n",
                                  c1, c2);
    if (!job.fixed.empty()) {
      std::string f;
      for (double x : job.fixed) f += fmt::format("{}{:.10g}", f.empty() ? "" : ",", x);
      job.provenance += fmt::format("# fixed: balls 3..{} start at {} rad\n", n, f);
    } else if (n > 2) {
      job.provenance += fmt::format("# others: balls 3..{} start in cell (i, j) at 2 pi times point i*{} + j + 1 of the "
                                    "Sobol sequence in {} dimensions (GSL), columns beta3_0..beta{}_0\n",
                                    n, c2, n - 2, n);
    }

    const BasinAttractors attractors = machine_basin_targets(job);
    const std::vector<BasinTarget>& targets = attractors.targets;
    {
      std::string t;
      for (const auto& x : targets) t += fmt::format("{}{}{}", t.empty() ? "" : ", ", x.label,
                                                     x.balanced_set ? " (set)" : fmt::format(" {}", x.member));
      job.provenance += fmt::format("# attractors of the settle test at omega = {:.10g} rad/s: {}\n", job.final_omega(),
                                    t.empty() ? "none stable" : t);
      // Each attractor's certified region (model.md §15.8), or why it has none.
      for (const auto& x : targets) {
        const std::string name = x.balanced_set ? x.label + " (set)" : fmt::format("{} {}", x.label, x.member);
        if (x.region.certified)
          job.provenance += fmt::format(
              "# certified region of {}: V = y^T P y < {:.6g} (scaled y), ball radius r = {:.6g}, |D^2 g| <= K2 = "
              "{:.6g}, eig(P) in [{:.6g}, {:.6g}] (model.md §15.8)\n",
              name, x.region.level, x.region.radius, x.region.second_derivative_bound, x.region.p_min, x.region.p_norm);
        else
          job.provenance += fmt::format("# no certified region for {}: {}\n", name, x.region.reason);
      }
      for (const auto& why : attractors.unresolved)
        job.provenance += fmt::format("# not an attractor of the settle test (no verdict): {}\n", why);
    }
    namespace fs = std::filesystem;
    const fs::path dir(b.output);
    const fs::path csv_path = dir / "basin.csv", fractions_path = dir / "basin_fractions.csv",
                   json_path = dir / "basin.json", png_path = dir / "basin.png";
    const fs::path tiles_dir = dir / ".basin.tiles";
    const BasinEstimate estimate = basin_estimate(job, b.threads);
    require_memory(estimate.memory, estimate.runs > estimate.cells ? "--every" : "--grid", "the basin",
                   fmt::format("{} workers' recorded runs and {} cells' text", std::max(1, std::min(b.threads, job.cells1)),
                               job.cells1 * job.cells2),
                   estimate.runs > estimate.cells ? "use a longer --every, a shorter --t-end or fewer --threads"
                                                  : "use a smaller --grid");
    require_disk(estimate.disk, dir, "-o", "the basin", fmt::format("{} cells: tiles, then CSV", job.cells1 * job.cells2),
                 "use a smaller --grid or write elsewhere");
    if (estimate.memory > 1e8) fmt::print(stderr, "basin: memory: at most about {}\n", gigabytes(estimate.memory));
    const TiledRunFlags flags{b.resume, b.fresh, b.progress, b.quiet, b.threads};
    const TileStore store(tiles_dir, basin_manifest(job), job.cells1, tile_store_mode(flags));
    const std::optional<FinishedTiles> counts = run_missing_tiles(store, tiles_dir, job.cells1, flags,
                           [&job, &targets](const auto& missing, const auto& run_options, const auto& sink) {
                             return compute_basin_tiles(job, targets, missing, run_options, sink);
                           });
    if (!counts) return interrupted_exit_code();
    const MapRunStats& stats = counts->stats;

    // Count the attractors.
    // By rank, then label; an unround race's states (equilibrium, orbit) also by their number,
    // written "orbit 3": which state a start reaches is the design answer there.
    struct FractionKey {
      int rank;
      std::string label;
      int member;
      auto operator<=>(const FractionKey&) const = default;
      std::string name() const { return member > 0 ? fmt::format("{} {}", label, member) : label; }
    };
    std::map<FractionKey, long> count;
    std::set<std::pair<int, std::string>> classes;  // of the chart: attractor/member
    long cells = 0, early = 0, certified = 0;
    // coulomb-set (model.md §14.8): the end angles of the cells where every ball stuck, the
    // largest |s_i| and |q| there, and how many lie outside the stick set.
    const bool set_valued = scene.law == FrictionLaw::coulomb_set;
    std::vector<std::vector<double>> stuck_angles(static_cast<std::size_t>(n));
    long stuck_cells = 0, outside = 0;
    double worst_s = 0, worst_q = 0;
    std::vector<double> residuals;  // |q| at each cell's end (model.md §21.1's residual, at the settle test's entry or t_end)
    double stuck_max = 0;           // the largest of them among the stuck cells (the chart's shading)
    {
      std::istringstream in(counts->rows);
      for (std::string row; std::getline(in, row);) {
        std::vector<std::string> f;
        std::stringstream ss(row);
        for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
        const bool numbered = (f[4] == "orbit" || f[4] == "equilibrium") && !f[5].empty();
        ++count[{label_rank(f[4]), f[4], numbered ? std::stoi(f[5]) : 0}];
        classes.insert({label_rank(f[4]), f[5].empty() ? f[4] : f[4] + "/" + f[5]});
        early += f[6] != "0";
        residuals.push_back(std::stod(f[9]));
        if (f[4] == "stuck") stuck_max = std::max(stuck_max, residuals.back());
        certified += f[6] == "1";
        ++cells;
        if (set_valued && f[std::size_t(14 + n)] != "-1") {
          ++stuck_cells;
          outside += f[std::size_t(14 + n)] == "0";
          worst_s = std::max(worst_s, std::stod(f[std::size_t(13 + n)]));
          worst_q = std::max(worst_q, std::stod(f[9]));
          for (int k = 0; k < n; ++k) stuck_angles[std::size_t(k)].push_back(std::stod(f[std::size_t(11 + k)]));
        }
      }
    }
    std::vector<double> spread;
    for (const auto& angles : stuck_angles) spread.push_back(shortest_arc(angles));
    std::string fractions = job.provenance + "attractor,cells,fraction\n";
    std::string json = fmt::format("{{\n  \"cells\": {},\n  \"grid\": [{}, {}],\n  \"omega_final\": {},\n  \"t_end\": {},\n"
                                   "  \"by_settle_test\": {},\n  \"by_certified_region\": {},\n  \"fractions\": {{",
                                   cells, job.cells1, job.cells2, job.final_omega(), job.sim.t_end, early, certified);
    std::string labels;
    bool first = true;
    for (const auto& [key, k] : count) {
      const double frac = double(k) / double(cells);
      fractions += fmt::format("{},{},{:.6f}\n", key.name(), k, frac);
      json += fmt::format("{}\n    \"{}\": {:.6f}", first ? "" : ",", key.name(), frac);
      first = false;
    }
    json += "\n  }";
    // The residual over the cells against the bare rotor (model.md §21.3's statistics; a rigid rotor's (16.5.1)).
    const double bare = scene.shaft ? 0.0 : steady_whirl_radius(scene, job.final_omega(), scene.rotor.unbalance);
    const QuantileEstimate r50 = quantile_estimate(residuals, 0.5), r90 = quantile_estimate(residuals, 0.9),
                           r100 = quantile_estimate(residuals, 1.0);
    json += fmt::format(",\n  \"residual_q\": {{\"median\": [{}, {}, {}], \"p90\": [{}, {}, {}], \"worst\": {}, "
                        "\"bare_rotor\": {}}}",
                        format_number(r50.value, "residual"), json_number_or_null(r50.low, "residual"),
                        json_number_or_null(r50.high, "residual"), format_number(r90.value, "residual"),
                        json_number_or_null(r90.low, "residual"), json_number_or_null(r90.high, "residual"),
                        format_number(r100.value, "residual"), bare > 0 ? format_number(bare, "bare rotor") : "null");
    if (set_valued) {
      std::string sp;
      for (double x : spread) sp += fmt::format("{}{:.9f}", sp.empty() ? "" : ", ", x);
      json += fmt::format(",\n  \"stick_slip\": {{\"stuck_cells\": {}, \"outside_stick_set\": {}, \"max_abs_s\": {:.9f}, "
                          "\"worst_q_abs_end\": {:.9e}, \"spread\": [{}], \"set_tolerance\": {:g}}}",
                          stuck_cells, outside, worst_s, worst_q, sp, stick_set_tolerance);
    }
    json += "\n}\n";
    for (const auto& c : classes) labels += (labels.empty() ? "" : " ") + c.second;
    {
      OutputTransaction out;
      out.stage(csv_path, basin_csv_header(job) + counts->rows);
      out.stage(fractions_path, fractions);
      out.stage(json_path, json);
      out.commit();
    }
    store.remove();
    int code = exit_ok;
    if (b.chart) {
      OutputTransaction chart;
      if (run_gnuplot(plots_dir() / "basin.gp", {{"csv", csv_path.string()},
                                                 {"png", chart.reserve(png_path).string()},
                                                 {"labels", labels},
                                                 {"cells1", std::to_string(job.cells1)},
                                                 {"cells2", std::to_string(job.cells2)},
                                                 {"stuck_max", fmt::format("{}", stuck_max)},
                                                 {"title", fmt::format("{}: {}", escaped(scene.file), job.speed.describe())}}))
        chart.commit();
    }
    if (!b.quiet) {
      fmt::print(stderr, "{} cells ({} ended by the settle test), {} tiles computed in {:.2f} s\n", cells, early,
                 stats.tiles, stats.seconds);
      for (const auto& [key, k] : count)
        fmt::print(stderr, "  {:<14} {:>6} cells  {:6.2f} %\n", key.name(), k, 100.0 * double(k) / double(cells));
      fmt::print(stderr, "  |q| at the cells' ends: median {}, 90th percentile {}, worst {:.4g} µm{}\n",
                 interval_text(r50, 1e6, " µm"), interval_text(r90, 1e6, " µm"), r100.value * 1e6, bare > 0 ? fmt::format(" (the bare rotor's {:.4g} µm, (16.5.1))", bare * 1e6) : "");
      if (set_valued && stuck_cells == 0) {
        fmt::print(stderr, "  no cell ends with every ball stuck (none inside the stick set)\n");
      } else if (set_valued) {
        fmt::print(stderr, "  every ball stuck in {} of {} cells; end points outside the stick set: {}; max |s_i| = {:.6g}; "
                           "largest end |q| = {:.6g} m\n  spread of the end angles (shortest arc holding them):",
                   stuck_cells, cells, outside, worst_s, worst_q);
        for (int k = 0; k < n; ++k)
          fmt::print(stderr, " ball {} {:.4f} rad ({:.1f} deg)", k + 1, spread[std::size_t(k)],
                     spread[std::size_t(k)] * 180 / M_PI);
        fmt::print(stderr, "\n");
      }
      fmt::print(stderr, "wrote {}, {}, {}{}\n", csv_path.string(), fractions_path.string(), json_path.string(),
                 b.chart && fs::exists(png_path) ? ", " + png_path.string() : "");
    }
    if (outside > 0) {
      fmt::print(stderr,
                 "stability-scan: numerical failure: {} end points with every ball stuck lie outside the stick set "
                 "(max |s_i| = {:.9g} > 1 + {:g}; model.md §14.8)\n",
                 outside, worst_s, stick_set_tolerance);
      code = exit_numerical;
    }
    return code;
  };
}

}  // namespace abu::cli
