// abu._abu, the compiled part of the Python module (docs/python.md): the library's errors
// as Python exceptions, scenes, equilibria with their spectra, and stability maps. The
// functions call what the CLI's commands call (src/cli/*_command.cpp), so the numbers are
// the CLI's numbers; continuation and simulation are in runs.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include "abu/core/errors.hpp"
#include "abu/output/format.hpp"
#include "abu/output/provenance.hpp"
#include "abu/analysis/map_setup.hpp"
#include "abu/analysis/equilibria.hpp"
#include "abu/output/equilibria_report.hpp"
#include "abu/output/report.hpp"
#include "abu/input/scene.hpp"
#include "abu/scan/scan.hpp"
#include "abu/input/ranges.hpp"
#include "bindings.hpp"

namespace abu::python {

namespace {

// ---------------------------------------------------------------------------------------
// Scenes

// The value of a parameter by its model.md symbol (an every-ball symbol: ball 1's value,
// as params.hpp's get says).
double scene_get(const Scene& scene, const std::string& name) {
  const auto ref = parse_param(name, int(scene.balls.size()));
  if (!ref) throw InputError("get", 0, name, fmt::format("unknown parameter; known: {}", param_symbols_help()));
  return get(params_of<any_balls>(scene), *ref);
}

// `--set NAME=VALUE` with VALUE written in the shortest form that reads back to the same
// double, so that the override goes through the CLI's parser and rules (apply_override).
void scene_set(Scene& scene, const std::string& name, double value) {
  apply_override(scene, fmt::format("{}={}", name, value));
}

std::string scene_repr(const Scene& s) {
  return fmt::format("<abu.Scene '{}': {} balls{}, {} friction, omega = {} rad/s>", s.file, s.balls.size(),
                     s.ring ? " (ring)" : "", to_string(s.law), s.omega);
}

// ---------------------------------------------------------------------------------------
// Equilibria

// Every equilibrium of one analysis as arrays, row i = equilibrium i in the CLI's order
// (equilibria --format csv/json): the same doubles the CSV prints.
template <class A, int N>
py::dict equilibria_dict(const A& a, const ParamsT<double, N>& p, const EquilibriaReport& report) {
  const auto points = a.equilibria.points();
  const auto rows = py::ssize_t(points.size());
  const int n = p.n_balls(), dim = 2 * n + 4;
  auto q = zeros<double>({rows, 2}), beta = zeros<double>({rows, n}), q_abs = zeros<double>({rows});
  auto residual = zeros<double>({rows}), abscissa = zeros<double>({rows});
  auto eigenvalues = zeros<std::complex<double>>({rows, dim});
  auto error = zeros<double>({rows, dim}), condition = zeros<double>({rows, dim});
  auto structural = zeros<bool>({rows, dim}), on_axis = zeros<bool>({rows, dim});
  auto member = zeros<int>({rows}), newton = zeros<int>({rows}), n_unstable = zeros<int>({rows});
  auto n_marginal = zeros<int>({rows}), n_structural = zeros<int>({rows});
  auto stable = zeros<bool>({rows}), converged = zeros<bool>({rows}), spectrum_converged = zeros<bool>({rows});
  auto ill = zeros<bool>({rows}), is_set = zeros<bool>({rows}), on_set = zeros<bool>({rows});
  py::list family, pattern, stability, status, reason;
  auto Q = q.mutable_unchecked<2>();
  auto B = beta.mutable_unchecked<2>();
  auto L = eigenvalues.mutable_unchecked<2>();
  auto E = error.mutable_unchecked<2>();
  auto C = condition.mutable_unchecked<2>();
  auto S = structural.mutable_unchecked<2>();
  auto X = on_axis.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < rows; ++i) {
    const auto& e = points[std::size_t(i)];
    const auto& sp = a.spectra[std::size_t(i)];
    family.append(std::string(to_string(e.family)));
    pattern.append(e.family == Family::balanced ? std::string() : pattern_string(e.pattern, n));
    member.mutable_data()[i] = e.member;
    Q(i, 0) = double(e.position(0));
    Q(i, 1) = double(e.position(1));
    for (int b = 0; b < n; ++b) B(i, b) = double(e.position(2 + b));
    q_abs.mutable_data()[i] = std::hypot(double(e.position(0)), double(e.position(1)));
    residual.mutable_data()[i] = e.residual;
    newton.mutable_data()[i] = e.newton_iterations;
    converged.mutable_data()[i] = e.converged;
    is_set.mutable_data()[i] = e.is_set;
    on_set.mutable_data()[i] = e.on_balanced_set;
    for (int k = 0; k < sp.count && k < dim; ++k) {
      const auto kk = std::size_t(k);
      L(i, k) = sp.eigenvalues[kk];
      E(i, k) = sp.error[kk];
      // As the JSON's null: a structural zero has no condition number, nor has an eigenvalue 0.
      C(i, k) = std::isfinite(sp.condition[kk]) && !sp.structural[kk] ? sp.condition[kk] : std::nan("");
      S(i, k) = sp.structural[kk];
      X(i, k) = sp.on_axis[kk];
    }
    abscissa.mutable_data()[i] = sp.abscissa;
    stability.append(std::string(to_string(sp.stability)));
    stable.mutable_data()[i] = sp.stability == Stability::stable;
    n_unstable.mutable_data()[i] = sp.n_unstable;
    n_marginal.mutable_data()[i] = sp.n_marginal;
    n_structural.mutable_data()[i] = sp.n_structural;
    ill.mutable_data()[i] = sp.ill_conditioned;
    spectrum_converged.mutable_data()[i] = sp.converged;
    // One status per equilibrium: the polish's, then the spectrum's (the worse one wins).
    Status st = e.status;
    st.merge(sp.status);
    status.append(outcome_name(st));
    reason.append(std::string(st.reason));
  }
  py::dict d;
  d["n_balls"] = n;
  d["omega"] = p.omega;
  d["family"] = family;
  d["pattern"] = pattern;
  d["member"] = member;
  d["q"] = q;
  d["beta"] = beta;
  d["q_abs"] = q_abs;
  d["residual"] = residual;
  d["newton_iterations"] = newton;
  d["converged"] = converged;
  d["is_set"] = is_set;
  d["on_balanced_set"] = on_set;
  d["eigenvalues"] = eigenvalues;
  d["error"] = error;
  d["condition"] = condition;
  d["structural"] = structural;
  d["on_axis"] = on_axis;
  d["spectral_abscissa"] = abscissa;
  d["stability"] = stability;
  d["stable"] = stable;
  d["n_unstable"] = n_unstable;
  d["n_marginal"] = n_marginal;
  d["n_structural_zero"] = n_structural;
  d["ill_conditioned"] = ill;
  d["spectrum_converged"] = spectrum_converged;
  d["status"] = status;
  d["reason"] = reason;
  d["degeneracy"] = a.equilibria.degeneracy;
  d["degeneracies"] = describe_degeneracy(a.equilibria.degeneracy);
  d["warnings"] = analysis_warnings(a, fmt::format("omega={}", p.omega));
  d["table"] = equilibria_text(report, "table", OutputContext{});
  return d;
}

// A scene beyond the rigid rotor's smooth laws (a shaft, LuGre, coulomb-set, an unround race,
// an anisotropic support, a composition of §20): the CLI's JSON object of the same report,
// its table and its stderr lines (abu.MachineEquilibria).
py::dict machine_equilibria_dict(const Scene& scene, const EquilibriaReport& report) {
  const OutputContext context{"", scene.file, SpeedUnit::rad_per_s};
  py::dict d;
  d["kind"] = "machine";
  d["route"] = std::string(to_string(route_of(scene)));
  d["json"] = py::module_::import("json").attr("loads")(equilibria_text(report, "json", context));
  d["table"] = equilibria_text(report, "table", context);
  d["warnings"] = equilibria_warnings(report);
  return d;
}

py::dict equilibria(const Scene& scene, int samples_per_sheet) {
  check_numerical_range(scene, "abu.equilibria");  // the CLI's range checks (input/ranges.hpp)
  EquilibriaOptions options;
  options.sampling.samples_per_sheet = samples_per_sheet;
  if (const auto rule = options_violation(options.sampling)) throw InputError("equilibria", 0, "samples_per_sheet", *rule);
  // As the CLI's `equilibria`: the same analysis call (two balls on the fixed-size path).
  EquilibriaReport report;
  {
    py::gil_scoped_release release;
    report = analyze_equilibria(scene, options);
  }
  if (const auto* two = std::get_if<RigidStates2>(&report.states)) return equilibria_dict(two->analysis, two->params, report);
  if (!std::holds_alternative<RigidStatesN>(report.states)) return machine_equilibria_dict(scene, report);
  const auto& any = std::get<RigidStatesN>(report.states);
  py::dict d = equilibria_dict(any.analysis, any.params, report);
  const auto& info = any.analysis.equilibria.balanced_set;
  py::dict set;
  set["exists"] = info.exists;
  set["dimension"] = info.dimension;
  set["grid"] = info.grid;
  set["grid_points"] = info.grid_points;
  set["samples"] = info.samples;
  d["balanced_set"] = set;
  return d;
}

// ---------------------------------------------------------------------------------------
// Maps

// What the map keeps of a cell, for both kinds of map (two balls / any count): the
// summary CSV's columns, and the long CSV's rows.
struct CellSummary {
  int balls = 2;
  int balanced = 0, together = 0, opposite = 0;  // two balls
  double balanced_stable = std::nan("");         // 1, 0, or NaN: no balanced state
  double capacity = 0, unbalance = 0;            // n balls
  bool balanced_exists = false;
  int balanced_samples = 0;
  double balanced_stable_fraction = std::nan(""), normal_abscissa_max = std::nan("");
  int aligned = 0, aligned_stable = 0;
  int n_stable = 0;
  std::string best_family, best_pattern;
  int best_member = 0;
  double best_q_abs = std::nan("");
  unsigned degeneracy = 0;
  int fallbacks = 0;
};
struct CellRow {
  int ix = 0, iy = 0, balls = 2;
  Family family = Family::balanced;
  unsigned pattern = 0;
  int member = 1, n_unstable = 0, n_structural = 0;
  bool stable = false;
  double abscissa = 0, q_abs = 0;
  std::array<double, max_balls> beta{};
  int n_undecided = 0;  ///< two balls: the map's undecided eigenvalues (scan/map.hpp); n balls 0
};

void check_cell_finite(double v, const MapJob& job, int ix, int iy, const char* what) {
  if (!std::isfinite(v))
    throw NumericalError(fmt::format("map cell ({}, {}) at {} = {}, {} = {}: {} is not finite", ix, iy, job.x.name(),
                                     job.x.value(ix), job.y.name(), job.y.value(iy), what));
}

// One tile (the columns compute_tile takes, in its order: the analyzers keep per-column
// state, so the cells are those of the CLI's map whatever the thread count).
void map_tile(const MapJob& job, int tile, CellWorkspace& ws, std::vector<CellSummary>& cells,
              std::vector<std::vector<CellRow>>& rows_of_column) {
  const int first = tile * job.tile_columns(), last = std::min(job.x.count, first + job.tile_columns());
  for (int ix = first; ix < last; ++ix) {
    auto& rows = rows_of_column[std::size_t(ix)];
    for (int iy = 0; iy < job.y.count; ++iy) {
      CellSummary& s = cells[std::size_t(ix) * std::size_t(job.y.count) + std::size_t(iy)];
      if (job.any_balls) {
        ws.any_balls->analyze(ix, iy, ws.cell_n);
        const MapCellN& c = ws.cell_n;
        s.balls = c.n_balls;
        s.capacity = c.capacity;
        s.unbalance = c.unbalance;
        s.balanced_exists = c.balanced_exists;
        s.balanced_samples = c.balanced_samples;
        if (c.balanced_samples > 0) {
          s.balanced_stable_fraction = double(c.balanced_stable) / double(c.balanced_samples);
          s.normal_abscissa_max = c.normal_abscissa_max;
          check_cell_finite(s.normal_abscissa_max, job, ix, iy, "the normal abscissa");
        }
        s.aligned = c.aligned;
        s.aligned_stable = c.aligned_stable;
        s.degeneracy = c.degeneracy;
        s.fallbacks = int(c.equilibria.size());
        for (const MapEquilibriumN& e : c.equilibria) {
          s.n_stable += e.stable;
          check_cell_finite(e.abscissa, job, ix, iy, "a spectral abscissa");
          check_cell_finite(e.q_abs, job, ix, iy, "|q|");
          CellRow r{ix, iy, c.n_balls, e.family, e.pattern, e.member, e.n_unstable, e.n_structural, e.stable,
                    e.abscissa, e.q_abs, e.beta};
          rows.push_back(r);
        }
        if (const int best = c.best_stable(); best >= 0) {
          const MapEquilibriumN& e = c.equilibria[std::size_t(best)];
          s.best_family = std::string(to_string(e.family));
          s.best_pattern = e.family == Family::balanced ? std::string() : pattern_string(e.pattern, c.n_balls);
          s.best_member = e.member;
          s.best_q_abs = e.q_abs;
        }
      } else {
        ws.two_balls->analyze(ix, iy, ws.cell);
        const MapCell& c = ws.cell;
        int balanced_stable = -1;
        for (int k = 0; k < c.count; ++k) {
          const MapEquilibrium& e = c.equilibria[std::size_t(k)];
          (e.family == Family::balanced ? s.balanced : e.family == Family::together ? s.together : s.opposite)++;
          s.n_stable += e.stable;
          if (e.family == Family::balanced) balanced_stable = std::max(balanced_stable, int(e.stable));
          check_cell_finite(e.abscissa, job, ix, iy, "a spectral abscissa");
          check_cell_finite(e.q_abs, job, ix, iy, "|q|");
          const CellRow r{ix,       iy,         2,       e.family,           0, e.member, e.n_unstable, 0,
                          e.stable, e.abscissa, e.q_abs, {e.beta1, e.beta2}, e.n_undecided};
          rows.push_back(r);
        }
        if (balanced_stable >= 0) s.balanced_stable = balanced_stable;
        if (const int best = c.best_stable(); best >= 0) {
          const MapEquilibrium& e = c.equilibria[std::size_t(best)];
          s.best_family = std::string(to_string(e.family));
          s.best_member = e.member;
          s.best_q_abs = e.q_abs;
        }
        s.degeneracy = c.degeneracy;
        s.fallbacks = c.fallbacks;
      }
    }
  }
}

py::dict map(const Scene& scene, const std::string& x, const std::string& y, const std::string& method,
             int samples_per_sheet, int threads) {
  require_parts(scene, "map", {.lugre = true});
  if (method != "fast" && method != "full")
    throw InputError("map", 0, "method", fmt::format("must be 'fast' or 'full', got '{}'", method));
  if (threads < 1 || threads > 1024) throw InputError("map", 0, "threads", "must lie in 1..1024");
  MapRequest request;
  request.x = x;
  request.y = y;
  request.method = method == "full" ? CellMethod::full : CellMethod::fast;
  request.sampling.samples_per_sheet = samples_per_sheet;
  if (const auto rule = options_violation(request.sampling)) throw InputError("map", 0, "samples_per_sheet", *rule);
  const MapJob job = map_job(scene, request);  // axes checked against the scene: InputError
  const int nx = job.x.count, ny = job.y.count, tiles = tile_count(job);
  std::vector<CellSummary> cells(std::size_t(nx) * std::size_t(ny));
  std::vector<std::vector<CellRow>> rows_of_column(static_cast<std::size_t>(nx));
  std::exception_ptr failure;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::atomic<int> next{0}, running{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;
    std::condition_variable finished;
    auto worker = [&] {
      try {
        CellWorkspace ws(job);
        for (int t = next++; t < tiles && !stop; t = next++) map_tile(job, t, ws, cells, rows_of_column);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
      }
      const std::lock_guard lock(mutex);
      --running;
      finished.notify_all();
    };
    const int count = std::max(1, std::min(threads, tiles));
    running = count;
    std::vector<std::thread> pool;
    for (int i = 0; i < count; ++i) pool.emplace_back(worker);
    // The calling thread watches for Ctrl-C (Python's handlers run only on it) and stops
    // the workers after their current tile.
    {
      std::unique_lock lock(mutex);
      while (running > 0) {
        finished.wait_for(lock, std::chrono::milliseconds(100));
        if (running > 0 && !interrupted) {
          lock.unlock();
          if (python_signal_pending()) interrupted = true, stop = true;
          lock.lock();
        }
      }
    }
    for (auto& th : pool) th.join();
  }
  if (interrupted) throw py::error_already_set();
  if (failure) std::rethrow_exception(failure);

  // The summary: 2-D arrays indexed [ix, iy], as the summary CSV's rows.
  const bool n_map = job.any_balls;
  auto x_values = zeros<double>({nx}), y_values = zeros<double>({ny});
  for (int i = 0; i < nx; ++i) x_values.mutable_data()[i] = job.x.value(i);
  for (int i = 0; i < ny; ++i) y_values.mutable_data()[i] = job.y.value(i);
  auto grid_int = [&] { return zeros<int>({nx, ny}); };
  auto grid_double = [&] { return zeros<double>({nx, ny}); };
  auto n_stable = grid_int(), best_member = grid_int(), degenerate = grid_int(), fallbacks = grid_int();
  auto best_q_abs = grid_double();
  py::list best_family, best_pattern;  // flat, [ix * ny + iy]: __init__.py makes them 2-D str arrays
  py::dict summary;
  if (n_map) {
    auto balls = grid_int(), samples = grid_int(), aligned = grid_int(), aligned_stable = grid_int();
    auto exists = zeros<bool>({nx, ny});
    auto capacity = grid_double(), unbalance = grid_double(), fraction = grid_double(), normal_max = grid_double();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const CellSummary& s = cells[c];
      balls.mutable_data()[c] = s.balls;
      capacity.mutable_data()[c] = s.capacity;
      unbalance.mutable_data()[c] = s.unbalance;
      exists.mutable_data()[c] = s.balanced_exists;
      samples.mutable_data()[c] = s.balanced_samples;
      fraction.mutable_data()[c] = s.balanced_stable_fraction;
      normal_max.mutable_data()[c] = s.normal_abscissa_max;
      aligned.mutable_data()[c] = s.aligned;
      aligned_stable.mutable_data()[c] = s.aligned_stable;
    }
    summary["balls"] = balls;
    summary["capacity"] = capacity;
    summary["U"] = unbalance;
    summary["balanced_exists"] = exists;
    summary["balanced_samples"] = samples;
    summary["balanced_stable_fraction"] = fraction;
    summary["normal_abscissa_max"] = normal_max;
    summary["aligned"] = aligned;
    summary["aligned_stable"] = aligned_stable;
  } else {
    auto balanced = grid_int(), together = grid_int(), opposite = grid_int();
    auto balanced_stable = grid_double();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const CellSummary& s = cells[c];
      balanced.mutable_data()[c] = s.balanced;
      together.mutable_data()[c] = s.together;
      opposite.mutable_data()[c] = s.opposite;
      balanced_stable.mutable_data()[c] = s.balanced_stable;
    }
    summary["balanced"] = balanced;
    summary["together"] = together;
    summary["opposite"] = opposite;
    summary["balanced_stable"] = balanced_stable;
  }
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const CellSummary& s = cells[c];
    n_stable.mutable_data()[c] = s.n_stable;
    best_member.mutable_data()[c] = s.best_member;
    best_q_abs.mutable_data()[c] = s.best_q_abs;
    degenerate.mutable_data()[c] = int(s.degeneracy);
    fallbacks.mutable_data()[c] = s.fallbacks;
    best_family.append(s.best_family);
    best_pattern.append(s.best_pattern);
  }
  summary["n_stable"] = n_stable;
  summary["best_family"] = best_family;
  if (n_map) summary["best_pattern"] = best_pattern;
  summary["best_member"] = best_member;
  summary["best_q_abs"] = best_q_abs;
  summary["degenerate"] = degenerate;
  summary["fallbacks"] = fallbacks;

  // The long table: one row per equilibrium per cell, cells ix outer, iy inner.
  std::size_t total = 0;
  for (const auto& rows : rows_of_column) total += rows.size();
  const auto nr = py::ssize_t(total);
  const int max_n = job.max_balls_in_map();
  auto r_ix = zeros<int>({nr}), r_iy = zeros<int>({nr}), r_balls = zeros<int>({nr}), r_member = zeros<int>({nr});
  auto r_unstable = zeros<int>({nr}), r_structural = zeros<int>({nr}), r_undecided = zeros<int>({nr});
  auto r_stable = zeros<bool>({nr});
  auto r_abscissa = zeros<double>({nr}), r_q_abs = zeros<double>({nr}), r_beta = zeros<double>({nr, max_n});
  py::list r_family, r_pattern;
  py::ssize_t k = 0;
  auto B = r_beta.mutable_unchecked<2>();
  for (const auto& rows : rows_of_column)
    for (const CellRow& r : rows) {
      r_ix.mutable_data()[k] = r.ix;
      r_iy.mutable_data()[k] = r.iy;
      r_balls.mutable_data()[k] = r.balls;
      r_family.append(std::string(to_string(r.family)));
      r_pattern.append(r.family == Family::balanced || !n_map ? std::string() : pattern_string(r.pattern, r.balls));
      r_member.mutable_data()[k] = r.member;
      r_stable.mutable_data()[k] = r.stable;
      r_unstable.mutable_data()[k] = r.n_unstable;
      r_structural.mutable_data()[k] = r.n_structural;
      r_undecided.mutable_data()[k] = r.n_undecided;
      r_abscissa.mutable_data()[k] = r.abscissa;
      r_q_abs.mutable_data()[k] = r.q_abs;
      for (int b = 0; b < max_n; ++b) B(k, b) = b < r.balls ? r.beta[std::size_t(b)] : std::nan("");
      ++k;
    }
  py::dict rows;
  rows["ix"] = r_ix;
  rows["iy"] = r_iy;
  rows["balls"] = r_balls;
  rows["family"] = r_family;
  rows["pattern"] = r_pattern;
  rows["member"] = r_member;
  rows["stable"] = r_stable;
  rows["n_unstable"] = r_unstable;
  rows["n_structural_zero"] = r_structural;
  rows["n_undecided"] = r_undecided;
  rows["spectral_abscissa"] = r_abscissa;
  rows["q_abs"] = r_q_abs;
  rows["beta"] = r_beta;

  py::dict d;
  d["x_name"] = job.x.name();
  d["y_name"] = job.y.name();
  d["x"] = x_values;
  d["y"] = y_values;
  d["n_balls_map"] = n_map;
  d["summary"] = summary;
  d["equilibria"] = rows;
  return d;
}

}  // namespace

}  // namespace abu::python

