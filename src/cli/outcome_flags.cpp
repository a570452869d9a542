// The shared flags of the outcome study's runs (outcome_flags.hpp).
#include "outcome_flags.hpp"

#include <thread>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/speed_units.hpp"

namespace abu::cli {

void add_outcome_flags(CLI::App& sub, OutcomeFlags& f, int samples) {
  auto* ramp = sub.add_option("--ramp", f.ramp, "Run-up OMEGA0:OMEGA1:ALPHA [rad/s, rad/s^2], then held (as simulate; "
                                                "default: the scene's [simulate] run-up, else its constant speed)")
                   ->type_name("W0:W1:ALPHA");
  auto* prof = sub.add_option("--speed-profile", f.profile_file, "Speed profile FILE (as simulate)")->type_name("FILE");
  ramp->excludes(prof);
  sub.add_option("--t-end", f.study.sim.t_end, "End of each run [s] (default: the profile's change + 2 s)");
  f.study.samples = samples;
  sub.add_option("--samples", f.study.samples, "Runs (points of the design) of each machine")->capture_default_str();
  sub.add_option("--seed", f.study.seed, "Seed of the points (the same seed, the same study)")->capture_default_str();
  sub.add_option("--design", f.design, "Points: sobol (shifted Sobol sequence) or random (independent)")
      ->check(CLI::IsMember({"sobol", "random"}))
      ->capture_default_str();
  sub.add_option("--uncertain", f.uncertain,
                 "An input known within a range, uniform: NAME=LOW:HIGH with NAME a --set name (repeatable)")
      ->type_name("NAME=LOW:HIGH");
  sub.add_option("--limit", f.study.residual_limit,
                 "Residual |q| that counts as good enough [m] (default 0: each run's bare rotor)");
  sub.add_option("--confidence", f.study.confidence, "Level of every interval")->capture_default_str();
  sub.add_option("--every", f.study.sim.every, "Sample interval [s] (default t_end / 2000)")->type_name("DT");
  sub.add_option("--rtol", f.study.sim.rtol, "Integration tolerance (model.md §15.1)")->capture_default_str();
  sub.add_option("--method", f.method, "Integrator (auto: by the stiffness ratio, model.md §15.1)")
      ->check(CLI::IsMember({"auto", "bdf", "rk8pd", "rk4imp", "bsimp", "rkf45"}))
      ->capture_default_str();
  f.study.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  sub.add_option("--threads", f.study.threads, "Worker threads (the output does not depend on it)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  auto* progress = sub.add_flag("--progress", f.progress, "Progress on stderr even if not a terminal");
  auto* quiet = sub.add_flag("--quiet", f.quiet, "No progress and no summary on stderr");
  progress->excludes(quiet);
}

SpeedProfile speed_of(const OutcomeFlags& f, const SceneOptions& scene_options, const Scene& scene) {
  return run_speed(scene_options, f.ramp, f.profile_file, scene);
}

OutcomeOptions outcome_options(const OutcomeFlags& f, const CLI::App& sub, const Scene& scene, const SpeedProfile& speed) {
  OutcomeOptions s = f.study;
  const bool scene_end = scene.simulate && scene.simulate->t_end;
  if (scene.simulate) {
    const SimulateSettings& k = *scene.simulate;
    if (k.t_end && sub.count("--t-end") == 0) s.sim.t_end = *k.t_end;
    if (k.every && sub.count("--every") == 0) s.sim.every = *k.every;
    if (k.rtol && sub.count("--rtol") == 0) s.sim.rtol = *k.rtol;
  }
  if (sub.count("--t-end") == 0 && !scene_end) s.sim.t_end = default_outcome_end(speed);
  const bool scene_method = scene.simulate && scene.simulate->method && sub.count("--method") == 0;
  s.sim.method = *integration_method_from_string(scene_method ? *scene.simulate->method : f.method);
  s.design = *sample_design_from_string(f.design);
  std::vector<UncertainInput> given;
  for (const auto& u : f.uncertain) given.push_back(parse_uncertain(u));
  s.uncertain = study_inputs(scene, given);  // the scene's [uncertain], the flags replacing an entry
  s.interrupt = &stop_flag();
  return s;
}

}  // namespace abu::cli
