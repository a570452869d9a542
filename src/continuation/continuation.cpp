#include "abu/continuation/continuation.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "abu/continuation/bifurcation.hpp"
#include "abu/core/errors.hpp"
#include "abu/continuation/corrector.hpp"
#include "abu/model/static_equations.hpp"
#include "abu/continuation/tracking.hpp"

namespace abu {

namespace {

using ld = long double;
using Vec5 = StaticEquations::Vec5;
using Mat45 = StaticEquations::Mat45;

// One direction of one branch.
class Tracer {
 public:
  Tracer(const StaticEquations& eq, const ContinuationOptions& options) : eq_(eq), options_(options) {}

  void run(const Vec5& z0, const Vec5& t0);

  std::vector<BranchPoint> points;
  std::vector<SpecialPoint> specials;
  StopReason stop = StopReason::max_steps;
  std::string detail;
  mutable ContinuationStats stats;

 private:
  // The point at z with its modes matched to `predicted` (none: the first point, sorted
  // order); `ambiguity` receives tracking_ambiguity.
  BranchPoint make_point(const Vec5& z, const Vec5& t, const Mat45& DF, const ModePrediction* predicted,
                         double* ambiguity) const;
  ModePrediction predict(const Vec5& z) const;
  // An eigenvector with q in displacement-scale units, unit norm (for overlaps).
  Vec4c scaled_vector(const Vec4c& v) const {
    const double length = double(eq_.length());
    return Vec4c(v(0) / length, v(1) / length, v(2), v(3)).normalized();
  }
  void add(const Vec5& z, const Vec5& t);
  void detect(std::size_t a);
  void locate_singular_between(std::size_t a, bool fold_test);
  std::optional<Vec5> root_on_branch(std::size_t a, bool fold_test) const;
  void locate_hopf_between(std::size_t a);
  SpecialPoint special_at(Label label, const Vec5& z, std::size_t a) const;

