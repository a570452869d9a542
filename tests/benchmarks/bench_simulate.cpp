// Speed against error of `simulate`'s integrators (model.md §15) on the problems of the
// scipy comparison (tests/benchmarks/bench_simulate_scipy.py, scripts/bench.sh section 9):
//
//   stiff3   coulomb kappa = 1e3, omega = 900 rad/s, 1 s from the balanced state with
//            beta1 += 0.5 rad, beta2 += 0.3 rad (default scene)
//   stiff6   the same with kappa = 1e6
//   runup    coulomb kappa = 1e3, omega 150 -> 350 rad/s at 1000 rad/s^2 (through omega_n at
//            0.1 s), held to 0.3 s, balls at rest at 2 and 4 rad
//
//   bench_simulate SCENE [--repeat R] [--json FILE]
//
// For each problem: a reference (bsimp at rtol 1e-13 with the default 2000 samples), then every
// method at rtol 1e-4 .. 1e-12, each twice: with free steps and nothing recorded (median wall
// time of R runs, library call; steps, evaluations, the error of the end state against the
// reference in the scaled max norm of model.md §15.1: q / L, angles in rad, q' / (L omega_max),
// beta' / omega_max), and with the default 2000 samples by dense output (§15.1: wall time,
// steps, the worst sample against the reference's at the same time, the located largest |q|
// against the reference's, relative). --json writes the problems' definitions, start states,
// the reference end states and every run (both ways) for the scipy script.
#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "abu/dynamics/simulation.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/input/scene.hpp"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Problem {
  std::string name;
  abu::Params p;
  abu::SpeedProfile speed;
  abu::State<double, 2> x0;
  double t_end;
};

double scaled_error(const abu::Params& p, const abu::State<double, 2>& a, const abu::State<double, 2>& b, double w) {
  const double L = abu::displacement_scale(p);
  const double s[8] = {L, L, 1, 1, L * w, L * w, w, w};
  double e = 0;
  for (int i = 0; i < 8; ++i) e = std::max(e, std::abs(a(i) - b(i)) / s[i]);
  return e;
}

