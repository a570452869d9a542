#include "abu/continuation/boundaries.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <optional>

#include "abu/continuation/bifurcation.hpp"
#include "abu/model/static_equations.hpp"

namespace abu {

namespace {

using ld = long double;
using Vec5 = StaticEquations::Vec5;

// The fold (N = 6: y = (z, p2)) or Hopf (N = 7: y = (z, p2, w / w0)) curve system, the
// second parameter scaled like the first: 0 at its start value, 1 at its end value.
template <int N>
class CurveSystem {
 public:
  using Vec = Eigen::Matrix<ld, N, 1>;
  using Res = Eigen::Matrix<ld, N - 1, 1>;
  static constexpr bool hopf = N == 7;

  CurveSystem(const Params& base, const ContinuationRun& run, ParamRef param2, double from2, double to2, ld omega0)
      : base_(base), run_(run), param2_(param2), from2_(from2), span2_(ld(to2) - ld(from2)), omega0_(omega0) {}

  StaticEquations at(const Vec& y) const {
    Params p = base_;
    set(p, param2_, double(parameter2(y)));
    return StaticEquations(p, run_.param, run_.from, ld(run_.to) - ld(run_.from));
  }
  ld parameter2(const Vec& y) const { return from2_ + span2_ * y(5); }
  ld omega(const Vec& y) const { return hopf ? omega0_ * y(6) : 0; }
  static Vec5 z(const Vec& y) { return y.template head<5>(); }

  // Hopf curves: keeps the scaled frequency y(6) = w / w0 at most 2 by raising w0 (never
  // lowering it: towards a Bogdanov-Takens point w must be free to reach 0). Otherwise a
  // curve along which w grows 1000-fold (coulomb, mu from 0.1 to 1e-4) is almost all
  // arclength in w and takes 10^4 steps.
  void rescale_frequency(Vec& y, Vec& t) {
    if (!hopf || y(N - 1) <= 2) return;
    const ld r = y(N - 1);
    omega0_ *= r;
    y(N - 1) = 1;
    t(N - 1) /= r;
    t.normalize();
  }

  // Rebuilds the fold / Hopf condition's borders at y (the null vectors move along the curve).
  void refresh(const Vec& y) {
    const StaticEquations eq = at(y);
    if constexpr (hopf) {
      hopf_.emplace(eq, z(y), omega(y));
    } else {
      fold_.emplace(eq, z(y));
    }
  }

  Res residual(const Vec& y) const {
    const StaticEquations eq = at(y);
    Res r;
    r.template head<4>() = eq.residual(z(y));
    if constexpr (hopf) {
      const std::complex<ld> g = (*hopf_)(eq, z(y), omega(y));
      r(4) = g.real();
      r(5) = g.imag();
    } else {
      r(4) = (*fold_)(eq, z(y));
    }
    return r;
  }

  // Central differences in the scaled unknowns (all O(1)); see bifurcation.cpp for h.
  Eigen::Matrix<ld, N - 1, N> jacobian(const Vec& y) const {
    constexpr ld h = 1e-7L;
    Eigen::Matrix<ld, N - 1, N> D;
    for (int k = 0; k < N; ++k) {
      Vec yp = y, ym = y;
      yp(k) += h;
      ym(k) -= h;
      D.col(k) = (residual(yp) - residual(ym)) / (2 * h);
    }
    return D;
  }

 private:
  Params base_;
  const ContinuationRun& run_;
  ParamRef param2_;
  ld from2_, span2_, omega0_;
  std::optional<FoldCondition> fold_;
  std::optional<HopfCondition> hopf_;
};

// Codimension-two test functions at one curve point; a sign change between consecutive
// points flags the label.
struct Tests {
  FoldCoefficients fold;              // fold curves: cusp and Bogdanov-Takens coefficients
  int hopf_sign = 1, n_unstable = 0;  // fold curves (zero-Hopf)
  ld static_det = 0, lyapunov = 0;   // Hopf curves (zero-Hopf, generalized Hopf)
};

template <int N>
class CurveTracer {
 public:
  using Vec = typename CurveSystem<N>::Vec;
  CurveTracer(CurveSystem<N>& system, const ContinuationOptions& options, const Params& base)
      : sys_(system), options_(options), base_(base) {}

  void run(const Vec& y0, const Vec& t0, BoundaryCurve& out, int end);

 private:
  struct Corrected {
    Vec y;
    bool converged = false;
  };
  Corrected correct(const Vec& y_pred, const Vec& d) const;
  Vec tangent(const Vec& y, const Vec& previous) const;
  Tests tests(const Vec& y, const Tests* previous) const;
  BoundaryPoint point(const Vec& y, Label label) const;
  void detect(const Vec& ya, const Tests& a, const Vec& yb, const Tests& b, std::vector<BoundaryPoint>& out) const;

