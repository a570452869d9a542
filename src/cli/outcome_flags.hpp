// The options a command shares for the runs of an outcome study (`outcomes`, `design`): the
// speed profile, the end time, the points, the uncertain inputs, the limit, the integrator and
// the threads (docs/cli.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "abu/analysis/outcomes.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/speed_profile.hpp"
#include "cli.hpp"

namespace abu::cli {

struct OutcomeFlags {
  std::string ramp, profile_file, design = "sobol", method = "auto";
  std::vector<std::string> uncertain;
  OutcomeOptions study;
  bool progress = false, quiet = false;
};

/// Declares the flags on `sub` (defaults as OutcomeOptions's; `samples` the command's own).
void add_outcome_flags(CLI::App& sub, OutcomeFlags& f, int samples);

/// The run's speed (run_speed of the flags' --ramp and --speed-profile).
SpeedProfile speed_of(const OutcomeFlags& f, const SceneOptions& scene_options, const Scene& scene);

/// The options from the flags and the scene's [simulate] keys where no flag is given; the end
/// time defaults to the profile's change plus two seconds of hold.
OutcomeOptions outcome_options(const OutcomeFlags& f, const CLI::App& sub, const Scene& scene, const SpeedProfile& speed);

}  // namespace abu::cli
