// abu._abu, continued: continuation (the CLI's `continue`, src/cli/continue_command.cpp)
// and simulation (`simulate`, src/cli/simulate_command.cpp), on the same library calls
// and with the same checks, results as dicts of arrays for python/abu/__init__.py.
#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "abu/continuation/branches_n.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/continuation/special_rows.hpp"
#include "abu/core/errors.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/analysis/equilibrium_start.hpp"
#include "abu/analysis/machine_parts.hpp"
#include "abu/analysis/race_end.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/ranges.hpp"
#include "abu/output/report.hpp"
#include "abu/output/report_simulation.hpp"
#include "abu/input/scene.hpp"
#include "abu/scan/scan.hpp"
#include "bindings.hpp"

namespace abu::python {

namespace {

const double nan_value = std::nan("");

// ---------------------------------------------------------------------------------------
// Continuation

// The end value must move the parameter away from the scene's value (as the CLI's check_moves;
// the rest of the parameter's checks is the library's checked_param, input/ranges.hpp).
void check_moves(const Scene& scene, ParamRef ref, const std::string& symbol, double to) {
  const double from = get(params_of<any_balls>(scene), ref);
  if (to == from) throw InputError("to", 0, symbol, fmt::format("must differ from the start value {}", from));
}

py::dict stats_dict(const ContinuationStats& st) {
  py::dict d;
  d["steps"] = st.steps;
  d["rejected"] = st.rejected;
  d["newton_iterations"] = st.newton_iterations;
  d["tracked_spectra"] = st.tracked_spectra;
  d["full_spectra"] = st.full_spectra;
  return d;
}

template <class PointT>
int point_balls(const PointT& pt) {
  return int(pt.position.size()) - 2;
}

// One branch's points as arrays (angles wrapped to [0, 2 pi) as in branch_NAME.csv, and
// as followed, unwrapped).
template <class BranchT>
py::dict branch_dict(const BranchT& b, int n) {
  constexpr bool two = std::is_same_v<BranchT, Branch>;
  const auto P = py::ssize_t(b.points.size());
  const int dim = 2 * n + 4;
  auto parameter = zeros<double>({P}), q = zeros<double>({P, 2}), beta = zeros<double>({P, n});
  auto unwrapped = zeros<double>({P, n}), q_abs = zeros<double>({P}), abscissa = zeros<double>({P});
  auto eigenvalues = zeros<std::complex<double>>({P, dim});
  auto stable = zeros<bool>({P});
  auto n_unstable = zeros<int>({P}), n_structural = zeros<int>({P});
  py::list label, stability, family;
  auto Q = q.mutable_unchecked<2>();
  auto B = beta.mutable_unchecked<2>();
  auto U = unwrapped.mutable_unchecked<2>();
  auto L = eigenvalues.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < P; ++i) {
    const auto& pt = b.points[std::size_t(i)];
    parameter.mutable_data()[i] = double(pt.parameter);
    // q = 0 on balanced points is 0 exactly, as the CLI prints it (the polish leaves ~1e-44).
    bool balanced = b.family == Family::balanced;
    if constexpr (two) balanced = pt.family == Family::balanced;
    Q(i, 0) = balanced ? 0.0 : double(pt.position(0));
    Q(i, 1) = balanced ? 0.0 : double(pt.position(1));
    for (int k = 0; k < n; ++k) {
      B(i, k) = double(wrap_angle(pt.position(2 + k)));
      U(i, k) = double(pt.position(2 + k));
    }
    q_abs.mutable_data()[i] = std::hypot(Q(i, 0), Q(i, 1));
    for (int k = 0; k < pt.spectrum.count && k < dim; ++k) L(i, k) = pt.spectrum.eigenvalues[std::size_t(k)];
    abscissa.mutable_data()[i] = pt.spectrum.abscissa;
    stable.mutable_data()[i] = pt.spectrum.stability == Stability::stable;
    stability.append(std::string(to_string(pt.spectrum.stability)));
    n_unstable.mutable_data()[i] = pt.spectrum.n_unstable;
    n_structural.mutable_data()[i] = pt.spectrum.n_structural;
    label.append(pt.label == Label::none ? std::string() : std::string(to_string(pt.label)));
    if constexpr (two) {
      family.append(std::string(to_string(pt.family)));
    } else {
      family.append(std::string(to_string(b.family)));
    }
  }
  py::dict d;
  d["family"] = std::string(to_string(b.family));
  d["member"] = b.member;
  d["start_parameter"] = double(b.start_parameter);
  d["parameter"] = parameter;
  d["q"] = q;
  d["beta"] = beta;
  d["beta_unwrapped"] = unwrapped;
  d["q_abs"] = q_abs;
  d["eigenvalues"] = eigenvalues;
  d["spectral_abscissa"] = abscissa;
  d["stable"] = stable;
  d["stability"] = stability;
  d["n_unstable"] = n_unstable;
  d["n_structural_zero"] = n_structural;
  d["label"] = label;
  d["point_family"] = family;
  d["stop"] = std::vector<std::string>{std::string(to_string(b.stop[0])), std::string(to_string(b.stop[1]))};
  d["stop_detail"] = std::vector<std::string>{b.stop_detail[0], b.stop_detail[1]};
  if constexpr (two) {
    d["pattern"] = b.family == Family::together ? "++" : b.family == Family::opposite ? "+-" : "";
    d["images"] = 0;
    auto modes = zeros<std::complex<double>>({P, 8});
    auto M = modes.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < P; ++i)
      for (int k = 0; k < 8; ++k) M(i, k) = b.points[std::size_t(i)].modes[std::size_t(k)];
    d["modes"] = modes;
    d["residual"] = py::none();
  } else {
    d["pattern"] = b.family == Family::aligned ? pattern_string(b.pattern, n) : std::string();
    d["images"] = b.images;
    d["modes"] = py::none();
    auto residual = zeros<double>({P});
    for (py::ssize_t i = 0; i < P; ++i) residual.mutable_data()[i] = b.points[std::size_t(i)].residual;
    d["residual"] = residual;
  }
  return d;
}

