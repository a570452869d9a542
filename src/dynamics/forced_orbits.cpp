// The aligned states on an anisotropic support as pi/omega-periodic orbits: multiple
// shooting over the forcing period, continued in the anisotropy homotopy parameter with
// the arclength engine (forced_orbits.hpp, docs/model.md §10.14).
#include "abu/dynamics/forced_orbits.hpp"

#include <fmt/format.h>

#include <numbers>

#include "abu/equilibria/equilibria_n.hpp"
#include "forced_problem.hpp"

namespace abu {
namespace {
using detail::ForcedProblem;
using StateX = State<double, any_balls>;
using detail::failed;

std::string kind_of(const EquilibriumN& e, int n) {
  if (e.family == Family::aligned) return fmt::format("aligned {} {}", pattern_string(e.pattern, n), e.member);
  return fmt::format("{} {}", to_string(e.family), e.member);
}

// The result of an orbit of kind `kind` of the machine at p: period pi/omega.
ForcedOrbit orbit_at(const ParamsN& p, std::string kind) {
  ForcedOrbit out;
  out.kind = std::move(kind);
  out.period = std::numbers::pi / p.omega;
  return out;
}

}  // namespace

ForcedOrbit forced_orbit(const ParamsN& p, const AnisotropicSupport& s, const EquilibriumN& e,
                         const ForcedOrbitOptions& o) {
  ForcedOrbit out;
  out.family = e.family;
  out.pattern = e.pattern;
  out.member = e.member;
  out.kind = kind_of(e, e.n_balls());
  out.period = std::numbers::pi / p.omega;
  const auto fail = [&](std::string why) {
    out.status.merge(e.converged ? Outcome::numerical_issue : Outcome::not_converged, "see reason");
    out.reason = std::move(why);
    return out;
  };
  if (e.family == Family::balanced) return fail("a balanced state is an equilibrium, not an orbit");
  if (!e.converged) return fail("its equilibrium of the mean system did not converge");
  if (e.singular()) return fail("its equilibrium of the mean system is singular (degenerate)");
  ForcedOrbit orbit = forced_orbit(p, RigidMachine{nullptr, &s}, at_rest<double, any_balls>(e.position_si()), out.kind, o);
  orbit.family = e.family;
  orbit.pattern = e.pattern;
  orbit.member = e.member;
  return orbit;
}

ForcedOrbit forced_orbit(const ParamsN& p, const RigidMachine& machine, const StateX& x0, std::string kind,
                         const ForcedOrbitOptions& o) {
  ForcedOrbit out = orbit_at(p, std::move(kind));
  const int d = 2 * p.n_balls() + 4;
  if (!machine.support) return failed(out, Outcome::numerical_issue, "no support to continue in (machine.support is null)");
  if (x0.size() != d || !x0.allFinite()) return failed(out, Outcome::numerical_issue, "the start is not a finite state of this machine");
  if (!(o.intervals >= 1) || !(o.steps_per_interval >= 2) || !(o.delta_end >= 0)) return failed(out, Outcome::numerical_issue, "bad options");
  const Eigen::VectorXd D = detail::forced_orbit_scale(p);
  ForcedProblem problem(p, machine, D, o);
  const int M = o.intervals;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  for (int j = 0; j < M; ++j) u.segment(d * j, d) = x0.cwiseQuotient(D);
  // delta = 0: the equilibrium itself solves the shooting equations exactly.
  if (o.delta_end > 0) {
    Eigen::VectorXd inward = Eigen::VectorXd::Zero(problem.size());
    inward(problem.param_index()) = 1;
    const arclength::Start<ForcedProblem> st = arclength::start(problem, u, inward, false);
    const auto r = arclength::trace(problem, st.u, st.tangent, st.jacobian, o.continuation);
    out.steps = r.stats.steps;
    out.newton_iterations = r.stats.newton_iterations;
    if (r.end != arclength::End::end_of_interval) {
      out.delta = problem.delta(r.last);
      return failed(out, r.status == Outcome::converged ? Outcome::not_converged : r.status,
                  fmt::format("{} at delta = {:.6g}: {}", to_string(r.end), out.delta, r.reason));
    }
    u = r.last;
  }
  return detail::refined_forced_orbit(problem, u, o, out);
}

ForcedOrbit forced_orbit_near(const ParamsN& p, const RigidMachine& machine, const ForcedOrbit& guess,
                              std::string kind, const ForcedOrbitOptions& o) {
  ForcedOrbit out = orbit_at(p, std::move(kind));
  const int d = 2 * p.n_balls() + 4;
  if (!machine.support) return failed(out, Outcome::numerical_issue, "no support (machine.support is null)");
  if (int(guess.state0.size()) != d || !(o.intervals >= 1) || !(o.steps_per_interval >= 2))
    return failed(out, Outcome::numerical_issue, "the guess is not an orbit of this machine, or bad options");
  const Eigen::VectorXd D = detail::forced_orbit_scale(p);
  ForcedOrbitOptions fixed = o;
  fixed.steps_per_interval = std::clamp(guess.steps_per_interval, o.steps_per_interval, o.max_steps_per_interval);
  ForcedProblem problem(p, machine, D, fixed);
  // The shooting unknowns from the guess's x(0): the states one uninterrupted run of this
  // machine at delta_end reaches at t_j (model.md (10.14.3)), delta / delta_end = 1.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  u(problem.param_index()) = 1;
  if (!problem.chain(Eigen::Map<const Eigen::VectorXd>(guess.state0.data(), d).cwiseQuotient(D), u))
    return failed(out, Outcome::numerical_issue, "integrating the guess over the period failed");
  Eigen::VectorXd fix = Eigen::VectorXd::Zero(problem.size());
  fix(problem.param_index()) = 1;
  const auto c = arclength::correct(problem, u, fix);
  out.newton_iterations = c.iterations;
  if (c.status != Outcome::converged)
    return failed(out, c.status, fmt::format("Newton from the neighbouring orbit: {}", c.reason));
  out.steps = 1;
  return detail::refined_forced_orbit(problem, c.u, fixed, out);
}


}  // namespace abu