// ---------------------------------------------------------------------------------------
// The module

PYBIND11_MODULE(_abu, m) {
  using namespace abu;
  using namespace abu::python;
  m.doc() =
      "Compiled part of the abu package (docs/python.md): use the functions of `abu` itself, which wrap these "
      "in documented result classes.";
  m.attr("__version__") = ABU_VERSION;

  // Errors: the library's exceptions as Python ones, str(e) the message the CLI prints
  // after "stability-scan: error: " (InputError) or "numerical failure: " (NumericalError).
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<NumericalError> numerical_error(m, "NumericalError", PyExc_RuntimeError);
  static py::exception<NotSupportedError> not_supported(m, "NotSupportedError", PyExc_NotImplementedError);
  input_error.attr("__doc__") =
      "Invalid input: a scene (file, dict), an override, an option value. str(e) is the CLI's message "
      "'FILE:LINE: key 'KEY': RULE'; the parts are e.file, e.line (0: no line), e.key and e.rule. A subclass of "
      "ValueError.";
  numerical_error.attr("__doc__") =
      "A computation that did not reach its result (where and why in the message; the CLI's exit code 3). A "
      "subclass of RuntimeError.";
  not_supported.attr("__doc__") =
      "A valid request the analyzer does not handle yet (e.g. a start state for n >= 3 balls). A subclass of "
      "NotImplementedError.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = py::handle(input_error.ptr())(e.what());
      error.attr("file") = e.file();
      error.attr("line") = e.line();
      error.attr("key") = e.key();
      error.attr("rule") = e.rule();
      PyErr_SetObject(input_error.ptr(), error.ptr());
    } catch (const NumericalError& e) {
      PyErr_SetString(numerical_error.ptr(), e.what());
    } catch (const NotSupportedError& e) {
      PyErr_SetString(not_supported.ptr(), e.what());
    }
  });

  py::class_<Scene>(m, "Scene",
                    "A validated scene (rotor, balls, friction law, speed), as the CLI reads it: abu.load_scene(path) "
                    "or abu.scene_from_dict(d). Change parameters with set(); every change is checked by the CLI's "
                    "rules (its --set).")
      .def_property_readonly("file", [](const Scene& s) { return s.file; },
                             "The file name as given (\"<dict>\" for a scene from a dict), used in messages.")
      .def_property_readonly("n_balls", [](const Scene& s) { return int(s.balls.size()); }, "Number of balls n.")
      .def_property_readonly("omega", [](const Scene& s) { return s.omega; }, "Spin speed omega [rad/s].")
      .def_property_readonly("friction_law", [](const Scene& s) { return std::string(to_string(s.law)); },
                             "'none', 'viscous', 'coulomb' or 'stribeck' (model.md §4).")
      .def_property_readonly("is_ring", [](const Scene& s) { return s.ring.has_value(); },
                             "True if the scene has a [balls] ring (then set_ball_count works).")
      .def("get", &scene_get, py::arg("name"),
           "The value of parameter NAME (a model.md symbol: omega U k c M_r kappa, m l r mu d mu_c mu_s v_s, or "
           "with a 1-based ball index, m2 l1 ...), in SI units. An every-ball symbol gives ball 1's value.")
      .def(
          "set",
          [](py::object self, const std::string& name, double value) {
            scene_set(self.cast<Scene&>(), name, value);
            return self;
          },
          py::arg("name"), py::arg("value"),
          "Sets parameter NAME to VALUE as the CLI's `--set NAME=VALUE` does (same rules, same messages: "
          "InputError with file '--set'); the scene is unchanged on error. Returns the scene, so calls chain.")
      .def(
          "set",
          [](py::object self, const std::string& assignment) {
            apply_override(self.cast<Scene&>(), assignment);
            return self;
          },
          py::arg("assignment"),
          "Applies one `NAME=VALUE` override exactly as the CLI's `--set NAME=VALUE` (the same parser). Returns "
          "the scene.")
      .def(
          "set_ball_count",
          [](py::object self, int count) {
            Scene& s = self.cast<Scene&>();
            if (!s.ring)
              throw InputError("set_ball_count", 0, "n", "the scene has no [balls] ring (its balls are [[ball]] tables)");
            set_ball_count(s, count, "set_ball_count");
            return self;
          },
          py::arg("count"),
          "A [balls] ring scene with COUNT balls (2..12): per-ball mass held, or the ring's total_mass shared "
          "(scene.hpp). Returns the scene.")
      .def("copy", [](const Scene& s) { return Scene(s); }, "An independent copy of the scene.")
      .def("__copy__", [](const Scene& s) { return Scene(s); })
      .def("__deepcopy__", [](const Scene& s, py::dict) { return Scene(s); }, py::arg("memo"))
      .def(
          "describe", [](const Scene& s) { return describe_parameters(params_of<any_balls>(s)); },
          "Every parameter in one line, as the CLI's CSV headers print them.")
      .def("__repr__", &scene_repr);

  m.def("load_scene", &load_scene, py::arg("path"),
        "Reads and validates a scene file (TOML, SI units). Raises InputError with the CLI's message.");
  m.def("parse_scene", &parse_scene, py::arg("text"), py::arg("file"),
        "Parses and validates scene TEXT (TOML); FILE names it in messages. Raises InputError.");
  m.def("equilibria", &equilibria, py::arg("scene"), py::arg("samples_per_sheet") = 64,
        "Every equilibrium with its spectrum, as a dict of arrays (abu.equilibria wraps it).");
  m.def("map", &map, py::arg("scene"), py::arg("x"), py::arg("y"), py::arg("method") = "fast",
        py::arg("samples_per_sheet") = 64, py::arg("threads") = 1,
        "A stability map over axes X and Y ('NAME:FROM:TO:N[:log]'), as a dict of arrays (abu.map wraps it).");
  m.def("format_number", [](double v) { return format_number(v, "value"); }, py::arg("value"),
        "The shortest decimal that reads back to the same double, as every CSV of the CLI writes numbers.");
  m.def("parameter_symbols", [] { return std::string(param_symbols_help()); },
        "The parameter symbols that set(), get() and the axes take.");
  bind_runs(m), bind_studies(m), bind_orbits(m);
}
