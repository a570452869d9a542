// The files of a sweep on an unround race with an anisotropic support (report_composed_sweep.hpp).
#include "abu/output/report_composed_sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace abu {

namespace {
std::string_view composed_row_status(const ComposedOrbitRow& row) {
  if (row.lost) return "lost";
  switch (row.orbit.status.outcome) {
    case Outcome::converged: return "converged";
    case Outcome::not_converged: return "not_converged";
    case Outcome::numerical_issue: return "numerical_issue";
  }
  return "?";
}
}  // namespace

std::string composed_sweep_csv(const ComposedSweep& s, const std::string& name, const std::string& header) {
  std::size_t count = 0;
  for (const auto& point : s.points)
    for (const auto& row : point.rows) count = std::max(count, row.orbit.multipliers.size());
  std::string out = header;
  out += "# unround race on an anisotropic support (docs/model.md §20.6): at each value every equilibrium of the race "
         "on the mean support continued in the anisotropy to a pi/omega-periodic orbit (§20.4); track: the same orbit "
         "from value to value (0: not converged, no identity); equilibrium: its equilibrium's number at this value "
         "(0: lost); Floquet multipliers over pi/omega (rotating frame), modulus descending, none trivial; "
         "rho_abs_max = max |rho|, decay_rate = (omega/pi) ln rho_abs_max [1/s]; q_abs_max, q_abs_min: |q| over the "
         "period [m] (fixed-frame whirl radius); band: the verdict's margin on ln max|rho| (§10.18); x0_1..x0_(2n+4): the orbit's state at t = 0 "
         "(q1, q2 [m], beta_i [rad], q1', q2' [m/s], beta_i' [rad/s], rotating frame, model.md (2.2))\n";
  for (const auto& point : s.points) {
    if (!point.search_doubt.empty()) out += fmt::format("# at {}={}: the search: {}\n", name, point.value, point.search_doubt);
    for (const auto& row : point.rows)
      if (row.lost)
        out += fmt::format("# at {}={}: lost: {}\n", name, point.value, row.orbit.reason);
      else if (!row.orbit.status.ok())
        out += fmt::format("# at {}={}: {} ({}): {}\n", name, point.value, row.orbit.kind, composed_row_status(row),
                           row.orbit.reason);
  }
  out += fmt::format("{},track,equilibrium,status,stability,rho_abs_max,decay_rate,q_abs_max,q_abs_min,band,"
                     "steps_per_interval",
                     name);
  for (std::size_t k = 1; k <= count; ++k) out += fmt::format(",mult_re{},mult_im{}", k, k);
  for (std::size_t k = 1; k <= count; ++k) out += fmt::format(",x0_{}", k);
  out += "\n";
  for (const auto& point : s.points) {
    for (const auto& row : point.rows) {
      const ForcedOrbit& o = row.orbit;
      out += fmt::format("{},{},{},{}", point.value, row.track, row.equilibrium, composed_row_status(row));
      if (o.status.ok() && !o.multipliers.empty()) {
        out += fmt::format(",{},{},{},{},{},{},{}", to_string(o.verdict), std::abs(o.multipliers.front()),
                           o.log_moduli.front() / o.period, o.q_abs_max, o.q_abs_min, o.band, o.steps_per_interval);
        for (std::size_t m = 0; m < count; ++m)
          out += m < o.multipliers.size() ? fmt::format(",{},{}", o.multipliers[m].real(), o.multipliers[m].imag())
                                          : std::string(",,");
        for (std::size_t m = 0; m < count; ++m)
          out += m < o.state0.size() ? fmt::format(",{}", o.state0[m]) : std::string(",");
      } else {
        out += std::string(7 + 3 * count, ',');
      }
      out += "\n";
    }
  }
  return out;
}

std::string composed_crossings_csv(const ComposedSweep& s, const std::string& name, const std::string& header) {
  std::string out = header;
  out += "# where an orbit's largest Floquet multiplier crosses the unit circle (docs/model.md §20.6): value by "
         "bisection on the parameter, the orbit at each bisection point by Newton from the last one; kind by the "
         "crossing multiplier (+1 fold, -1 flip, complex neimark-sacker)\n";
  for (const ComposedUnlocated& u : s.unlocated) out += fmt::format("# not located: {}\n", u.reason);
  out += fmt::format("orbit,{},kind,direction,mult_re,mult_im,mult_abs,bracket_lower,bracket_upper\n", name);
  for (const FloquetCrossing& c : s.crossings)
    out += fmt::format("{},{},{},{},{},{},{},{},{}\n", c.member, c.value, to_string(c.kind),
                       c.to_unstable ? "to_unstable" : "to_stable", c.multiplier.real(), c.multiplier.imag(),
                       std::abs(c.multiplier), c.lower, c.upper);
  return out;
}

std::string composed_sweep_text(const ComposedSweep& s, const std::string& name) {
  std::string out;
  for (const auto& point : s.points) {
    if (!point.search_doubt.empty())
      out += fmt::format("warning: {}={}: unround race: {}\n", name, point.value, point.search_doubt);
    for (const auto& row : point.rows)
      if (row.lost)
        out += fmt::format("note: {}={}: {}\n", name, point.value, row.orbit.reason);
      else if (!row.orbit.status.ok())
        out += fmt::format("warning: {}={}: {}: {}\n", name, point.value, row.orbit.kind, row.orbit.reason);
  }
  for (const ComposedUnlocated& u : s.unlocated) out += fmt::format("warning: {}\n", u.reason);
  if (s.crossings.empty()) out += "no Floquet multiplier crosses the unit circle in the sweep\n";
  for (const FloquetCrossing& c : s.crossings)
    out += fmt::format("orbit {}: {} at {} = {:.12g} ({}; multiplier {:.9f}{:+.9f}i, |rho| = {:.12f})\n", c.member,
                       to_string(c.kind), name, c.value, c.to_unstable ? "loses stability" : "gains stability",
                       c.multiplier.real(), c.multiplier.imag(), std::abs(c.multiplier));
  return out;
}

}  // namespace abu