bool failed_end(StopReason r) { return r == StopReason::step_underflow || r == StopReason::max_steps; }

// Every special point of the run, one row each in special_NAME.csv's order (each branch's
// located points, then an MX row per end that failed), `branch` 1-based.
template <class RunT>
py::dict special_points_dict(const RunT& run, int n) {
  constexpr bool two = std::is_same_v<RunT, ContinuationRun>;
  struct Row {
    int branch = 0;
    std::string label, family, pattern, note;
    int member = 1;
    double parameter = 0, frequency = nan_value, lyapunov = nan_value, bracket_from = nan_value,
           bracket_to = nan_value;
    std::array<double, max_balls + 2> position{};  // q1, q2, beta_1..beta_n (wrapped)
    std::complex<double> eigenvalue{nan_value, nan_value};
    bool converged = false;
    int before = 0, after = 0;
  };
  std::vector<Row> rows;
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    const auto& branch = run.branches[b];
    std::string pattern;
    if constexpr (two) {
      pattern = branch.family == Family::together ? "++" : branch.family == Family::opposite ? "+-" : "";
    } else {
      if (branch.family == Family::aligned) pattern = pattern_string(branch.pattern, n);
    }
    auto position = [&](const auto& s) {
      std::array<double, max_balls + 2> v{};
      for (int k = 0; k < n + 2 && k < int(v.size()); ++k)
        v[std::size_t(k)] = k < 2 ? double(s(k)) : double(wrap_angle(s(k)));
      return v;
    };
    for (const auto& sp : branch.specials) {
      Row r;
      r.branch = int(b) + 1;
      r.label = std::string(to_string(sp.label));
      r.parameter = double(sp.parameter);
      r.position = position(sp.position);
      r.eigenvalue = sp.eigenvalue;
      r.converged = sp.converged;
      r.before = sp.n_unstable_before;
      r.after = sp.n_unstable_after;
      r.bracket_from = double(sp.bracket_from);
      r.bracket_to = double(sp.bracket_to);
      r.note = sp.note;
      r.member = branch.member;
      r.pattern = pattern;
      if constexpr (two) {
        r.family = std::string(to_string(sp.family));
        if (sp.label == Label::HB) r.frequency = sp.frequency;
        if (sp.label == Label::HB && sp.converged) r.lyapunov = sp.lyapunov;
      } else {
        r.family = std::string(to_string(branch.family));
        if (sp.frequency) r.frequency = *sp.frequency;
      }
      if (r.family == "balanced") r.position[0] = r.position[1] = 0.0;  // as the CLI prints it
      rows.push_back(std::move(r));
    }
    for (int end = 0; end < 2; ++end) {
      if (!failed_end(branch.stop[std::size_t(end)])) continue;
      const auto& pt = end == 0 ? branch.points.front() : branch.points.back();
      Row r;
      r.branch = int(b) + 1;
      r.label = "MX";
      r.parameter = double(pt.parameter);
      r.position = position(pt.position);
      r.family = std::string(to_string(branch.family));
      r.pattern = pattern;
      r.member = branch.member;
      r.before = r.after = pt.spectrum.n_unstable;
      r.note = branch.stop_detail[std::size_t(end)];
      rows.push_back(std::move(r));
    }
  }
  const auto K = py::ssize_t(rows.size());
  auto branch = zeros<int>({K}), member = zeros<int>({K}), before = zeros<int>({K}), after = zeros<int>({K});
  auto parameter = zeros<double>({K}), q = zeros<double>({K, 2}), beta = zeros<double>({K, n});
  auto q_abs = zeros<double>({K}), frequency = zeros<double>({K}), lyapunov = zeros<double>({K});
  auto bracket_from = zeros<double>({K}), bracket_to = zeros<double>({K});
  auto eigenvalue = zeros<std::complex<double>>({K});
  auto converged = zeros<bool>({K});
  py::list label, family, pattern, note;
  auto Q = q.mutable_unchecked<2>();
  auto B = beta.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < K; ++i) {
    const Row& r = rows[std::size_t(i)];
    branch.mutable_data()[i] = r.branch;
    label.append(r.label);
    parameter.mutable_data()[i] = r.parameter;
    family.append(r.family);
    pattern.append(r.pattern);
    member.mutable_data()[i] = r.member;
    Q(i, 0) = r.position[0];
    Q(i, 1) = r.position[1];
    for (int k = 0; k < n; ++k) B(i, k) = r.position[std::size_t(k) + 2];
    q_abs.mutable_data()[i] = std::hypot(r.position[0], r.position[1]);
    frequency.mutable_data()[i] = r.frequency;
    eigenvalue.mutable_data()[i] = r.eigenvalue;
    lyapunov.mutable_data()[i] = r.lyapunov;
    converged.mutable_data()[i] = r.converged;
    before.mutable_data()[i] = r.before;
    after.mutable_data()[i] = r.after;
    bracket_from.mutable_data()[i] = r.bracket_from;
    bracket_to.mutable_data()[i] = r.bracket_to;
    note.append(r.note);
  }
  py::dict d;
  d["branch"] = branch;
  d["label"] = label;
  d["parameter"] = parameter;
  d["family"] = family;
  d["pattern"] = pattern;
  d["member"] = member;
  d["q"] = q;
  d["beta"] = beta;
  d["q_abs"] = q_abs;
  d["frequency"] = frequency;
  d["eigenvalue"] = eigenvalue;
  d["lyapunov"] = lyapunov;
  d["converged"] = converged;
  d["n_unstable_before"] = before;
  d["n_unstable_after"] = after;
  d["bracket_from"] = bracket_from;
  d["bracket_to"] = bracket_to;
  d["note"] = note;
  return d;
}