std::string vec(const abu::State<double, 2>& x) {
  std::string s = "[";
  for (int i = 0; i < 8; ++i) s += fmt::format("{}{:.17g}", i ? ", " : "", x(i));
  return s + "]";
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  if (argc < 2) {
    fmt::print(stderr, "usage: bench_simulate SCENE [--repeat R] [--json FILE]\n");
    return 2;
  }
  int repeats = 3;
  std::string json_path;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--repeat") repeats = std::max(1, std::stoi(argv[i + 1]));
    if (std::string(argv[i]) == "--json") json_path = argv[i + 1];
  }
  const abu::Scene scene = abu::load_scene(argv[1]);
  abu::Params base = abu::params_of<2>(scene);
  std::vector<Problem> problems;
  for (double kappa : {1e3, 1e6}) {
    abu::Params p = base;
    p.kappa = kappa;
    const auto eq = abu::find_equilibria(p);
    abu::State<double, 2> x0 = abu::at_rest<double, 2>(eq.points()[0].position_si());  // balanced, first
    x0(2) += 0.5;
    x0(3) += 0.3;
    problems.push_back({kappa == 1e3 ? "stiff3" : "stiff6", p, abu::SpeedProfile::constant(p.omega), x0, 1.0});
  }
  problems.push_back({"runup", base, abu::SpeedProfile::ramp(150, 350, 1000), abu::start_at_rest(base, {2.0, 4.0}), 0.3});

  std::string json = "[\n";
  fmt::print("{:8} {:7} {:>7} | {:>10} {:>6} {:>4} {:>8} {:>5} {:>9} | {:>10} {:>6} {:>4} {:>9} {:>9}\n", "", "", "",
             "free steps", "", "", "", "", "", "2000 samples (dense output)", "", "", "", "");
  fmt::print("{:8} {:7} {:>7} | {:>10} {:>6} {:>4} {:>8} {:>5} {:>9} | {:>10} {:>6} {:>4} {:>9} {:>9}\n", "problem",
             "method", "rtol", "wall [s]", "steps", "rej", "rhs", "jac", "error", "wall [s]", "steps", "rej", "samples",
             "max|q|");
  for (std::size_t k = 0; k < problems.size(); ++k) {
    const auto& pr = problems[k];
    abu::SimulationOptions o;
    o.t_end = pr.t_end;
    o.record = true;
    o.rtol = 1e-13;
    o.method = abu::IntegrationMethod::bsimp;  // rk8pd and scipy's Radau agree with it to ~1e-11 (msbdf does not)
    const auto ref = abu::simulate(pr.p, pr.speed, pr.x0, o);
    const double w = pr.speed.max_omega();
    fmt::print("{:8} reference bsimp rtol 1e-13 with 2000 samples: {} steps, {:.3f} s, status {}\n", pr.name,
               ref.stats.steps, ref.stats.wall_seconds, abu::to_string(ref.status));
    json += fmt::format(
        "{{\"problem\": \"{}\", \"kappa\": {}, \"mu\": {}, \"omega0\": {}, \"omega1\": {}, \"alpha\": {}, \"t_end\": {}, "
        "\"L\": {:.17g}, \"x0\": {}, \"x_ref\": {}, \"runs\": [",
        pr.name, pr.p.kappa, pr.p.balls[0].mu, pr.speed.omega(0), pr.speed.max_omega(),
        pr.speed.points().size() > 1 ? 1000.0 : 0.0, pr.t_end, abu::displacement_scale(pr.p), vec(pr.x0), vec(ref.x_end));
    bool first = true;
    for (auto method : {abu::IntegrationMethod::bsimp, abu::IntegrationMethod::rk8pd, abu::IntegrationMethod::bdf}) {
      if (method == abu::IntegrationMethod::rk8pd && pr.p.kappa > 1e3) continue;  // explicit on kappa = 1e6: hours
      for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12}) {
        if (method == abu::IntegrationMethod::bdf && pr.p.kappa > 1e3 && tol > 1e-9) continue;  // msbdf: minutes, wrong
        o.rtol = tol;
        o.method = method;
        // Free steps (nothing recorded: what scipy's solve_ivp without t_eval does), then the
        // default 2000 samples by dense output (model.md §15.1): the worst sample against the
        // reference's at the same time, and the located largest |q| (§15.4).
        std::vector<double> walls, walls_recorded;
        abu::SimulationResult<2> r, rr;
        for (int rep = 0; rep < repeats; ++rep) {
          o.record = false;
          r = abu::simulate(pr.p, pr.speed, pr.x0, o);
          walls.push_back(r.stats.wall_seconds);
          o.record = true;
          rr = abu::simulate(pr.p, pr.speed, pr.x0, o);
          walls_recorded.push_back(rr.stats.wall_seconds);
        }
        const double err = scaled_error(pr.p, r.x_end, ref.x_end, w);
        double sample_err = rr.samples.size() == ref.samples.size() ? 0.0 : HUGE_VAL;
        for (std::size_t j = 0; j < rr.samples.size() && j < ref.samples.size(); ++j)
          sample_err = std::max(sample_err, scaled_error(pr.p, rr.samples[j].x, ref.samples[j].x, w));
        const double peak_err = std::abs(rr.summary.max_q_abs - ref.summary.max_q_abs) / ref.summary.max_q_abs;
        const bool ok = r.status == abu::SimulationStatus::completed && rr.status == abu::SimulationStatus::completed;
        fmt::print("{:8} {:7} {:>7.0e} | {:>10.3e} {:>6} {:>4} {:>8} {:>5} {:>9.2e} | {:>10.3e} {:>6} {:>4} {:>9.2e} {:>9.2e}{}\n",
                   pr.name, abu::to_string(method), tol, median(walls), r.stats.steps, r.stats.rejected,
                   r.stats.rhs_evaluations, r.stats.jacobian_evaluations, err, median(walls_recorded), rr.stats.steps,
                   rr.stats.rejected, sample_err, peak_err, ok ? "" : "  " + r.reason + " " + rr.reason);
        json += fmt::format("{}\n  {{\"method\": \"{}\", \"rtol\": {}, \"wall\": {:.6e}, \"steps\": {}, \"error\": {:.6e}, "
                            "\"wall_recorded\": {:.6e}, \"error_recorded\": {:.6e}, \"ok\": {}}}",
                            first ? "" : ",", abu::to_string(method), tol, median(walls), r.stats.steps, err,
                            median(walls_recorded), std::max(sample_err, scaled_error(pr.p, rr.x_end, ref.x_end, w)),
                            ok ? "true" : "false");
        first = false;
      }
    }
    json += fmt::format("]}}{}\n", k + 1 < problems.size() ? "," : "");
  }
  json += "]\n";
  if (!json_path.empty()) {
    std::FILE* f = std::fopen(json_path.c_str(), "w");
    if (!f) return 1;
    std::fputs(json.c_str(), f);
    std::fclose(f);
  }
  return 0;
}
