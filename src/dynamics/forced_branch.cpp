// A branch of the composed machine's periodic orbits in a physical parameter (forced_branch.hpp,
// docs/model.md §20.9): the shooting problem of forced_problem.hpp with lambda as its last
// unknown, traced by the arclength engine, its special points located by Brent on the chord.
#include "abu/dynamics/forced_branch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "abu/core/bracketed_root.hpp"
#include "forced_problem.hpp"

namespace abu {
namespace {
using detail::ForcedProblem;
using Vec = Eigen::VectorXd;

// ln max|rho| of the discrete monodromy (the stability test); -inf if none.
double top_log_modulus(const ProductEigenvalues& f) {
  double top = -std::numeric_limits<double>::infinity();
  for (double l : f.log_moduli) top = std::max(top, l);
  return top;
}

// The multiplier a special point of `kind` puts on the unit circle (forced_branch.hpp).
std::complex<double> critical_multiplier(const ForcedOrbit& o, const std::string& kind) {
  std::complex<double> best;
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& rho : o.multipliers) {
    const bool complex_pair = std::abs(rho.imag()) > 1e-9 * std::abs(rho);
    if ((kind == "NS") != complex_pair) continue;
    const double gap = kind == "NS" ? std::abs(std::abs(rho) - 1) : std::abs(rho - (kind == "PD" ? -1.0 : 1.0));
    if (gap < nearest) nearest = gap, best = rho;
  }
  return best;
}

class BranchProblem : public ForcedProblem {
 public:
  static constexpr std::size_t test_count = 2;  // d lambda / ds (LP), ln max|rho| (stability)

  BranchProblem(const MachineFamily& family, double from, double span, const AnisotropicSupport& support,
                const Vec& scale, const ForcedOrbitOptions& o, const ForcedOrbit& start)
      : ForcedProblem(family, from, span, support, scale, o), start_(start), dim_(int(scale.size())),
        balls_(int(scale.size()) / 2 - 2) {}

  std::vector<ForcedBranchPoint> points;
  std::vector<ForcedSpecialPoint> specials;

  arclength::Crossing crossing(const Vec&, const Vec& to) const {
    return arclength::box_crossing(to, {param_index()});
  }

  arclength::Evaluation<double, test_count> evaluate(const Vec& u, const Vec& t, const Jacobian&, arclength::Stage) {
    arclength::Evaluation<double, test_count> e;
    const ProductEigenvalues f = multipliers(u);
    if (!f.status.ok()) {
      e.retry = true;
      e.reason = "the Floquet multipliers of a branch point failed";
    }
    e.tests = {t(param_index()), top_log_modulus(f)};
    return e;
  }

  void locate(unsigned changed, const arclength::Segment<Vec>& seg) {
    const bool fold = (changed & 1u) != 0;
    if (fold) record("LP", seg, [&](const Vec& u, const Vec& chord) { return fold_test(u, chord); });
    if (!(changed & 2u)) return;
    const auto located = record_at(seg, [&](const Vec& u, const Vec&) { return top_log_modulus(multipliers(u)); });
    // The multiplier on the unit circle there: +1 (at a fold it is the fold itself), -1, or a pair
    // (where the search failed, classified at the later branch point).
    const ProductEigenvalues f = multipliers(located ? *located : seg.to);
    std::size_t top = 0;
    for (std::size_t k = 1; k < f.log_moduli.size(); ++k)
      if (f.log_moduli[k] > f.log_moduli[top]) top = k;
    const double arg = f.arguments.empty() ? 0.0 : std::abs(f.arguments[top]);
    const std::string kind = arg < 1e-6 ? "BP" : arg > std::numbers::pi - 1e-6 ? "PD" : "NS";
    if (kind == "BP" && fold) return;
    add_special(kind, located, seg);
  }

  void commit(Vec& u, Vec&, arclength::Stage) { points.push_back({value(u), describe_at(u)}); }

  // A closed branch (the engine compares this with the step, an arclength): the Euclidean
  // distance of the scaled unknowns, ball angles modulo 2 pi.
  double distance(const Vec& a, const Vec& b) const {
    double sum = 0;
    for (int i = 0; i <= param_index(); ++i) {
      const int c = i % dim_;
      const bool angle = i < param_index() && c >= 2 && c < 2 + balls_;
      const double gap = angle ? std::remainder(a(i) - b(i), 2 * std::numbers::pi) : a(i) - b(i);
      sum += gap * gap;
    }
    return std::sqrt(sum);
  }

  // The orbit at a branch point: its multipliers with their discretization error (against
  // half the steps on the same unknowns, §10.18), |q| and the ball angles over the period.
  ForcedOrbit describe_at(const Vec& u) {
    ForcedOrbit o;
    o.family = start_.family;
    o.pattern = start_.pattern;
    o.member = start_.member;
    o.kind = start_.kind;
    const int steps = steps_per_interval();
    const ProductEigenvalues fine = multipliers(u);  // the corrector's last evaluation, cached
    set_steps(std::max(1, steps / 2));
    const ProductEigenvalues coarse = multipliers(u);
    set_steps(steps);
    describe(u, coarse, o, &fine);
    return o;
  }

 private:
  // The tangent's lambda component at the corrected point u (its sign change: a fold).
  double fold_test(const Vec& u, const Vec& chord) const {
    return arclength::tangent(*this, jacobian(u), chord)(param_index());
  }

