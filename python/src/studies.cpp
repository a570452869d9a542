// abu._abu, continued: the outcome study (the CLI's `outcomes`) and the design study (`design`),
// on the same library calls with the same option parsers, so that bad values raise the CLI's
// messages; results as dicts (the statistics as the CLI's JSON, the runs as arrays).
#include <optional>
#include <string>
#include <vector>

#include "abu/analysis/design_study.hpp"
#include "abu/analysis/outcomes.hpp"
#include "abu/output/report_design.hpp"
#include "abu/output/report_outcomes.hpp"
#include "bindings.hpp"

namespace abu::python {

namespace {

// The run's speed: a ramp (omega0, omega1, alpha), else the scene's [simulate] run-up, else its speed.
SpeedProfile speed_of(const Scene& scene, const std::optional<std::vector<double>>& ramp) {
  if (ramp) {
    if (ramp->size() != 3) throw InputError("ramp", 0, "", "expected (omega0, omega1, alpha)");
    return SpeedProfile::ramp((*ramp)[0], (*ramp)[1], (*ramp)[2], "ramp");
  }
  if (scene.simulate && scene.simulate->speed) return *scene.simulate->speed;
  return SpeedProfile::constant(scene.omega, scene.file, "speed.omega");
}

struct RunOptions {
  std::optional<double> t_end;
  int samples = 256;
  unsigned long seed = 1;
  std::string design = "sobol", method = "auto";
  std::vector<std::string> uncertain;
  double limit = 0, confidence = 0.95, rtol = 1e-7, every = 0;
  int threads = 1;
};

OutcomeOptions options_of(const Scene& scene, const RunOptions& r, const SpeedProfile& speed) {
  OutcomeOptions o;
  o.samples = r.samples;
  o.seed = r.seed;
  const auto design = sample_design_from_string(r.design);
  if (!design) throw InputError("design", 0, r.design, "expected 'sobol' or 'random'");
  o.design = *design;
  std::vector<UncertainInput> given;
  for (const auto& u : r.uncertain) given.push_back(parse_uncertain(u, "uncertain"));
  o.uncertain = study_inputs(scene, given);  // the scene's [uncertain], the call's replacing an entry
  o.residual_limit = r.limit;
  o.confidence = r.confidence;
  o.threads = r.threads;
  o.sim.t_end = r.t_end ? *r.t_end : default_outcome_end(speed);
  o.sim.rtol = r.rtol;
  o.sim.every = r.every;
  const auto method = integration_method_from_string(r.method);
  if (!method) throw InputError("method", 0, r.method, "expected auto, bdf, rk8pd, rk4imp, bsimp or rkf45");
  o.sim.method = *method;
  return o;
}

py::dict outcomes(const Scene& scene, const std::optional<std::vector<double>>& ramp, const RunOptions& r) {
  const SpeedProfile speed = speed_of(scene, ramp);
  const OutcomeOptions o = options_of(scene, r, speed);
  OutcomeStudy study;
  {
    py::gil_scoped_release release;
    study = analyze_outcomes(scene, speed, o);
  }
  py::dict d;
  d["summary"] = py::module_::import("json").attr("loads")(outcomes_json(study, "abu.outcomes", scene.file));
  std::vector<double> residual, bare, fixed, peak, settle;
  std::vector<std::string> outcome;
  std::vector<bool> stalled, stuck;
  py::list beta0, inputs;
  for (const auto& s : study.samples) {
    if (!s.done) continue;
    beta0.append(array_of(s.beta0));
    inputs.append(array_of(s.inputs));
    outcome.push_back(s.outcome);
    residual.push_back(s.residual);
    bare.push_back(s.bare_rotor);
    fixed.push_back(s.balls_fixed);
    peak.push_back(s.peak);
    settle.push_back(s.settle_time ? *s.settle_time : std::nan(""));
    stalled.push_back(s.stalled);
    stuck.push_back(s.stuck_off_balance);
  }
  d["beta0"] = beta0;
  d["inputs"] = inputs;
  d["outcome"] = outcome;
  d["residual_q"] = array_of(residual);
  d["bare_rotor_q"] = array_of(bare);
  d["balls_fixed_q"] = array_of(fixed);
  d["peak_q"] = array_of(peak);
  d["settle_time"] = array_of(settle);
  d["stalled"] = bool_array_of(stalled);
  d["stuck_off_balance"] = bool_array_of(stuck);
  d["csv"] = outcomes_csv(study, "");
  return d;
}

py::dict design(const Scene& scene, const std::vector<std::string>& vary, const std::string& objective,
                const std::vector<std::string>& constraints, bool optimize, int max_evaluations,
                const std::optional<std::vector<double>>& ramp, const RunOptions& r) {
  const SpeedProfile speed = speed_of(scene, ramp);
  DesignOptions o;
  o.outcomes = options_of(scene, r, speed);
  for (const auto& v : vary) o.variables.push_back(parse_design_variable(v, "vary"));
  o.objective = parse_design_objective(objective, "objective");
  for (const auto& c : constraints) o.constraints.push_back(parse_design_constraint(c, "constraint"));
  o.optimize = optimize;
  o.max_evaluations = max_evaluations;
  DesignStudy study;
  {
    py::gil_scoped_release release;
    study = run_design_study(scene, speed, o);
  }
  py::dict d = py::module_::import("json").attr("loads")(design_json(study, "abu.design", scene.file));
  d["text"] = design_text(study);
  d["csv"] = design_csv(study, "");
  return d;
}

}  // namespace

void bind_studies(py::module_& m) {
  m.def(
      "outcomes",
      [](const Scene& scene, std::optional<std::vector<double>> ramp, std::optional<double> t_end, int samples,
         unsigned long seed, const std::string& design_kind, const std::vector<std::string>& uncertain, double limit,
         double confidence, int threads, double rtol, double every, const std::string& method) {
        return outcomes(scene, ramp,
                        RunOptions{t_end, samples, seed, design_kind, method, uncertain, limit, confidence, rtol, every,
                                   threads});
      },
      py::arg("scene"), py::arg("ramp"), py::arg("t_end"), py::arg("samples"), py::arg("seed"), py::arg("design"),
      py::arg("uncertain"), py::arg("limit"), py::arg("confidence"), py::arg("threads"), py::arg("rtol"),
      py::arg("every"), py::arg("method"), "The outcome study (abu.outcomes wraps it).");
  m.def(
      "design",
      [](const Scene& scene, const std::vector<std::string>& vary, const std::string& objective,
         const std::vector<std::string>& constraints, bool optimize, int max_evaluations,
         std::optional<std::vector<double>> ramp, std::optional<double> t_end, int samples, unsigned long seed,
         const std::string& design_kind, const std::vector<std::string>& uncertain, double limit, int threads) {
        return design(scene, vary, objective, constraints, optimize, max_evaluations, ramp,
                      RunOptions{t_end, samples, seed, design_kind, "auto", uncertain, limit, 0.95, 1e-7, 0, threads});
      },
      py::arg("scene"), py::arg("vary"), py::arg("objective"), py::arg("constraints"), py::arg("optimize"),
      py::arg("max_evaluations"), py::arg("ramp"), py::arg("t_end"), py::arg("samples"), py::arg("seed"),
      py::arg("design"), py::arg("uncertain"), py::arg("limit"), py::arg("threads"),
      "The design study (abu.design wraps it).");
}

}  // namespace abu::python
