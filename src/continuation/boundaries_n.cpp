#include "abu/continuation/boundaries_n.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <vector>

#include "abu/continuation/arclength.hpp"
#include "abu/continuation/bifurcation.hpp"
#include "abu/model/static_equations.hpp"
#include "branch_systems_n.hpp"

namespace abu {

namespace {

using namespace n_balls;
using arclength::Stage;

// A fold (Hopf = false) or Hopf curve of an n-ball branch of kind S (AlignedSystem or
// HeldSystem) as a System and Problem of the engine: y = (u, p2 scaled, [w / w0]).
template <class S, bool Hopf>
class CurveN {
 public:
  using Vec = Eigen::Matrix<ld, Eigen::Dynamic, 1, 0, dof_capacity<any_balls> + 3, 1>;
  using Res = Eigen::Matrix<ld, Eigen::Dynamic, 1, 0, dof_capacity<any_balls> + 2, 1>;
  using Jacobian = Eigen::Matrix<ld, Eigen::Dynamic, Eigen::Dynamic, 0, dof_capacity<any_balls> + 2,
                                 dof_capacity<any_balls> + 3>;
  static constexpr std::size_t test_count = 0;  // no codimension-two tests for n >= 3
  static constexpr bool tangent_at_solution = true;

  CurveN(const ParamsN& base, const ContinuationRunN& run, const S& system, ParamRef param2, double from2, double to2,
         ld omega0, int m)
      : base_(base), run_(run), system_(system), param2_(param2), from2_(from2), span2_(ld(to2) - ld(from2)),
        omega0_(omega0), m_(m) {}

  StaticEquationsN at(const Vec& y) const {
    ParamsN p = base_;
    set(p, param2_, double(parameter2(y)));
    return StaticEquationsN(p, run_.param, run_.from, ld(run_.to) - ld(run_.from));
  }
  ld parameter2(const Vec& y) const { return from2_ + span2_ * y(m_); }
  ld omega(const Vec& y) const { return Hopf ? omega0_ * y(m_ + 1) : 0; }
  typename S::Vec u(const Vec& y) const { return y.head(m_); }
  Unknowns z(const StaticEquationsN& eq, const Vec& y) const { return system_.on(eq).full(u(y)); }

  void refresh(const Vec& y) {
    const StaticEquationsN eq = at(y);
    if constexpr (Hopf) {
      hopf_.emplace(eq, z(eq, y), omega(y));
    } else {
      fold_.emplace(eq, z(eq, y));
    }
  }
  // As for two balls (curve_system.hpp): keeps y's frequency entry at most 2 by raising w0.
  void rescale_frequency(Vec& y, Vec& t) {
    if (!Hopf || y(m_ + 1) <= 2) return;
    const ld r = y(m_ + 1);
    omega0_ *= r;
    y(m_ + 1) = 1;
    t(m_ + 1) /= r;
    t.normalize();
  }

  Res residual(const Vec& y) const {
    const StaticEquationsN eq = at(y);
    const auto F = system_.on(eq).residual(u(y));
    Res r(F.size() + (Hopf ? 2 : 1));
    r.head(F.size()) = F;
    if constexpr (Hopf) {
      const std::complex<ld> g = (*hopf_)(eq, z(eq, y), omega(y));
      r(F.size()) = g.real();
      r(F.size() + 1) = g.imag();
    } else {
      r(F.size()) = (*fold_)(eq, z(eq, y));
    }
    return r;
  }
  Jacobian jacobian(const Vec& y) const {
    constexpr ld h = 1e-7L;  // as curve_system.hpp: truncation and rounding balance
    Jacobian D(y.size() - 1, y.size());
    for (Eigen::Index k = 0; k < y.size(); ++k) {
      Vec yp = y, ym = y;
      yp(k) += h;
      ym(k) -= h;
      D.col(k) = (residual(yp) - residual(ym)) / (2 * h);
    }
    return D;
  }
  ld residual_size(const Vec& y) const {
    const StaticEquationsN eq = at(y);
    return system_.on(eq).residual(u(y)).cwiseAbs().maxCoeff();
  }
  static arclength::NewtonSettings newton() { return {12, 1e-14L, 1e-12L, 1e-14L, 1}; }

