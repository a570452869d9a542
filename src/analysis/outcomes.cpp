// The outcome of a machine in operation (docs/model.md §21): runs from sampled starts and
// inputs, their figures, and the statistics of the sample.
#include "abu/analysis/outcomes.hpp"

#include "abu/core/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <mutex>
#include <numbers>

#include "abu/analysis/machine_parts.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/resources.hpp"
#include "abu/dynamics/stick_slip.hpp"
#include "abu/input/option_values.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

namespace {

double total_mass(const Scene& s) {
  double m = s.rotor.mass;
  for (const auto& b : s.balls) m += b.mass;
  return m;
}

// The scene with sample k's uncertain inputs set (checked against the scene's rules).
Scene scene_of_sample(const Scene& scene, const OutcomeOptions& o, const std::vector<double>& inputs) {
  Scene s = scene;
  for (std::size_t u = 0; u < o.uncertain.size(); ++u) set_study_input(s, o.uncertain[u].name, inputs[u], "--uncertain");
  return s;
}

// Refuses an input the study cannot vary, before any run: an unknown name, omega, a reversed
// or non-finite range, a range the scene's rules refuse at either end; each at where it was given.
void check_uncertain(const Scene& scene, const OutcomeOptions& o) {
  for (const auto& u : o.uncertain) {
    const std::string key = u.line > 0 ? "uncertain." + u.name : u.name;
    if (u.name == "omega")
      throw InputError(u.origin, u.line, key, "the speed is the run's profile (--ramp, --speed-profile), not an uncertain input");
    if (u.name != "unroundness" && !parse_param(u.name, int(scene.balls.size())))
      throw InputError(u.origin, u.line, key,
                       "names no parameter of the scene (the --set names: U k c M_r mu m l r f ..., or unroundness)");
    if (!(std::isfinite(u.low) && std::isfinite(u.high) && u.low <= u.high))
      throw InputError(u.origin, u.line, key, fmt::format("the range {}:{} must be finite with LOW <= HIGH", u.low, u.high));
    for (const auto& v : o.uncertain)
      if (&v != &u && v.name == u.name) throw InputError(u.origin, u.line, key, "is given twice");
    for (double x : {u.low, u.high}) {
      Scene s = scene;
      try {
        set_study_input(s, u.name, x, u.origin);
      } catch (const InputError& e) {  // at where the range was given: the option or the scene's line
        throw InputError(u.origin, u.line, key, fmt::format("{} (the range's end {})", e.rule(), x));
      }
    }
  }
}

// The sample's figures from a recorded run (docs/model.md §21.1).
template <int N>
void take_run(OutcomeSample& s, const SimulationResult<N>& r) {
  s.bare_rotor = r.summary.bare_rotor_q_abs;   // (16.5.1) / (21.1) at the run's last speed
  s.balls_fixed = r.summary.balls_held_q_abs;  // the balls held at their start angles
  if (r.status == SimulationStatus::failed) {
    s.outcome = "failed";
    s.reason = r.reason;
    return;
  }
  s.residual = r.summary.residual_q_abs;
  s.peak = r.summary.max_q_abs;
  s.peak_run_up = r.summary.max_q_abs_run_up;
  s.stalled = r.summary.stalled;
  s.settle_time = r.summary.settle_time;
  s.steps = r.stats.steps;
  switch (r.summary.outcome) {
    case SimulationOutcome::balanced: s.outcome = "balanced"; break;
    case SimulationOutcome::aligned: s.outcome = "aligned:" + r.summary.pattern; break;
    case SimulationOutcome::rest: s.outcome = "stuck"; break;
    case SimulationOutcome::periodic: s.outcome = "periodic"; break;
    default: s.outcome = "not_settled"; break;
  }
}

// One run from rest at the sample's start angles (docs/model.md §21.1).
template <int N>
void run_sample(const Scene& scene, const SpeedProfile& speed, const SimulationOptions& base, OutcomeSample& s) {
  ParamsT<double, N> p = params_of<N>(scene);
  p.omega = speed.omega(0.0);
  const RaceShape race = race_shape(scene);
  SimulationOptions o = base;
  if (!race.round()) o.race = &race;
  if (scene.support) o.support = &*scene.support;
  const State<double, N> x0 = start_at_rest(p, s.beta0);
  if (p.law != FrictionLaw::coulomb_set) {
    take_run(s, simulate(p, speed, x0, o));
  } else {  // event-driven stick-slip (model.md §14.5): every ball stuck is a state at rest
    const StickSlipResult<N> r = simulate_stick_slip(p, speed, x0, o);
    take_run(s, r.run);
    if (s.outcome != "failed" && r.end.all_stuck && !r.end.in_set) {
      s.outcome = "failed";
      s.reason = fmt::format("every ball stuck outside the stick set (max |s_i| = {:.9g}, model.md §14.7)", r.end.max_abs_s);
    } else if (s.outcome != "failed" && !r.end.all_stuck && s.outcome != "periodic") {
      s.outcome = "slipping";
    }
    if (r.run.status == SimulationStatus::interrupted) s.outcome = "interrupted";
  }
  // On an unround race the states at rest are the race's equilibria (§11.4), none balanced:
  // `simulate` names them; here a run at rest is `at_rest`.
  if (!race.round() && (s.outcome == "balanced" || s.outcome == "stuck")) s.outcome = "at_rest";
  s.stuck_off_balance = s.outcome == "stuck";
}

// Runs sample s (its start and inputs set): the figures, or `failed` with the reason.
void run_one(const Scene& scene, const SpeedProfile& speed, const OutcomeOptions& o, OutcomeSample& s) {
  const Scene at = scene_of_sample(scene, o, s.inputs);
  SimulationOptions sim = o.sim;
  sim.record = true;
  sim.interrupt = o.interrupt;
  sim.progress = nullptr;
  sim.stop_at_sample = nullptr;
  if (two_ball_storage(at))
    run_sample<2>(at, speed, sim, s);
  else
    run_sample<any_balls>(at, speed, sim, s);
  s.done = s.outcome != "interrupted";
}

FigureStatistics figure(const std::vector<double>& v, double confidence) {
  FigureStatistics f;
  f.count = int(v.size());
  if (v.empty()) return f;
  f.median = quantile_estimate(v, 0.5, confidence);
  f.p90 = quantile_estimate(v, 0.9, confidence);
  f.worst = quantile_estimate(v, 1.0, confidence);
  return f;
}

}  // namespace

