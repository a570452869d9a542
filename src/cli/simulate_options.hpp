// The options of `stability-scan simulate` (simulate_command.cpp), shared with its flexible
// shaft route (simulate_shaft.cpp).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "abu/dynamics/simulation.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/speed_profile.hpp"
#include "cli.hpp"

namespace abu::cli {

struct SimulateOptions {
  SceneOptions scene;
  std::string ramp, profile_file;
  std::string balls, from_state, from_equilibrium;
  std::optional<double> perturb;
  SimulationOptions sim;
  std::string method = "auto";
  std::string output = "out/simulate";
  std::string summary;
  bool chart = true, progress = false, quiet = false;
};

/// The progress line on stderr (--progress, or a terminal), or an empty function.
std::function<void(double)> simulate_progress(const SimulateOptions& o, double t_end);

/// `simulate` on a scene with [shaft] (model.md §18.16): the whole run, files and exit code.
int run_shaft_simulation(const Scene& scene, const SimulateOptions& o, const SpeedProfile& speed);

}  // namespace abu::cli
