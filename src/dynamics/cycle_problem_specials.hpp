// LPC, PD and NS on a cycle branch (docs/model.md §17.5): the test function's zero between two
// accepted orbits, each value at an orbit corrected onto the branch, by Brent's method; an
// interpolation between the two orbits where that fails. Members of CycleProblem
// (cycle_problem.hpp); internal to src/dynamics.
#pragma once

#include <optional>

#include "abu/core/bracketed_root.hpp"
#include "cycle_problem.hpp"

namespace abu::cycle_problem {

template <bool Chord>
inline void CycleProblem<Chord>::locate(unsigned changed, const arclength::Segment<Vec>& seg) {
  static constexpr const char* labels[] = {"LPC", "PD", "NS"};
  for (unsigned k = 0; k < 3; ++k) {
    if (!(changed & (1u << k))) continue;
    // Two real multipliers with product 1 (a neutral saddle cycle), not a torus.
    if (k == 2 && !pending_pair_) continue;
    // A fold whose parameter excursion over the step (|tangent component| times the step)
    // is below the parameter's resolution (1e3 eps |p|) is not one the orbits resolve: near
    // a homoclinic end the branch runs at a constant parameter (to 1e-14 relative) while the
    // period grows, and the tangent's component there is rounding noise of either sign.
    if (k == 0 && std::max(std::abs(last_tests_[0]), std::abs(pending_tests_[0])) * (seg.to - seg.from).norm() *
                          std::abs(to_ - from_) <=
                      1e3 * std::numeric_limits<double>::epsilon() * std::abs(pending_.parameter))
      continue;
    CycleSpecial s;
    s.label = labels[k];

    // The stiff route's PD and NS tests need the frozen spectra's multipliers (evaluate):
    // interpolated there; its LPC (the tangent) is located like the others.
    const bool locatable = o_.locate_specials && (!radau_ || k == 0);
    if (!locatable || !root_on_branch(k, seg, s)) {
      const double a = last_tests_[k], b = pending_tests_[k];
      const double theta = a / (a - b);
      s.parameter = last_.parameter + theta * (pending_.parameter - last_.parameter);
      s.period = last_.period + theta * (pending_.period - last_.period);
      s.amplitude = last_.amplitude + theta * (pending_.amplitude - last_.amplitude);
      s.located = false;
      s.note = locatable ? "interpolated between two converged orbits (the test function's zero): locating it on the "
                           "branch failed"
                         : "interpolated between two converged orbits (the test function's zero)";
    }
    specials_.push_back(s);
  }
}

// Test function k (LPC: the tangent's parameter component; PD, NS: of the multipliers,
// model.md §17.5) at a converged orbit u, the tangent oriented along `previous`.
template <bool Chord>
inline double CycleProblem<Chord>::test_value(unsigned k, const Vec& u, const Vec& previous) const {
  const Evaluated& e = at(u);
  if (!e.ok) return std::numeric_limits<double>::quiet_NaN();
  if (k == 0) return arclength::tangent(*this, e.jacobian, previous)(param_index());
  std::size_t trivial = 0;
  const ProductEigenvalues f = multipliers(e, u, trivial);
  const CycleTestValues tv = radau_ ? cycle_test_values(f.values, f.log_moduli)
                                    : cycle_test_values(f.values, f.log_moduli, trivial);
  return k == 1 ? tv.period_doubling : tv.neimark_sacker;
}

// The orbit on the branch through from + sigma d, d the constraint direction (false: the
// corrector failed).
template <bool Chord>
inline bool CycleProblem<Chord>::on_branch(const Vec& from, const Vec& d, double sigma, Vec& u) const {
  const auto r = arclength::correct(*this, Vec(from + sigma * d), d);
  if (!r.converged()) return false;
  u = r.u;
  return true;
}

// The zero of test function k on the branch between the last orbit and the pending one:
// each value at an orbit corrected onto the branch with the chord as the constraint
// direction, Brent's method (GSL) to 1e-9 of the chord (model.md §17.5). The caches are the
// pending orbit's again afterwards (commit keeps its Newton matrix). False if a correction
// failed, the ends do not bracket a zero, or the root left the step.
template <bool Chord>
inline bool CycleProblem<Chord>::root_on_branch(unsigned k, const arclength::Segment<Vec>& seg, CycleSpecial& out) {
  const Vec chord = seg.to - seg.from;
  const double length = chord.norm();
  if (!(length > 0)) return false;
  const Evaluated kept_cache = cache_, kept_plain = plain_;
  const bool kept_accurate = cache_accurate_, kept_extrapolated = extrapolated_since_commit_;
  extrapolated_since_commit_ = true;  // no extrapolation from the orbits before the step
  // The corrections' Newton matrices between the step's two accurate ones, where both are
  // at hand (the last accepted orbit's kept, the pending one's cached); else integrated.
  if (Chord && o_.extrapolate_newton_matrix && !radau_ && kept_count_ >= 1 && kept_[2].u.size() == seg.from.size() &&
      kept_[2].u == seg.from && cache_accurate_ && cache_.u.size() == seg.to.size() && cache_.u == seg.to)
    segment_ends_.emplace(kept_[2], Kept{seg.to, cache_.jacobian, {}, {}});
  const Vec d = chord / length;
  const double at_from = last_tests_[k], at_to = pending_tests_[k];  // the test's values at the chord's ends
  double last_sigma = -1, last_value = 0;  // the last value's sigma, orbit and value
  Vec last_u;
  const auto test = [&](double sigma) -> std::optional<double> {
    // The ends are the two accepted orbits, their values known (GSL asks for them first).
    if (sigma == 0.0) return at_from;
    if (sigma == length) return at_to;
    Vec u;
    if (!on_branch(seg.from, d, sigma, u)) return std::nullopt;  // the caller falls back to the interpolation
    last_sigma = sigma;
    last_u = u;
    const double v = test_value(k, u, seg.from_tangent);
    last_value = v;
    if (!std::isfinite(v)) return std::nullopt;
    return v;
  };
  // Stops on a bracket below 1e-9 of the chord, on a value below 1e-8 of the ends' (the
  // zero within ~1e-8 of the chord where the test is linear), or on two roots 1e-8 of the
  // chord apart: the test functions' own noise (the LPC's tangent component at ~1e-7 of its
  // values at the ends on the viscous branch) stops Brent's bracket from shrinking further.
  // 60 iterations at most, the last estimate taken after them.
  const double value_tolerance = 1e-8 * std::max(std::abs(at_from), std::abs(at_to));
  RootSearch search;
  search.absolute_width = 1e-9 * length;
  search.max_iterations = 60;
  search.stop = [&](double root, double previous, int iteration) {
    return (root == last_sigma && std::abs(last_value) <= value_tolerance) ||
           (iteration > 0 && std::abs(root - previous) <= 1e-8 * length);
  };
  const BracketedRoot found = bracketed_root(test, 0.0, length, search);
  bool ok = found.converged() || found.end == BracketedRoot::End::max_iterations;
  const double root = found.root;
  Vec u;
  if (ok && root == last_sigma) {
    u = last_u;  // Brent's root is usually its last value's orbit
  } else {
    ok = ok && on_branch(seg.from, d, root, u);
  }
  ok = ok && (u - seg.from).norm() <= 2 * length && (u - seg.to).norm() <= 2 * length;
  if (ok) {
    CycleOrbit at_root;
    ok = sample(u, at_root);
    out.parameter = parameter(u);
    out.period = period(u);
    out.amplitude = at_root.amplitude;
    out.located = true;
    out.note = "located on the branch: the test function's zero by Brent's method to ~1e-8 of the step, each "
               "value at an orbit corrected onto the branch";
  }
  segment_ends_.reset();
  cache_ = kept_cache;
  plain_ = kept_plain;
  cache_accurate_ = kept_accurate;
  extrapolated_since_commit_ = kept_extrapolated;
  sampled_u_.resize(0);
  return ok;
}
}  // namespace abu::cycle_problem
