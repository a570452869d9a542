#include "abu/continuation/boundaries.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "abu/continuation/arclength.hpp"
#include "abu/continuation/bifurcation.hpp"
#include "abu/core/cancel.hpp"
#include "abu/model/static_equations.hpp"
#include "curve_system.hpp"

namespace abu {

namespace {

using ld = long double;
using Vec5 = StaticEquations::Vec5;
using arclength::Stage;

// Which side of a Hopf curve the equilibrium is stable on, in the first parameter: the
// equilibrium re-solved (Newton, the second parameter held) at 1e-3 of the interval on
// either side of z, and its spectrum: +1 stable at the larger value, -1 at the smaller,
// 0 on neither side (or both, or where Newton does not converge). 1e-3 of the interval
// puts the critical pair's real part well outside its error band (it moves linearly) and
// keeps the equilibrium's state within Newton's reach.
int stable_side(const StaticEquations& eq, const Vec5& z) {
  const auto stable_at = [&](ld shift) {
    Vec5 y = z;
    y(4) += shift;
    for (int it = 0; it < 30; ++it) {
      const auto F = eq.residual(y);
      if (F.norm() <= 1e-14L) {
        const Spectrum sp = compute_spectrum(eq.linearization(y));
        return sp.status.ok() && sp.stability == Stability::stable;
      }
      const Eigen::Matrix<ld, 4, 4> J = eq.jacobian(y).template leftCols<4>();
      y.head<4>() -= J.partialPivLu().solve(F);
    }
    return false;
  };
  const bool up = stable_at(1e-3L), down = stable_at(-1e-3L);
  const int direction = eq.span() > 0 ? 1 : -1;  // the scaled parameter runs with the interval
  return up == down ? 0 : (up ? direction : -direction);
}

// Codimension-two test functions at one curve point; a sign change between consecutive
// points flags the label.
struct Tests {
  FoldCoefficients fold;              // fold curves: cusp and Bogdanov-Takens coefficients
  int hopf_sign = 1, n_unstable = 0;  // fold curves (zero-Hopf)
  ld static_det = 0, lyapunov = 0;   // Hopf curves (zero-Hopf, generalized Hopf)
};

// One direction of a fold or Hopf curve as a Problem of the pseudo-arclength engine
// (arclength.hpp): its points, with the codimension-two points flagged between them.
template <int N>
class CurveTracer : public CurveSystem<N> {
 public:
  using Vec = typename CurveSystem<N>::Vec;
  using Jacobian = typename CurveSystem<N>::Jacobian;
  using Sys = CurveSystem<N>;
  // Fold curves: CP, BT, ZH; Hopf curves: ZH, GH (the bits of `changed`, in this order).
  static constexpr std::size_t test_count = Sys::hopf ? 2 : 3;

  explicit CurveTracer(const Sys& system) : Sys(system) {}

  arclength::Crossing crossing(const Vec& /*from*/, const Vec& to) const {
    // The frequency reaching zero ends a Hopf curve on a fold curve (Bogdanov-Takens).
    if (Sys::hopf && this->omega(to) <= 0)
      return arclength::Crossing::leaving("the Hopf frequency reached 0 (Bogdanov-Takens point)");
    return arclength::box_crossing(to, {4, 5});
  }
  arclength::Evaluation<ld, test_count> evaluate(const Vec& y, const Vec& /*t*/, const Jacobian& /*DF*/, Stage stage) {
    throw_if_stopped("two-parameter continuation");  // a stop request is seen at every curve point
    pending_ = tests(y, stage == Stage::start ? nullptr : &previous_);
    arclength::Evaluation<ld, test_count> e;
    if constexpr (Sys::hopf) {
      e.tests = {pending_.static_det, pending_.lyapunov};
    } else {
      e.tests = {pending_.fold.cusp, pending_.fold.bogdanov_takens, ld(pending_.hopf_sign)};
    }
    return e;
  }
  void locate(unsigned changed, const arclength::Segment<Vec>& between);
  // The generalized Hopf point between two points of a Hopf curve where l1 changes sign.
  void locate_generalized_hopf(const Vec& ya, const Vec& yb, ld la, ld lb);
  void commit(Vec& y, Vec& t, Stage stage) {
    previous_ = pending_;
    if (stage == Stage::step) this->rescale_frequency(y, t);
    if (stage != Stage::edge) this->refresh(y);
    points.push_back(point(y, stage == Stage::edge ? Label::EP : Label::none));
    if constexpr (Sys::hopf) {
      points.back().lyapunov = double(pending_.lyapunov);  // computed at y by evaluate
      points.back().stable_side = stable_side(this->at(y), Sys::z(y));
    }
  }

  BoundaryPoint point(const Vec& y, Label label) const;
  std::vector<BoundaryPoint> points;

