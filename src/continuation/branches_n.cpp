#include "abu/continuation/branches_n.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "abu/continuation/arclength.hpp"
#include "abu/continuation/bifurcation.hpp"
#include "abu/core/bracketed_root.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/model/static_equations.hpp"
#include "branch_ends.hpp"
#include "balanced_envelope.hpp"
#include "ball_symmetry.hpp"
#include "branch_systems_n.hpp"

namespace abu {

namespace {

using namespace n_balls;

// The max-norm distance of two scaled points, the angles (entries 2 .. size-2) compared
// modulo 2 pi.
template <class Vec>
ld angle_distance(const Vec& a, const Vec& b) {
  ld d = 0;
  const Eigen::Index last = a.size() - 1;
  for (Eigen::Index k = 0; k <= last; ++k) {
    ld x = a(k) - b(k);
    if (k >= 2 && k < last) x = std::remainder(x, 2 * std::numbers::pi_v<ld>);
    d = std::max(d, std::abs(x));
  }
  return d;
}

// One direction of one branch as a Problem of the engine.
template <class S>
class Tracer : public S {
 public:
  using Vec = typename S::Vec;
  using Jacobian = typename S::Jacobian;
  static constexpr std::size_t test_count = 3;
  enum Test : unsigned { lp_test = 1u << 0, bp_test = 1u << 1, hb_test = 1u << 2 };

  explicit Tracer(const S& system) : S(system) {}

  arclength::Crossing crossing(const Vec& /*from*/, const Vec& to) const {
    const int last = int(to.size()) - 1;
    arclength::Crossing x = arclength::box_crossing(to, {last});
    if (x.kind != arclength::Crossing::inside) return x;
    const double value = double(this->eq.parameter(this->full(to)));
    if (const auto rule = range_violation(this->eq.param().quantity, value))
      return arclength::Crossing::leaving(fmt::format("{} would become {:.17g}: {}", to_string(this->eq.param()), value, *rule));
    return x;
  }

  arclength::Evaluation<ld, test_count> evaluate(const Vec& u, const Vec& t, const Jacobian& DF, arclength::Stage stage) {
    throw_if_stopped("continuation");  // a stop request (SIGINT/SIGTERM) is seen at every point
    pending_ = make_point(u);
    pending_.tangent_parameter = double(t(t.size() - 1));
    pending_.branch_test = double(arclength::bordered_determinant(DF, t));
    arclength::Evaluation<ld, test_count> e;
    // A step is only checked at its ends: the test functions see sign changes between
    // points, not what the branch did in between, and a long step in the parameter
    // across a resonance can land on the branch beyond an excursion (the aligned
    // branches near omega_n rise by two orders in |q| and come back), with tangents
    // alike at both ends. So the chord's midpoint is corrected onto the branch (normal
    // to the chord): on a branch that the step followed, it lies within the sagitta
    // ~ ds^2 kappa / 8 of the chord's middle, which the step control keeps near 0.025 ds
    // (predictor error 0.1 ~ kappa ds / 2); beyond 0.1 ds, or if no point is found,
    // the step is retried shorter (the engine takes it anyway near ds_min).
    if (stage == arclength::Stage::step && !us_.empty()) {
      const Vec& last = us_.back();
      const ld chord = (u - last).norm();
      const Vec middle = (u + last) / 2;
      const auto mid = arclength::correct(static_cast<const S&>(*this), middle, Vec((u - last) / chord));
      e.retry = !mid.converged() || (mid.u - middle).norm() > 0.1L * chord;
      e.reason = "the branch strays from the step's chord between its ends";
    }
    e.tests = {ld(pending_.tangent_parameter), ld(pending_.branch_test), ld(hopf_test_sign(pending_.spectrum))};
    return e;
  }

  void commit(Vec& u, Vec& /*t*/, arclength::Stage stage) {
    points.push_back(std::move(pending_));
    if (stage == arclength::Stage::edge) points.back().label = Label::EP;
    us_.push_back(u);
  }

  // The engine ends a branch as closed when it comes back within one step of its start:
  // measured in the step's own (Euclidean) norm, angles modulo 2 pi. (The max norm would
  // be up to sqrt(n + 3) times smaller than the arclength travelled: with 11 balls it
  // ended branches after six steps.)
  ld distance(const Vec& a, const Vec& b) const {
    ld sum = 0;
    const Eigen::Index last = a.size() - 1;
    for (Eigen::Index k = 0; k <= last; ++k) {
      ld x = a(k) - b(k);
      if (k >= 2 && k < last) x = std::remainder(x, 2 * std::numbers::pi_v<ld>);
      sum += x * x;
    }
    return std::sqrt(sum);
  }