  // The engine's hooks.
  arclength::Crossing crossing(const Vec& /*from*/, const Vec& to) const {
    if (Hopf && omega(to) <= 0)
      return arclength::Crossing::leaving("the Hopf frequency reached 0 (a Bogdanov-Takens point)");
    return arclength::box_crossing(to, {int(m_) - 1, int(m_)});
  }
  arclength::Evaluation<ld, test_count> evaluate(const Vec&, const Vec&, const Jacobian&, Stage) { return {}; }
  void locate(unsigned, const arclength::Segment<Vec>&) {}
  void commit(Vec& y, Vec& t, Stage stage) {
    if (stage == Stage::step) rescale_frequency(y, t);
    if (stage != Stage::edge) refresh(y);
    points.push_back(point(y, stage == Stage::edge ? Label::EP : Label::none));
  }

  BoundaryPointN point(const Vec& y, Label label) const {
    const StaticEquationsN eq = at(y);
    const Unknowns zz = z(eq, y);
    BoundaryPointN pt;
    pt.parameter = eq.parameter(zz);
    pt.parameter2 = parameter2(y);
    pt.position = eq.position(zz);
    if (Hopf) pt.frequency = double(omega(y));
    pt.label = label;
    return pt;
  }
  std::vector<BoundaryPointN> points;

