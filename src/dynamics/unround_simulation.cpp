// model.md §15.7: what a run on an unround race ended in (see unround_simulation.hpp).
#include "abu/dynamics/unround_simulation.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace abu {

double unround_distance(const ParamsN& p, const State<double, any_balls>& x, const UnroundEquilibrium& e) {
  const double L = displacement_scale(p);
  double d = std::max(std::abs(x(0) - double(e.position(0))), std::abs(x(1) - double(e.position(1)))) / L;
  for (int i = 0; i < p.n_balls(); ++i)
    d = std::max(d, std::abs(std::remainder(x(2 + i) - double(e.position(2 + i)), 2 * std::numbers::pi)));
  return d;
}

void classify_unround_end(SimulationSummary& s, const ParamsN& p, const UnroundResult& found, double tolerance) {
  if (s.outcome != SimulationOutcome::balanced && s.outcome != SimulationOutcome::aligned &&
      s.outcome != SimulationOutcome::rest)
    return;
  if (s.state_end.empty()) return;
  State<double, any_balls> x(int(s.state_end.size()));
  for (int i = 0; i < x.size(); ++i) x(i) = s.state_end[std::size_t(i)];
  int best = -1;
  double best_d = HUGE_VAL;
  for (std::size_t k = 0; k < found.list.size(); ++k) {
    const double d = unround_distance(p, x, found.list[k]);
    if (d < best_d) best_d = d, best = int(k);
  }
  s.pattern.clear();
  if (best >= 0 && best_d <= tolerance) {
    const auto& e = found.list[std::size_t(best)];
    s.outcome = SimulationOutcome::equilibrium;
    s.unround_member = best + 1;
    s.unround_q_abs = e.amplitude;
    s.unround_distance = best_d;
    s.note = fmt::format("at rest at equilibrium {} of {} of the unround race (model.md §11.4), {}: residual whirl "
                         "|q| = {:.6g} m, scaled distance {:.3g}",
                         best + 1, found.list.size(), to_string(e.spectrum.stability), e.amplitude, best_d);
    return;
  }
  s.outcome = SimulationOutcome::rest;
  s.note = best < 0 ? "at rest, and the unround race has no equilibrium at the final speed"
                    : fmt::format("at rest off every equilibrium of the unround race (the nearest, {} of {}, at scaled "
                                  "distance {:.3g}): the balls creep too slowly to move within the window",
                                  best + 1, found.list.size(), best_d);
}

}  // namespace abu
