// Basins of attraction (model.md §15.5): see basin.hpp.
#include "abu/scan/basin.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <memory>
#include <stdexcept>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/sampling.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/dynamics/stick_slip.hpp"
#include "abu/dynamics/unround_simulation.hpp"
#include "abu/linear/unround_spectrum.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/scan.hpp"

namespace abu {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// The sign of each ball along the line of q, ball 1 is + (as model.md §15.2 writes it).
std::string line_pattern(const std::vector<double>& position, int n) {
  const double phi = std::atan2(position[1], position[0]);
  const double ref = std::cos(position[2] - phi) >= 0 ? 1.0 : -1.0;
  std::string s;
  for (int i = 0; i < n; ++i) s += std::cos(position[std::size_t(2 + i)] - phi) * ref >= 0 ? '+' : '-';
  return s;
}

template <class EquilibriumSpan, class Spectra>
std::vector<BasinTarget> targets_of(const EquilibriumSpan& points, const Spectra& spectra, int n) {
  std::vector<BasinTarget> out;
  bool any_set = false, set_stable = true;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& e = points[k];
    const bool stable = spectra[k].stability == Stability::stable;
    if (e.on_balanced_set) {
      any_set = true;
      set_stable = set_stable && stable;
      continue;
    }
    if (!stable) continue;
    BasinTarget t;
    const auto pos = e.position_si();
    t.position.assign(pos.data(), pos.data() + pos.size());
    t.label = e.family == Family::balanced ? "balanced" : "aligned:" + line_pattern(t.position, n);
    for (const auto& o : out) t.member += o.label == t.label;
    ++t.member;
    out.push_back(std::move(t));
  }
  if (!(any_set && set_stable)) return out;
  BasinTarget set;
  set.label = "balanced";
  set.balanced_set = true;
  std::vector<BasinTarget> all{std::move(set)};  // the balanced set first
  for (auto& t : out) all.push_back(std::move(t));
  return all;
}

template <int N>
const ParamsT<double, N>& params_for(const BasinJob& job) {
  if constexpr (N == 2)
    return job.params;
  else
    return job.params_n;
}

// The options of one cell's run: recorded (the settle test looks at every sample), Ctrl-C polled.
SimulationOptions cell_options(const BasinJob& job) {
  SimulationOptions o = job.sim;
  if (!job.race.round()) o.race = &job.race;  // the balls on the race's paths (model.md §15.6)
  if (job.support) o.support = &*job.support;  // the support turning with the spin angle (model.md §20)
  o.record = true;
  o.interrupt = &stop_flag();
  o.progress = nullptr;
  return o;
}

// A cell's end figures from its run; a failed run fails the basin (exit 3, where and why).
template <int N>
void take_run(BasinCell& c, const SimulationResult<N>& r) {
  if (r.status == SimulationStatus::interrupted) throw Interrupted(stop_signal(), "basin cell");
  if (r.status == SimulationStatus::failed)
    throw NumericalError(fmt::format("basin cell ({}, {}) from beta1 = {:.9g}, beta2 = {:.9g} rad: {}", c.i, c.j,
                                     c.beta1, c.beta2, r.reason));
  c.t_end = r.t_reached;
  c.state_end.assign(r.x_end.data(), r.x_end.data() + r.x_end.size());
  c.q_abs_end = std::hypot(r.x_end(0), r.x_end(1));
  c.max_q_abs = r.summary.max_q_abs;
  c.steps = r.stats.steps;
  c.rejected = r.stats.rejected;
}