 private:
  ParamsN base_;
  const ContinuationRunN& run_;
  S system_;
  ParamRef param2_;
  ld from2_, span2_, omega0_;
  Eigen::Index m_;  // entries of u
  std::optional<FoldConditionT<any_balls>> fold_;
  std::optional<HopfConditionT<any_balls>> hopf_;
};

template <class C>
std::pair<StopReason, std::string> finish(C& tracer, const arclength::Result<C>& r, const ContinuationOptions& options) {
  switch (r.end) {
    case arclength::End::end_of_interval:
    case arclength::End::edge_not_reached: return {StopReason::end_of_range, {}};
    case arclength::End::left_domain: {
      const ld wa = tracer.omega(r.last), wb = tracer.omega(r.beyond);
      tracer.points.push_back(tracer.point(r.last + (wa / (wa - wb)) * (r.beyond - r.last), Label::BT));
      return {StopReason::end_of_range, r.reason};
    }
    case arclength::End::closed_loop: return {StopReason::closed_loop, {}};
    case arclength::End::max_steps:
      return {StopReason::max_steps, fmt::format("stopped after {} steps", options.max_steps)};
    case arclength::End::step_underflow: {
      const BoundaryPointN p = tracer.point(r.last, Label::none);
      return {StopReason::step_underflow,
              fmt::format("{} at ({:.17g}, {:.17g})", r.reason, double(p.parameter), double(p.parameter2))};
    }
  }
  return {StopReason::step_underflow, r.reason};
}

template <bool Hopf, class S>
BoundaryCurveN trace_curve(const ParamsN& p, const ContinuationRunN& run, const S& system, const SpecialPointN& sp,
                           ParamRef param2, double to2, const ContinuationOptions& options) {
  using C = CurveN<S, Hopf>;
  using Vec = typename C::Vec;
  const double from2 = get(p, param2);
  const StaticEquationsN eq(p, run.param, run.from, ld(run.to) - ld(run.from));
  const typename S::Vec u0 = system.on(eq).reduced(eq.scaled(sp.position, sp.parameter));
  const Eigen::Index m = u0.size();
  Vec y0 = Vec::Zero(m + (Hopf ? 2 : 1));
  y0.head(m) = u0;
  if constexpr (Hopf) y0(m + 1) = 1;
  C forward(p, run, system, param2, from2, to2, Hopf ? ld(*sp.frequency) : 1, int(m));
  forward.refresh(y0);
  C backward(forward);
  Vec inward = Vec::Zero(y0.size());
  inward(m) = 1;
  const arclength::StepRules rules{.predictor_error = 0.05L};
  const auto start = arclength::start(forward, y0, inward, true, rules);
  const auto both = arclength::trace_both_ways(forward, backward, start, options, rules);
  BoundaryCurveN curve;
  curve.kind = Hopf ? Label::HB : Label::LP;
  std::tie(curve.stop[1], curve.stop_detail[1]) = finish(forward, both.forward, options);
  curve.points = std::move(forward.points);
  if (both.backward_traced) {
    std::tie(curve.stop[0], curve.stop_detail[0]) = finish(backward, both.backward, options);
    curve.points.insert(curve.points.begin(), backward.points.rbegin(), backward.points.rend() - 1);
  } else {
    curve.stop[0] = StopReason::end_of_range;
    curve.stop_detail[0] = "the start value of the second parameter is an end of its interval";
    curve.points.front().label = Label::EP;
  }
  return curve;
}

}  // namespace

BoundaryRunN continue_boundaries(const ParamsN& p, const ContinuationRunN& run, ParamRef param2, double to2,
                                 const ContinuationOptions& options) {
  BoundaryRunN out;
  out.param = run.param;
  out.param2 = param2;
  out.from = run.from;
  out.to = run.to;
  out.from2 = get(p, param2);
  out.to2 = to2;
  out.n_balls = run.n_balls;
  const StaticEquationsN eq(p, run.param, run.from, ld(run.to) - ld(run.from));
  struct Done {
    Label label;
    ld parameter, q_abs, frequency;
  };
  std::vector<Done> done;
  const auto near = [](ld a, ld b) { return std::abs(a - b) <= 1e-9L * std::max(std::abs(a), std::abs(b)) + 1e-300L; };
  for (std::size_t b = 0; b < run.branches.size(); ++b) {
    const BranchN& branch = run.branches[b];
    for (const auto& sp : branch.specials) {
      if ((sp.label != Label::LP && sp.label != Label::HB) || !sp.converged) continue;
      // Folds of balanced samples (in U or a ball's m l, where balls 1 and 2 become
      // collinear) are the edge of the set's existence, not a stability boundary.
      if (sp.label == Label::LP && branch.family == Family::balanced) continue;
      const ld q_abs = std::hypot(sp.position(0), sp.position(1));
      const ld frequency = sp.frequency ? ld(*sp.frequency) : 0;
      bool image = false;
      for (const auto& d : done)
        image = image || (d.label == sp.label && near(d.parameter, sp.parameter) && near(d.q_abs, q_abs) &&
                          near(d.frequency, frequency));
      if (image) {
        out.notes.push_back(fmt::format("{} at {}={:.17g} on branch {}: an image of a point already continued "
                                        "(equal balls permuted); not continued again",
                                        to_string(sp.label), to_string(run.param), double(sp.parameter), b + 1));
        continue;
      }
      done.push_back({sp.label, sp.parameter, q_abs, frequency});
      BoundaryCurveN curve;
      if (branch.family == Family::balanced) {
        const HeldSystem held{eq, eq.scaled(sp.position, sp.parameter)};
        curve = trace_curve<true>(p, run, held, sp, param2, to2, options);
      } else if (sp.label == Label::HB) {
        curve = trace_curve<true>(p, run, AlignedSystem{eq}, sp, param2, to2, options);
      } else {
        curve = trace_curve<false>(p, run, AlignedSystem{eq}, sp, param2, to2, options);
      }
      curve.source_branch = int(b) + 1;
      curve.family = branch.family;
      curve.pattern = branch.pattern;
      curve.member = branch.member;
      out.curves.push_back(std::move(curve));
    }
  }
  return out;
}

}  // namespace abu
