// A full omega continuation of every branch of a scene from 0.2 omega_n to 8 omega_n with
// the special points located, against finding the same points on plain sweep grids:
// speed against error.
//
//   bench_continuation SCENE [--repeat R] [--max-grid N]
//
// Prints the continuation's median wall time (library call, one thread), its steps and
// Newton iterations, then for sweep grids of increasing size the time and the relative
// error of each special point located between grid values (midpoint of the bracket).
// The whole process (start-up, parsing, output) is timed by scripts/bench.sh around the
// `stability-scan continue` command.
#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/scan/scan.hpp"
#include "abu/io/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Located {
  abu::Label label;
  double parameter;
};

// Special points on a grid: a fold where the number of together equilibria changes, a
// Hopf point where the balanced state's count of unstable eigenvalues changes by two.
std::vector<Located> grid_points(const abu::SweepResult& s) {
  std::vector<Located> out;
  const auto count = [](const abu::Analysis& a, abu::Family f) {
    int n = 0;
    for (const auto& e : a.equilibria.points()) n += e.family == f;
    return n;
  };
  const auto balanced_unstable = [](const abu::Analysis& a) {
    const auto pts = a.equilibria.points();
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (pts[i].family == abu::Family::balanced) return a.spectra[i].n_unstable;
    return -1;
  };
  for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
    const double mid = (s.values[i] + s.values[i + 1]) / 2;
    if (count(s.points[i], abu::Family::together) != count(s.points[i + 1], abu::Family::together))
      out.push_back({abu::Label::LP, mid});
    const int a = balanced_unstable(s.points[i]), b = balanced_unstable(s.points[i + 1]);
    if (a >= 0 && b >= 0 && std::abs(a - b) == 2) out.push_back({abu::Label::HB, mid});
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  if (argc < 2) {
    fmt::print(stderr, "usage: bench_continuation SCENE [--repeat R] [--max-grid N]\n");
    return 2;
  }
  int repeats = 11, max_grid = 10000;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--repeat") repeats = std::max(1, std::stoi(argv[i + 1]));
    if (std::string(argv[i]) == "--max-grid") max_grid = std::max(100, std::stoi(argv[i + 1]));
  }
  abu::Params p = abu::params_of<2>(abu::load_scene(argv[1]));
  const double omega_n = std::sqrt(p.rotor.stiffness / p.total_mass());
  const double from = 0.2 * omega_n, to = 8 * omega_n;
  p.omega = from;
  const abu::ParamRef omega = *abu::parse_param("omega", 2);

  std::vector<double> times;
  abu::ContinuationRun run;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    run = abu::continue_branches(p, omega, to, abu::ContinuationOptions{});
    times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::vector<Located> exact;
  for (const auto& b : run.branches)
    for (const auto& sp : b.specials) {
      bool seen = false;
      for (const auto& e : exact) seen = seen || (e.label == sp.label && std::abs(e.parameter - double(sp.parameter)) < 1e-9);
      if (!seen) exact.push_back({sp.label, double(sp.parameter)});
    }
  const auto& st = run.stats;
  fmt::print("scene {}: omega from {:.6g} to {:.6g} rad/s (0.2 .. 8 omega_n), median of {} runs, 1 thread\n", argv[1],
             from, to, repeats);
  fmt::print("continuation: {:.2f} ms; {} branches, {} steps ({} retried), {} Newton iterations, {} spectra tracked, {} "
             "computed afresh; special points:",
             median(times) * 1e3, run.branches.size(), st.steps, st.rejected, st.newton_iterations, st.tracked_spectra,
             st.full_spectra);
  for (const auto& e : exact) fmt::print(" {} {:.17g}", abu::to_string(e.label), e.parameter);
  fmt::print("\n{:>10} {:>12} {:>26}\n", "sweep N", "time [ms]", "worst rel. error of a point");
  for (int n = 100; n <= max_grid; n *= 10) {
    const auto values = abu::grid_values(from, to, n, false);
    const auto t0 = Clock::now();
    const abu::SweepResult s = abu::sweep(p, omega, values);
    const double ms = std::chrono::duration<double>(Clock::now() - t0).count() * 1e3;
    const auto found = grid_points(s);
    double worst = 0;
    int missed = 0;
    for (const auto& e : exact) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& f : found)
        if (f.label == e.label) best = std::min(best, std::abs(f.parameter - e.parameter) / e.parameter);
      if (!std::isfinite(best)) ++missed;
      else worst = std::max(worst, best);
    }
    fmt::print("{:>10} {:>12.1f} {:>26.2e}{}\n", n, ms, worst, missed ? fmt::format("  ({} missed)", missed) : "");
  }
  return 0;
}
