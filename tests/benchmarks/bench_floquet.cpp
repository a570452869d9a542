// Benchmark (not a test): the cost of the balanced state's Floquet verdict on an anisotropic
// support (Hill + Magnus cross-check, docs/model.md §10.5-10.6) against the isotropic
// eigenvalue verdict (scan.hpp equilibrium_spectrum) of the same state, and against a
// numpy script that integrates the monodromy by RK4 (bench_floquet_numpy.py), in one run.
//
//   build/tests/benchmarks/bench_floquet [tests/benchmarks/bench_floquet_numpy.py] [reps]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/balanced_floquet.hpp"
#include "abu/linear/floquet_hill.hpp"
#include "abu/linear/magnus_monodromy.hpp"
#include "abu/scan/map.hpp"
#include "abu/scan/scan.hpp"
#include "../anisotropic_base.hpp"

using namespace abu;
using Clock = std::chrono::steady_clock;

template <class F>
double seconds_per_call(int reps, F&& f) {
  const auto t0 = Clock::now();
  for (int i = 0; i < reps; ++i) f();
  return std::chrono::duration<double>(Clock::now() - t0).count() / reps;
}

int main(int argc, char** argv) {
  const std::string script = argc > 1 ? argv[1] : "tests/benchmarks/bench_floquet_numpy.py";
  const int reps = argc > 2 ? std::atoi(argv[2]) : 20;
  for (FrictionLaw law : {FrictionLaw::viscous, FrictionLaw::coulomb}) {
    const ParamsN p = testing::anisotropic_base(law);  // BASE of docs/model.md §10.8
    const AnisotropicSupport s = testing::anisotropic_base_support(p, 1.0);
    const EquilibriumSetN set = find_equilibria(p);
    const EquilibriumN e = set.points()[0];
    volatile double sink = 0.0;
    const double t_iso = seconds_per_call(reps, [&] { sink = sink + equilibrium_spectrum(p, e).abscissa; });
    const PeriodicJacobian J = balanced_periodic_jacobian(p, s, e.position);
    const double t_hill = seconds_per_call(reps, [&] { sink = sink + std::abs(hill_multipliers(J).multipliers[0]); });
    const double t_magnus = seconds_per_call(reps, [&] { sink = sink + magnus_monodromy(J, 256)(0, 0); });
    const double t_verdict = seconds_per_call(reps, [&] { sink = sink + balanced_floquet(p, s, e).max_modulus; });
    FloquetOptions fast;
    fast.route = FloquetRoute::magnus;
    const double t_fast = seconds_per_call(reps, [&] { sink = sink + balanced_floquet(p, s, e, fast).max_modulus; });
    fmt::print("{}: isotropic eigenvalue verdict {:.3g} ms; Floquet verdict, hill route (before) {:.3g} ms (Hill "
               "{:.3g} ms, Magnus-256 {:.3g} ms): ratio {:.1f}; magnus route (after, model.md §10.10) {:.3g} ms: "
               "ratio {:.1f}\n",
               to_string(law), 1e3 * t_iso, 1e3 * t_verdict, 1e3 * t_hill, 1e3 * t_magnus, t_verdict / t_iso,
               1e3 * t_fast, t_fast / t_iso);
    // Error against each other: long-double Hill (the reference of §10.8) on every multiplier.
    {
      HillOptions ext;
      ext.extended = true;
      const auto ref = hill_multipliers(J, ext).multipliers;
      const BalancedFloquet a = balanced_floquet(p, s, e), b = balanced_floquet(p, s, e, fast);
      auto err = [&](const std::vector<std::complex<double>>& r) {
        double w = 0.0;
        for (std::size_t i = 0; i < r.size() && i < ref.size(); ++i)
          w = std::max(w, std::abs(r[i] - ref[i]) / std::max(std::abs(ref[i]), 1e-6));
        return w;
      };
      fmt::print("  max relative error against long-double Hill: hill route {:.2g}, magnus route {:.2g} ({}, "
                 "step-halving estimate {:.2g}, band {:.2g})\n",
                 err(a.multipliers), err(b.multipliers), b.by_hill ? "fell back to Hill" : "Magnus decided",
                 b.monodromy_deviation, b.band);
    }
    // A map cell (model.md §10.12): CellAnalyzerN on a one-cell grid at these parameters,
    // isotropic (the mean support) against anisotropic (every balanced state by Floquet).
    const Axis x{ParamRef{Quantity::omega, -1}, p.omega, p.omega, 1}, y{ParamRef{Quantity::unbalance, -1},
                                                                          p.rotor.unbalance, p.rotor.unbalance, 1};
    CellAnalyzerN iso_cells(p, {}, x, y, {}), aniso_cells(p, {}, x, y, {}, s);
    MapCellN cell;
    const double t_cell_iso = seconds_per_call(reps, [&] { iso_cells.analyze(0, 0, cell); });
    const double t_cell = seconds_per_call(reps, [&] { aniso_cells.analyze(0, 0, cell); });
    // The isotropic two-ball map's own cell (CellAnalyzer: characteristic polynomial, Routh).
    Params p2;
    p2.rotor = p.rotor;
    p2.omega = p.omega;
    p2.law = p.law;
    p2.kappa = p.kappa;
    for (std::size_t i = 0; i < 2; ++i) p2.balls[i] = p.balls[i];
    CellAnalyzer two_ball_cells(p2, x, y);
    MapCell cell2;
    const double t_cell_2 = seconds_per_call(reps, [&] { two_ball_cells.analyze(0, 0, cell2); });
    fmt::print("  map cell ({} balanced states): isotropic two-ball path {:.3g} ms, isotropic n-ball path {:.3g} ms, "
               "anisotropic {:.3g} ms: ratios {:.1f} and {:.1f}\n",
               cell.equilibria.size(), 1e3 * t_cell_2, 1e3 * t_cell_iso, 1e3 * t_cell, t_cell / t_cell_2,
               t_cell / t_cell_iso);
    // The same J (scaled coordinates) for the numpy script.
    const std::string file = "/tmp/bench_floquet_J.txt";
    {
      std::ofstream out(file);
      out.precision(17);
      out << J.omega << " " << J.dimension() << "\n" << J.mean << "\n" << J.cos2 << "\n" << J.sin2 << "\n";
    }
    if (law == FrictionLaw::viscous) {
      const std::string cmd =
          fmt::format("/usr/bin/python3 {} {} {:.6g} {:.6g} {}", script, file, t_fast, t_cell, cell.equilibria.size());
      std::fflush(stdout);  // the script prints after this run's lines
      if (std::system(cmd.c_str()) != 0) fmt::print("numpy script failed: {}\n", cmd);
    } else {
      fmt::print("coulomb: no numpy RK4 comparison (ball rates {:.2g} 1/s need ~1e6 explicit steps per period)\n",
                 -hill_multipliers(J).exponents.back().real());
    }
    std::remove(file.c_str());
  }
}