  void locate(unsigned changed, const arclength::Segment<Vec>& between) {
    const BranchPointN& a = points.back();
    // The pending point is b (evaluated, not yet committed).
    const BranchPointN& b = pending_;
    if (changed & lp_test) {
      locate_singular(a, b, between, Label::LP);
    } else if (changed & bp_test) {
      locate_singular(a, b, between, Label::BP);
    }
    if (changed & hb_test) locate_hopf(a, b, between);
  }

  std::vector<BranchPointN> points;
  std::vector<SpecialPointN> specials;
  ContinuationStats stats;

 private:
  BranchPointN make_point(const Vec& u) {
    BranchPointN pt;
    const Unknowns z = this->full(u);
    pt.parameter = this->eq.parameter(z);
    pt.position = this->eq.position(z);
    pt.spectrum = spectrum_at(z);
    const ParamsN p = this->eq.params(z);
    pt.residual = static_residual<any_balls>(p, pt.position);
    return pt;
  }

  SpectrumN spectrum_at(const Unknowns& z) {
    ++stats.full_spectra;
    const Linearization<ld, any_balls> lin = this->eq.linearization(z);
    // LuGre (model.md §12.8): the bristles hold the balls, no direction of the balanced
    // set is neutral; the full spectrum of (12.10) decides.
    if constexpr (S::balanced) {
      if (!this->eq.lugre())
        return compute_normal_spectrum(lin, balanced_tangent_basis(this->eq.params(z), this->eq.position(z)));
    }
    return compute_spectrum<any_balls>(lin);
  }

  SpecialPointN special_at(Label label, const Vec& u, const BranchPointN& a, const BranchPointN& b) const {
    SpecialPointN sp;
    sp.label = label;
    const Unknowns z = this->full(u);
    sp.parameter = this->eq.parameter(z);
    sp.position = this->eq.position(z);
    sp.n_unstable_before = a.spectrum.n_unstable;
    sp.n_unstable_after = b.spectrum.n_unstable;
    sp.bracket_from = a.parameter;
    sp.bracket_to = b.parameter;
    sp.next_point = int(points.size());  // b, the pending point, is committed next
    return sp;
  }

  // The system with Newton's rules relaxed for the location of branch points, where the
  // corrector converges only linearly (the bordered matrix is singular at the point):
  // more iterations, and a stalled run accepted at steps of 1e-9 (the point is then
  // determined to ~1e-9 of the scaled unknowns, near sqrt(eps) as it can be).
  struct Relaxed : S {
    static arclength::NewtonSettings newton() {
      arclength::NewtonSettings rules;
      rules.max_iterations = 60;
      rules.stall_tolerance = 1e-9L;
      rules.residual_tolerance = 1e-13L;
      return rules;
    }
  };

  // Where a test function vanishes between two points: `u` on the branch, `width` the
  // final bracket relative to the chord (1e-13 when Brent converged).
  struct ChordRoot {
    std::optional<Vec> u;
    double width = 1;
  };

  // Brent (GSL) on f(sigma), sigma the arclength along the chord from `from` to `to`,
  // f evaluated on the branch (the corrector with the chord as constraint direction).
  // Next to a branch point the bordered corrector loses its quadratic convergence (F_u
  // has a two-dimensional kernel there) and its stall rule stops it: the root is then
  // the last point found, accepted if the bracket has shrunk below 1e-6 of the chord
  // (a branch point is determined only to ~sqrt(eps) along the null direction anyway).
  template <class F>
  ChordRoot root_on_chord(const Vec& from, const Vec& to, F&& f) const {
    const ld length = (to - from).norm();
    if (!(length > 0)) return {};
    const Vec d = (to - from) / length;
    std::optional<Vec> last;  // the last point found on the branch
    const auto test = [&](double sigma) -> std::optional<double> {
      const Vec guess = from + ld(sigma) * d;
      auto on = arclength::correct(static_cast<const S&>(*this), guess, d);
      if (!on.converged()) {
        // Linear convergence next to a branch point: the relaxed rules below.
        const auto relaxed = arclength::correct(Relaxed{*this}, guess, d);
        on.u = relaxed.u, on.jacobian = relaxed.jacobian, on.status = relaxed.status;
      }
      if (!on.converged()) return std::nullopt;  // ends the search (below)
      last = on.u;
      return f(on);
    };
    // A bracket of 1e-13 |sigma| |z_b - z_a|; 200 iterations at most, the last estimate taken.
    RootSearch search;
    search.relative_width = 1e-13 * double(length);
    const BracketedRoot found = bracketed_root(test, 0.0, double(length), search);
    ChordRoot out;
    out.width = std::max(1e-13, (found.upper - found.lower) / double(length));
    if (found.end == BracketedRoot::End::evaluation_failed) {
      if (out.width <= 1e-6 && last) out.u = last;
      return out;
    }
    if (!found.converged() && found.end != BracketedRoot::End::max_iterations) return out;
    const double root = found.root;
    const auto on = arclength::correct(static_cast<const S&>(*this), Vec(from + ld(root) * d), d);
    if (on.converged()) out.u = on.u;
    return out;
  }

