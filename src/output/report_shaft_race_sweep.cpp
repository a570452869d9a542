// The files of a sweep of an unround race on a flexible shaft (report_shaft_race_sweep.hpp).
#include "abu/output/report_shaft_race_sweep.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abu/output/format.hpp"

namespace abu {

namespace {
// An empty field for a number that does not exist (no eigenvalue off the structural zeros).
std::string finite_or_empty(double v, std::string_view what) { return std::isfinite(v) ? format_number(v, what) : ""; }
}  // namespace

std::string shaft_race_sweep_csv(const ShaftRaceSweep& s, std::string_view name, std::string_view unit,
                                 const std::string& header) {
  std::string out = header;
  out += fmt::format("# unround race on a flexible shaft (model.md §18.18): every equilibrium of the race on the shaft "
                     "per value of {} [{}], numbered by |q| of the race on the equivalent rigid balancer; q [m] at the "
                     "balancer node, rotating frame (|q| = fixed-frame whirl radius); max_deflection [m] the largest "
                     "node translation, at max_deflection_node; beta [rad]; rightmost [1/s] the largest real part of "
                     "the {} rightmost eigenvalues with |Im| <= {} (rotating frame, ARPACK, structural zeros left "
                     "out); stable = 1 only for the verdict stable; best = the stable state of least |q|\n",
                     name, unit, s.spectrum.eigenvalues,
                     s.spectrum.band > 0 ? fmt::format("{} 1/s", s.spectrum.band) : std::string("10 omega"));
  out += fmt::format("{},equilibrium,q1,q2,q_abs", name);
  for (int b = 0; b < s.n_balls; ++b) out += fmt::format(",beta{}", b + 1);
  out += ",max_deflection,max_deflection_node,rightmost,verdict,stable,best,status,residual\n";
  for (const auto& pt : s.points)
    for (std::size_t k = 0; k < pt.states.size(); ++k) {
      const ShaftState& st = pt.states[k];
      const auto& x = st.eq.position;
      const int first_ball = int(x.size()) - s.n_balls;  // the balls' angles close the configuration
      out += fmt::format("{},{},{},{},{}", format_number(pt.value, name), st.eq.member,
                         format_number(x[s.balancer_dof], "q1"), format_number(x[s.balancer_dof + 1], "q2"),
                         format_number(st.q_abs, "|q|"));
      for (int b = 0; b < s.n_balls; ++b) out += fmt::format(",{}", format_number(x[first_ball + b], "beta"));
      out += fmt::format(",{},{},{},{},{},{},{},{}\n", format_number(st.max_deflection, "deflection"), st.max_node,
                         finite_or_empty(st.rightmost, "rightmost"), st.verdict, st.verdict == "stable" ? 1 : 0,
                         pt.best == k ? 1 : 0, to_string(st.eq.status.outcome),
                         format_number(st.eq.residual, "residual"));
    }
  return out;
}

std::string shaft_race_sweep_summary_csv(const ShaftRaceSweep& s, std::string_view name, std::string_view unit,
                                         const std::string& header) {
  std::string out = header;
  out += fmt::format("# unround race on a flexible shaft (model.md §18.18), per value of {} [{}]: best_q_abs = |q| "
                     "of the stable state of least |q| [m] (empty: none stable); q_bare = omega^2 U |h|, the balancer "
                     "node's whirl with the balls held at the node [m] ((18.8.1); empty at an undamped critical "
                     "speed); complete = the race's box search (§11.4) proved its list complete\n",
                     name, unit);
  out += fmt::format("{},equilibria,stable,unstable,undetermined,best_q_abs,q_bare,complete\n", name);
  for (const auto& pt : s.points) {
    int stable = 0, unstable = 0;
    for (const auto& st : pt.states) stable += st.verdict == "stable", unstable += st.verdict == "unstable";
    const int undetermined = int(pt.states.size()) - stable - unstable;
    out += fmt::format("{},{},{},{},{},{},{},{}\n", format_number(pt.value, name), pt.states.size(), stable, unstable,
                       undetermined, pt.best ? format_number(pt.states[*pt.best].q_abs, "|q|") : std::string(),
                       pt.q_bare ? format_number(*pt.q_bare, "q0") : std::string(), pt.complete ? 1 : 0);
  }
  return out;
}

}  // namespace abu
