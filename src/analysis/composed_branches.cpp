// `continue` on the composed machine (composed_branches.hpp, docs/model.md §20.9).
#include "abu/analysis/composed_branches.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

#include "abu/core/cancel.hpp"
#include "abu/core/parallel.hpp"

namespace abu {

namespace {

// The orbits found at one end: their x(0) and kinds.
std::vector<ForcedOrbit> usable_orbits(const ComposedSweepPoint& point) {
  std::vector<ForcedOrbit> out;
  for (const ComposedOrbitRow& row : point.rows)
    if (composed_orbit_usable(row.orbit)) out.push_back(row.orbit);
  return out;
}

// How many branch ends lie at `value` on the orbit `orbit` (x(0) within 1e-6 scaled, as the
// sweep matches orbits; the ends on an edge are located there exactly by the engine).
int ends_at(const std::vector<ComposedBranch>& branches, const ParamsN& p, double value, double width,
            const ForcedOrbit& orbit) {
  int count = 0;
  for (const ComposedBranch& b : branches) {
    if (b.branch.points.empty()) continue;
    for (const ForcedBranchPoint* end : {&b.branch.points.front(), &b.branch.points.back()}) {
      if (end == &b.branch.points.back() && b.branch.points.size() == 1) break;
      if (std::abs(end->value - value) <= width &&
          composed_orbit_distance(p, end->orbit.state0, orbit.state0) <= 1e-6)
        ++count;
    }
  }
  return count;
}

void note(ComposedBranches& out, Outcome outcome, std::string why) {
  if (out.status.ok()) out.reason = std::move(why);
  out.status.merge(outcome, "see reason");
}
}  // namespace

ComposedBranches composed_branches(const AnisotropicSupport& support, const ComposedAt& at, double start, double end,
                                   const ForcedBranchOptions& options) {
  ComposedBranches out;
  out.start = start;
  out.end = end;
  const double lo = std::min(start, end), hi = std::max(start, end), width = 1e-9 * (hi - lo);
  const ComposedSweepPoint first = composed_orbits_at(support, at(start), start, options.orbit);
  const std::vector<ForcedOrbit> at_start = usable_orbits(first);
  out.orbits_at_start = int(at_start.size());
  if (!first.search_doubt.empty()) note(out, Outcome::not_converged, fmt::format("at {}: {}", start, first.search_doubt));
  // The seeds of one end: on one thread each is traced unless a branch already ends on it; on
  // several all are traced at once, then kept in seed order unless a kept branch ends on the
  // seed — the same branches either way (a dropped one retraces a kept one backwards).
  const auto trace_from = [&](const std::vector<ForcedOrbit>& seeds, double value, const ParamsN& p) {
    std::vector<std::optional<ForcedBranch>> traced(seeds.size());
    std::vector<std::size_t> open;  // the seeds no branch traced before this end reaches
    for (std::size_t i = 0; i < seeds.size(); ++i)
      if (ends_at(out.branches, p, value, width, seeds[i]) == 0) open.push_back(i);
    if (options.continuation.threads != 1)
      for_each_index(int(open.size()), options.continuation.threads, [&](int k) {
        const std::size_t i = open[std::size_t(k)];
        traced[i] = continue_forced_orbit(support, at, lo, hi, seeds[i], value, options);
        return !stop_requested();
      });
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      throw_if_stopped("continue: composed orbits");
      if (ends_at(out.branches, p, value, width, seeds[i]) != 0) continue;
      ComposedBranch b{value, traced[i] ? std::move(*traced[i])
                                        : continue_forced_orbit(support, at, lo, hi, seeds[i], value, options)};
      if (!b.branch.status.ok())
        note(out, b.branch.status.outcome, fmt::format("{} from {}: {}", seeds[i].kind, value, b.branch.reason));
      out.branches.push_back(std::move(b));
    }
  };
  const ParamsN p_start = at(start).params;
  trace_from(at_start, start, p_start);
  const ComposedSweepPoint last = composed_orbits_at(support, at(end), end, options.orbit);
  const std::vector<ForcedOrbit> at_end = usable_orbits(last);
  out.orbits_at_end = int(at_end.size());
  if (!last.search_doubt.empty()) note(out, Outcome::not_converged, fmt::format("at {}: {}", end, last.search_doubt));
  const ParamsN p_end = at(end).params;
  trace_from(at_end, end, p_end);
  // Every orbit at either end ends exactly one branch (a run that jumped to a neighbouring
  // orbit would end two there, or none on an orbit found).
  for (const auto& [orbits, value, p] : {std::tuple{&at_start, start, &p_start}, std::tuple{&at_end, end, &p_end}})
    for (const ForcedOrbit& orbit : *orbits)
      if (const int ends = ends_at(out.branches, *p, value, width, orbit); ends != 1)
        note(out, Outcome::not_converged,
             fmt::format("the orbit {} at {} ends {} branches instead of one: a run may have jumped to a neighbouring "
                         "orbit (try a smaller --ds-max)",
                         orbit.kind, value, ends));
  return out;
}

}  // namespace abu
