// The pseudo-arclength engine: one predictor-corrector loop for every continuation of
// the program (equilibrium branches in one parameter, fold and Hopf curves in two, and
// whatever comes next), generic over the problem.
//
// One step from the last accepted point u with unit tangent t:
//   predict   u_pred = u + ds t
//   correct   Newton on [F(u); t . (u - u_pred)] = 0 (bordered.hpp)
//   check     converged, within ds of u_pred, the new tangent turned by < max_turning;
//             else the step is halved and retried, and below ds_min the run ends
//   domain    the problem says whether the point left its box (the run ends on the edge,
//             the point there found by the corrector with the crossing coordinate fixed)
//             or its domain (the run ends there)
//   evaluate  the problem computes its data at the point (and may ask for a shorter
//             step: e.g. eigenvalue tracking that lost the modes' identity) and returns
//             its test functions
//   detect    a test function whose sign differs from the last point's flags an event;
//             the problem locates it (by an augmented system, bisection, ...)
//   commit    the problem records the point (and may rescale its unknowns)
//   adapt     ds *= clamp(sqrt(predictor_error / (|u_new - u_pred| / ds)), shrink, grow):
//             the predictor's relative error ~ curvature * ds / 2 aimed at predictor_error
//
// This is the structure of AUTO-07p's algebraic continuation (a step, its test functions
// compared with the last point's, special points located between) and of BifurcationKit's
// iterator (an event is a sign change of a continuous indicator, or a change of a
// discrete one such as a count of unstable eigenvalues, +1/-1 here).
//
// A Problem is a System (bordered.hpp) with, further (see the concept below):
//   static constexpr std::size_t test_count;                       // its test functions
//   Crossing crossing(const Vec& from, const Vec& to) const;      // the domain
//   Evaluation<Scalar, test_count> evaluate(u, t, J, Stage);       // data and test values
//   void locate(unsigned changed, const Segment<Vec>& between);    // bit k: test k changed sign
//   void commit(Vec& u, Vec& t, Stage);                            // record (may rescale)
// and optionally
//   static constexpr bool tangent_at_solution = true;  // F_u for the tangent evaluated at
//                                                      // the corrected point (finite differences)
//   Scalar distance(const Vec& a, const Vec& b) const; // ends a branch that closes on itself
//
//   abu::arclength::Start<P> s = abu::arclength::start(problem, u0, inward);
//   abu::arclength::Result<P> r = abu::arclength::trace(problem, s.u, s.tangent, s.jacobian, options, rules);
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "abu/continuation/bordered.hpp"

