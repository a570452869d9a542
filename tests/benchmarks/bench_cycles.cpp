// Cost per orbit of cycle continuation (docs/developers.md "Periodic orbits: benchmark"):
// the viscous two-ball scene (the default rotor, viscous d = 1e-4), the cycle branch of its
// Hopf point at omega_H = 281.31 rad/s, 30 steps, integrator rtol 1e-13, in four configurations
// in one run: M = 40 with full Newton (the method before the chord corrector), then the chord
// corrector (model.md §17.7) at M = 40, 20 and 10. Optional second argument: one configuration.
// Prints CPU seconds per orbit (process CPU time: the machine is shared), flows, Newton
// iterations, and the fast rotor multiplier pair of the last orbit.
//   build/tests/benchmarks/bench_cycles [steps]
#include <fmt/format.h>

#include <cmath>
#include <ctime>
#include <iterator>
#include <string>

#include "abu/continuation/continuation.hpp"
#include "abu/dynamics/periodic_orbits.hpp"

int main(int argc, char** argv) {
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = abu::FrictionLaw::viscous;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-4, 0.0, 0.0, 0.0};
  const abu::ParamRef omega = *abu::parse_param("omega", 2);
  abu::StartSelection sel;
  sel.family = abu::Family::balanced;
  const abu::ContinuationRun run = abu::continue_branches(p, omega, 50.0, {}, sel);
  const abu::SpecialPoint* hb = nullptr;
  for (const auto& b : run.branches)
    for (const auto& s : b.specials)
      if (s.label == abu::Label::HB && s.converged && !hb) hb = &s;
  if (!hb) return fmt::print(stderr, "no Hopf point\n"), 1;
  const int steps = argc > 1 ? std::stoi(argv[1]) : 30;
  // Configurations: (intervals, chord corrector); the first is the method before the chord
  // corrector (full Newton, M = 40).
  struct Config {
    int intervals;
    bool chord;
  };
  const Config configs[] = {{40, false}, {40, true}, {20, true}, {10, true}};
  const int only = argc > 2 ? std::stoi(argv[2]) : -1;  // one configuration (for a profiler)
  for (int ci = 0; ci < int(std::size(configs)); ++ci) {
    if (only >= 0 && ci != only) continue;
    const Config& cf = configs[ci];
    abu::CycleOptions o;
    o.continuation.max_steps = steps;
    o.intervals = cf.intervals;
    o.chord_corrector = cf.chord;
    const std::clock_t c0 = std::clock();
    const abu::CycleBranch c = abu::continue_cycles(p, omega, *hb, 50.0, 900.0, o);
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    const std::size_t n = c.orbits.size();
    fmt::print("M {} {}: orbits {}, CPU {:.3f} s, {:.1f} ms per orbit; flows {} ({:.0f} per orbit) + state-only {} ({:.0f} "
               "per orbit), Newton iterations {}\n",
               cf.intervals, cf.chord ? "chord" : "full Newton", n, cpu, 1e3 * cpu / double(n), c.flow_evaluations,
               double(c.flow_evaluations) / double(n), c.state_flow_evaluations, double(c.state_flow_evaluations) / double(n),
               c.newton_iterations);
    if (n == 0) return 1;
    const abu::CycleOrbit& last = c.orbits.back();
    fmt::print("  last orbit: omega {:.17g}, period {:.15g} s, amplitude {:.6g} m, trivial |mu - 1| {:.2e}\n",
               last.parameter, last.period, last.amplitude, last.trivial_distance);
    for (std::size_t k = 0; k < last.multipliers.size(); ++k)
      fmt::print("    mu{} = {:.10g} {:+.10g} i   |mu| = {:.6g}\n", k + 1, last.multipliers[k].real(),
                 last.multipliers[k].imag(), std::abs(last.multipliers[k]));
  }
  return 0;
}