// A coulomb-set cell (model.md §14.8): the stick-slip run ends once every ball has stuck and the
// rotor is within the settle radius of its static displacement (5.4) for settle_samples
// samples in a row, after the speed change; the end point is checked against the stick set.
template <int N>
BasinCell stick_slip_cell(const BasinJob& job, const ParamsT<double, N>& p, const State<double, N>& x0, BasinCell c) {
  const int n = ball_count(p);
  const double L = displacement_scale(p), w = job.final_omega(), t_change = job.speed.end_of_change();
  const std::complex<double> dynamic_stiffness(p.rotor.stiffness - w * w * p.total_mass(), p.rotor.damping * w);
  SimulationOptions o = cell_options(job);
  int run = 0;
  double t_entry = -1;
  o.stop_at_sample = [&](double t, const double* x) {
    if (t < t_change) return false;
    bool settled = true;
    std::complex<double> W = p.rotor.unbalance;
    for (int k = 0; k < n; ++k) {
      settled = settled && x[n + 4 + k] == 0.0;  // a stuck ball's speed is exactly zero (14.5.1)
      W += p.balls[std::size_t(k)].mass * p.balls[std::size_t(k)].race_radius * std::polar(1.0, x[2 + k]);
    }
    const std::complex<double> q_static = w * w * W / dynamic_stiffness;
    settled = settled && std::abs(std::complex<double>(x[0], x[1]) - q_static) <= job.settle_radius * L &&
              std::hypot(x[n + 2], x[n + 3]) <= job.settle_radius * L * w;
    if (!settled) {
      run = 0;
      return false;
    }
    if (run++ == 0) t_entry = t;
    return run >= job.settle_samples;
  };
  const StickSlipResult<N> r = simulate_stick_slip(p, job.speed, x0, o);
  take_run(c, r.run);
  c.max_abs_s = r.end.max_abs_s;
  c.in_stick_set = r.end.all_stuck ? (r.end.in_set ? 1 : 0) : -1;
  c.by_settle_test = r.run.stopped_early ? 2 : 0;
  c.t_settle = r.run.stopped_early ? t_entry : (r.run.summary.settle_time ? *r.run.summary.settle_time : -1.0);
  if (r.end.all_stuck)
    c.attractor = r.end.in_set ? "stuck" : "stuck_outside";
  else
    c.attractor = r.run.summary.outcome == SimulationOutcome::periodic ? "periodic" : "slipping";
  return c;
}

// A cell's start angles (grid and Sobol points) in c.
BasinCell cell_start(const BasinJob& job, int i, int j, std::vector<double>& beta) {
  BasinCell c;
  c.i = i;
  c.j = j;
  c.beta1 = job.beta1(i);
  c.beta2 = job.beta2(j);
  c.beta_others = job.start_of_others(i, j);
  beta = {c.beta1, c.beta2};
  beta.insert(beta.end(), c.beta_others.begin(), c.beta_others.end());
  return c;
}