  void locate_singular(const BranchPointN& a, const BranchPointN& b, const arclength::Segment<Vec>& br, Label label) {
    const Vec ta = br.from_tangent;
    const bool fold = label == Label::LP;
    const auto test = [&](const auto& on) -> double {
      const Vec t = arclength::tangent(on.jacobian, ta);
      return fold ? double(t(t.size() - 1)) : double(arclength::bordered_determinant(on.jacobian, t));
    };
    const ChordRoot root = root_on_chord(br.from, br.to, test);
    const std::optional<Vec>& u = root.u;
    SpecialPointN sp = special_at(label, u ? *u : Vec((br.from + br.to) / 2), a, b);
    sp.converged = u.has_value();
    const SpectrumN s = spectrum_at(this->full(u ? *u : Vec((br.from + br.to) / 2)));
    // The eigenvalue nearest 0 that is not structural: the one that crosses.
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < s.count; ++k)
      if (!s.structural[std::size_t(k)] && std::abs(s.eigenvalues[std::size_t(k)]) < best)
        best = std::abs(s.eigenvalues[std::size_t(k)]), sp.eigenvalue = s.eigenvalues[std::size_t(k)];
    if (!sp.converged)
      sp.note = fmt::format("test function changed sign but its root was not located (corrector failed; bracket {:.2g} "
                            "of the step)", root.width);
    else if (root.width > 1e-13)
      sp.note = fmt::format("located to {:.2g} of the step (the corrector stalls next to the point)", root.width);
    specials.push_back(sp);
  }

  void locate_hopf(const BranchPointN& a, const BranchPointN& b, const arclength::Segment<Vec>& br) {
    // A Hopf crossing changes the number of unstable eigenvalues by two; a neutral
    // saddle (lambda, -lambda) changes the test's sign but not the count: not reported.
    if (std::abs(a.spectrum.n_unstable - b.spectrum.n_unstable) != 2) return;
    Vec ua = br.from, ub = br.to;
    SpectrumN sa = a.spectrum, sb = b.spectrum;
    const int sign_a = hopf_test_sign(sa);
    // Narrow the bracket until the crossing pair is complex at both ends (it can be
    // complex in a sliver of the step only, near a coalescence on the real axis).
    std::optional<std::pair<std::complex<double>, std::complex<double>>> pair;
    for (int it = 0; it < 90 && !(pair = crossing_pair(sa, sb)); ++it) {
      if (angle_distance(ua, ub) < 1e-15L) break;
      const Vec d = (ub - ua).normalized();
      const auto mid = arclength::correct(static_cast<const S&>(*this), Vec((ua + ub) / 2), d);
      if (!mid.converged()) break;
      const SpectrumN sm = spectrum_at(this->full(mid.u));
      if (hopf_test_sign(sm) == sign_a) {
        ua = mid.u, sa = sm;
      } else {
        ub = mid.u, sb = sm;
      }
    }
    if (!pair) return;  // a neutral saddle (or unresolvable coalescence): not a Hopf point
    // Brent on the real part of the crossing eigenvalue, followed by nearness to the
    // linear interpolation between the bracket's pair.
    const std::complex<double> la = pair->first, lb = pair->second;
    const ld chord = (ub - ua).norm();
    std::complex<double> critical = la;
    const Vec from = ua;
    const auto real_part = [&](const auto& on) -> double {
      const SpectrumN s = spectrum_at(this->full(on.u));
      const double theta = chord > 0 ? double((on.u - from).norm() / chord) : 0.0;
      const std::complex<double> guess = la + theta * (lb - la);
      std::size_t best = 0;
      for (std::size_t k = 1; k < std::size_t(s.count); ++k)
        if (std::abs(s.eigenvalues[k] - guess) < std::abs(s.eigenvalues[best] - guess)) best = k;
      critical = s.eigenvalues[best];
      return critical.real();
    };
    const ChordRoot root = root_on_chord(ua, ub, real_part);
    const std::optional<Vec>& u = root.u;
    const double theta = la.real() / (la.real() - lb.real());
    const Vec at = u ? *u : Vec(ua + ld(theta) * (ub - ua));
    SpecialPointN sp = special_at(Label::HB, at, a, b);
    sp.converged = u.has_value();
    if (sp.converged) real_part(arclength::correct(static_cast<const S&>(*this), at, Vec((ub - ua).normalized())));
    sp.eigenvalue = sp.converged ? critical : la + theta * (lb - la);
    sp.frequency = std::abs(sp.eigenvalue.imag());
    if (!sp.converged) sp.note = "Hopf crossing detected, its location by Brent's method failed (interpolated)";
    specials.push_back(sp);
  }

