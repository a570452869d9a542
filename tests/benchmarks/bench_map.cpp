// Throughput of the stability map's per-cell analysis on the default (omega, mu) map, and
// how often its fast decision (characteristic polynomial: Routh count and certified
// abscissa) disagrees with the full eigenvalues.
//
//   bench_map SCENE [--nx 1000] [--ny 1000] [--threads N] [--sample 10]
//
// Reports cells/s and eigenproblems/s (one eigenproblem = one equilibrium of one cell)
// with 1 thread and with N threads (columns dealt round-robin, each thread its own
// CellAnalyzer), computation only (no CSV). Then every `sample`-th column and row is
// decided again with the full refined eigenvalues and compared: stability flag,
// n_unstable and spectral abscissa.
#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "abu/analysis/map_setup.hpp"
#include "abu/scan/map.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Totals {
  long cells = 0, equilibria = 0, fallbacks = 0;
};

Totals run(const abu::Params& p, const abu::Axis& x, const abu::Axis& y, int threads) {
  std::atomic<int> next{0};
  std::vector<Totals> per(static_cast<std::size_t>(threads));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      abu::CellAnalyzer cells(p, x, y, abu::CellMethod::fast);
      abu::MapCell cell;
      Totals& mine = per[std::size_t(t)];
      for (int ix = next++; ix < x.count; ix = next++)
        for (int iy = 0; iy < y.count; ++iy) {
          cells.analyze(ix, iy, cell);
          ++mine.cells;
          mine.equilibria += cell.count;
          mine.fallbacks += cell.fallbacks;
        }
    });
  for (auto& th : pool) th.join();
  Totals all;
  for (const auto& t : per) all.cells += t.cells, all.equilibria += t.equilibria, all.fallbacks += t.fallbacks;
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  if (argc < 2) {
    fmt::print(stderr, "usage: bench_map SCENE [--nx N] [--ny N] [--threads N] [--sample K]\n");
    return 2;
  }
  int nx = 1000, ny = 1000, sample = 10;
  int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const int v = std::stoi(argv[i + 1]);
    if (a == "--nx") nx = v;
    if (a == "--ny") ny = v;
    if (a == "--threads") threads = std::max(1, v);
    if (a == "--sample") sample = std::max(1, v);
  }
  const abu::Scene scene = abu::load_scene(argv[1]);
  const abu::Params p = abu::params_of<2>(scene);
  const double omega_n = std::sqrt(p.rotor.stiffness / p.total_mass());
  const abu::Axis x = abu::parse_axis(fmt::format("omega:{}:{}:{}", 0.2 * omega_n, 8 * omega_n, nx), scene, "--x");
  const abu::Axis y = abu::parse_axis(fmt::format("mu:1e-4:1e-1:{}:log", ny), scene, "--y");
  fmt::print("scene {}: omega 0.2..8 omega_n x mu 1e-4..1e-1 (log), {} x {} cells, computation only\n", argv[1], nx, ny);
  for (int t : {1, threads}) {
    const auto t0 = Clock::now();
    const Totals r = run(p, x, y, t);
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    fmt::print("{:>2} thread(s): {:.2f} s, {:.3g} cells/s, {:.3g} eigenproblems/s ({} equilibria, {:.2f}% by the full "
               "eigensolver)\n",
               t, s, double(r.cells) / s, double(r.equilibria) / s, r.equilibria,
               100.0 * double(r.fallbacks) / double(r.equilibria));
    if (t == threads) break;
  }
  // Disagreement of the fast decision with the full eigenvalues on a subgrid; the fast
  // analyzer walks every cell of the sampled columns so that its tracking is as in a map.
  abu::CellAnalyzer fast(p, x, y, abu::CellMethod::fast), full(p, x, y, abu::CellMethod::full);
  abu::MapCell a, b;
  long compared = 0, stable_differs = 0, count_differs = 0;
  double worst = 0;
  for (int ix = 0; ix < nx; ix += sample)
    for (int iy = 0; iy < ny; ++iy) {
      fast.analyze(ix, iy, a);
      if (iy % sample) continue;
      full.analyze(ix, iy, b);
      for (int k = 0; k < a.count; ++k) {
        const auto& ea = a.equilibria[std::size_t(k)];
        const auto& eb = b.equilibria[std::size_t(k)];
        ++compared;
        stable_differs += ea.stable != eb.stable;
        count_differs += ea.n_unstable != eb.n_unstable;
        worst = std::max(worst, std::abs(ea.abscissa - eb.abscissa) / std::abs(eb.abscissa));
      }
    }
  fmt::print("fast vs full eigenvalues on every {}th column and row: {} eigenproblems, stability flag differs {} "
             "({:.3g}%), n_unstable differs {}, worst relative difference of the abscissa {:.2e}\n",
             sample, compared, stable_differs, 100.0 * double(stable_differs) / double(compared), count_differs, worst);
  return 0;
}