template <class RunT>
py::dict run_dict(const RunT& run, int n) {
  py::dict d;
  d["param"] = to_string(run.param);
  d["from_value"] = run.from;
  d["to_value"] = run.to;
  d["n_balls"] = n;
  d["stats"] = stats_dict(run.stats);
  d["notes"] = run.notes;
  d["warnings"] = continuation_warnings(run);
  py::list branches;
  bool ok = true;
  for (const auto& b : run.branches) {
    branches.append(branch_dict(b, n));
    for (int end = 0; end < 2; ++end) ok = ok && b.stop[std::size_t(end)] != StopReason::step_underflow;
  }
  d["branches"] = branches;
  d["special_points"] = special_points_dict(run, n);
  d["ok"] = ok;
  return d;
}

py::dict continue_run(const Scene& scene, const std::string& param, double to, std::optional<std::string> family,
                      std::optional<std::vector<double>> state, double ds, double ds_min, double ds_max,
                      int max_steps, int samples_per_sheet) {
  if (unround_on_anisotropic_support(scene))
    throw NotSupportedError(fmt::format("abu.continue_branches continues equilibria; {} has an unround race on an "
                                        "anisotropic support, whose states are periodic orbits: abu.continue_orbits "
                                        "continues them (model.md §20.9)",
                                        scene.file));
  require_parts(scene, "continue_branches", {});
  const int n = int(scene.balls.size());
  check_numerical_range(scene, "abu.continue_branches");  // the start, as the CLI checks a scene
  const ParamRef ref = checked_param(scene, "param", param, "to", to);  // the CLI's checks, the same library call
  check_moves(scene, ref, param, to);
  ContinuationOptions options;
  options.ds = ds;
  options.ds_min = ds_min;
  options.ds_max = ds_max;
  options.max_steps = max_steps;
  if (const auto rule = options_violation(options)) throw InputError("options", 0, "", *rule);
  BalancedSampling sampling;
  sampling.samples_per_sheet = samples_per_sheet;
  if (const auto rule = options_violation(sampling)) throw InputError("continue_branches", 0, "samples_per_sheet", *rule);
  if (n != 2) {
    if (family || state)
      throw NotSupportedError(fmt::format("family / state with {} balls (every aligned equilibrium and balanced sample "
                                          "is continued)", n));
    const ParamsN p = params_of<any_balls>(scene);
    ContinuationRunN run;
    {
      py::gil_scoped_release release;
      run = continue_branches(p, ref, to, options, sampling);
      insert_special_rows(p, run);  // the branch CSV's rows at the special points, as the CLI writes them
    }
    py::dict d = run_dict(run, n);
    py::list intervals;
    for (const auto& iv : run.envelope.intervals) {
      py::dict i;
      i["from"] = double(iv.from);
      i["to"] = double(iv.to);
      i["stable"] = iv.stable;
      i["samples"] = iv.samples;
      intervals.append(i);
    }
    py::dict envelope;
    envelope["intervals"] = intervals;
    envelope["samples"] = run.envelope.samples;
    envelope["samples_with_hopf"] = run.envelope.samples_with_hopf;
    d["envelope"] = envelope;
    return d;
  }
  StartSelection start;
  start.family_option = "family";
  if (family) {
    if (*family != "balanced" && *family != "together" && *family != "opposite")
      throw InputError("family", 0, *family, "must be 'balanced', 'together' or 'opposite'");
    if (state) throw InputError("state", 0, "", "give family or state, not both");
    start.family = *family == "balanced" ? Family::balanced : *family == "together" ? Family::together : Family::opposite;
  }
  if (state) {
    if (state->size() != 4)
      throw InputError("state", 0, "", "expected four finite numbers q1,q2,beta1,beta2 (SI)");
    Coordinates<long double, 2> s;
    for (int i = 0; i < 4; ++i) {
      if (!std::isfinite((*state)[std::size_t(i)]))
        throw InputError("state", 0, "", "expected four finite numbers q1,q2,beta1,beta2 (SI)");
      s(i) = (*state)[std::size_t(i)];
    }
    start.state = s;
  }
  const Params p = params_of<2>(scene);
  ContinuationRun run;
  {
    py::gil_scoped_release release;
    run = continue_branches(p, ref, to, options, start);
    insert_special_rows(p, run);  // the branch CSV's rows at the special points, as the CLI writes them
  }
  py::dict d = run_dict(run, 2);
  d["envelope"] = py::none();
  return d;
}