  BranchPointN pending_;
  std::vector<Vec> us_;  // the committed points, for the midpoint check
};

// How one direction of a branch ended (branch_ends.hpp).
template <class P>
std::pair<StopReason, std::string> stop_of(const StaticEquationsN& eq, const P& problem,
                                           const arclength::Result<P>& r, const ContinuationOptions& options) {
  return stop_of(r, options, [&](const typename P::Vec& u) {
    return fmt::format("{}={:.17g}", to_string(eq.param()), double(eq.parameter(problem.full(u))));
  });
}

// Traces the branch of `system` through z0 (scaled parameter `end`: 0 the start value,
// 1 the far end), heading into the interval.
template <class S>
BranchN trace_branch(const S& system, const Unknowns& z0, ld end, const ContinuationOptions& options,
                     ContinuationStats& stats) {
  using Vec = typename S::Vec;
  const Vec u0 = system.reduced(z0);
  Vec inward = Vec::Zero(u0.size());
  inward(u0.size() - 1) = end == 0 ? 1 : -1;
  Tracer<S> forward(system), backward(system);
  const auto start = arclength::start(forward, u0, inward);
  const auto run = arclength::trace_both_ways(forward, backward, start, options);
  for (const auto* r : {&run.forward, &run.backward}) {
    stats.steps += r->stats.steps;
    stats.rejected += r->stats.rejected;
    stats.newton_iterations += r->stats.newton_iterations;
  }
  stats += forward.stats;
  stats += backward.stats;
  BranchN b;
  b.start_parameter = system.eq.parameter(z0);
  // Backward point j (j >= 1) becomes point back - j, the start (j = 0) is forward's
  // first, at `back`; a special before backward point j lies before assembled point
  // back - j + 1.
  const int back = backward.points.empty() ? 0 : int(backward.points.size()) - 1;
  for (std::size_t k = backward.points.size(); k > 1; --k) b.points.push_back(backward.points[k - 1]);
  for (auto it = backward.specials.rbegin(); it != backward.specials.rend(); ++it) {
    SpecialPointN sp = *it;  // traversed the other way: before and after swap
    std::swap(sp.n_unstable_before, sp.n_unstable_after);
    std::swap(sp.bracket_from, sp.bracket_to);
    sp.next_point = back - sp.next_point + 1;
    b.specials.push_back(sp);
  }
  b.points.insert(b.points.end(), forward.points.begin(), forward.points.end());
  for (SpecialPointN sp : forward.specials) {
    sp.next_point += back;
    b.specials.push_back(sp);
  }
  std::tie(b.stop[1], b.stop_detail[1]) = stop_of(system.eq, forward, run.forward, options);
  if (run.backward_traced) {
    std::tie(b.stop[0], b.stop_detail[0]) = stop_of(system.eq, backward, run.backward, options);
  } else {
    b.stop[0] = StopReason::end_of_range;
    b.stop_detail[0] = "the start value is an end of the interval";
    b.points.front().label = Label::EP;
  }
  return b;
}

// Does an aligned branch pass through the configuration z (scaled)?
bool passes_through(const StaticEquationsN& eq, const BranchN& b, const Unknowns& z) {
  for (const auto& pt : b.points)
    if (angle_distance(eq.scaled(pt.position, pt.parameter), z) < 1e-8L) return true;
  return false;
}

}  // namespace