// The settle test of model.md §15.5 around one run: `integrate` takes the cell's options (the
// test in stop_at_sample, which sees the 2n + 4 values of (2.2), the balancer's on a shaft) and
// returns the run; p gives the scales (L, the balls' capacity). The run's end figures go to c, and
// its attractor: the target the test named (returns true) or §15.2's outcome of the run.
template <int N, class Integrate>
bool settle_run(const BasinJob& job, const std::vector<BasinTarget>& targets, const ParamsT<double, N>& p, BasinCell& c,
                Integrate&& integrate, SimulationResult<N>& r) {
  const int n = ball_count(p);
  const double L = displacement_scale(p), w = job.final_omega();
  double capacity = p.rotor.unbalance;
  for (const auto& b : p.balls) capacity += b.mass * b.race_radius;
  const double t_change = job.speed.end_of_change();
  // Scaled distance (model.md §15.2's scaling) of x to a target at rest, or to a periodic
  // orbit's state at the spin angle theta (§20.8).
  const auto distance = [&](const BasinTarget& t, const double* x, double theta) {
    if (t.orbit) return t.orbit->distance(x, theta, L);
    double d = 0;
    for (int k = 0; k < 2; ++k) d = std::max(d, std::abs(x[n + 2 + k]) / (L * w));
    for (int k = 0; k < n; ++k) d = std::max(d, std::abs(x[n + 4 + k]) / w);
    if (t.balanced_set) {
      double w1 = p.rotor.unbalance, w2 = 0;
      for (int k = 0; k < n; ++k) {
        const double a = p.balls[std::size_t(k)].mass * p.balls[std::size_t(k)].race_radius;
        w1 += a * std::cos(x[2 + k]);
        w2 += a * std::sin(x[2 + k]);
      }
      return std::max({d, std::hypot(x[0], x[1]) / L, std::hypot(w1, w2) / capacity});
    }
    for (int k = 0; k < 2; ++k) d = std::max(d, std::abs(x[k] - t.position[std::size_t(k)]) / L);
    for (int k = 0; k < n; ++k)
      d = std::max(d, std::abs(std::remainder(x[2 + k] - t.position[std::size_t(2 + k)], kTwoPi)));
    return d;
  };
  SimulationOptions o = cell_options(job);
  const BasinTarget* inside = nullptr;
  int run = 0;
  double t_entry = -1;
  o.stop_at_sample = [&](double t, const double* x) {
    if (t < t_change) return false;  // the attractors are those of the final, constant speed
    const BasinTarget* now = nullptr;
    const double theta = job.speed.angle(t);
    // A certified region (model.md §15.8) decides by itself; without one, the radius test (§15.5).
    for (const auto& target : targets)
      if (target.region.certified ? inside_region(target.region, x)
                                  : distance(target, x, theta) <= job.settle_radius) {
        now = &target;
        break;
      }
    if (now != inside) {
      inside = now;
      run = 0;
      t_entry = t;
    }
    return inside && ++run >= job.settle_samples;
  };
  r = integrate(o);
  take_run(c, r);
  if (r.stopped_early && inside) {
    c.attractor = inside->label;
    c.member = inside->member;
    c.by_settle_test = inside->region.certified ? 1 : 2;
    c.t_settle = t_entry;
    return true;
  }
  switch (r.summary.outcome) {
    case SimulationOutcome::balanced: c.attractor = "balanced"; break;
    case SimulationOutcome::aligned: c.attractor = "aligned:" + r.summary.pattern; break;
    case SimulationOutcome::rest: c.attractor = "stuck"; break;
    case SimulationOutcome::periodic: c.attractor = "periodic"; break;
    case SimulationOutcome::not_settled: c.attractor = "not_settled"; break;
    case SimulationOutcome::equilibrium: c.attractor = "equilibrium"; break;  // unround race only (§15.7)
    case SimulationOutcome::orbit: c.attractor = "orbit"; break;  // not from the run's own summary (§20.8)
  }
  if (r.summary.settle_time) c.t_settle = *r.summary.settle_time;
  return false;
}

// At rest, not named by the settle test (§15.2's balanced, aligned or stuck).
bool at_rest_end(const BasinCell& c) {
  return c.attractor == "balanced" || c.attractor.rfind("aligned:", 0) == 0 || c.attractor == "stuck";
}

template <int N>
BasinCell cell(const BasinJob& job, const std::vector<BasinTarget>& targets, int i, int j) {
  ParamsT<double, N> p = params_for<N>(job);
  p.omega = job.speed.omega(0.0);
  std::vector<double> beta;
  BasinCell c = cell_start(job, i, j, beta);
  const State<double, N> x0 = start_at_rest(p, beta);
  if (p.law == FrictionLaw::coulomb_set) return stick_slip_cell(job, p, x0, c);
  SimulationResult<N> r;
  const bool named =
      settle_run<N>(job, targets, p, c, [&](const SimulationOptions& o) { return simulate(p, job.speed, x0, o); }, r);
  if constexpr (N == any_balls) {
    // On an unround race a run at rest is matched against the race's equilibria (§15.7).
    // On an anisotropic support they are periodic orbits (§20.4): only the settle test names those.
    if (!named && !job.race.round() && !job.support && at_rest_end(c)) {
      SimulationSummary s = r.summary;
      ParamsN at = p;
      at.omega = job.final_omega();
      classify_unround_end(s, at, *job.race_equilibria, job.sim.settle_tolerance);
      c.attractor = s.outcome == SimulationOutcome::equilibrium ? "equilibrium" : "stuck";
      c.member = s.unround_member;
    }
  }
  return c;
}