 private:
  Tests tests(const Vec& y, const Tests* previous) const;
  Tests previous_, pending_;
};

template <int N>
Tests CurveTracer<N>::tests(const Vec& y, const Tests* previous) const {
  const StaticEquations eq = this->at(y);
  const Vec5 z = Sys::z(y);
  Tests t;
  if constexpr (Sys::hopf) {
    t.static_det = eq.jacobian(z).template leftCols<4>().partialPivLu().determinant();
    t.lyapunov = first_lyapunov_coefficient(eq.params(z), eq.position(z), this->omega(y));
  } else {
    t.fold = fold_coefficients(eq, z, previous ? &previous->fold : nullptr);
    const Spectrum sp = compute_spectrum(eq.linearization(z), SpectrumMethod::refined, 1);
    t.hopf_sign = hopf_test_sign(sp);
    t.n_unstable = sp.n_unstable;
  }
  return t;
}

template <int N>
BoundaryPoint CurveTracer<N>::point(const Vec& y, Label label) const {
  const StaticEquations eq = this->at(y);
  const Vec5 z = Sys::z(y);
  BoundaryPoint p;
  p.parameter = eq.parameter(z);
  p.parameter2 = this->parameter2(y);
  p.position = eq.position(z);
  p.frequency = this->omega(y);
  p.family = classify(this->base(), p.position);
  p.label = label;
  return p;
}

template <int N>
void CurveTracer<N>::locate(unsigned changed, const arclength::Segment<Vec>& between) {
  // Codimension-two points are flagged on the curve where their test function changes
  // sign, at the zero of its linear interpolation between the two points.
  const Vec &ya = between.from, &yb = between.to;
  const auto flag = [&](unsigned bit, Label label, ld fa, ld fb) {
    if (!(changed & bit)) return;
    const ld theta = fa / (fa - fb);
    points.push_back(point(ya + theta * (yb - ya), label));
  };
  if constexpr (Sys::hopf) {
    flag(1u << 0, Label::ZH, previous_.static_det, pending_.static_det);
    if (changed & (1u << 1)) locate_generalized_hopf(ya, yb, previous_.lyapunov, pending_.lyapunov);
  } else {
    flag(1u << 0, Label::CP, previous_.fold.cusp, pending_.fold.cusp);
    flag(1u << 1, Label::BT, previous_.fold.bogdanov_takens, pending_.fold.bogdanov_takens);
    // A sign change from a neutral saddle (a real pair lambda, -lambda) leaves the number
    // of unstable eigenvalues alone; a pair crossing the axis changes it by two.
    if ((changed & (1u << 2)) && std::abs(previous_.n_unstable - pending_.n_unstable) == 2)
      points.push_back(point((ya + yb) / 2, Label::ZH));
  }
}

template <int N>
void CurveTracer<N>::locate_generalized_hopf(const Vec& ya, const Vec& yb, ld la, ld lb) {
  // l1 is exact to long-double rounding (Taylor coefficients, bifurcation.cpp), so its zero
  // along the curve is located, not interpolated: the point at chord fraction theta is
  // corrected onto the curve in the hyperplane normal to the chord (the engine's
  // corrector), and theta is found by the Illinois variant of regula falsi on l1 there
  // (superlinear, never leaves the bracket). Linear interpolation of l1 between the two
  // curve points, what this replaces, put the default scene's GH at mu = 3.24e-3, 3.14e-3
  // or 3.12e-3 depending on where the steps fell.
  const Vec chord = yb - ya;
  Vec y = ya;
  const auto l1_at = [&](ld theta, bool& ok) -> ld {
    const auto c = arclength::correct(*this, Vec(ya + theta * chord), chord);
    ok = c.converged();
    if (!ok) return 0;
    y = c.u;
    const StaticEquations eq = this->at(y);
    return first_lyapunov_coefficient(eq.params(Sys::z(y)), eq.position(Sys::z(y)), this->omega(y));
  };
  ld a = 0, b = 1, fa = la, fb = lb;
  int side = 0;
  bool located = false;
  for (int it = 0; it < 100 && !located; ++it) {
    const ld theta = (a * fb - b * fa) / (fb - fa);
    bool ok = false;
    const ld f = l1_at(theta, ok);
    if (!ok) break;
    // Stop when the bracket is below 1e-13 of the chord (the corrector's own accuracy is
    // ~1e-14 in the scaled unknowns) or l1 is zero to its rounding.
    if (f == 0 || b - a < 1e-13L) {
      located = true;
      break;
    }
    if ((f > 0) == (fb > 0)) {
      b = theta, fb = f;
      if (side == -1) fa /= 2;
      side = -1;
    } else {
      a = theta, fa = f;
      if (side == 1) fb /= 2;
      side = 1;
    }
    if (b - a < 1e-13L) located = true;
  }
  if (!located) {  // the corrector failed inside the segment: the interpolated point, said so
    y = ya + (la / (la - lb)) * chord;
  }
  BoundaryPoint p = point(y, Label::GH);
  p.located = located;  // l1 = 0 there: the CSV leaves it empty, as at every codimension-two point
  points.push_back(p);
}

// How one direction of a curve ended; the points of a curve that ended on a
// Bogdanov-Takens point get that point, interpolated to w = 0.
template <int N>
std::pair<StopReason, std::string> finish(CurveTracer<N>& tracer, const arclength::Result<CurveTracer<N>>& r,
                                          const ContinuationOptions& options) {
  switch (r.end) {
    case arclength::End::end_of_interval:
    case arclength::End::edge_not_reached: return {StopReason::end_of_range, {}};
    case arclength::End::left_domain: {
      const ld wa = tracer.omega(r.last), wb = tracer.omega(r.beyond);
      tracer.points.push_back(tracer.point(r.last + (wa / (wa - wb)) * (r.beyond - r.last), Label::BT));
      return {StopReason::end_of_range, r.reason};
    }
    case arclength::End::closed_loop: return {StopReason::closed_loop, {}};
    case arclength::End::max_steps: return {StopReason::max_steps, fmt::format("stopped after {} steps", options.max_steps)};
    case arclength::End::step_underflow: {
      const BoundaryPoint p = tracer.point(r.last, Label::none);
      return {StopReason::step_underflow,
              fmt::format("{} at ({:.17g}, {:.17g})", r.reason, double(p.parameter), double(p.parameter2))};
    }
  }
  return {StopReason::step_underflow, r.reason};
}

template <int N>
BoundaryCurve trace_curve(const Params& p, const ContinuationRun& run, const SpecialPoint& sp, ParamRef param2,
                          double to2, const ContinuationOptions& options) {
  using Vec = typename CurveSystem<N>::Vec;
  const double from2 = get(p, param2);
  const ld omega0 = N == 7 ? ld(sp.frequency) : 1;
  const StaticEquations eq(p, run.param, run.from, ld(run.to) - ld(run.from));
  Vec y0 = Vec::Zero();
  y0.template head<5>() = eq.scaled(sp.position, sp.parameter);
  y0(5) = 0;
  if constexpr (N == 7) y0(6) = 1;
  CurveTracer<N> forward(CurveSystem<N>(p, run, param2, from2, to2, omega0));
  forward.refresh(y0);
  // Each way with its own copy of the system: the frequency scale w0 and the borders
  // adapt along a curve, and the way back starts from the start's.
  CurveTracer<N> backward(forward);
  // Head into the box: towards increasing second parameter. The start is the box's lower
  // edge in p2: if the curve crosses it, the other way leaves the box at once.
  Vec inward = Vec::Zero();
  inward(5) = 1;
  const arclength::StepRules rules{.predictor_error = 0.05L};
  const auto start = arclength::start(forward, y0, inward, true, rules);
  const auto both = arclength::trace_both_ways(forward, backward, start, options, rules);
  BoundaryCurve curve;
  curve.kind = N == 7 ? Label::HB : Label::LP;
  std::tie(curve.stop[1], curve.stop_detail[1]) = finish(forward, both.forward, options);
  curve.points = std::move(forward.points);
  if (both.backward_traced) {
    std::tie(curve.stop[0], curve.stop_detail[0]) = finish(backward, both.backward, options);
    // Traced against the curve's orientation: reversed, its start (shared) left out.
    curve.points.insert(curve.points.begin(), backward.points.rbegin(), backward.points.rend() - 1);
  } else {
    curve.stop[0] = StopReason::end_of_range;
    curve.stop_detail[0] = "the start value of the second parameter is an end of its interval";
    curve.points.front().label = Label::EP;
  }
  return curve;
}

}  // namespace

BoundaryRun continue_boundaries(const Params& p, const ContinuationRun& run, ParamRef param2, double to2,
                                const ContinuationOptions& options) {
  BoundaryRun out;
  out.param = run.param;
  out.param2 = param2;
  out.from = run.from;
  out.to = run.to;
  out.from2 = get(p, param2);
  out.to2 = to2;
  std::vector<std::pair<Label, long double>> done;
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    for (const auto& sp : run.branches[b].specials) {
      if ((sp.label != Label::LP && sp.label != Label::HB) || !sp.converged) continue;
      bool mirror = false;
      for (const auto& [label, value] : done)
        mirror = mirror || (label == sp.label && std::abs(value - sp.parameter) <= 1e-9L * std::abs(value));
      if (mirror) {
        out.notes.push_back(fmt::format("{} at {}={:.17g} on branch {}: on a curve already continued (its mirror "
                                        "image or that curve's other end); not continued again",
                                        to_string(sp.label), to_string(run.param), double(sp.parameter), b + 1));
        continue;
      }
      done.emplace_back(sp.label, sp.parameter);
      BoundaryCurve curve = sp.label == Label::HB ? trace_curve<7>(p, run, sp, param2, to2, options)
                                                  : trace_curve<6>(p, run, sp, param2, to2, options);
      curve.source_branch = int(b) + 1;
      // A curve that comes back to the start value of param2 elsewhere ends on another of
      // the run's points of the same kind (a Hopf curve joining two Hopf points): that
      // one is this curve's other end, not continued again.
      for (const auto& pt : {curve.points.front(), curve.points.back()})
        if (pt.label == Label::EP && std::abs(pt.parameter2 - ld(out.from2)) <= 1e-12L * (1 + std::abs(ld(out.from2))))
          done.emplace_back(sp.label, pt.parameter);
      out.curves.push_back(std::move(curve));
    }
  }
  return out;
}

}  // namespace abu