// ---------------------------------------------------------------------------------------
// Simulation

struct SimulationRequest {
  double t_end = 1.0;
  std::optional<std::vector<double>> balls, state;
  std::optional<EquilibriumChoice> equilibrium;  // from_equilibrium
  double perturb = 1e-3;
  std::optional<SpeedProfile> speed;
  SimulationOptions options;
  std::string method = "auto";
};

template <int N>
py::dict simulate_scene(const Scene& scene, SimulationRequest& q) {
  ParamsT<double, N> p = params_of<N>(scene);
  const int n = ball_count(p);
  const SpeedProfile speed = q.speed ? *q.speed : SpeedProfile::constant(scene.omega, scene.file, "speed.omega");
  p.omega = speed.omega(0.0);
  const int starts = int(q.balls.has_value()) + int(q.state.has_value()) + int(q.equilibrium.has_value());
  if (starts != 1) throw InputError("simulate", 0, "", "give exactly one start: balls, state or from_equilibrium");
  State<double, N> x0;
  if (q.balls) x0 = start_at_rest(p, *q.balls);
  if (q.state) {
    if (int(q.state->size()) != 2 * n + 4)
      throw InputError("state", 0, "",
                       fmt::format("a state of {} balls has 2n + 4 = {} values (q1,q2,beta1..,dq1,dq2,dbeta1..), got {}",
                                   n, 2 * n + 4, q.state->size()));
    x0 = State<double, N>::Zero(2 * n + 4);
    for (int i = 0; i < 2 * n + 4; ++i) x0(i) = (*q.state)[std::size_t(i)];
  }
  if (q.equilibrium) {
    if (!(std::isfinite(q.perturb) && q.perturb >= 0 && q.perturb <= 1))
      throw InputError("perturb", 0, "", fmt::format("EPS must lie in [0, 1] (scaled units), got {}", q.perturb));
    x0 = start_from_equilibrium(p, analyze(p), *q.equilibrium, q.perturb, "from_equilibrium");
  }
  SimulationOptions so = q.options;
  // An unround race (model.md §15.6) and an anisotropic support (§20), as `simulate`.
  const RaceShape race = race_shape(scene);
  if constexpr (N == any_balls) {
    if (!race.round()) so.race = &race;
    if (scene.support) so.support = &*scene.support;
  }
  const auto method = integration_method_from_string(q.method);
  if (!method)
    throw InputError("simulate", 0, "method",
                     fmt::format("must be one of auto, bdf, rk8pd, rk4imp, bsimp, rkf45 (got '{}')", q.method));
  so.method = *method;
  if (!(std::isfinite(so.t_end) && so.t_end > 0))
    throw InputError("t_end", 0, "", fmt::format("the end time must be > 0 s (got {})", so.t_end));
  if (!(so.every >= 0)) throw InputError("every", 0, "", "the output interval must be > 0 s");
  if (!(so.settle_tolerance > 0 && so.settle_tolerance < 1)) throw InputError("settle_tol", 0, "", "must lie in (0, 1)");

  // Ctrl-C: the progress hook (called at every sample) looks for Python's signals and
  // stops the run; the KeyboardInterrupt is raised once it has returned.
  std::atomic<bool> stop{false};
  bool interrupted = false;
  so.interrupt = &stop;
  so.progress = [&](double) {
    if (!interrupted && python_signal_pending()) interrupted = true, stop = true;
  };
  SimulationResult<N> r;
  {
    py::gil_scoped_release release;
    r = simulate(p, speed, x0, so);
  }
  if (interrupted) throw py::error_already_set();
  if constexpr (N == any_balls) judge_race_end(r, p, speed, race, so.support, so.settle_tolerance);  // §15.7, §20.8

  const auto S = py::ssize_t(r.samples.size());
  const int dim = 2 * n + 4;
  auto t = zeros<double>({S}), omega = zeros<double>({S}), state = zeros<double>({S, dim});
  auto X = state.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < S; ++i) {
    const auto& s = r.samples[std::size_t(i)];
    t.mutable_data()[i] = s.t;
    omega.mutable_data()[i] = s.omega;
    for (int k = 0; k < dim; ++k) X(i, k) = s.x(k);
  }
  auto x_end = zeros<double>({dim});
  for (int k = 0; k < dim && k < r.x_end.size(); ++k) x_end.mutable_data()[k] = r.x_end(k);
  const SimulationSummary& m = r.summary;
  py::dict summary;
  summary["outcome"] = to_string(m.outcome);
  summary["pattern"] = m.pattern;
  summary["note"] = m.note;
  summary["t_end"] = m.t_end;
  summary["state_end"] = array_of(m.state_end);
  summary["max_q_abs"] = m.max_q_abs;
  summary["t_max_q_abs"] = m.t_max_q_abs;
  summary["settle_time"] = m.settle_time ? py::object(py::float_(*m.settle_time)) : py::object(py::none());
  summary["window_from"] = m.window_from;
  summary["stalled"] = m.stalled;
  summary["stalled_balls"] = m.stalled_balls;
  summary["ball_speed_fixed"] = array_of(m.ball_speed_fixed);
  summary["omega_mean_window"] = m.omega_mean_window;
  summary["omega_n"] = m.omega_n;
  summary["t_omega_n"] = array_of(m.t_omega_n);
  summary["max_q_abs_run_up"] =
      m.max_q_abs_run_up ? py::object(py::float_(*m.max_q_abs_run_up)) : py::object(py::none());
  summary["speed_changing_at_end"] = m.speed_changing_at_end;
  if (m.unround_member > 0)  // model.md §15.7
    summary["unround_equilibrium"] =
        py::dict(py::arg("member") = m.unround_member, py::arg("q_abs") = m.unround_q_abs,
                 py::arg("distance") = m.unround_distance);
  if (m.orbit_member > 0)  // model.md §20.8
    summary["periodic_orbit"] = py::dict(py::arg("member") = m.orbit_member, py::arg("q_abs_max") = m.orbit_q_abs_max,
                                         py::arg("distance") = m.orbit_distance);
  py::dict stats;
  stats["steps"] = r.stats.steps;
  stats["rejected"] = r.stats.rejected;
  stats["rhs_evaluations"] = r.stats.rhs_evaluations;
  stats["jacobian_evaluations"] = r.stats.jacobian_evaluations;
  stats["restarts"] = r.stats.restarts;
  stats["wall_seconds"] = r.stats.wall_seconds;
  py::dict d;
  d["n_balls"] = n;
  d["t"] = t;
  d["omega"] = omega;
  d["state"] = state;
  d["x_end"] = x_end;
  d["t_reached"] = r.t_reached;
  d["status"] = to_string(r.status);
  d["reason"] = r.reason;
  d["method"] = to_string(r.method);
  d["spectral_radius"] = r.spectral_radius;
  d["stiffness_ratio"] = r.stiffness_ratio;
  d["displacement_scale"] = r.displacement_scale;
  d["start_below_resolution"] = r.start_below_resolution;
  d["speed"] = speed.describe();
  d["stats"] = stats;
  d["summary"] = summary;
  d["text"] = r.samples.empty() ? std::string() : simulation_text(r, speed);
  return d;
}

