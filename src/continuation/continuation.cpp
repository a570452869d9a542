#include "abu/continuation/continuation.hpp"

#include "abu/core/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <thread>
#include <tuple>

#include "abu/continuation/arclength.hpp"
#include "abu/continuation/corrector.hpp"
#include "abu/core/errors.hpp"
#include "abu/model/static_equations.hpp"
#include "branch_ends.hpp"
#include "branch_tracer.hpp"

namespace abu {

namespace {

using ld = long double;
using Vec5 = StaticEquations::Vec5;

std::vector<Equilibrium> start_points(const Params& p, const StartSelection& start, std::vector<std::string>& notes) {
  std::vector<Equilibrium> out;
  if (start.state) {
    Equilibrium guess;
    guess.position = *start.state;
    guess.family = classify(p, *start.state);
    out.push_back(polish_equilibrium(p, guess));
    if (!out.back().converged)
      notes.push_back(fmt::format("the given start state did not converge to an equilibrium (residual {:.3g})",
                                  out.back().residual));
    return out;
  }
  const EquilibriumSet found = find_equilibria(p);
  for (const auto& e : found.points()) {
    if (start.family && e.family != *start.family) continue;
    if (e.is_set) {
      notes.push_back(fmt::format("{} {} is a circle of equilibria (U = 0): continuation needs isolated "
                                  "equilibria; not continued",
                                  to_string(e.family), e.member));
      continue;
    }
    out.push_back(e);
  }
  return out;
}

// "together, opposite" (or "none"): the families with an equilibrium in `p`.
std::string families_at(const Params& p) {
  std::string out;
  const EquilibriumSet found = find_equilibria(p);
  const auto points = found.points();
  for (const Family f : {Family::balanced, Family::together, Family::opposite}) {
    if (std::none_of(points.begin(), points.end(), [f](const Equilibrium& e) { return e.family == f; })) continue;
    if (!out.empty()) out += ", ";
    out += to_string(f);
  }
  return out.empty() ? "none" : out;
}

}  // namespace

std::string_view to_string(Label label) {
  switch (label) {
    case Label::none: return "";
    case Label::EP: return "EP";
    case Label::LP: return "LP";
    case Label::BP: return "BP";
    case Label::HB: return "HB";
    case Label::MX: return "MX";
    case Label::BT: return "BT";
    case Label::ZH: return "ZH";
    case Label::CP: return "CP";
    case Label::GH: return "GH";
  }
  return "?";
}

std::string_view to_string(StopReason r) {
  switch (r) {
    case StopReason::end_of_range: return "end of the parameter interval";
    case StopReason::max_steps: return "maximum number of steps";
    case StopReason::step_underflow: return "step below its minimum";
    case StopReason::invalid_parameter: return "parameter left its valid range";
    case StopReason::closed_loop: return "closed loop";
  }
  return "?";
}

Family classify(const Params& p, const Coordinates<long double, 2>& s) {
  const ld length = displacement_scale(p.cast<ld>());
  if (std::hypot(s(0), s(1)) <= 1e-7L * length) return Family::balanced;
  const ld apart = std::abs(std::remainder(s(2) - s(3), 2 * std::numbers::pi_v<ld>));
  return apart < std::numbers::pi_v<ld> / 2 ? Family::together : Family::opposite;
}

namespace {
// How one direction of a branch ended (branch_ends.hpp).
std::pair<StopReason, std::string> stop_of(const StaticEquations& eq, const arclength::Result<BranchTracer>& r,
                                           const ContinuationOptions& options) {
  return stop_of(r, options,
                 [&](const Vec5& z) { return fmt::format("{}={:.17g}", to_string(eq.param()), double(eq.parameter(z))); });
}

// Traces the branch through `e` at scaled parameter z4 = end (0: the start value, 1 the
// far end), heading into the interval, and appends it to the run.
Branch trace_branch(const StaticEquations& eq, const Equilibrium& e, ld parameter, ld end,
                    const ContinuationOptions& options, ContinuationStats& stats) {
  Vec5 inward = Vec5::Zero();
  inward(4) = end == 0 ? 1 : -1;
  BranchTracer forward(eq), backward(eq);
  // Backwards only if the branch does not leave the interval at once (a fold at the start).
  const auto start = arclength::start(forward, eq.scaled(e.position, parameter), inward);
  const auto run = arclength::trace_both_ways(forward, backward, start, options);
  for (const auto* r : {&run.forward, &run.backward}) {
    stats.steps += r->stats.steps;
    stats.rejected += r->stats.rejected;
    stats.newton_iterations += r->stats.newton_iterations;
  }
  stats += forward.stats;
  stats += backward.stats;
  Branch b;
  b.family = e.family;
  b.member = e.member;
  b.start_parameter = parameter;
  for (std::size_t k = backward.points.size(); k > 1; --k) b.points.push_back(backward.points[k - 1]);
  for (auto it = backward.specials.rbegin(); it != backward.specials.rend(); ++it) {
    SpecialPoint sp = *it;  // traversed the other way: before and after swap
    std::swap(sp.n_unstable_before, sp.n_unstable_after);
    std::swap(sp.bracket_from, sp.bracket_to);
    b.specials.push_back(sp);
  }
  b.points.insert(b.points.end(), forward.points.begin(), forward.points.end());
  b.specials.insert(b.specials.end(), forward.specials.begin(), forward.specials.end());
  std::tie(b.stop[1], b.stop_detail[1]) = stop_of(eq, run.forward, options);
  if (run.backward_traced) {
    std::tie(b.stop[0], b.stop_detail[0]) = stop_of(eq, run.backward, options);
  } else {
    b.stop[0] = StopReason::end_of_range;
    b.stop_detail[0] = "the start value is an end of the interval";
    b.points.front().label = Label::EP;
  }
  return b;
}

// A start's branch traced on a worker: the branch, its statistics, or the exception it threw.
struct Traced {
  Branch branch;
  ContinuationStats stats;
  std::exception_ptr error;
};

// Threads for `count` tasks: `threads`, 0 meaning one per core, at most one per task.
std::size_t workers_for(std::size_t count, int threads) {
  const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  return std::min(count, threads > 0 ? std::size_t(threads) : hardware);
}

// Does the branch pass through the configuration z at the scaled parameter of z?
bool passes_through(const StaticEquations& eq, const Branch& b, const Vec5& z) {
  for (const auto& pt : b.points)
    if (distance(eq.scaled(pt.position, pt.parameter), z) < 1e-8L) return true;
  return false;
}
}  // namespace

ContinuationRun continue_branches(const Params& p, ParamRef param, double to, const ContinuationOptions& options,
                                  const StartSelection& start) {
  ContinuationRun run;
  run.param = param;
  run.from = get(p, param);
  run.to = to;
  if (const auto rule = range_violation(param.quantity, to)) throw InputError("continuation", 0, to_string(param), *rule);
  if (to == run.from) throw InputError("continuation", 0, to_string(param), "the end value equals the start value");
  const StaticEquations eq(p, param, run.from, ld(to) - ld(run.from));
  // Branches from the equilibria at the start value; then, so that no branch of the
  // interval is missed, from those at the far end that no branch has reached (a family
  // that exists only in part of the interval, beyond a fold).
  Params far = p;
  set(far, param, to);
  struct Start {
    Equilibrium e;
    ld parameter, end;
  };
  std::vector<Start> starts;
  for (const auto& e : start_points(p, start, run.notes)) starts.push_back({e, run.from, 0});
  const std::size_t near_starts = starts.size();
  if (!start.state)
    for (const auto& e : start_points(far, start, run.notes)) starts.push_back({e, ld(to), 1});
  if (start.family && starts.empty())
    throw InputError(std::string(start.family_option), 0, std::string(to_string(*start.family)),
                     fmt::format("no {} equilibrium at {} = {} or at {} (model.md §5): nothing to continue (there: {}; "
                                 "{})",
                                 to_string(*start.family), to_string(param), run.from, to, families_at(p), families_at(far)));
  run.memory_estimate = require_branch_memory(options, sizeof(BranchPoint), starts.size());
  // Each start's branch is traced independently of the others (trace_branch reads only
  // the equations and its start), so the starts of one batch are traced concurrently and
  // then kept or dropped in their order, exactly as one after the other: a start is
  // dropped if it lies on a branch kept before it, and only kept branches count in the
  // statistics. The output is the same whatever the thread count; a dropped start costs
  // its (discarded) trace in CPU time, not in wall time. Two batches: the starts at the
  // far end are first checked against the branches from the start value (most of them lie
  // on one), and only the rest are traced.
  const auto on_kept = [&](const Start& s) -> const Branch* {
    const Vec5 z = eq.scaled(s.e.position, s.parameter);
    const Branch* on = nullptr;
    for (const auto& b : run.branches)
      if (passes_through(eq, b, z)) on = &b;
    return on;
  };
  const auto batch = [&](std::size_t first, std::size_t last, bool prefilter) {
    std::vector<std::size_t> todo;
    for (std::size_t i = first; i < last; ++i)
      if (!prefilter || !on_kept(starts[i])) todo.push_back(i);
    const std::size_t workers = workers_for(todo.size(), options.threads);
    if (workers <= 1) {  // one after the other: a start on a kept branch is not traced at all
      for (const std::size_t i : todo) {
        const Start& s = starts[i];
        if (const Branch* on = on_kept(s)) {
          if (s.end == 0)
            run.notes.push_back(fmt::format("{} {} lies on the branch of {} {}; not traced again",
                                            to_string(s.e.family), s.e.member, to_string(on->family), on->member));
          continue;
        }
        run.branches.push_back(trace_branch(eq, s.e, s.parameter, s.end, options, run.stats));
      }
      return;
    }
    std::vector<Traced> traced(todo.size());
    for_each_index(int(todo.size()), int(workers), [&](int j) {  // each start's errors kept for its turn below
      const std::size_t k = std::size_t(j);
      const Start& s = starts[todo[k]];
      try {
        traced[k].branch = trace_branch(eq, s.e, s.parameter, s.end, options, traced[k].stats);
      } catch (...) {
        traced[k].error = std::current_exception();
      }
      return true;
    });
    for (std::size_t k = 0; k < todo.size(); ++k) {
      const Start& s = starts[todo[k]];
      if (const Branch* on = on_kept(s)) {
        if (s.end == 0)
          run.notes.push_back(fmt::format("{} {} lies on the branch of {} {}; not traced again", to_string(s.e.family),
                                          s.e.member, to_string(on->family), on->member));
        continue;
      }
      if (traced[k].error) std::rethrow_exception(traced[k].error);
      run.stats += traced[k].stats;
      run.branches.push_back(std::move(traced[k].branch));
    }
  };
  batch(0, near_starts, false);
  batch(near_starts, starts.size(), true);
  // A singular point one branch could not locate may be one another branch located: two
  // branches meeting where a fold and a branch point coincide (F_s of rank 2) are
  // approachable only along one of them. Adopt that location, and say so.
  for (auto& b : run.branches)
    for (auto& sp : b.specials) {
      if (sp.converged || (sp.label != Label::LP && sp.label != Label::BP)) continue;
      // Close in the scaled unknowns, the parameter included (a fold's parameter lies
      // beyond both of its bracketing points, so the bracket itself cannot be the test).
      for (std::size_t k = 0; k < run.branches.size() && !sp.converged; ++k)
        for (const auto& other : run.branches[k].specials) {
          if (!other.converged || (other.label != Label::LP && other.label != Label::BP)) continue;
          if (distance(eq.scaled(other.position, other.parameter), eq.scaled(sp.position, sp.parameter)) > 1e-2L) continue;
          sp.label = other.label;
          sp.parameter = other.parameter;
          sp.position = other.position;
          sp.eigenvalue = other.eigenvalue;
          sp.converged = true;
          sp.note = fmt::format("located on branch {}, which meets this one there", k + 1);
          break;
        }
    }
  return run;
}

}  // namespace abu
