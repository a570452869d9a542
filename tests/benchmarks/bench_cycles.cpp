// Cost per orbit of cycle continuation against its error (docs/developers.md "Periodic
// orbits: benchmark", model.md §17.9): the viscous two-ball scene (the default rotor, viscous
// d = 1e-4), the cycle branch of its Hopf point at omega_H = 281.31 rad/s.
//
// 1. A reference branch (every tolerance 1e-14, full Newton) of `steps` steps; the reference
//    orbit is its orbit number `steps / 2`.
// 2. Per configuration (intervals at the first orbit, Newton, tolerances of the state, of the
//    Newton matrix's and of the Floquet transition matrices): CPU time per orbit over a branch
//    of `steps` steps, and the same configuration's orbit at the reference orbit's parameter
//    (correct_cycle from the reference orbit): its period's and its multipliers' errors
//    against the reference orbit.
// Third argument "light": the lightly damped support of model.md §17.10; "long": the branch
// followed from the Hopf point until its period exceeds 7 s (the homoclinic approach of
// model.md §17.9), CPU time per orbit and the mesh at the end, no reference.
// Process CPU time (the machine is shared). AUTO-07p's figures, measured beside it on the
// same branch, are in docs/developers.md.
//   build/tests/benchmarks/bench_cycles [steps] [configuration, -1 all] [light | long]
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <iterator>
#include <string>

#include "abu/continuation/continuation.hpp"
#include "abu/dynamics/periodic_orbits.hpp"