ContinuationRunN continue_branches(const ParamsN& p, ParamRef param, double to, const ContinuationOptions& options,
                                   const BalancedSampling& sampling) {
  ContinuationRunN run;
  run.param = param;
  run.from = get(p, param);
  run.to = to;
  run.n_balls = p.n_balls();
  if (run.n_balls < 3)
    throw InputError("continuation", 0, "n", "the n-ball continuation needs n >= 3 (two balls: continuation.hpp)");
  if (const auto rule = range_violation(param.quantity, to)) throw InputError("continuation", 0, to_string(param), *rule);
  if (to == run.from) throw InputError("continuation", 0, to_string(param), "the end value equals the start value");
  run.memory_estimate = require_branch_memory(options, sizeof(BranchPointN), 1);
  const StaticEquationsN eq(p, param, run.from, ld(to) - ld(run.from));
  ParamsN near = p;  // LuGre: the z = 0 equilibria are the frictionless model's (model.md §12.3)
  if (p.law == FrictionLaw::lugre) near.law = FrictionLaw::none;
  ParamsN far = near;
  set(far, param, to);
  const EquilibriumSetN here = find_equilibria(near, sampling);
  const EquilibriumSetN there = find_equilibria(far, sampling);
  run.balanced_set = here.balanced_set;

  // Interchangeable balls (equal parameters): only one of every set of images is traced,
  // the others are counted on its branch (BranchN::images) and named in the notes.
  const std::vector<int> class_of = ball_classes(p);

  // Balanced samples, free angles held: from the start value, or from the far end if
  // the set exists only there. Images permute free angles among interchangeable free
  // balls (balls 1 and 2 close the polygon and stay).
  const bool samples_here = here.balanced_set.samples > 0;
  const auto& sample_source = samples_here ? here : there;
  const ld sample_parameter = samples_here ? ld(run.from) : ld(to);
  for (const auto& e : sample_source.points()) {
    if (e.family != Family::balanced) continue;
    const Coordinates<ld, any_balls> s = canonical(e.position, class_of, 2);
    const Unknowns z = eq.scaled(s, sample_parameter);
    BranchN* image_of = nullptr;
    for (auto& b : run.branches)
      if (passes_through(eq, b, z)) image_of = &b;
    if (image_of) {
      ++image_of->images;
      continue;
    }
    const HeldSystem system{eq, z};
    BranchN b = trace_branch(system, system.frame, samples_here ? 0 : 1, options, run.stats);
    b.family = Family::balanced;
    b.member = e.member;
    run.branches.push_back(std::move(b));
  }
  if (!samples_here && there.balanced_set.samples > 0)
    run.notes.push_back(fmt::format("the balanced set exists only towards {}={}: its samples start there",
                                    to_string(param), to));

  // Aligned equilibria, at the start value and then those at the far end no branch reached.
  const AlignedSystem aligned{eq};
  for (int side = 0; side < 2; ++side) {
    const ld parameter = side == 0 ? ld(run.from) : ld(to);
    for (const auto& e : (side == 0 ? here : there).points()) {
      if (e.family == Family::balanced) continue;
      if (e.singular()) {
        if (side == 0)
          run.notes.push_back(fmt::format("aligned {} {} is singular ({} structural zero eigenvalues): not continued",
                                          pattern_string(e.pattern, run.n_balls), e.member, e.structural_zeros));
        continue;
      }
      const Coordinates<ld, any_balls> s = canonical(e.position, class_of, 0);
      const Unknowns z = eq.scaled(s, parameter);
      BranchN* on = nullptr;
      for (auto& b : run.branches)
        if (b.family != Family::balanced && passes_through(eq, b, z)) on = &b;
      if (on) {
        // An image of another equilibrium, or the canonical image of the branch's own
        // start (traced from a permuted one); else a point the branch reached (a fold).
        const bool image = canonical(e.position, class_of, 0) != e.position ||
                           (on->pattern == pattern_of(s) && on->member == e.member);
        if (side == 0 && image) ++on->images;
        if (side == 0 && !image)
          run.notes.push_back(fmt::format("aligned {} {} lies on the branch of {} {}; not traced again",
                                          pattern_string(e.pattern, run.n_balls), e.member,
                                          pattern_string(on->pattern, run.n_balls), on->member));
        continue;
      }
      BranchN b = trace_branch(aligned, z, side, options, run.stats);
      b.family = Family::aligned;
      b.pattern = pattern_of(s);
      b.member = e.member;
      run.branches.push_back(std::move(b));
    }
  }
  for (std::size_t k = 0; k < run.branches.size(); ++k)
    if (run.branches[k].images > 0)
      run.notes.push_back(fmt::format(
          "branch {} ({} {}) also stands for {} {} under permutations of equal balls (same spectra at every "
          "parameter value; not traced again)",
          k + 1, run.branches[k].family == Family::balanced ? "balanced sample" : "aligned",
          run.branches[k].family == Family::balanced ? std::to_string(run.branches[k].member)
                                                     : pattern_string(run.branches[k].pattern, run.n_balls),
          run.branches[k].images, run.branches[k].family == Family::balanced ? "other samples" : "other equilibria"));
  run.envelope = envelope_of(run.branches, run.from, to);
  return run;
}

}  // namespace abu
