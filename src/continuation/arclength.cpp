#include "abu/continuation/arclength.hpp"

#include <fmt/format.h>

#include "abu/core/resources.hpp"

namespace abu {

std::optional<std::string> options_violation(const ContinuationOptions& o) {
  if (!(o.ds_min > 0)) return fmt::format("--ds-min must be > 0 (got {})", o.ds_min);
  if (!(o.ds >= o.ds_min)) return fmt::format("--ds must be >= --ds-min (got {} < {})", o.ds, o.ds_min);
  if (!(o.ds_max >= o.ds)) return fmt::format("--ds-max must be >= --ds (got {} < {})", o.ds_max, o.ds);
  if (!(o.ds_max <= 0.5)) return fmt::format("--ds-max must be <= 0.5 of the interval (got {})", o.ds_max);
  if (o.max_steps < 1 || o.max_steps > 1000000)
    return fmt::format("--max-steps must be in [1, 1000000] (got {})", o.max_steps);
  if (o.threads < 0 || o.threads > 1024) return fmt::format("--threads must be in [0, 1024] (got {})", o.threads);
  return std::nullopt;
}

double branch_memory_bound(const ContinuationOptions& o, std::size_t point_bytes) {
  return 2.0 * (double(o.max_steps) + 1) * 2.0 * double(point_bytes);
}

double require_branch_memory(const ContinuationOptions& o, std::size_t point_bytes, std::size_t branches) {
  const double bytes = 20e6 + double(branches) * branch_memory_bound(o, point_bytes);
  require_memory(bytes, "--max-steps", "the branches",
                 fmt::format("{} branch{} of up to {} points each way, {} bytes a point", branches,
                             branches == 1 ? "" : "es", o.max_steps + 1, point_bytes),
                 "use fewer --max-steps");
  return bytes;
}

namespace arclength {

std::string_view to_string(End e) {
  switch (e) {
    case End::end_of_interval: return "reached the end of the interval";
    case End::edge_not_reached: return "no solution found on the end of the interval";
    case End::left_domain: return "left the domain";
    case End::closed_loop: return "closed loop";
    case End::max_steps: return "maximum number of steps";
    case End::step_underflow: return "step below its minimum";
  }
  return "?";
}

std::string turning_reason(long double max_turning) {
  return fmt::format("the tangent turned by more than {:g} rad", double(max_turning));
}

}  // namespace arclength
}  // namespace abu