namespace {

struct Config {
  int intervals;
  bool chord;
  double rtol, newton_rtol, floquet_rtol;
  bool extrapolate = true;  // the Newton matrix extrapolated from the last orbits (model.md §17.7)
  bool locate = true;       // LPC/PD/NS located on the branch (model.md §17.5)
};

abu::CycleOptions options(const Config& cf, int steps) {
  abu::CycleOptions o;
  o.continuation.max_steps = steps;
  o.intervals = cf.intervals;
  o.chord_corrector = cf.chord;
  o.rtol = cf.rtol;
  o.newton_rtol = cf.newton_rtol;
  o.floquet_rtol = cf.floquet_rtol;
  o.extrapolate_newton_matrix = cf.extrapolate;
  o.locate_specials = cf.locate;
  return o;
}

// Largest relative error of the multipliers (both sorted by modulus, descending).
double multiplier_error(const abu::CycleOrbit& a, const abu::CycleOrbit& ref) {
  if (a.multipliers.size() != ref.multipliers.size()) return INFINITY;
  double worst = 0;
  for (std::size_t k = 0; k < a.multipliers.size(); ++k)
    worst = std::max(worst, std::abs(a.multipliers[k] - ref.multipliers[k]) / std::abs(ref.multipliers[k]));
  return worst;
}

// The branch from the Hopf point until the period exceeds 7 s (the branch ends there: the
// period bound of CycleOptions), in the fast configuration (0) or the defaults (1).
int long_run(const abu::Params& p, abu::ParamRef omega, const abu::SpecialPoint& hb, int steps, int only) {
  fmt::print("| configuration | orbits | CPU [s] | ms CPU per orbit | last period [s] | last omega [rad/s] | meshes "
             "re-chosen, intervals at the end | LPC, PD, NS |\n|---|---|---|---|---|---|---|---|\n");
  const Config configs[] = {{5, true, 1e-10, 1e-4, 1e-8}, {5, true, 1e-13, 1e-6, 1e-11}};
  const char* names[] = {"fast (1e-10 / 1e-4 / 1e-8)", "defaults (1e-13 / 1e-6 / 1e-11)"};
  for (int ci = 0; ci < 2; ++ci) {
    if (only >= 0 && ci != only) continue;
    abu::CycleOptions o = options(configs[ci], steps);
    o.max_period_factor = 7.0 / (2 * 3.14159265358979323846 / hb.frequency);
    const std::clock_t c0 = std::clock();
    const abu::CycleBranch c = abu::continue_cycles(p, omega, hb, 50.0, 900.0, o);
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    if (c.orbits.empty()) return fmt::print(stderr, "{}: {}\n", names[ci], c.reason), 1;
    std::string specials;
    for (const auto& sp : c.specials) specials += fmt::format("{}{} {:.10g}", specials.empty() ? "" : ", ", sp.label, sp.parameter);
    fmt::print("| {} | {} | {:.2f} | {:.2f} | {:.4f} | {:.12g} | {}, {} | {} |\n", names[ci], c.orbits.size(), cpu,
               1e3 * cpu / double(c.orbits.size()), c.orbits.back().period, c.orbits.back().parameter, c.remeshes,
               c.intervals, specials);
    if (c.orbits.back().period < 6.5) fmt::print(stderr, "{}: stopped at T = {} s: {}\n", names[ci], c.orbits.back().period, c.reason);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  abu::Params p;
  // Third argument "light": the lightly damped support of model.md §17.10 (c = 0.05 N s/m),
  // whose orbits are well conditioned at a fixed omega (no fold of cycles nearby).
  const std::string mode = argc > 3 ? std::string(argv[3]) : std::string();
  const bool light = mode == "light", long_branch = mode == "long";
  p.rotor = {0.12, 7500.0, light ? 0.05 : 2.0, 6e-7};
  p.omega = light ? 2000.0 : 900.0;
  p.law = abu::FrictionLaw::viscous;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-4, 0.0, 0.0, 0.0};
  const abu::ParamRef omega = *abu::parse_param("omega", 2);
  abu::StartSelection sel;
  sel.family = abu::Family::balanced;
  const abu::ContinuationRun run = abu::continue_branches(p, omega, light ? 20.0 : 50.0, {}, sel);
  const abu::SpecialPoint* hb = nullptr;
  for (const auto& b : run.branches)
    for (const auto& s : b.specials)
      if (s.label == abu::Label::HB && s.converged && !hb) hb = &s;
  if (!hb) return fmt::print(stderr, "no Hopf point\n"), 1;
  const int steps = argc > 1 ? std::stoi(argv[1]) : 30;
  const int only = argc > 2 ? std::stoi(argv[2]) : -1;  // one configuration (for a profiler)

  // Full Newton: the reference orbit does not depend on the chord corrector's stopping rule.
  const Config reference{40, false, 1e-14, 1e-14, 1e-14};
  abu::CycleOrbit ref;
  if (long_branch) return long_run(p, omega, *hb, steps, only);
  if (only < 0) {
    const abu::CycleBranch r = abu::continue_cycles(p, omega, *hb, 50.0, 900.0, options(reference, steps));
    if (r.orbits.size() < 3) return fmt::print(stderr, "reference branch: {}\n", r.reason), 1;
    ref = r.orbits[r.orbits.size() / 2];
    fmt::print("reference orbit (M 40, full Newton, tolerances 1e-14): omega {:.17g} rad/s, period {:.17g} s, amplitude {:.10g} m, "
               "trivial |mu - 1| {:.2e}\n",
               ref.parameter, ref.period, ref.amplitude, ref.trivial_distance);
    for (std::size_t k = 0; k < ref.multipliers.size(); ++k)
      fmt::print("  mu{} = {:.14g} {:+.14g} i   |mu| = {:.8g}\n", k + 1, ref.multipliers[k].real(),
                 ref.multipliers[k].imag(), std::abs(ref.multipliers[k]));
  }

  // (intervals, chord, rtol of the state, of the Newton matrix, of the Floquet matrices)
  const Config configs[] = {
      {40, false, 1e-13, 1e-13, 1e-13},  // full Newton, one tolerance (before the chord corrector)
      {40, true, 1e-13, 1e-13, 1e-13},   // chord, one tolerance (before model.md §17.8)
      {40, true, 1e-13, 1e-6, 1e-11},    // chord, split tolerances
      {20, true, 1e-13, 1e-6, 1e-11},
      {10, true, 1e-13, 1e-6, 1e-11},
      {10, true, 1e-12, 1e-6, 1e-10},
      {10, true, 1e-11, 1e-6, 1e-10},
      {10, true, 1e-12, 1e-6, 1e-8},
      {10, true, 1e-12, 1e-4, 1e-8},
      {10, true, 1e-11, 1e-4, 1e-8},
      {10, true, 1e-10, 1e-4, 1e-8},
      {10, true, 1e-10, 1e-4, 1e-7},
      {5, true, 1e-10, 1e-4, 1e-8},
      {20, true, 1e-10, 1e-4, 1e-8},
      {4, true, 1e-10, 1e-4, 1e-8},
      {5, true, 1e-10, 1e-4, 1e-8, false},  // 12 without the extrapolated Newton matrix (stop 23's fast configuration)
      {10, true, 1e-10, 1e-4, 1e-8, false},
      {40, true, 1e-13, 1e-6, 1e-11, false},  // 2 without it (the defaults of stop 23)
      {5, true, 1e-10, 1e-4, 1e-8, true, false},  // 12 with the branch's LPC interpolated, not located
  };
  fmt::print("\n| M | Newton | rtol state / Newton matrix / Floquet | ms CPU per orbit | period error | "
             "multiplier error | steps per orbit (state / Newton / Floquet) | Newton it. per orbit | orbits |\n"
             "|---|---|---|---|---|---|---|---|---|\n");
  for (int ci = 0; ci < int(std::size(configs)); ++ci) {
    if (only >= 0 && ci != only) continue;
    const Config& cf = configs[ci];
    const abu::CycleOptions o = options(cf, steps);
    const std::clock_t c0 = std::clock();
    const abu::CycleBranch c = abu::continue_cycles(p, omega, *hb, 50.0, 900.0, o);
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    const double n = double(c.orbits.size());
    if (c.orbits.empty()) return fmt::print(stderr, "configuration {}: {}\n", ci, c.reason), 1;
    std::string period_error = "-", mult_error = "-";
    if (only < 0) {
      const abu::CycleCorrection at = abu::correct_cycle(p, omega, *hb, ref, 50.0, 900.0, o);
      if (!at.status.ok()) return fmt::print(stderr, "configuration {} at the reference: {}\n", ci, at.reason), 1;
      period_error = fmt::format("{:.1e}", std::abs(at.orbit.period / ref.period - 1));
      mult_error = fmt::format("{:.1e}", multiplier_error(at.orbit, ref));
    }
    // The Newton column: full, chord, or chord with k of the orbits' Newton matrices extrapolated.
    const std::string newton = !cf.chord ? std::string("full")
                               : cf.extrapolate ? fmt::format("chord, {} extrap.", c.extrapolated_matrices)
                                                : std::string("chord");
    const std::string specials = cf.locate ? "" : ", LPC interp.";
    fmt::print("| {} | {} | {:.0e} / {:.0e} / {:.0e} | {:.2f} | {} | {} | {:.0f} / {:.0f} / {:.0f} | {:.1f} | {} |\n",
               cf.intervals, newton + specials, cf.rtol, cf.chord ? cf.newton_rtol : cf.rtol,
               cf.chord ? cf.floquet_rtol : cf.rtol, 1e3 * cpu / n, period_error, mult_error,
               double(c.state_steps) / n, double(c.newton_steps) / n, double(c.floquet_steps) / n, double(c.newton_iterations) / n, c.orbits.size());
  }
  return 0;
}