  // The point between seg.from and seg.to where `test` changes sign, by Brent's method on
  // the chord's fraction s, each trial point corrected onto the branch across the chord; the
  // bracket 1e-10 of the chord (itself <= ds_max = 0.05 of the interval). Nothing if a trial
  // point did not converge (the caller then reports the point as detected, not located).
  template <class Test>
  std::optional<Vec> record_at(const arclength::Segment<Vec>& seg, Test&& test) {
    const Vec chord = seg.to - seg.from;
    std::optional<Vec> last;
    const auto f = [&](double s) -> std::optional<double> {
      if (s <= 0) return test(seg.from, chord);
      if (s >= 1) return test(seg.to, chord);
      const auto c = arclength::correct(*this, Vec(seg.from + s * chord), chord);
      if (!c.converged()) return std::nullopt;
      last = c.u;
      return test(c.u, chord);
    };
    RootSearch search;
    search.absolute_width = 1e-10;
    const BracketedRoot r = bracketed_root(f, 0.0, 1.0, search);
    if (!r.converged()) return std::nullopt;
    if (const auto c = arclength::correct(*this, Vec(seg.from + r.root * chord), chord); c.converged()) return c.u;
    return last;
  }
  template <class Test>
  void record(const char* kind, const arclength::Segment<Vec>& seg, Test&& test) {
    add_special(kind, record_at(seg, test), seg);
  }
  // The special point at u; without u (the search failed) detected in seg, described at its
  // later end, and not located.
  void add_special(const std::string& kind, const std::optional<Vec>& u, const arclength::Segment<Vec>& seg) {
    const Vec& at = u ? *u : seg.to;
    ForcedSpecialPoint s;
    s.kind = kind;
    s.value = value(at);
    s.orbit = describe_at(at);
    s.multiplier = critical_multiplier(s.orbit, kind);
    if (!u) {
      s.located = false;
      s.bracket = {value(seg.from), value(seg.to)};
      s.reason = "its test changed sign between two branch points, but a trial point of Brent's search on the chord "
                 "between them did not converge";
    }
    specials.push_back(std::move(s));
  }

  ForcedOrbit start_;
  int dim_, balls_;
};

static_assert(arclength::Problem<BranchProblem>);

void failed_branch(ForcedBranch& b, Outcome outcome, std::string why) {
  if (b.status.ok()) b.reason = std::move(why);
  b.status.merge(outcome, "see reason");
}
}  // namespace

ForcedBranch continue_forced_orbit(const AnisotropicSupport& support, const MachineFamily& family, double from,
                                   double to, const ForcedOrbit& start, double start_value,
                                   const ForcedBranchOptions& options) {
  ForcedBranch out;
  const double span = to - from;
  const MachineAtValue m0 = family(start_value);
  const int d = 2 * m0.params.n_balls() + 4;
  if (!(span > 0) || !(start_value >= from && start_value <= to) || int(start.state0.size()) != d) {
    failed_branch(out, Outcome::numerical_issue, "bad interval or start (not an orbit of this machine inside it)");
    return out;
  }
  const Vec D = detail::forced_orbit_scale(m0.params);
  ForcedOrbitOptions orbit = options.orbit;
  orbit.steps_per_interval =
      std::clamp(start.steps_per_interval, orbit.steps_per_interval, orbit.max_steps_per_interval);
  BranchProblem forward(family, from, span, support, D, orbit, start);
  BranchProblem backward = forward;
  // The start's shooting unknowns at lambda = start_value, corrected with lambda fixed.
  Vec u = Vec::Zero(forward.size()), fix = Vec::Zero(forward.size());
  u(forward.param_index()) = (start_value - from) / span;
  fix(forward.param_index()) = 1;
  if (!forward.chain(Eigen::Map<const Vec>(start.state0.data(), d).cwiseQuotient(D), u)) {
    failed_branch(out, Outcome::numerical_issue, "integrating the start orbit over the period failed");
    return out;
  }
  const auto c = arclength::correct(forward, u, fix);
  if (!c.converged()) {
    failed_branch(out, c.status, fmt::format("the start orbit at {}: {}", start_value, c.reason));
    return out;
  }
  Vec inward = Vec::Zero(forward.size());
  inward(forward.param_index()) = start_value == to ? -1 : 1;
  const bool on_edge = start_value == from || start_value == to;
  const auto s = arclength::start(forward, c.u, inward, on_edge);
  const auto runs = arclength::trace_both_ways(forward, backward, s, options.continuation);
  out.end_forward = std::string(arclength::to_string(runs.forward.end));
  if (runs.backward_traced) {
    out.end_backward = std::string(arclength::to_string(runs.backward.end));
    // The backward run reversed; its first point is the start, the forward run's first too.
    out.points.assign(backward.points.rbegin(), backward.points.rend() - 1);
    out.specials = backward.specials;
  }
  out.points.insert(out.points.end(), forward.points.begin(), forward.points.end());
  out.specials.insert(out.specials.end(), forward.specials.begin(), forward.specials.end());
  for (const ForcedSpecialPoint& sp : out.specials)
    if (!sp.located)
      failed_branch(out, Outcome::not_converged,
                    fmt::format("a {} point between {:.10g} and {:.10g} was detected but not located: {}", sp.kind,
                                sp.bracket[0], sp.bracket[1], sp.reason));
  for (const auto* run : {&runs.forward, &runs.backward}) {
    if (run == &runs.backward && !runs.backward_traced) continue;
    if (run->status != Outcome::converged)
      failed_branch(out, run->status,
                    fmt::format("the run {} from {} ended early ({} at {:.10g}: {})",
                                run == &runs.forward ? "forward" : "backward", start_value,
                                arclength::to_string(run->end), from + span * run->last(forward.param_index()),
                                run->reason));
  }
  return out;
}

}  // namespace abu