// A cell of a flexible shaft (model.md §18.16, §18.21): the whole shaft integrated, the settle
// test on the balancer's view (job.params_n: its scales). On a race the run at rest that the test
// did not name is `stuck` (not within the radius of a stable equilibrium of the race).
BasinCell shaft_cell(const BasinJob& job, const std::vector<BasinTarget>& targets, int i, int j) {
  std::vector<double> beta;
  BasinCell c = cell_start(job, i, j, beta);
  const Eigen::VectorXd x0 = shaft_start_at_rest(*job.shaft, beta);
  SimulationResult<any_balls> r;
  const bool named = settle_run<any_balls>(
      job, targets, job.params_n, c,
      [&](const SimulationOptions& o) { return simulate_shaft(*job.shaft, job.speed, x0, o).run; }, r);
  if (!named && !job.race.round() && at_rest_end(c)) c.attractor = "stuck";
  return c;
}

}  // namespace

void BasinOrbit::at(double theta, double* x) const {
  const int count = phases();
  double u = std::fmod(theta, M_PI);
  if (u < 0) u += M_PI;
  u *= count / M_PI;
  const int k = std::min(int(u), count - 1), next = (k + 1) % count;
  const double f = u - k;
  const double* a = states.data() + std::size_t(k) * std::size_t(dim);
  const double* b = states.data() + std::size_t(next) * std::size_t(dim);
  const int n = (dim - 4) / 2;
  for (int m = 0; m < dim; ++m) {
    const bool angle = m >= 2 && m < 2 + n;  // along the short arc: the orbit's angles are not wrapped
    const double step = angle ? std::remainder(b[m] - a[m], kTwoPi) : b[m] - a[m];
    x[m] = a[m] + f * step;
  }
}

double BasinOrbit::distance(const double* x, double theta, double L) const {
  std::array<double, 2 * (max_balls + 2)> y{};  // no allocation: called at every sample
  at(theta, y.data());
  const int n = (dim - 4) / 2;
  double d = 0;
  for (int k = 0; k < 2; ++k) {
    d = std::max(d, std::abs(x[k] - y[std::size_t(k)]) / L);
    d = std::max(d, std::abs(x[n + 2 + k] - y[std::size_t(n + 2 + k)]) / (L * omega));
  }
  for (int k = 0; k < n; ++k) {
    d = std::max(d, std::abs(std::remainder(x[2 + k] - y[std::size_t(2 + k)], kTwoPi)));
    d = std::max(d, std::abs(x[n + 4 + k] - y[std::size_t(n + 4 + k)]) / omega);
  }
  return d;
}

int BasinJob::n_balls() const { return any_balls ? ball_count(params_n) : 2; }
double BasinJob::beta1(int i) const { return kTwoPi * i / cells1; }
double BasinJob::beta2(int j) const { return kTwoPi * j / cells2; }

std::vector<double> BasinJob::start_of_others(int i, int j) const {
  if (!fixed.empty() || others.empty()) return fixed;
  const auto m = std::size_t(n_balls() - 2);
  const auto at = others.begin() + std::ptrdiff_t((std::size_t(i) * std::size_t(cells2) + std::size_t(j)) * m);
  return {at, at + std::ptrdiff_t(m)};
}

void set_sobol_starts(BasinJob& job) {
  const int m = job.n_balls() - 2;
  job.others.clear();
  if (m < 1 || !job.fixed.empty()) return;
  job.others = sobol_points(job.cells1 * job.cells2, m);  // in (0, 1); GSL's first point is (1/2, ..., 1/2)
  for (double& u : job.others) u *= kTwoPi;
}

double shortest_arc(std::vector<double> angles) {
  if (angles.size() < 2) return 0.0;
  for (double& a : angles) a = std::fmod(std::fmod(a, kTwoPi) + kTwoPi, kTwoPi);
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + kTwoPi - angles.back();  // the gap across 0
  for (std::size_t k = 1; k < angles.size(); ++k) gap = std::max(gap, angles[k] - angles[k - 1]);
  return kTwoPi - gap;
}