std::vector<UncertainInput> study_inputs(const Scene& scene, const std::vector<UncertainInput>& given) {
  std::vector<UncertainInput> out;
  for (const auto& u : scene.uncertain) {
    const bool replaced = std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.name == u.name; });
    if (!replaced) out.push_back({u.name, u.low, u.high, scene.file, u.line});
  }
  out.insert(out.end(), given.begin(), given.end());
  return out;
}

void set_study_input(Scene& scene, const std::string& name, double value, const std::string& origin) {
  if (name == "unroundness") return scale_race(scene, value, origin);
  const auto ref = parse_param(name, int(scene.balls.size()));
  if (!ref) throw InputError(origin, 0, name, "names no parameter of the scene");
  set_checked(scene, *ref, value, origin);
}

UncertainInput parse_uncertain(const std::string& text, const std::string& origin) {
  const auto eq = text.find('=');
  const auto colon = text.find(':', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || eq == 0 || colon == std::string::npos)
    throw InputError(origin, 0, text, "expected NAME=LOW:HIGH, e.g. mu=0.001:0.003");
  UncertainInput u;
  u.name = text.substr(0, eq);
  u.origin = origin;
  const auto bounds = parse_real_list(text.substr(eq + 1, colon - eq - 1) + "," + text.substr(colon + 1), origin);
  if (bounds.size() != 2) throw InputError(origin, 0, text, "expected NAME=LOW:HIGH, e.g. mu=0.001:0.003");
  u.low = bounds[0];
  u.high = bounds[1];
  return u;
}

double steady_whirl_radius(const Scene& scene, double omega, std::complex<double> W) {
  return abu::steady_whirl_radius(total_mass(scene), scene.rotor.stiffness, scene.rotor.damping,
                                  scene.support ? &*scene.support : nullptr, omega, W);
}

double default_outcome_end(const SpeedProfile& speed) { return speed.end_of_change() + 2.0; }

double outcome_memory_estimate(const OutcomeOptions& o, int balls) {
  SimulationOptions sim = o.sim;
  sim.record = true;
  const double per_sample = 400.0 + 8.0 * double(balls + int(o.uncertain.size())) * 3;
  return double(std::max(1, o.threads)) * simulation_memory_estimate(sim, balls, false) + o.samples * per_sample;
}