  const StaticEquations& eq_;
  const ContinuationOptions& options_;
  std::vector<Vec5> zs_, ts_;
};

// Each mode's eigenvalue extrapolated linearly in arclength from the last two points to
// z; its eigenvector as at the last point.
ModePrediction Tracer::predict(const Vec5& z) const {
  const std::size_t n = points.size();
  ModePrediction out;
  out.values = points[n - 1].modes;
  out.si_vectors = points[n - 1].mode_vectors;
  for (std::size_t k = 0; k < 8; ++k) out.vectors[k] = scaled_vector(points[n - 1].mode_vectors[k]);
  if (n < 2) return out;
  const ld last = (zs_[n - 1] - zs_[n - 2]).norm();
  const double ratio = last > 0 ? double((z - zs_[n - 1]).norm() / last) : 0.0;
  for (std::size_t k = 0; k < 8; ++k) out.values[k] += ratio * (points[n - 1].modes[k] - points[n - 2].modes[k]);
  return out;
}

BranchPoint Tracer::make_point(const Vec5& z, const Vec5& t, const Mat45& DF, const ModePrediction* predicted,
                               double* ambiguity) const {
  BranchPoint pt;
  pt.parameter = eq_.parameter(z);
  pt.position = eq_.position(z);
  pt.family = classify(eq_.base(), pt.position);
  const Linearization<ld, 2> lin = eq_.linearization(z);
  // Eigenvalue continuation from the predicted modes first (cheap, keeps every mode's
  // identity); a fresh spectrum matched to the prediction where that fails.
  if (predicted) {
    if (auto tracked = track_spectrum(lin, predicted->values, predicted->si_vectors)) {
      ++stats.tracked_spectra;
      pt.spectrum = tracked->spectrum;
      pt.modes = tracked->modes;
      pt.mode_vectors = tracked->mode_vectors;
      if (ambiguity) *ambiguity = 0;
      pt.tangent_parameter = double(t(4));
      pt.branch_test = double(branch_test(DF, t));
      return pt;
    }
  }
  pt.spectrum = compute_spectrum(lin);
  ++stats.full_spectra;
  if (predicted) {
    std::array<Vec4c, 8> scaled{};
    for (std::size_t k = 0; k < 8; ++k) scaled[k] = scaled_vector(pt.spectrum.vectors[k]);
    std::array<int, 8> source{};
    track(*predicted, pt.spectrum, scaled, pt.modes, source);
    for (std::size_t k = 0; k < 8; ++k) pt.mode_vectors[k] = pt.spectrum.vectors[std::size_t(source[k])];
    if (ambiguity) *ambiguity = tracking_ambiguity(*predicted, pt.spectrum, scaled, source);
  } else {
    pt.modes = pt.spectrum.eigenvalues;
    pt.mode_vectors = pt.spectrum.vectors;
  }
  // Signs relative to the direction of increasing parameter, whichever way we travel.
  pt.tangent_parameter = double(t(4));
  pt.branch_test = double(branch_test(DF, t));
  return pt;
}

void Tracer::add(const Vec5& z, const Vec5& t) {
  const Mat45 DF = eq_.jacobian(z);
  if (points.empty()) {
    points.push_back(make_point(z, t, DF, nullptr, nullptr));
  } else {
    const ModePrediction predicted = predict(z);
    points.push_back(make_point(z, t, DF, &predicted, nullptr));
  }
  zs_.push_back(z);
  ts_.push_back(t);
  if (points.size() >= 2) detect(points.size() - 2);
}

void Tracer::run(const Vec5& z0, const Vec5& t0) {
  add(z0, t0);
  ld ds = options_.ds;
  const auto range_rule = [&](const Vec5& z) { return range_violation(eq_.param().quantity, double(eq_.parameter(z))); };
  for (int step = 0; step < options_.max_steps; ++step) {
    const Vec5 z = zs_.back(), t = ts_.back();
    const Vec5 z_pred = z + ds * t;
    const Corrected c = correct(eq_, z_pred, t);
    stats.newton_iterations += c.iterations;
    Vec5 t_new = t;
    bool ok = c.converged && (c.z - z_pred).norm() <= ds;
    if (ok) {
      t_new = tangent(c.jacobian, t);
      ok = t_new.dot(t) > std::cos(0.5L);  // turning by more than 0.5 rad per step: too coarse
    }
    if (!ok) {
      ++stats.rejected;
      ds /= 2;
      if (ds < options_.ds_min) {
        stop = StopReason::step_underflow;
        detail = fmt::format("the corrector did not converge with step {:.3g} at {}={:.17g}", double(ds * 2),
                             to_string(eq_.param()), double(eq_.parameter(z)));
        return;
      }
      continue;
    }
    if (c.z(4) < 0 || c.z(4) > 1) {
      // The end of the interval: the equilibrium at the end value exactly.
      const ld end = c.z(4) > 1 ? 1 : 0;
      const ld theta = (end - z(4)) / (c.z(4) - z(4));
      Vec5 guess = z + theta * (c.z - z);
      guess(4) = end;
      Vec5 e5 = Vec5::Zero();
      e5(4) = 1;
      const Corrected last = correct(eq_, guess, e5);
      if (last.converged) {
        add(last.z, tangent(last.jacobian, t));
        points.back().label = Label::EP;
        stop = StopReason::end_of_range;
      } else {
        stop = StopReason::step_underflow;
        detail = fmt::format("no equilibrium found at the end value {}={:.17g}", to_string(eq_.param()),
                             double(eq_.parameter(guess)));
      }
      return;
    }
    // Inside the interval the parameter can still leave its physical range only if the
    // interval itself crosses it (the library's callers check the end value).
    if (const auto rule = range_rule(c.z)) {
      stop = StopReason::invalid_parameter;
      detail = fmt::format("{} would become {:.17g}: {}", to_string(eq_.param()), double(eq_.parameter(c.z)), *rule);
      return;
    }
    // Eigenvalue tracking needs the modes to move little per step: else halve the step.
    const ModePrediction predicted = predict(c.z);
    double ambiguity = 0;
    BranchPoint candidate = make_point(c.z, t_new, c.jacobian, &predicted, &ambiguity);
    if (ambiguity > 1 && ds > 16 * options_.ds_min) {
      ++stats.rejected;
      ds /= 2;
      continue;
    }
    points.push_back(std::move(candidate));
    ++stats.steps;
    zs_.push_back(c.z);
    ts_.push_back(t_new);
    detect(points.size() - 2);
    if (points.size() > 5 && distance(c.z, zs_.front()) < ds) {
      stop = StopReason::closed_loop;
      return;
    }
    // Next step from the predictor's relative error |z - z_pred| / ds ~ curvature * ds / 2:
    // aim at 10% (the tangent then stays a good predictor), change by at most 2x per step.
    const ld relative_error = (c.z - z_pred).norm() / ds;
    const ld factor = std::clamp(std::sqrt(0.1L / std::max(relative_error, 1e-12L)), 0.5L, 2.0L);
    ds = std::clamp<ld>(ds * factor, options_.ds_min, options_.ds_max);
  }
  stop = StopReason::max_steps;
  detail = fmt::format("stopped after {} steps at {}={:.17g}", options_.max_steps, to_string(eq_.param()),
                       double(points.back().parameter));
}

void Tracer::detect(std::size_t a) {
  const BranchPoint& pa = points[a];
  const BranchPoint& pb = points[a + 1];
  const bool fold_test = (pa.tangent_parameter > 0) != (pb.tangent_parameter > 0);
  const bool branch_test_changed = (pa.branch_test > 0) != (pb.branch_test > 0);
  // Both mark a point where F_s is singular; along the fork of a pitchfork both change
  // sign at once (the fork turns there): one singular point, classified when located.
  if (fold_test || branch_test_changed) locate_singular_between(a, fold_test);
  if (hopf_test_sign(pa.spectrum) != hopf_test_sign(pb.spectrum)) locate_hopf_between(a);
}

SpecialPoint Tracer::special_at(Label label, const Vec5& z, std::size_t a) const {
  SpecialPoint sp;
  sp.label = label;
  sp.parameter = eq_.parameter(z);
  sp.position = eq_.position(z);
  sp.family = classify(eq_.base(), sp.position);
  sp.n_unstable_before = points[a].spectrum.n_unstable;
  sp.n_unstable_after = points[a + 1].spectrum.n_unstable;
  sp.bracket_from = points[a].parameter;
  sp.bracket_to = points[a + 1].parameter;
  return sp;
}

// The eigenvalue of `sp` nearest to `target`.
std::complex<double> nearest(const Spectrum& sp, std::complex<double> target) {
  std::complex<double> best = sp.eigenvalues[0];
  for (const auto& l : sp.eigenvalues)
    if (std::abs(l - target) < std::abs(best - target)) best = l;
  return best;
}

// A located point must lie on the piece of branch it was bracketed on (within a
// margin of the chord), else the augmented Newton wandered off.
bool inside(const Vec5& za, const Vec5& zb, const Vec5& z) {
  const ld chord = distance(za, zb);
  return distance(z, za) <= 2 * chord && distance(z, zb) <= 2 * chord;
}

void Tracer::locate_singular_between(std::size_t a, bool fold_test) {
  // The singular point solves the fold's augmented system (F = 0, F_s singular); where
  // that fails (fold and branch point coinciding, F_s of rank 2) the test function's root
  // on the branch is found by Brent's method instead. Then: a fold if F_p is outside the
  // range of F_s (w^T F_p != 0, w its left null vector), a branch point if inside.
  const ld fa = fold_test ? ld(points[a].tangent_parameter) : ld(points[a].branch_test);
  const ld fb = fold_test ? ld(points[a + 1].tangent_parameter) : ld(points[a + 1].branch_test);
  const Vec5 guess = zs_[a] + (fa / (fa - fb)) * (zs_[a + 1] - zs_[a]);
  const Located f = locate_fold(eq_, guess);
  std::optional<Vec5> z;
  if (f.converged && inside(zs_[a], zs_[a + 1], f.z)) z = f.z;
  if (!z) z = root_on_branch(a, fold_test);
  if (!z) {
    SpecialPoint sp = special_at(fold_test ? Label::LP : Label::BP, guess, a);
    sp.eigenvalue = nearest(compute_spectrum(eq_.linearization(guess)), 0.0);
    sp.note = "a singular point was detected here but could not be located (neither its augmented system nor the "
              "test function's root on the branch converged)";
    specials.push_back(sp);
    return;
  }
  const Mat45 DF = eq_.jacobian(*z);
  const Eigen::JacobiSVD<Eigen::Matrix<ld, 4, 4>> svd(DF.leftCols<4>(), Eigen::ComputeFullU);
  const ld in_range = std::abs(svd.matrixU().col(3).dot(DF.col(4))) / DF.col(4).norm();
  // w^T F_p / |F_p|: 0 at a branch point, of order 1 at a fold. Measured: 1e-22 where a
  // branch crosses a branch point, 2e-7 on the fork of a pitchfork (whose location is
  // exact in the parameter, uncertain by ~1e-8 along the null direction), 0.999 at the
  // folds of the together family. 1e-5 separates them by orders of magnitude.
  SpecialPoint sp = special_at(in_range <= 1e-5L ? Label::BP : Label::LP, *z, a);
  sp.converged = true;
  sp.eigenvalue = nearest(compute_spectrum(eq_.linearization(*z)), 0.0);
  specials.push_back(sp);
}

std::optional<Vec5> Tracer::root_on_branch(std::size_t a, bool fold_test) const {
  // The test function (t_p, or det [F_u; t^T]) along the chord from z_a to z_b, each value
  // on the branch (the corrector with the chord as constraint direction); Brent (GSL).
  const Vec5 za = zs_[a];
  const ld length = (zs_[a + 1] - za).norm();
  const Vec5 d = (zs_[a + 1] - za) / length;
  struct Context {
    const StaticEquations* eq;
    Vec5 za, d, t;
    bool fold_test;
    bool failed = false;
  } ctx{&eq_, za, d, ts_[a], fold_test};
  gsl_function fn;
  fn.params = &ctx;
  fn.function = [](double sigma, void* raw) -> double {
    auto* c = static_cast<Context*>(raw);
    const Corrected on = correct(*c->eq, c->za + ld(sigma) * c->d, c->d);
    if (!on.converged) c->failed = true;
    const Vec5 t = tangent(on.jacobian, c->t);
    return c->fold_test ? double(t(4)) : double(branch_test(on.jacobian, t));
  };
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  double lo = 0, hi = double(length), root = 0.5 * hi;
  bool ok = gsl_root_fsolver_set(solver, &fn, lo, hi) == GSL_SUCCESS;
  for (int it = 0; ok && it < 200; ++it) {
    if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS) {
      ok = false;
      break;
    }
    root = gsl_root_fsolver_root(solver);
    lo = gsl_root_fsolver_x_lower(solver);
    hi = gsl_root_fsolver_x_upper(solver);
    if (gsl_root_test_interval(lo, hi, 0, 1e-15) == GSL_SUCCESS) break;
  }
  gsl_root_fsolver_free(solver);
  const Corrected on = correct(eq_, za + ld(root) * d, d);
  if (!(ok && on.converged && !ctx.failed && inside(zs_[a], zs_[a + 1], on.z))) return std::nullopt;
  return on.z;
}

void Tracer::locate_hopf_between(std::size_t a) {
  // Narrow the bracket on the branch (bisection on the test function's sign, each point
  // corrected onto the branch) until the crossing pair is complex at both ends: a Hopf
  // pair can be complex only in a sliver of the step (near omega_n with coulomb
  // friction its frequency is 1e-5 omega_n). Then solve the Hopf system from there.
  Vec5 za = zs_[a], zb = zs_[a + 1];
  Spectrum sa = points[a].spectrum, sb = points[a + 1].spectrum;
  // A neutral saddle (a real pair lambda, -lambda: one eigenvalue on each side of the
  // axis) changes the test function's sign but not the number of unstable eigenvalues;
  // a Hopf crossing changes it by two. Only the latter is worth locating.
  if (std::abs(sa.n_unstable - sb.n_unstable) != 2) return;
  const int sign_a = hopf_test_sign(sa);
  std::optional<std::pair<std::complex<double>, std::complex<double>>> pair;
  for (int it = 0; it < 90 && !(pair = crossing_pair(sa, sb)); ++it) {
    if (distance(za, zb) < 1e-15L) break;
    const Vec5 d = (zb - za).normalized();
    const Corrected mid = correct(eq_, (za + zb) / 2, d);
    if (!mid.converged) break;
    const Spectrum sm = compute_spectrum(eq_.linearization(mid.z));
    if (hopf_test_sign(sm) == sign_a) {
      za = mid.z, sa = sm;
    } else {
      zb = mid.z, sb = sm;
    }
  }
  if (!pair) {
    // The sign change came from a real pair lambda, -lambda: a neutral saddle, not a
    // Hopf point (or a crossing too close to a coalescence to resolve): not reported.
    return;
  }
  const auto [la, lb] = *pair;
  const double theta = la.real() / (la.real() - lb.real());
  const Vec5 guess = za + ld(theta) * (zb - za);
  const ld omega_guess = la.imag() + theta * (lb.imag() - la.imag());
  const Located h = locate_hopf(eq_, guess, omega_guess);
  const bool ok = h.converged && inside(zs_[a], zs_[a + 1], h.z);
  SpecialPoint sp = special_at(Label::HB, ok ? h.z : guess, a);
  sp.converged = ok;
  sp.frequency = double(ok ? h.frequency : omega_guess);
  const Spectrum s = compute_spectrum(eq_.linearization(ok ? h.z : guess));
  sp.eigenvalue = nearest(s, std::complex<double>(0, sp.frequency));
  if (ok) {
    sp.lyapunov = first_lyapunov_coefficient(eq_.params(h.z), eq_.position(h.z), h.frequency);
    if (sp.lyapunov == 0) sp.note = "degenerate Hopf point (l1 = 0 within its accuracy)";
  } else {
    sp.note = "Hopf crossing detected but its augmented system did not converge";
  }
  specials.push_back(sp);
}

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
// Traces the branch through `e` at scaled parameter z4 = end (0: the start value, 1 the
// far end), heading into the interval, and appends it to the run.
Branch trace_branch(const StaticEquations& eq, const Equilibrium& e, ld parameter, ld end,
                    const ContinuationOptions& options, ContinuationStats& stats) {
  Vec5 inward = Vec5::Zero();
  inward(4) = end == 0 ? 1 : -1;
  const Vec5 z0 = eq.scaled(e.position, parameter);
  const Vec5 t0 = tangent(eq.jacobian(z0), inward);
  Tracer forward(eq, options), backward(eq, options);
  forward.run(z0, t0);
  // Backwards only if the branch does not leave the interval at once (a fold at the start).
  const bool transversal = t0.dot(inward) > 1e-6L;
  if (!transversal) backward.run(z0, -t0);
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
  b.stop = {transversal ? StopReason::end_of_range : backward.stop, forward.stop};
  b.stop_detail = {transversal ? std::string("the start value is an end of the interval") : backward.detail,
                   forward.detail};
  if (transversal) b.points.front().label = Label::EP;
  return b;
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
  if (!start.state)
    for (const auto& e : start_points(far, start, run.notes)) starts.push_back({e, ld(to), 1});
  for (const auto& s : starts) {
    const Vec5 z = eq.scaled(s.e.position, s.parameter);
    const Branch* on = nullptr;
    for (const auto& b : run.branches)
      if (passes_through(eq, b, z)) on = &b;
    if (on) {
      if (s.end == 0)
        run.notes.push_back(fmt::format("{} {} lies on the branch of {} {}; not traced again", to_string(s.e.family),
                                        s.e.member, to_string(on->family), on->member));
      continue;
    }
    run.branches.push_back(trace_branch(eq, s.e, s.parameter, s.end, options, run.stats));
  }
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