  CurveSystem<N>& sys_;
  const ContinuationOptions& options_;
  const Params& base_;
};

template <int N>
typename CurveTracer<N>::Corrected CurveTracer<N>::correct(const Vec& y_pred, const Vec& d) const {
  Corrected c{y_pred};
  ld last = std::numeric_limits<ld>::infinity();
  for (int it = 0; it < 12; ++it) {
    Eigen::Matrix<ld, N, N> M;
    M.template topRows<N - 1>() = sys_.jacobian(c.y);
    M.row(N - 1) = d.transpose();
    Vec r;
    r << sys_.residual(c.y), d.dot(c.y - y_pred);
    const Vec step = M.partialPivLu().solve(-r);
    if (!step.allFinite()) return c;
    c.y += step;
    const ld size = step.cwiseAbs().maxCoeff();
    if (size <= 1e-14L || (it >= 2 && size > last / 2)) {
      c.converged = size <= 1e-12L && sys_.residual(c.y).template head<4>().cwiseAbs().maxCoeff() <= 1e-14L;
      return c;
    }
    if (size > 1) return c;
    last = size;
  }
  return c;
}

template <int N>
typename CurveTracer<N>::Vec CurveTracer<N>::tangent(const Vec& y, const Vec& previous) const {
  Eigen::Matrix<ld, N, N> M;
  M.template topRows<N - 1>() = sys_.jacobian(y);
  M.row(N - 1) = previous.transpose();
  Vec e = Vec::Zero();
  e(N - 1) = 1;
  Vec t = M.partialPivLu().solve(e);
  t.normalize();
  return t.dot(previous) < 0 ? Vec(-t) : t;
}

template <int N>
Tests CurveTracer<N>::tests(const Vec& y, const Tests* previous) const {
  const StaticEquations eq = sys_.at(y);
  const Vec5 z = CurveSystem<N>::z(y);
  Tests t;
  if constexpr (N == 7) {
    t.static_det = eq.jacobian(z).template leftCols<4>().partialPivLu().determinant();
    t.lyapunov = first_lyapunov_coefficient(eq.params(z), eq.position(z), sys_.omega(y));
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
  const StaticEquations eq = sys_.at(y);
  const Vec5 z = CurveSystem<N>::z(y);
  BoundaryPoint p;
  p.parameter = eq.parameter(z);
  p.parameter2 = sys_.parameter2(y);
  p.position = eq.position(z);
  p.frequency = sys_.omega(y);
  p.family = classify(base_, p.position);
  p.label = label;
  return p;
}

template <int N>
void CurveTracer<N>::detect(const Vec& ya, const Tests& a, const Vec& yb, const Tests& b,
                            std::vector<BoundaryPoint>& out) const {
  // Codimension-two points are flagged on the curve where their test function changes
  // sign, at the zero of its linear interpolation between the two points.
  const auto flag = [&](Label label, ld fa, ld fb) {
    if ((fa > 0) == (fb > 0) || fa == fb) return;
    const ld theta = fa / (fa - fb);
    out.push_back(point(ya + theta * (yb - ya), label));
  };
  if constexpr (N == 7) {
    flag(Label::ZH, a.static_det, b.static_det);
    flag(Label::GH, a.lyapunov, b.lyapunov);
  } else {
    flag(Label::CP, a.fold.cusp, b.fold.cusp);
    flag(Label::BT, a.fold.bogdanov_takens, b.fold.bogdanov_takens);
    if (a.hopf_sign != b.hopf_sign && std::abs(a.n_unstable - b.n_unstable) == 2)
      out.push_back(point((ya + yb) / 2, Label::ZH));
  }
}

template <int N>
void CurveTracer<N>::run(const Vec& y0, const Vec& t0, BoundaryCurve& out, int end) {
  std::vector<BoundaryPoint> pts;
  Vec y = y0, t = t0;
  sys_.refresh(y);
  Tests tests_y = tests(y, nullptr);
  pts.push_back(point(y, Label::none));
  ld ds = options_.ds;
  StopReason stop = StopReason::max_steps;
  std::string detail = fmt::format("stopped after {} steps", options_.max_steps);
  const auto outside = [](const Vec& v, int& k, ld& bound) {
    for (int i : {4, 5}) {
      if (v(i) < 0 || v(i) > 1) {
        k = i;
        bound = v(i) > 1 ? 1 : 0;
        return true;
      }
    }
    return false;
  };
  for (int step = 0; step < options_.max_steps; ++step) {
    const Vec y_pred = y + ds * t;
    const Corrected c = correct(y_pred, t);
    bool ok = c.converged && (c.y - y_pred).norm() <= ds;
    Vec t_new = t;
    if (ok) {
      t_new = tangent(c.y, t);
      ok = t_new.dot(t) > std::cos(0.5L);
    }
    if (ok && N == 7 && sys_.omega(c.y) <= 0) {
      // The frequency reached zero: the Hopf curve ends on a fold curve (Bogdanov-Takens).
      const ld theta = sys_.omega(y) / (sys_.omega(y) - sys_.omega(c.y));
      pts.push_back(point(y + theta * (c.y - y), Label::BT));
      stop = StopReason::end_of_range;
      detail = "the Hopf frequency reached 0 (Bogdanov-Takens point)";
      break;
    }
    if (!ok) {
      ds /= 2;
      if (ds < options_.ds_min) {
        stop = StopReason::step_underflow;
        const BoundaryPoint p = point(y, Label::none);
        detail = fmt::format("the corrector did not converge at ({:.17g}, {:.17g})", double(p.parameter),
                             double(p.parameter2));
        break;
      }
      continue;
    }
    int k = 0;
    ld bound = 0;
    if (outside(c.y, k, bound)) {
      // The end of the parameter box: the curve point on its edge exactly.
      const ld theta = (bound - y(k)) / (c.y(k) - y(k));
      Vec guess = y + theta * (c.y - y);
      guess(k) = bound;
      Vec e = Vec::Zero();
      e(k) = 1;
      const Corrected last = correct(guess, e);
      if (last.converged) {
        const Tests tl = tests(last.y, &tests_y);
        detect(y, tests_y, last.y, tl, pts);
        pts.push_back(point(last.y, Label::EP));
      }
      stop = StopReason::end_of_range;
      detail.clear();
      break;
    }
    const Tests tn = tests(c.y, &tests_y);
    detect(y, tests_y, c.y, tn, pts);
    y = c.y;
    t = t_new;
    tests_y = tn;
    sys_.rescale_frequency(y, t);
    sys_.refresh(y);
    pts.push_back(point(y, Label::none));
    const ld relative_error = (c.y - y_pred).norm() / ds;
    ds = std::clamp<ld>(ds * std::clamp(std::sqrt(0.05L / std::max(relative_error, 1e-12L)), 0.5L, 2.0L),
                        options_.ds_min, options_.ds_max);
  }
  out.stop[std::size_t(end)] = stop;
  out.stop_detail[std::size_t(end)] = detail;
  if (end == 0) {  // traced against the curve's orientation: reverse and prepend
    out.points.insert(out.points.begin(), pts.rbegin(), pts.rend() - 1);
  } else {
    out.points.insert(out.points.end(), pts.begin(), pts.end());
  }
}

template <int N>
BoundaryCurve trace_curve(const Params& p, const ContinuationRun& run, const SpecialPoint& sp, ParamRef param2,
                          double to2, const ContinuationOptions& options) {
  const double from2 = get(p, param2);
  const ld omega0 = N == 7 ? ld(sp.frequency) : 1;
  CurveSystem<N> sys(p, run, param2, from2, to2, omega0);
  const StaticEquations eq(p, run.param, run.from, ld(run.to) - ld(run.from));
  typename CurveSystem<N>::Vec y0 = CurveSystem<N>::Vec::Zero();
  y0.template head<5>() = eq.scaled(sp.position, sp.parameter);
  y0(5) = 0;
  if constexpr (N == 7) y0(6) = 1;
  sys.refresh(y0);
  // Head into the box: towards increasing second parameter.
  typename CurveSystem<N>::Vec inward = CurveSystem<N>::Vec::Zero();
  inward(5) = 1;
  CurveTracer<N> tracer(sys, options, p);
  BoundaryCurve curve;
  curve.kind = N == 7 ? Label::HB : Label::LP;
  auto t0 = inward;
  {
    Eigen::Matrix<ld, N, N> M;
    M.template topRows<N - 1>() = sys.jacobian(y0);
    M.row(N - 1) = inward.transpose();
    typename CurveSystem<N>::Vec e = CurveSystem<N>::Vec::Zero();
    e(N - 1) = 1;
    t0 = M.partialPivLu().solve(e).normalized();
    if (t0(5) < 0) t0 = -t0;
  }
  tracer.run(y0, t0, curve, 1);
  if (t0(5) > 1e-6L) {  // the start is the box's lower edge in p2: the other way leaves it at once
    curve.stop[0] = StopReason::end_of_range;
    curve.stop_detail[0] = "the start value of the second parameter is an end of its interval";
    curve.points.front().label = Label::EP;
  } else {
    tracer.run(y0, -t0, curve, 0);
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