OutcomeSummary summarize_outcomes(const std::vector<OutcomeSample>& samples, double residual_limit,
                                  double confidence) {
  OutcomeSummary s;
  std::vector<double> residual, ratio_bare, ratio_fixed, peak, settle, bare;
  int balanced = 0, below = 0, stalled = 0, stuck = 0, unsettled = 0;
  for (const auto& x : samples) {
    if (!x.done) continue;
    if (x.outcome == "failed") {
      ++s.failed;
      continue;
    }
    ++s.runs;
    residual.push_back(x.residual);
    bare.push_back(x.bare_rotor);
    if (x.bare_rotor > 0) ratio_bare.push_back(x.residual / x.bare_rotor);
    if (x.balls_fixed > 0) ratio_fixed.push_back(x.residual / x.balls_fixed);
    peak.push_back(x.peak);
    if (x.settle_time) settle.push_back(*x.settle_time);
    balanced += x.outcome == "balanced";
    below += x.residual <= (residual_limit > 0 ? residual_limit : x.bare_rotor);
    stalled += x.stalled;
    stuck += x.stuck_off_balance;
    unsettled += x.outcome == "not_settled" || x.outcome == "slipping";
  }
  s.residual = figure(residual, confidence);
  s.ratio_bare = figure(ratio_bare, confidence);
  s.ratio_fixed = figure(ratio_fixed, confidence);
  s.peak = figure(peak, confidence);
  s.settle_time = figure(settle, confidence);
  if (!bare.empty()) s.bare_rotor_median = quantile_estimate(bare, 0.5, confidence).value;
  s.balanced = proportion_estimate(balanced, s.runs, confidence);
  s.below_limit = proportion_estimate(below, s.runs, confidence);
  s.stalled = proportion_estimate(stalled, s.runs, confidence);
  s.stuck_off_balance = proportion_estimate(stuck, s.runs, confidence);
  s.not_settled = proportion_estimate(unsettled, s.runs, confidence);
  return s;
}

OutcomeStudy analyze_outcomes(const Scene& scene, const SpeedProfile& speed, const OutcomeOptions& o) {
  if (scene.shaft)
    throw NotSupportedError("outcomes: a flexible shaft is not studied over many starts yet; `simulate` and `basin` "
                            "answer it start by start");
  refuse_unmodelled(scene, "outcomes", handles_of("outcomes"));
  if (!(o.confidence > 0 && o.confidence < 1))
    throw InputError("--confidence", 0, "", fmt::format("must lie in (0, 1), got {}", o.confidence));
  if (!(o.residual_limit >= 0 && std::isfinite(o.residual_limit)))
    throw InputError("--limit", 0, "", "the residual limit must be >= 0 m (0: each run's bare rotor)");
  check_uncertain(scene, o);
  const int n = int(scene.balls.size()), dims = n + int(o.uncertain.size());
  {
    SimulationOptions sim = o.sim;  // the runs' options; their memory is the study's estimate below
    sim.record = false;
    const std::vector<double> at_rest(std::size_t(2 * n + 4), 0.0);
    check_simulation_input(sim, 2 * n + 4, at_rest.data(), 2 * n + 4, n);
  }
  OutcomeStudy study;
  study.balls = n;
  study.omega_final = speed.omega(o.sim.t_end);
  study.speed = speed.describe();
  study.options = o;
  study.options.progress = nullptr;
  study.options.interrupt = nullptr;
  study.memory_estimate = outcome_memory_estimate(o, n);
  require_memory(study.memory_estimate, "--samples", "the study", fmt::format("{} runs, {} threads", o.samples, o.threads),
                 "take fewer --samples or a longer --every");
  const std::vector<double> u = sample_points(o.samples, dims, o.design, o.seed);
  study.samples.resize(std::size_t(o.samples));
  for (int k = 0; k < o.samples; ++k) {
    OutcomeSample& s = study.samples[std::size_t(k)];
    s.index = k;
    const double* x = u.data() + std::size_t(k) * std::size_t(dims);
    for (int i = 0; i < n; ++i) s.beta0.push_back(2 * std::numbers::pi * x[i]);
    for (std::size_t j = 0; j < o.uncertain.size(); ++j)
      s.inputs.push_back(o.uncertain[j].low + (o.uncertain[j].high - o.uncertain[j].low) * x[n + int(j)]);
  }
  std::atomic<int> done{0};
  std::mutex report;
  for_each_index(o.samples, std::max(1, o.threads), [&](int k) {
    if (o.interrupt && o.interrupt->load()) return false;
    run_one(scene, speed, o, study.samples[std::size_t(k)]);
    const int d = ++done;
    if (o.progress) {
      const std::lock_guard lock(report);
      o.progress(d, o.samples);
    }
    return true;
  });
  for (const auto& s : study.samples) {
    if (!s.done) study.status.merge(Outcome::not_converged, fmt::format("interrupted: {} of {} runs done", done.load(), o.samples));
    if (s.done && s.outcome == "failed")
      study.status.merge(Outcome::numerical_issue, fmt::format("run {} failed: {}", s.index, s.reason));
  }
  study.summary = summarize_outcomes(study.samples, o.residual_limit, o.confidence);
  return study;
}

}  // namespace abu