namespace abu {

/// Step-length control, in the scaled arclength (every problem scales its unknowns to
/// O(1): for branches the parameter interval is 1 unit long).
struct ContinuationOptions {
  double ds = 0.01;      ///< first step
  double ds_min = 1e-9;  ///< below this a failing step ends the branch (MX)
  double ds_max = 0.2;   ///< upper bound (the step also adapts to the branch's curvature)
  int max_steps = 5000;  ///< predictor-corrector attempts (retries included) per branch and direction
  /// Branches traced at once (continue_branches, two balls; the composed machine's orbits,
  /// composed_branches; 0: one per core). The result does not depend on it.
  int threads = 1;
};
/// Checks the options up front; returns the rule broken, if any.
std::optional<std::string> options_violation(const ContinuationOptions& o);

/// What one branch traced both ways from its start holds at most [bytes]: max_steps + 1
/// points each way of point_bytes, twice over for the vectors' growth.
double branch_memory_bound(const ContinuationOptions& o, std::size_t point_bytes);
/// Refuses (InputError naming --max-steps) branches whose bound, `branches` of them held at
/// once, is more than this machine can hold (core/resources.hpp); returns that estimate.
double require_branch_memory(const ContinuationOptions& o, std::size_t point_bytes, std::size_t branches);

namespace arclength {

/// The engine's own rules; the defaults are those of equilibrium branches.
struct StepRules {
  long double predictor_error = 0.1L;  ///< aimed-at |u_new - u_pred| / ds
  long double max_turning = 0.5L;      ///< rad between consecutive tangents, at most
  long double shrink = 0.5L;           ///< the step changes by at least this factor ...
  long double grow = 2;                ///< ... and at most this one per accepted step
  /// A problem's request for a shorter step is granted while ds > retry_floor * ds_min;
  /// below, the point is taken anyway (a preference is no reason to end the branch).
  long double retry_floor = 16;
  /// A start on the edge of the box whose tangent points inwards by more than this
  /// (cosine) is traced one way only: the other way leaves the box at once.
  long double transversal = 1e-6L;
};

/// Which point a hook is called for.
enum class Stage { start, step, edge };

/// What a corrected point does to the run: inside the domain; across an edge of the box
/// (coordinate `component` beyond `bound`); or out of the domain (the run ends, `reason`
/// says why).
struct Crossing {
  enum Kind { inside, edge, exit } kind = inside;
  int component = 0;
  long double bound = 0;
  std::string reason;
  static Crossing at_edge(int component, long double bound) { return {edge, component, bound, {}}; }
  static Crossing leaving(std::string reason) { return {exit, 0, 0, std::move(reason)}; }
};

/// The first of `components` of `to` outside [0, 1], as an edge crossing.
template <class Vec>
Crossing box_crossing(const Vec& to, std::initializer_list<int> components) {
  for (int k : components)
    if (to(k) < 0 || to(k) > 1) return Crossing::at_edge(k, to(k) > 1 ? 1 : 0);
  return {};
}

/// A problem's verdict on a corrected point, and its test functions there.
template <class Scalar, std::size_t K>
struct Evaluation {
  bool retry = false;       ///< asks for the step to be retried shorter
  std::string_view reason;  ///< why (reported if the step then underflows)
  std::array<Scalar, K> tests{};
};

/// Two consecutive points with their tangents, between which a test function changed sign.
template <class Vec>
struct Segment {
  const Vec& from;
  const Vec& from_tangent;
  const Vec& to;
  const Vec& to_tangent;
};

template <class P>
concept Problem = System<P> &&
    requires(P& p, const P& cp, typename P::Vec& u, const typename P::Vec& cu, const typename P::Jacobian& J,
             const Segment<typename P::Vec>& seg) {
  { P::test_count } -> std::convertible_to<std::size_t>;
  { cp.crossing(cu, cu) } -> std::same_as<Crossing>;
  { p.evaluate(cu, cu, J, Stage::step) }
      -> std::same_as<Evaluation<typename P::Vec::Scalar, P::test_count>>;
  p.locate(0u, seg);
  p.commit(u, u, Stage::step);
};

/// How a run ended.
enum class End {
  end_of_interval,   ///< on the edge of the box: the last point lies on it
  edge_not_reached,  ///< crossed the edge, but the corrector found no point on it
  left_domain,       ///< the problem's domain ended it (Crossing::exit)
  closed_loop,       ///< came back to its start
  max_steps,         ///< ran out of attempts
  step_underflow,    ///< a step failed at ds < ds_min
};
std::string_view to_string(End e);
/// "the tangent turned by more than X rad" (X as printf %g): the engine's reason for a
/// step refused on turning (kept out of the header so that it needs no formatting library).
std::string turning_reason(long double max_turning);

struct Stats {
  long steps = 0;              ///< accepted points (start and edge points not counted)
  long rejected = 0;           ///< attempts retried with a shorter step
  long newton_iterations = 0;  ///< of the predictor-corrector steps (edge corrections not counted)
};

template <class P>
struct Result {
  End end = End::max_steps;
  /// converged for a run that ended where it should (an edge, the domain, a closed loop);
  /// otherwise not_converged, or numerical_issue if its last corrector broke down.
  Status status = Status::converged;
  /// Why: for step_underflow the last failure (the corrector's reason, the step's
  /// length or turning, or the problem's); for left_domain the problem's; for
  /// edge_not_reached the corrector's.
  std::string reason;
  typename P::Vec last;    ///< the last accepted point
  typename P::Vec beyond;  ///< left_domain: the point outside; edge_not_reached: the guess on the edge
  long double ds = 0;      ///< step_underflow: the step that failed last
  Stats stats;
};

/// The first point of a run: u0, F_u there, and the unit tangent heading along `inward`.
template <class P>
struct Start {
  typename P::Vec u;
  typename P::Jacobian jacobian;
  typename P::Vec tangent;
  /// Worth tracing against the tangent too: false when u0 lies on the box's edge and the
  /// tangent crosses it transversally (the other way leaves the box at once).
  bool both_ways = true;
};

template <System P>
Start<P> start(const P& p, const typename P::Vec& u0, const typename P::Vec& inward, bool on_edge = true,
               const StepRules& rules = {}) {
  Start<P> s{u0, p.jacobian(u0), inward};
  s.tangent = tangent(p, s.jacobian, inward);
  s.both_ways = !(on_edge && s.tangent.dot(inward) > rules.transversal);
  return s;
}

namespace detail {

template <class P>
auto tangent_jacobian(const P& p, const Correction<P>& c) {
  if constexpr (requires { requires P::tangent_at_solution; }) {
    return typename P::Jacobian(p.jacobian(c.u));
  } else {
    return c.jacobian;
  }
}

// Evaluates the problem at an accepted point, flags the test functions that changed sign
// since the last one, has them located, and commits the point.
template <class P>
void advance(P& p, typename P::Vec& u, typename P::Vec& t,
             std::array<typename P::Vec::Scalar, P::test_count>& tests, const typename P::Vec& u_new,
             const typename P::Vec& t_new, const Evaluation<typename P::Vec::Scalar, P::test_count>& e, Stage stage) {
  unsigned changed = 0;
  for (std::size_t k = 0; k < P::test_count; ++k)
    if ((tests[k] > 0) != (e.tests[k] > 0)) changed |= 1u << k;
  if (changed) p.locate(changed, Segment<typename P::Vec>{u, t, u_new, t_new});
  u = u_new;
  t = t_new;
  tests = e.tests;
  p.commit(u, t, stage);
}

// The run crossed an edge of the box between u and `beyond`: its last point is the one on
// the edge exactly, found by the corrector with the crossing coordinate fixed, from the
// secant's intersection with the edge.
template <class P>
void end_on_edge(P& p, typename P::Vec& u, typename P::Vec& t, std::array<typename P::Vec::Scalar, P::test_count>& tests,
                 const typename P::Vec& beyond, const Crossing& x, Result<P>& out) {
  using Vec = typename P::Vec;
  using Scalar = typename Vec::Scalar;
  const int k = x.component;
  const Scalar theta = (Scalar(x.bound) - u(k)) / (beyond(k) - u(k));
  Vec guess = u + theta * (beyond - u);
  guess(k) = Scalar(x.bound);
  Vec e = Vec::Zero(u.size());
  e(k) = 1;
  const Correction<P> last = correct(p, guess, e);
  if (!last.converged()) {
    out.end = End::edge_not_reached;
    out.status = last.status;
    out.reason = last.reason;
    out.last = u;
    out.beyond = guess;
    return;
  }
  const Vec t_edge = tangent(p, tangent_jacobian(p, last), t);
  advance(p, u, t, tests, last.u, t_edge, p.evaluate(last.u, t_edge, last.jacobian, Stage::edge), Stage::edge);
  out.end = End::end_of_interval;
  out.last = u;
}

}  // namespace detail

/// Traces from the start point (u0, t0; J0 = F_u at u0) until the run ends.
template <Problem P>
Result<P> trace(P& p, const typename P::Vec& u0, const typename P::Vec& t0, const typename P::Jacobian& J0,
                const ContinuationOptions& options, const StepRules& rules = {}) {
  using Vec = typename P::Vec;
  using Scalar = typename Vec::Scalar;
  Result<P> out;
  Vec u = u0, t = t0;
  std::array<Scalar, P::test_count> tests = p.evaluate(u, t, J0, Stage::start).tests;
  p.commit(u, t, Stage::start);
  const Vec first = u;
  long accepted = 1;
  const Scalar min_cos = std::cos(Scalar(rules.max_turning));
  const Scalar ds_min = options.ds_min;
  Scalar ds = options.ds;
  // A failed attempt: halve the step; false (and the result filled) once below ds_min.
  const auto shrink = [&](Status status, const auto& why) {
    ++out.stats.rejected;
    ds /= 2;
    if (ds >= ds_min) return true;
    out.end = End::step_underflow;
    out.status = status;
    out.reason = why();
    out.ds = ds * 2;
    return false;
  };
  for (int attempt = 0; attempt < options.max_steps; ++attempt) {
    const Vec u_pred = u + ds * t;
    const Correction<P> c = correct(p, u_pred, t);
    out.stats.newton_iterations += c.iterations;
    const Scalar moved = (c.u - u_pred).norm();
    if (!c.converged() || !(moved <= ds)) {
      const auto why = [&]() -> std::string {
        return c.converged() ? std::string("the corrector converged farther than one step from the predictor")
                             : "the corrector did not converge (" + std::string(c.reason) + ")";
      };
      if (!shrink(c.converged() ? Status::not_converged : c.status, why)) break;
      continue;
    }
    const Vec t_new = tangent(p, detail::tangent_jacobian(p, c), t);
    if (!(t_new.dot(t) > min_cos)) {
      const auto why = [&] { return turning_reason(rules.max_turning); };
      if (!shrink(Status::not_converged, why)) break;
      continue;
    }
    Crossing x = p.crossing(u, c.u);
    if (x.kind == Crossing::edge) {
      detail::end_on_edge(p, u, t, tests, c.u, x, out);
      return out;
    }
    if (x.kind == Crossing::exit) {
      out.end = End::left_domain;
      out.reason = std::move(x.reason);
      out.last = u;
      out.beyond = c.u;
      return out;
    }
    const auto e = p.evaluate(c.u, t_new, c.jacobian, Stage::step);
    if (e.retry && ds > rules.retry_floor * ds_min) {
      if (!shrink(Status::not_converged, [&] { return std::string(e.reason); })) break;
      continue;
    }
    ++out.stats.steps;
    detail::advance(p, u, t, tests, c.u, t_new, e, Stage::step);
    ++accepted;
    if constexpr (requires { p.distance(u, first); }) {
      // Back within one step of the start, a few points out (not the first steps away).
      if (accepted > 5 && p.distance(u, first) < ds) {
        out.end = End::closed_loop;
        out.last = u;
        return out;
      }
    }
    const Scalar relative_error = moved / ds;
    const Scalar factor = std::clamp(std::sqrt(Scalar(rules.predictor_error) / std::max(relative_error, Scalar(1e-12L))),
                                     Scalar(rules.shrink), Scalar(rules.grow));
    ds = std::clamp<Scalar>(ds * factor, ds_min, Scalar(options.ds_max));
  }
  if (out.end != End::step_underflow) {
    out.end = End::max_steps;
    out.status = Status::not_converged;
    out.reason = "ran out of steps";
  }
  out.last = u;
  return out;
}

/// Both ways from a start: along its tangent with `forward`, against it with `backward`
/// (a separate problem: its own points, its own state) unless the start says one way is
/// enough.
template <Problem P>
struct BothWays {
  Result<P> forward, backward;
  bool backward_traced = false;
};

template <Problem P>
BothWays<P> trace_both_ways(P& forward, P& backward, const Start<P>& s, const ContinuationOptions& options,
                            const StepRules& rules = {}) {
  BothWays<P> out;
  out.forward = trace(forward, s.u, s.tangent, s.jacobian, options, rules);
  if (s.both_ways) {
    out.backward = trace(backward, s.u, typename P::Vec(-s.tangent), s.jacobian, options, rules);
    out.backward_traced = true;
  }
  return out;
}

}  // namespace arclength
}  // namespace abu
