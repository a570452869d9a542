// `stability-scan simulate` on a flexible shaft (model.md §18.16): the options of the rigid
// command, the run by simulate_shaft, the rigid route's files with the shaft's columns. On an
// unround race (model.md §18.20) the balls run on its paths and a settled run is matched against
// the race's equilibria on the shaft (§15.7).
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>

#include "abu/analysis/shaft_race_end.hpp"
#include "abu/analysis/shaft_states.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_shaft_simulation.hpp"
#include "simulate_options.hpp"

namespace abu::cli {

namespace {

Eigen::VectorXd shaft_start(const ShaftSystem& sys, const SimulateOptions& o) {
  const int starts = int(!o.balls.empty()) + int(!o.from_state.empty()) + int(!o.from_equilibrium.empty());
  if (!o.from_equilibrium.empty())
    throw InputError("--from-equilibrium", 0, "",
                     "not on a flexible shaft (model.md §18.16): start from --balls, or from a state with --from-state "
                     "(the 2 (4 N_nodes + n) values; `simulate --summary` writes a run's end state as shaft.x_end)");
  if (o.perturb) throw InputError("--perturb", 0, "", "--perturb goes with --from-equilibrium");
  if (starts != 1) throw InputError("simulate", 0, "", "give exactly one start: --balls or --from-state");
  if (!o.balls.empty()) return shaft_start_at_rest(sys, parse_real_list(o.balls, "--balls"));
  const std::vector<double> v = parse_real_list(o.from_state, "--from-state");
  if (int(v.size()) != sys.state_size())
    throw InputError("--from-state", 0, "",
                     fmt::format("a state of this shaft has 2 (4 N_nodes + n) = 2 (4 x {} + {}) = {} values (u1,u2,"
                                 "psi1,psi2 per node, beta1..beta{}, then their rates), got {}",
                                 sys.nodes(), sys.n_balls(), sys.state_size(), sys.n_balls(), v.size()));
  return Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size()));
}

}  // namespace

int run_shaft_simulation(const Scene& scene, const SimulateOptions& o, const SpeedProfile& speed) {
  ShaftSystem sys = shaft_system_of(scene);
  const Eigen::VectorXd x0 = shaft_start(sys, o);
  SimulationOptions so = o.sim;
  so.method = *integration_method_from_string(o.method);
  so.interrupt = &stop_flag();  // set by the CLI's signal thread (cli.cpp)
  so.progress = simulate_progress(o, so.t_end);
  const RaceShape race = race_shape(scene);
  if (!race.round()) so.race = &race;  // the balls on the race's paths (model.md §18.20)
  ShaftSimulationResult r = simulate_shaft(sys, speed, x0, so);
  if (so.progress) fmt::print(stderr, "\r{:80}\r", "");
  if (so.race && r.run.status == SimulationStatus::completed && so.record)  // §15.7: the race's equilibria on the shaft
    judge_shaft_race_end(r.run.summary, sys, race, speed.omega(r.run.t_reached), r.run.displacement_scale,
                         so.settle_tolerance);

  namespace fs = std::filesystem;
  const fs::path csv_path = fs::path(o.output) / "simulation.csv", png_path = fs::path(o.output) / "simulation.png";
  {
    OutputTransaction out;
    std::string header = provenance_header(command_line(), scene.file, sys.balancer);
    if (so.race) header += describe_race(race, "# ");
    out.stage(csv_path, shaft_simulation_csv(r, sys, speed, header));
    if (!o.summary.empty()) out.stage(o.summary, shaft_simulation_json(r, sys, speed, command_line(), scene.file));
    out.commit();
  }
  const SimulationResult<any_balls>& run = r.run;
  int code = run.status == SimulationStatus::completed     ? exit_ok
             : run.status == SimulationStatus::interrupted ? interrupted_exit_code()
                                                           : exit_numerical;
  if (o.chart && run.samples.size() >= 2) {
    try {  // the CSV is in place already: a failing chart loses nothing else
      OutputTransaction chart;
      std::vector<double> beta(std::size_t(sys.n_balls()));
      for (int i = 0; i < sys.n_balls(); ++i) beta[std::size_t(i)] = run.x_end(2 + i);
      run_gnuplot(plots_dir() / "simulation.gp",
                  {{"csv", csv_path.string()},
                   {"png", chart.reserve(png_path).string()},
                   {"n", std::to_string(sys.n_balls())},
                   // No balanced set to measure from on an unround race (§15.7).
                   {"rel", !so.race && nearest_balanced_angles(sys.balancer, beta) ? "1" : "0"},
                   {"omega_n", "0"},  // the shaft has no single omega_n (model.md §18.16)
                   {"stick", "0"},
                   {"title", fmt::format("{}: flexible shaft, balancer node {}, {} ({}), outcome {}", scene.file,
                                         sys.spec.balancer_node, speed.describe(), to_string(run.method),
                                         to_string(run.summary.outcome))}});
      chart.commit();
    } catch (const std::exception& e) {
      fmt::print(stderr, "stability-scan: warning: chart not drawn ({}); the CSV is complete\n", e.what());
      if (code == exit_ok) code = exit_chart_failed;
    }
  }
  if (!o.quiet) fmt::print(stderr, "{}", shaft_simulation_text(r, sys, speed));
  if (run.status == SimulationStatus::failed) fmt::print(stderr, "stability-scan: numerical failure: {}\n", run.reason);
  if (run.status == SimulationStatus::interrupted)
    fmt::print(stderr, "stability-scan: {}; kept what was computed\n", run.reason);
  if (!o.quiet)
    fmt::print(stderr, "wrote {}{}{}\n", csv_path.string(), o.summary.empty() ? "" : " and " + o.summary,
               o.chart && fs::exists(png_path) ? " and " + png_path.string() : "");
  return code;
}

}  // namespace abu::cli