static bool set_valued(const BasinJob& job) {
  return (job.any_balls ? job.params_n.law : job.params.law) == FrictionLaw::coulomb_set;
}

// An unround race's stable equilibria at the final speed (model.md §11.4, §15.7), numbered as
// `equilibria` lists them; no certified region (the settle radius test).
std::vector<BasinTarget> unround_targets(const BasinJob& job) {
  const UnroundResult& found = *job.race_equilibria;
  std::vector<BasinTarget> out;
  for (std::size_t k = 0; k < found.list.size(); ++k) {
    const UnroundEquilibrium& e = found.list[k];
    if (e.spectrum.stability != Stability::stable) continue;
    BasinTarget t;
    t.label = "equilibrium";
    t.member = int(k) + 1;
    for (int i = 0; i < e.position.size(); ++i) t.position.push_back(double(e.position(i)));
    t.region.reason = "an unround race: no certified region yet (model.md §15.8); the settle radius test";
    out.push_back(std::move(t));
  }
  return out;
}

void set_basin_race(BasinJob& job, RaceShape race) {
  job.race = std::move(race);
  job.race_equilibria.reset();
  // With an anisotropic support the race's states are periodic orbits, on a shaft its equilibria
  // on the shaft: both found with the targets (analysis/basin_targets.hpp).
  if (job.race.round() || job.support || job.shaft) return;
  ParamsN p = job.params_n;
  p.omega = job.final_omega();
  job.race_equilibria = std::make_shared<const UnroundResult>(find_unround_equilibria(p, job.race));
}

std::vector<BasinTarget> balanced_targets(const std::vector<EquilibriumN>& states, const std::vector<bool>& stable,
                                          const std::string& why) {
  struct Judged {
    Stability stability;
  };
  std::vector<Judged> judged;
  for (bool s : stable) judged.push_back({s ? Stability::stable : Stability::unstable});
  std::vector<BasinTarget> out = targets_of(states, judged, states.empty() ? 0 : states.front().n_balls());
  for (auto& t : out) t.region.reason = why;
  return out;
}

std::vector<BasinTarget> basin_targets(const BasinJob& job) {
  if (job.shaft) throw std::invalid_argument("basin_targets: a shaft's states are analysis/basin_targets.hpp's");
  if (job.support)
    throw std::invalid_argument("basin_targets: on an anisotropic support the balanced states are judged by their "
                                "Floquet multipliers (analysis/basin_targets.hpp: machine_basin_targets)");
  if (set_valued(job)) return {};  // the stick set, not points: each end point is checked against it (§14.8)
  if (!job.race.round()) return unround_targets(job);
  if (!job.any_balls) {
    Params p = job.params;
    p.omega = job.final_omega();
    const Analysis a = analyze(p);
    std::vector<BasinTarget> out = targets_of(a.equilibria.points(), a.spectra, 2);
    for (auto& t : out) t.region = certify_basin_region(p, t.position);  // model.md §15.8
    return out;
  }
  ParamsN p = job.params_n;
  p.omega = job.final_omega();
  const AnalysisN a = analyze(p);
  std::vector<BasinTarget> out = targets_of(a.equilibria.points(), a.spectra, ball_count(p));
  for (auto& t : out) t.region.reason = "n >= 3 balls: no certified region yet (model.md §15.8); the settle radius test";
  return out;
}

BasinCell compute_basin_cell(const BasinJob& job, const std::vector<BasinTarget>& targets, int i, int j) {
  if (job.shaft) return shaft_cell(job, targets, i, j);
  return job.any_balls ? cell<any_balls>(job, targets, i, j) : cell<2>(job, targets, i, j);
}

std::string basin_csv_header(const BasinJob& job) {
  std::string h = job.provenance;
  h += "i,j,beta1_0,beta2_0,attractor,member,by_settle_test,t_settle,t_end,q_abs_end,max_q_abs";
  for (int k = 1; k <= job.n_balls(); ++k) h += fmt::format(",beta{}_end", k);
  h += set_valued(job) ? ",steps,rejected,max_abs_s,in_stick_set" : ",steps,rejected";
  // Last, so that the columns before keep their places for every ball count.
  for (int k = 3; k <= job.n_balls(); ++k) h += fmt::format(",beta{}_0", k);
  h += '\n';
  return h;
}

