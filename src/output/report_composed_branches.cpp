// The files of `continue` on the composed machine (report_composed_branches.hpp).
#include "abu/output/report_composed_branches.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace abu {

namespace {
// The multipliers' count over every point (2n + 4 where every orbit converged).
std::size_t multiplier_count(const ComposedBranches& b) {
  std::size_t count = 0;
  for (const auto& br : b.branches)
    for (const auto& pt : br.branch.points) count = std::max(count, pt.orbit.multipliers.size());
  return count;
}

// stability, rho_abs_max, decay_rate, q_abs_max, q_abs_min, band, steps_per_interval; empty
// fields for an orbit whose multipliers failed (never a NaN).
std::string orbit_fields(const ForcedOrbit& o) {
  if (!o.status.ok() || o.multipliers.empty()) return std::string(6, ',');
  return fmt::format("{},{},{},{},{},{},{}", to_string(o.verdict), std::abs(o.multipliers.front()),
                     o.log_moduli.front() / o.period, o.q_abs_max, o.q_abs_min, o.band, o.steps_per_interval);
}
}  // namespace

std::string composed_branches_csv(const ComposedBranches& b, const std::string& name, const std::string& header) {
  const std::size_t count = multiplier_count(b);
  std::string out = header;
  out += "# unround race on an anisotropic support (docs/model.md §20.9): every pi/omega-periodic orbit found at the "
         "start value continued by pseudo-arclength in the parameter (multiple shooting, the parameter an unknown), "
         "through its folds; then the orbits at the other end that no branch reached; a blank line between branches. "
         "branch: its number; start: the value it was started from; point: its index along the branch (arclength "
         "order); Floquet multipliers over pi/omega (rotating frame), modulus descending, none trivial; rho_abs_max = "
         "max |rho|, decay_rate = (omega/pi) ln rho_abs_max [1/s]; q_abs_max, q_abs_min: |q| over the period [m] "
         "(fixed-frame whirl radius); band: the verdict's margin on ln max|rho| (§10.18); x0_1..x0_(2n+4): the orbit's "
         "state at t = 0 (q1, q2 [m], beta_i [rad], q1', q2' [m/s], beta_i' [rad/s], rotating frame, model.md (2.2))\n";
  if (!b.status.ok()) out += fmt::format("# doubt: {}\n", b.reason);
  for (std::size_t i = 0; i < b.branches.size(); ++i) {
    const ForcedBranch& br = b.branches[i].branch;
    out += fmt::format("# branch {}: from {} = {} ({}), {} points; run one way: {}{}{}\n", i + 1, name,
                       b.branches[i].start_value, br.points.empty() ? std::string("-") : br.points.front().orbit.kind,
                       br.points.size(), br.end_forward,
                       br.end_backward.empty() ? std::string() : fmt::format(", the other: {}", br.end_backward),
                       br.status.ok() ? std::string() : fmt::format("; {}", br.reason));
  }
  out += fmt::format("branch,start,point,{},orbit,stability,rho_abs_max,decay_rate,q_abs_max,q_abs_min,band,"
                     "steps_per_interval",
                     name);
  for (std::size_t k = 1; k <= count; ++k) out += fmt::format(",mult_re{},mult_im{}", k, k);
  for (std::size_t k = 1; k <= count; ++k) out += fmt::format(",x0_{}", k);
  out += "\n";
  for (std::size_t i = 0; i < b.branches.size(); ++i) {
    if (i > 0) out += "\n";
    const auto& br = b.branches[i];
    for (std::size_t k = 0; k < br.branch.points.size(); ++k) {
      const ForcedOrbit& o = br.branch.points[k].orbit;
      out += fmt::format("{},{},{},{},{},{}", i + 1, br.start_value, k + 1, br.branch.points[k].value, o.kind,
                         orbit_fields(o));
      for (std::size_t m = 0; m < count; ++m)
        out += m < o.multipliers.size() ? fmt::format(",{},{}", o.multipliers[m].real(), o.multipliers[m].imag())
                                        : std::string(",,");
      for (std::size_t m = 0; m < count; ++m)
        out += m < o.state0.size() ? fmt::format(",{}", o.state0[m]) : std::string(",");
      out += "\n";
    }
  }
  return out;
}

std::string composed_specials_csv(const ComposedBranches& b, const std::string& name, const std::string& header) {
  std::string out = header;
  out += "# special points along the branches (docs/model.md §20.9), each located by Brent's method on the chord "
         "between two branch points: LP a fold (the branch turns back in the parameter: a multiplier +1), BP a real "
         "multiplier +1 where the branch goes on, PD a multiplier -1 (period doubling), NS a complex pair on the unit "
         "circle (Neimark-Sacker: a torus); mult: the critical multiplier there (LP, BP: the real one nearest +1; PD: "
         "nearest -1; NS: the complex one of modulus nearest 1; rotating frame, over pi/omega); rho_abs_max: the "
         "largest modulus (the orbit's stability)\n";
  out += fmt::format("branch,kind,{},orbit,q_abs_max,mult_re,mult_im,mult_abs,rho_abs_max\n", name);
  for (std::size_t i = 0; i < b.branches.size(); ++i)
    for (const ForcedSpecialPoint& s : b.branches[i].branch.specials) {
      const ForcedOrbit& o = s.orbit;
      if (!s.located) {  // no row: its value is not known
        out += fmt::format("# not located: branch {}, {} between {} = {} and {}: {}\n", i + 1, s.kind, name,
                           s.bracket[0], s.bracket[1], s.reason);
        continue;
      }
      out += fmt::format("{},{},{},{},", i + 1, s.kind, s.value, o.kind);
      out += o.status.ok() && !o.multipliers.empty()
                 ? fmt::format("{},{},{},{},{}\n", o.q_abs_max, s.multiplier.real(), s.multiplier.imag(),
                               std::abs(s.multiplier), std::abs(o.multipliers.front()))
                 : std::string(",,,,\n");
    }
  return out;
}

std::string composed_branches_text(const ComposedBranches& b, const std::string& name) {
  std::string out;
  std::size_t specials = 0;
  for (std::size_t i = 0; i < b.branches.size(); ++i) {
    const auto& br = b.branches[i].branch;
    for (const ForcedSpecialPoint& s : br.specials) {
      ++specials;
      if (!s.located) {
        out += fmt::format("branch {} ({}): {} between {} = {:.12g} and {:.12g}, detected but not located ({})\n", i + 1,
                           s.orbit.kind, s.kind, name, s.bracket[0], s.bracket[1], s.reason);
        continue;
      }
      out += fmt::format("branch {} ({}): {} at {} = {:.12g}", i + 1, s.orbit.kind, s.kind, name, s.value);
      if (s.orbit.status.ok() && !s.orbit.multipliers.empty())
        out += fmt::format(" (max |q| {:.6g} m; multiplier {:.9f}{:+.9f}i, |rho| {:.12f}; {})", s.orbit.q_abs_max,
                           s.multiplier.real(), s.multiplier.imag(), std::abs(s.multiplier), to_string(s.orbit.verdict));
      out += "\n";
    }
  }
  if (specials == 0) out += "no fold, branch, flip or Neimark-Sacker point on the branches\n";
  if (!b.status.ok()) out += fmt::format("warning: {}\n", b.reason);
  return out;
}

}  // namespace abu
