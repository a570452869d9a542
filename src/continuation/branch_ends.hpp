// How one direction of an equilibrium branch ended, in the terms of continuation.hpp
// (StopReason and its detail), for the two-ball and the n-ball branches alike. Internal.
#pragma once

#include <fmt/format.h>

#include <string>
#include <utility>

#include "abu/continuation/arclength.hpp"
#include "abu/continuation/continuation.hpp"

namespace abu {

/// `at(u)`: "NAME=VALUE" of the parameter at the engine's point u.
template <class Result, class At>
std::pair<StopReason, std::string> stop_of(const Result& r, const ContinuationOptions& options, const At& at) {
  switch (r.end) {
    case arclength::End::end_of_interval: return {StopReason::end_of_range, {}};
    case arclength::End::edge_not_reached:
      return {StopReason::step_underflow, fmt::format("no equilibrium found at the end value {}", at(r.beyond))};
    case arclength::End::left_domain: return {StopReason::invalid_parameter, r.reason};
    case arclength::End::closed_loop: return {StopReason::closed_loop, {}};
    case arclength::End::max_steps:
      return {StopReason::max_steps, fmt::format("stopped after {} steps at {}", options.max_steps, at(r.last))};
    case arclength::End::step_underflow:
      return {StopReason::step_underflow, fmt::format("{} with step {:.3g} at {}", r.reason, double(r.ds), at(r.last))};
  }
  return {StopReason::step_underflow, r.reason};
}

}  // namespace abu