std::string basin_row(const BasinCell& c) {
  std::string row = fmt::format("{},{},{:.10g},{:.10g}", c.i, c.j, c.beta1, c.beta2);
  row += fmt::format(",{},{},{},{},{:.10g},{:.6e},{:.6e}", c.attractor, c.member == 0 ? std::string() : std::to_string(c.member),
                                c.by_settle_test, c.t_settle >= 0 ? fmt::format("{:.6g}", c.t_settle) : "",
                                c.t_end, c.q_abs_end, c.max_q_abs);
  const int n = (int(c.state_end.size()) - 4) / 2;
  // End angles wrapped to [0, 2 pi): where the balls came to lie on the race.
  for (int k = 0; k < n; ++k) {
    double b = std::fmod(c.state_end[std::size_t(2 + k)], kTwoPi);
    if (b < 0) b += kTwoPi;
    row += fmt::format(",{:.8f}", b);
  }
  row += fmt::format(",{},{}", c.steps, c.rejected);
  if (c.max_abs_s >= 0) row += fmt::format(",{:.9f},{}", c.max_abs_s, c.in_stick_set);
  for (double b : c.beta_others) row += fmt::format(",{:.10g}", b);
  row += '\n';
  return row;
}

std::string basin_manifest(const BasinJob& job) {
  std::string out = fmt::format("abu basin tiles: 1 column per tile, {} tiles\n", job.cells1);
  out += fmt::format("# grid {} x {}, {}", job.cells1, job.cells2, job.fixed.empty() ? "others sobol" : "fixed");
  for (double f : job.fixed) out += fmt::format(" {:.17g}", f);
  out += fmt::format("\n# speed {}, t_end {:.17g}, every {:.17g}, rtol {:.17g}, method {}\n", job.speed.describe(),
                     job.sim.t_end, job.sim.every, job.sim.rtol, to_string(job.sim.method));
  out += fmt::format("# settle radius {:.17g}, samples {}, settle tolerance {:.17g}\n", job.settle_radius,
                     job.settle_samples, job.sim.settle_tolerance);
  for (const auto& p : job.speed.points()) out += fmt::format("# profile {:.17g} {:.17g}\n", p.t, p.omega);
  // The header, without the lines that name the command and the scene file's path.
  std::size_t start = 0;
  const std::string h = basin_csv_header(job);
  while (start < h.size()) {
    const std::size_t end = std::min(h.find('\n', start), h.size());
    const std::string line = h.substr(start, end - start);
    if (line.rfind("# command:", 0) != 0 && line.rfind("# scene:", 0) != 0) out += line + '\n';
    start = end + 1;
  }
  return out;
}

BasinEstimate basin_estimate(const BasinJob& job, int threads) {
  BasinEstimate e;
  const double cells = double(job.cells1) * double(job.cells2);
  const int workers = std::max(1, std::min(threads, job.cells1));
  e.runs = workers * simulation_memory_estimate(cell_options(job), job.n_balls(), false);
  e.cells = 2 * 600 * cells;
  e.memory = 20e6 + e.runs + e.cells;
  e.disk = 2 * 600 * cells;
  return e;
}

TileText compute_basin_tile(const BasinJob& job, const std::vector<BasinTarget>& targets, int tile) {
  TileText text;
  for (int j = 0; j < job.cells2; ++j) {
    throw_if_stopped("basin tile");
    text.rows += basin_row(compute_basin_cell(job, targets, tile, j));
    ++text.cells;
  }
  return text;
}

MapRunStats compute_basin_tiles(const BasinJob& job, const std::vector<BasinTarget>& targets,
                                const std::vector<int>& tiles, const MapRunOptions& options, const TileSink& sink) {
  return run_text_tiles(tiles, options, sink, [&](int tile) { return compute_basin_tile(job, targets, tile); });
}

}  // namespace abu