py::dict simulate_run(const Scene& scene, double t_end, std::optional<std::vector<double>> balls,
                      std::optional<std::vector<double>> state, std::optional<std::string> from_equilibrium,
                      std::optional<double> perturb, std::optional<std::vector<double>> ramp,
                      std::optional<std::vector<std::pair<double, double>>> speed_profile, const std::string& method,
                      double rtol, double every, unsigned long max_steps, double settle_tol) {
  // Smooth laws on a rigid rotor with any of its parts (docs/cli.md's table, `simulate`).
  require_parts(scene, "simulate", {.unround = true, .anisotropic = true, .unround_anisotropic = true});
  check_numerical_range(scene, "abu.simulate");
  SimulationRequest q;
  q.balls = std::move(balls);
  q.state = std::move(state);
  if (perturb && !from_equilibrium) throw InputError("perturb", 0, "", "perturb goes with from_equilibrium");
  if (from_equilibrium) {
    q.equilibrium = parse_equilibrium_choice(*from_equilibrium, "from_equilibrium", !scene.race.round(), "balls", "state");
    q.perturb = perturb.value_or(1e-3);
  }
  if (ramp && speed_profile) throw InputError("simulate", 0, "", "give ramp or speed_profile, not both");
  if (ramp) {
    if (ramp->size() != 3) throw InputError("ramp", 0, "", "expected (omega0, omega1, alpha)");
    q.speed = SpeedProfile::ramp((*ramp)[0], (*ramp)[1], (*ramp)[2], "ramp");
  }
  if (speed_profile) {
    std::vector<SpeedProfile::Point> points;
    for (const auto& [time, w] : *speed_profile) points.push_back({time, w});
    q.speed = SpeedProfile::piecewise_linear(std::move(points), "speed_profile");
  }
  q.options.t_end = t_end;
  q.options.rtol = rtol;
  q.options.every = every;
  q.options.max_steps = max_steps;
  q.options.settle_tolerance = settle_tol;
  q.method = method;
  if (two_ball_storage(scene)) return simulate_scene<2>(scene, q);  // as the CLI's simulate
  return simulate_scene<any_balls>(scene, q);
}

}  // namespace

void bind_runs(py::module_& m) {
  m.def("continue_branches", &continue_run, py::arg("scene"), py::arg("param"), py::arg("to"), py::arg("family"),
        py::arg("state"), py::arg("ds"), py::arg("ds_min"), py::arg("ds_max"), py::arg("max_steps"),
        py::arg("samples_per_sheet"),
        "Continuation of every equilibrium branch in PARAM up to TO, as a dict (abu.continue_branches wraps it).");
  m.def("simulate", &simulate_run, py::arg("scene"), py::arg("t_end"), py::arg("balls"), py::arg("state"),
        py::arg("from_equilibrium"), py::arg("perturb"), py::arg("ramp"), py::arg("speed_profile"), py::arg("method"),
        py::arg("rtol"), py::arg("every"), py::arg("max_steps"), py::arg("settle_tol"),
        "A trajectory and its summary, as a dict (abu.simulate wraps it).");
}

}  // namespace abu::python
