// Basins on a flexible shaft (docs/model.md §18.21): the whole shaft integrated per cell, the
// settle test on the balancer's view, the attractors the shaft's stable states. Small enough to
// run under the sanitizers (the command's contract is tests/cli/check_basin_shaft.py).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "abu/analysis/basin_targets.hpp"
#include "abu/analysis/shaft_states.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/basin.hpp"

using namespace abu;

namespace {

BasinJob shaft_job(const std::string& relative) {
  const Scene scene = load_scene(std::string(ABU_SOURCE_DIR) + "/" + relative);
  BasinJob job;
  job.any_balls = true;
  job.shaft = std::make_shared<const ShaftSystem>(shaft_system_of(scene));
  job.params_n = shaft_summary_params(*job.shaft);
  job.speed = SpeedProfile::constant(scene.omega);
  job.params_n.omega = scene.omega;
  job.sim.t_end = 10;
  job.cells1 = job.cells2 = 3;
  set_basin_race(job, race_shape(scene));
  return job;
}

// The scaled distance of the settle test (model.md §15.5) between a cell's end and a target at
// rest, from the cell's own figures: ball angles and |q| at the balancer node.
double end_distance(const BasinCell& c, const BasinTarget& t, double L) {
  const int n = (int(c.state_end.size()) - 4) / 2;
  double d = std::abs(c.q_abs_end - std::hypot(t.position[0], t.position[1])) / L;
  for (int k = 0; k < n; ++k)
    d = std::max(d, std::abs(std::remainder(c.state_end[std::size_t(2 + k)] - t.position[std::size_t(2 + k)],
                                            2 * std::numbers::pi)));
  return d;
}

}  // namespace

TEST_CASE("shaft basin: cells of a one-node shaft and of a race on a shaft end on their stable states",
          "[shaft_basin]") {
  // A one-node shaft with two equal balls above its critical speed (900 rad/s: the mirror
  // balanced states stable) and the four-element shaft with two balls on their own unround paths
  // (600 rad/s: the race's equilibria 1 and 3 stable, as `equilibria` lists them). A cell off the
  // diagonal must end by the settle test (by_settle_test 2, before t_end) on one of the targets,
  // within the settle radius of it (asserted on the end's own figures, 1e-2 + 1e-9).
  for (const char* scene : {"tests/scenes/shaft/one_node_viscous.toml", "tests/scenes/shaft/race_four_elements.toml"}) {
    const BasinJob job = shaft_job(scene);
    const BasinAttractors a = machine_basin_targets(job);
    INFO(scene);
    REQUIRE(a.targets.size() == 2);
    CHECK(a.targets[0].label == (job.race.round() ? "balanced" : "equilibrium"));
    const BasinCell c = compute_basin_cell(job, a.targets, 1, 2);
    INFO(c.attractor << " " << c.member << " at " << c.t_end << " s");
    CHECK(c.by_settle_test == 2);
    CHECK(c.t_end < job.sim.t_end);
    const BasinTarget* named = nullptr;
    for (const auto& t : a.targets)
      if (t.label == c.attractor && t.member == c.member) named = &t;
    REQUIRE(named);
    CHECK(end_distance(c, *named, displacement_scale(job.params_n)) <= job.settle_radius + 1e-9);
  }
}
