// The shooting problem of one cycle branch for the arclength engine (docs/model.md §17.2-§17.8,
// §17.11): the unknowns (M points, the period, the parameter), the residuals from state-only
// flows, the Newton matrix (integrated, or extrapolated along the branch, §17.7), the orbit's
// multipliers, amplitude and test functions, and the location of LPC, PD and NS on the branch
// (§17.5). Internal to src/dynamics (periodic_orbits.cpp).
#pragma once

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "abu/continuation/arclength.hpp"
#include "abu/core/cancel.hpp"
#include "abu/dynamics/periodic_orbits.hpp"
#include "abu/linear/floquet.hpp"
#include "abu/model/model.hpp"
#include "cycle_flow.hpp"
#include "cycle_mesh.hpp"
#include "cycle_period_shift.hpp"
#include "cyclic_jacobian.hpp"
#include "shooting_flow.hpp"
#include "stiff_cycles.hpp"

namespace abu::cycle_problem {

using namespace cycle_flow;  // the flow of the shooting intervals (cycle_flow.hpp)
using detail::cyclic_max;


// The scaling D (model.md §17.2) and the stepper at a Hopf point: the implicit
// extrapolation stepper when the ball modes are far faster than the orbit (stiff).
struct ShootingSetup {
  Eigen::Matrix<double, kDim, 1> scale;
  const gsl_odeiv2_step_type* type;
  bool radau = false;  // very stiff: the fixed-step Radau route (model.md §17.11)
};
inline ShootingSetup shooting_setup(const Params& p0, ParamRef ref, const SpecialPoint& hopf) {
  Params p = p0;
  const double w = hopf.frequency;
  set(p, ref, double(hopf.parameter));
  const State8 xH = at_rest<double, 2>(Coordinates<double, 2>(hopf.position.cast<double>()));
  ShootingSetup s;
  const double L = displacement_scale(p);
  s.scale << L, L, 1, 1, L * w, L * w, w, w;
  const Eigen::MatrixXd JH = jacobian(p, xH);
  Eigen::EigenSolver<Eigen::MatrixXd> es(JH, false);
  const double rho = es.info() == Eigen::Success ? es.eigenvalues().cwiseAbs().maxCoeff() : 0.0;
  s.type = rho / w > 1e3 ? gsl_odeiv2_step_bsimp : gsl_odeiv2_step_rk8pd;
  s.radau = rho / w > detail::kRadauStiffness;
  return s;
}

using CycleJacobian = detail::CyclicJacobian<kDim>;

// One evaluation of the shooting problem at its unknowns u: the residuals, the Newton matrix
// in its block structure and the intervals' transition matrices (the Floquet factors).
struct Evaluated {
  Eigen::VectorXd u;
  Eigen::VectorXd residual;
  CycleJacobian jacobian;
  std::vector<Eigen::MatrixXd> transitions;
  bool ok = false;
  std::string_view why;
};

template <bool Chord>
class CycleProblem {
 public:
  using Vec = Eigen::VectorXd;
  using Jacobian = CycleJacobian;
  static constexpr std::size_t test_count = 3;  // LPC, PD, NS
  static constexpr bool tangent_at_solution = true;
  // The corrector keeps the Newton matrix of the predicted orbit (model.md §17.7): its
  // iterations then integrate the 8 states only, not the 80 variational components.
  static constexpr bool chord_corrector = Chord;

  CycleProblem(const Params& p, ParamRef ref, double from, double to, double period_h, const CycleOptions& o,
               const gsl_odeiv2_step_type* type, const Eigen::Matrix<double, kDim, 1>& scale, bool radau = false)
      : o_(o), from_(from), to_(to), period_h_(period_h), m_(radau ? o.stiff_intervals : o.intervals),
        mesh_(detail::CycleMesh::uniform(m_, !radau)),
        // Full Newton takes its residuals from the variational pass: one tolerance then.
        newton_(type, kAugmented, Chord ? std::max(o.newton_rtol, o.rtol) : o.rtol, radau),
        floquet_(type, kAugmented, Chord ? std::max(o.floquet_rtol, o.rtol) : o.rtol, radau),
        state_(type, kDim, o.rtol, radau), radau_(radau), steps_(o.stiff_steps) {
    ctx_.p = p;
    ctx_.ref = ref;
    ctx_.scale = scale;
    ctx_.span = to - from;
  }

  int size() const { return kDim * m_ + 2; }
  int intervals() const { return m_; }
  /// The mesh (model.md §17.2): point j's phase theta_j in [0, 1) and the weight of its
  /// unknowns (u_j = weight_j y_j).
  double node(int j) const { return mesh_.node(j); }
  double weight(int j) const { return mesh_.weight(j); }
  /// The scaled state y_j at point j of u.
  Eigen::Matrix<double, kDim, 1> point(const Vec& u, int j) const {
    return u.template segment<kDim>(kDim * j) / mesh_.weight(j);
  }
  double interval_length(const Vec& u, int j) const { return of_interval(period(u), j); }
  /// x times interval j's fraction of the period (x / M on a uniform mesh, as before meshes
  /// were chosen: the stiff route's steps keep their bits).
  double of_interval(double x, int j) const { return mesh_.is_uniform() ? x / m_ : x * mesh_.fraction(j); }
  /// The stiff route's Radau steps per shooting interval (model.md §17.11).
  int steps_per_interval() const { return radau_ ? steps_ : 0; }
  void set_steps_per_interval(int steps) {
    steps_ = steps;
    cache_.u.resize(0);
    plain_.u.resize(0);
  }
  bool radau() const { return radau_; }
  int period_index() const { return kDim * m_; }
  int param_index() const { return kDim * m_ + 1; }
  double parameter(const Vec& u) const { return from_ + u(param_index()) * (to_ - from_); }
  double period(const Vec& u) const { return u(period_index()) * period_h_; }

  void set_phase(const Vec& u) {
    y_ref_ = point(u, 0);
    ctx_.variational = false;
    set(ctx_.p, ctx_.ref, parameter(u));
    double f[kDim];
    flow_rhs(0, y_ref_.data(), f, &ctx_);
    f_ref_ = Eigen::Map<Eigen::Matrix<double, kDim, 1>>(f);
    const double n = f_ref_.norm();
    if (n > 0) f_ref_ /= n;
  }

  // Starts an evaluation of u into e (the residual zeroed, the context set to u's
  // parameter); false, e marked failed, if the period is not positive.
  bool begin(Evaluated& e, const Vec& u, bool variational) const {
    throw_if_stopped("cycle continuation");
    e.u = u;
    e.ok = true;
    e.why = {};
    e.residual = Vec::Zero(size() - 1);
    ctx_.variational = variational;
    set(ctx_.p, ctx_.ref, parameter(u));
    const double h = period(u) / m_;
    ctx_.radau_step = h / steps_;  // the stiff route's mesh is uniform
    if (h > 0 && std::isfinite(h)) return true;
    e.ok = false;
    e.why = "the period is not positive";
    e.residual.setConstant(1e300);
    return false;
  }

  // A converged orbit: the state-only residual at u is at the integration's noise (the
  // corrector has just accepted u). Its transition matrices give the multipliers.
  bool converged_orbit(const Vec& u) const {
    return plain_.ok && plain_.u.size() == u.size() && plain_.u == u &&
           plain_.residual.cwiseAbs().maxCoeff() <= 1e3 * o_.rtol;
  }

  // Full evaluation at u (cached): residual, Jacobian, transition matrices. With the chord
  // corrector the variational equations are integrated to floquet_rtol at a converged orbit
  // (the multipliers, the tangent) and to newton_rtol elsewhere (the predicted orbit, whose
  // Newton matrix only sets the chord iteration's contraction: model.md §17.8).
  const Evaluated& at(const Vec& u) const {
    const bool accurate = Chord && converged_orbit(u);
    if (cache_.u.size() == u.size() && cache_.u == u && (cache_accurate_ || !accurate)) return cache_;
    if (!accurate && segment_ends_) return interpolated(u);
    if (!accurate && can_extrapolate()) return extrapolated(u);
    cache_accurate_ = accurate;
    Integrator& full = accurate ? floquet_ : newton_;
    Evaluated& e = cache_;
    const int n = size();
    e.jacobian.resize(m_);
    e.transitions.assign(std::size_t(m_), Eigen::MatrixXd::Identity(kDim, kDim));
    if (!begin(e, u, true)) return e;
    std::vector<double> y(kAugmented);
    for (int j = 0; j < m_; ++j) {
      const double h = interval_length(u, j);
      std::fill(y.begin(), y.end(), 0.0);
      const Eigen::Matrix<double, kDim, 1> yj = point(u, j);
      for (int i = 0; i < kDim; ++i) y[std::size_t(i)] = yj(i), y[std::size_t(kDim * (1 + i) + i)] = 1.0;
      std::string_view why;
      if (!full.run(ctx_, y.data(), h, {h}, {}, why)) return failed(e, why);
      interval_residual(e, u, j, y.data(), full);
      const Eigen::Map<const Eigen::Matrix<double, kDim, kDim>> phi(y.data() + kDim);
      e.transitions[std::size_t(j)] = phi;
      // The unknowns are weighted (u_j = w_j y_j): d r_j / d u_j = Phi_j / w_j, d r_j / d u_{j+1} = -I / w_{j+1}.
      e.jacobian.diag[std::size_t(j)] = phi / mesh_.weight(j);
      e.jacobian.next[std::size_t(j)].setConstant(-1.0 / mesh_.weight(j + 1));
      // d/d(T / T_H): the field at the end times dh/d(T/T_H) = T_H (theta_{j+1} - theta_j).
      double f[kDim];
      ctx_.variational = false;
      flow_rhs(0, y.data(), f, &ctx_);
      ctx_.variational = true;
      for (int i = 0; i < kDim; ++i) {
        e.jacobian.border[std::size_t(j)](i, 0) = of_interval(f[i] * period_h_, j);
        e.jacobian.border[std::size_t(j)](i, 1) = y[std::size_t(kDim * kColumns + i)];
      }
    }
    e.residual(n - 2) = (point(u, 0) - y_ref_).dot(f_ref_);
    e.jacobian.phase = f_ref_ / mesh_.weight(0);
    flows_ += m_;
    return e;
  }

  // Interval j's residual rows: its flow's end minus the next point (on the stiff route the
  // increment summed apart from the state, model.md §17.11).
  void interval_residual(Evaluated& e, const Vec& u, int j, const double* end, const Integrator& flow) const {
    const Eigen::Matrix<double, kDim, 1> here = point(u, j), there = point(u, (j + 1) % m_);
    for (int i = 0; i < kDim; ++i)
      e.residual(kDim * j + i) = flow.radau() ? (here(i) - there(i)) + flow.increment()(i) : end[i] - there(i);
  }
  static const Evaluated& failed(Evaluated& e, std::string_view why) {
    e.ok = false;
    e.why = why;
    e.residual.setConstant(1e300);
    return e;
  }

  // The residual alone: with the chord corrector from flows of the state only, at rtol
  // (the full evaluation's residual is at the variational tolerance, which may be looser).
  // With `sampling` the same pass also stops at samples_per_interval uniform times per
  // interval and keeps the samples as u's orbit: the corrector's last residual is taken at
  // the orbit it accepts, which sample() would otherwise integrate again (a sixth of the
  // state steps per orbit, model.md §17.9).
  const Evaluated& residual_at(const Vec& u, bool sampling = false) const {
    if constexpr (!Chord) return at(u);
    const bool cached = plain_.u.size() == u.size() && plain_.u == u;
    if (cached && (!sampling || sampled_for(u))) return plain_;
    Evaluated& e = plain_;
    if (!begin(e, u, false)) return e;
    const int n = size();
    if (sampling) clear_samples();
    for (int j = 0; j < m_; ++j) {
      const double h = interval_length(u, j);
      std::vector<double> targets{h};
      std::vector<char> is_sample;
      if (sampling) sample_plan(u, j, targets, is_sample);
      std::size_t at_target = 0;
      std::function<void(const double*)> keep;
      if (sampling)
        keep = [&](const double* x) {
          if (is_sample[at_target++]) keep_sample(x);
        };
      double y[kDim];
      const Eigen::Matrix<double, kDim, 1> yj = point(u, j);
      for (int i = 0; i < kDim; ++i) y[i] = yj(i);
      std::string_view why;
      if (!state_.run(ctx_, y, h, targets, keep, why)) return failed(e, why);
      interval_residual(e, u, j, y, state_);
    }
    e.residual(n - 2) = (point(u, 0) - y_ref_).dot(f_ref_);
    state_flows_ += m_;
    if (sampling) sampled_u_ = u;
    return e;
  }

  Vec residual(const Vec& u) const { return residual_at(u).residual; }
  Jacobian jacobian(const Vec& u) const { return at(u).jacobian; }
  /// The bordered system's LU in the Newton matrix's block structure (cyclic_jacobian.hpp).
  detail::CyclicBorderedLu<kDim> factor_bordered(const Jacobian& J, const Vec& d) const {
    return detail::CyclicBorderedLu<kDim>(J, d);
  }
  // Asked by the corrector only at the iterate it is about to accept: sampled as well,
  // except on the stiff route, whose fixed Radau steps would be split at the sample times
  // (another discrete map than the one the corrector solved, model.md §17.11).
  double residual_size(const Vec& u) const {
    const Evaluated& e = residual_at(u, !radau_);
    return e.ok ? e.residual.cwiseAbs().maxCoeff() : 1e300;
  }
  arclength::NewtonSettings newton() const {
    // The residual is an integration to rtol: Newton stops at its noise level, not at eps.
    arclength::NewtonSettings s;
    s.max_iterations = 10;
    s.step_tolerance = 10 * o_.rtol;
    // On the stiff route the orbits next to the Hopf point are conditioned like 1/|mu_2 - 1|
    // (~2.5e6 there) and the Radau stages round at ~1e-13 |y| per step (model.md §17.15):
    // Newton's steps stall near 1e-6 scaled, above 1e7 rtol, and whether a first orbit was
    // accepted depended on the parameter's scaling (--to 251 and 255 yes, 252 and 300 no).
    // A stalled Newton is accepted there when its residual is at the noise level (checked
    // below): the orbit is then as accurate as the discrete map lets it be.
    s.stall_tolerance = radau_ ? 1e-3 : 1e7 * o_.rtol;
    s.residual_tolerance = 1e3 * o_.rtol;
    // The chord's linear rate predicts the next step: stop when it is at the integration's
    // noise (rtol) instead of taking it (about one state pass per orbit, model.md §17.9).
    // Not on the stiff route: its orbits next to the Hopf point are so ill-determined
    // (|mu_2 - 1| ~ 4e-7) that the skipped step still moved the amplitude by 4e-4 relative.
    s.predicted_tolerance = radau_ ? 0.0 : o_.rtol;
    return s;
  }

  arclength::Crossing crossing(const Vec&, const Vec& to) const {
    if (!(to(period_index()) > 0)) return arclength::Crossing::leaving("the period went to zero");
    if (to(period_index()) > o_.max_period_factor)
      return arclength::Crossing::leaving(fmt::format("the period exceeded {:g} times 2 pi / omega_H (a homoclinic "
                                                      "approach?)", o_.max_period_factor));
    return arclength::box_crossing(to, {param_index()});
  }

  // The orbit at u: Floquet multipliers, amplitude, ball ranges; the test functions.
  arclength::Evaluation<double, 3> evaluate(const Vec& u, const Vec& t, const Jacobian&, arclength::Stage) {
    const Evaluated& e = at(u);
    arclength::Evaluation<double, 3> out;
    CycleOrbit orbit;
    orbit.parameter = parameter(u);
    orbit.period = period(u);
    const bool sampled = sample(u, orbit);
    std::size_t trivial = 0;
    const ProductEigenvalues f = multipliers(e, u, trivial);
    orbit.floquet_status = f.status;
    orbit.multipliers = f.values;
    orbit.log_moduli = f.log_moduli;
    if (radau_ && sampled) {  // the multipliers no factor represents (model.md §17.13)
      orbit.steps_per_interval = steps_;
      orbit.unresolved_multipliers = detail::replace_unresolved_multipliers(
          ctx_.p, samples_, orbit.period, long(m_) * steps_, orbit.multipliers, orbit.log_moduli, orbit.liouville_error);
      if (orbit.unresolved_multipliers < 0)
        orbit.floquet_status.merge(Outcome::numerical_issue, "the frozen spectra along the orbit failed");
    }
    const CycleTestValues tv = radau_ ? cycle_test_values(orbit.multipliers, orbit.log_moduli)
                                      : cycle_test_values(orbit.multipliers, orbit.log_moduli, trivial);
    orbit.trivial_distance = tv.trivial_distance;
    orbit.unstable = tv.unstable;
    out.tests = {t(param_index()), tv.period_doubling, tv.neimark_sacker};
    // A step on which a multiplier moved far could have carried a test function across
    // zero and back: shorter (model.md §17.5, "whatever the step").
    if (!orbits_.empty() && o_.max_multiplier_jump > 0) {
      const double jump = multiplier_jump(nontrivial(last_.multipliers, last_trivial_), nontrivial(orbit.multipliers, tv.trivial));
      if (jump > o_.max_multiplier_jump) {
        out.retry = true;
        out.reason = "a Floquet multiplier moved farther than max_multiplier_jump in one step";
      }
    }
    if (!sampled) {
      out.retry = true;  // (taken anyway below the retry floor: the CSV then skips the row, the note says so)
      out.reason = "the orbit could not be sampled for its amplitude (the integrator failed)";
    }
    orbit.state0.resize(kDim);
    for (int i = 0; i < kDim; ++i) orbit.state0[std::size_t(i)] = point(u, 0)(i) * ctx_.scale(i);
    for (int j = 0; j < m_; ++j) {
      std::vector<double> row{mesh_.node(j)};
      for (int i = 0; i < kDim; ++i) row.push_back(point(u, j)(i) * ctx_.scale(i));
      orbit.profile.push_back(std::move(row));
    }
    pending_ = orbit;
    pending_trivial_ = tv.trivial;
    pending_tests_ = out.tests;
    pending_pair_ = tv.complex_pair_near_circle;
    return out;
  }

  // The multipliers without the trivial one (the step's jump check, model.md §17.6: near a
  // homoclinic end the trivial one is determined only to the flow speed's accuracy there).
  static std::vector<std::complex<double>> nontrivial(std::vector<std::complex<double>> m, std::size_t trivial) {
    if (trivial < m.size()) m.erase(m.begin() + long(trivial));
    return m;
  }

  // The orbit's multipliers from its transition matrices (model.md §17.4), `trivial` the flow
  // direction's index: the product's eigenvalues, the trivial one the closest to 1. Where that
  // one is farther than 1e-3 from 1 (a strongly unstable orbit near a homoclinic end: its
  // eigenvector nearly the largest multiplier's, its value lost to the factors' errors times
  // e^{ln |mu_max|}), the product deflated along the flow direction f(y_j) instead: the other
  // multipliers then keep the factors' accuracy (perturbed by the flow vectors' mismatch at the
  // points, |J r| / |f| for a residual r, which is why it is not used everywhere: on small orbits
  // near a Hopf point that is 1e-6 where the plain product is right to 1e-9). On the stiff route
  // the plain product always (its fast factors are R(h lambda)^N, §17.13).
  ProductEigenvalues multipliers(const Evaluated& e, const Vec& u, std::size_t& trivial) const {
    ProductEigenvalues plain = product_eigenvalues(e.transitions);
    trivial = cycle_test_values(plain.values, plain.log_moduli).trivial;
    if (radau_ || !plain.status.ok() || std::abs(plain.values[trivial] - 1.0) <= 1e-3) return plain;
    std::vector<Eigen::VectorXd> flow(static_cast<std::size_t>(m_));
    ctx_.variational = false;
    set(ctx_.p, ctx_.ref, parameter(u));
    for (int j = 0; j < m_; ++j) {
      const Eigen::Matrix<double, kDim, 1> y = point(u, j);
      Eigen::VectorXd f(kDim);
      flow_rhs(0, y.data(), f.data(), &ctx_);
      flow[std::size_t(j)] = f;
    }
    DeflatedProductEigenvalues d = deflated_product_eigenvalues(e.transitions, flow);
    if (!d.eigen.status.ok()) return plain;
    trivial = d.trivial;
    return std::move(d.eigen);
  }

  void locate(unsigned changed, const arclength::Segment<Vec>& seg) {
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
  double test_value(unsigned k, const Vec& u, const Vec& previous) const {
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
  bool on_branch(const Vec& from, const Vec& d, double sigma, Vec& u) const {
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
  bool root_on_branch(unsigned k, const arclength::Segment<Vec>& seg, CycleSpecial& out) {
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
    struct Context {
      CycleProblem* self;
      unsigned k;
      const Vec* from;
      Vec d;
      const Vec* previous;
      double length, at_from, at_to;  // the chord's length, the test's values at its ends
      bool failed = false;
      double last_sigma = -1, last_value = 0;  // the last value's sigma, orbit and value
      Vec last_u;
    } ctx{this, k, &seg.from, chord / length, &seg.from_tangent, length, last_tests_[k], pending_tests_[k], false, -1, 0, Vec()};
    gsl_function fn;
    fn.params = &ctx;
    fn.function = [](double sigma, void* raw) -> double {
      auto& c = *static_cast<Context*>(raw);
      // The ends are the two accepted orbits, their values known (GSL asks for them first).
      if (sigma == 0.0) return c.at_from;
      if (sigma == c.length) return c.at_to;
      Vec u;
      if (!c.self->on_branch(*c.from, c.d, sigma, u)) {
        c.failed = true;
        return 0.0;  // ends the search: the caller falls back to the interpolation
      }
      c.last_sigma = sigma;
      c.last_u = u;
      const double v = c.self->test_value(c.k, u, *c.previous);
      c.last_value = v;
      if (!std::isfinite(v)) c.failed = true;
      return std::isfinite(v) ? v : 0.0;
    };
    gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    bool ok = solver && gsl_root_fsolver_set(solver, &fn, 0.0, length) == GSL_SUCCESS;
    // Stops on a bracket below 1e-9 of the chord, on a value below 1e-8 of the ends' (the
    // zero within ~1e-8 of the chord where the test is linear), or on two roots 1e-8 of the
    // chord apart: the test functions' own noise (the LPC's tangent component at ~1e-7 of its
    // values at the ends on the viscous branch) stops Brent's bracket from shrinking further.
    const double value_tolerance = 1e-8 * std::max(std::abs(ctx.at_from), std::abs(ctx.at_to));
    double root = 0.5 * length;
    for (int it = 0; ok && !ctx.failed && it < 60; ++it) {
      const double before = root;
      if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS) ok = false;
      root = gsl_root_fsolver_root(solver);
      if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 1e-9 * length,
                                 0.0) == GSL_SUCCESS ||
          (root == ctx.last_sigma && std::abs(ctx.last_value) <= value_tolerance) ||
          (it > 0 && std::abs(root - before) <= 1e-8 * length))
        break;
    }
    if (solver) gsl_root_fsolver_free(solver);
    Vec u;
    if (ok && !ctx.failed && root == ctx.last_sigma) {
      u = ctx.last_u;  // Brent's root is usually its last value's orbit
    } else {
      ok = ok && !ctx.failed && on_branch(seg.from, ctx.d, root, u);
    }
    ok = ok && !ctx.failed && (u - seg.from).norm() <= 2 * length && (u - seg.to).norm() <= 2 * length;
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

  void commit(Vec& u, Vec& t, arclength::Stage) {
    // The accurate Newton matrix of the orbit just accepted (evaluate() integrated it), kept
    // for the next predicted orbit's extrapolation.
    if (Chord && cache_accurate_ && cache_.ok && cache_.u.size() == u.size() && cache_.u == u) {
      std::rotate(kept_.begin(), kept_.begin() + 1, kept_.end());
      kept_.back() = kept_at(u, cache_.jacobian);
      kept_count_ = std::min(kept_count_ + 1, int(kept_.size()));
    } else {
      kept_count_ = 0;
    }
    extrapolated_since_commit_ = false;
    orbits_.push_back(pending_);
    last_ = pending_;
    last_trivial_ = pending_trivial_;
    last_tests_ = pending_tests_;
    set_phase(u);
    if (Chord && !radau_ && o_.adapt_intervals) remesh(u, t);
  }

  // A new mesh for the orbit just accepted where its transition matrices' growth is spread
  // unevenly, or over too few or too many intervals (model.md §17.9): its points from state
  // flows of the accepted orbit, the Newton matrix there integrated (its multipliers are
  // those already found), the tangent from it. u and t change size; the Newton matrices kept
  // for the extrapolation start again with this one.
  void remesh(Vec& u, Vec& t) {
    if (!(cache_accurate_ && cache_.ok && cache_.u.size() == u.size() && cache_.u == u)) return;
    std::vector<double> growth(static_cast<std::size_t>(m_));
    for (int j = 0; j < m_; ++j) {
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(cache_.transitions[std::size_t(j)]);
      growth[std::size_t(j)] = std::log(std::max(svd.singularValues()(0), 1.0));
    }
    const std::vector<double> theta =
        detail::equidistributed_nodes(mesh_, growth, last_.log_moduli.empty() ? 0.0 : last_.log_moduli.front(),
                                      o_.interval_growth, o_.intervals, o_.max_intervals);
    if (theta.empty()) return;
    // The new points: the accepted orbit flowed from each old point to the new ones in its interval.
    const detail::CycleMesh mesh = detail::CycleMesh::nodes(theta);
    const int m = mesh.intervals();
    Vec v(kDim * m + 2);
    v(kDim * m) = u(period_index());
    v(kDim * m + 1) = u(param_index());
    ctx_.variational = false;
    set(ctx_.p, ctx_.ref, parameter(u));
    int i = 0;
    for (int j = 0; j < m_ && i < m; ++j) {
      Eigen::Matrix<double, kDim, 1> y = point(u, j);
      std::vector<double> targets;
      const int first = i;
      for (; i < m && mesh.node(i) < mesh_.node(j + 1); ++i)
        if (mesh.node(i) > mesh_.node(j)) targets.push_back((mesh.node(i) - mesh_.node(j)) * period(u));
      int k = first;
      if (k < m && !(mesh.node(k) > mesh_.node(j))) {  // a new point on the old one
        v.template segment<kDim>(kDim * k) = mesh.weight(k) * y;
        ++k;
      }
      if (targets.empty()) continue;
      std::string_view why;
      if (!state_.run(ctx_, y.data(), targets.back(), targets, [&](const double* x) {
            v.template segment<kDim>(kDim * k) = mesh.weight(k) * Eigen::Map<const Eigen::Matrix<double, kDim, 1>>(x);
            ++k;
          }, why))
        return;
    }
    // The tangent carried over approximately (linear between the old points), as the border
    // that orients the new one.
    Vec previous(kDim * m + 2);
    previous.template tail<2>() = t.template tail<2>();
    for (int k = 0, j = 0; k < m; ++k) {
      while (j + 1 < m_ && mesh_.node(j + 1) <= mesh.node(k)) ++j;
      const double lambda = (mesh.node(k) - mesh_.node(j)) / mesh_.fraction(j);
      previous.template segment<kDim>(kDim * k) =
          mesh.weight(k) * ((1 - lambda) * t.template segment<kDim>(kDim * j) / mesh_.weight(j) +
                            lambda * t.template segment<kDim>(kDim * ((j + 1) % m_)) / mesh_.weight(j + 1));
    }
    const detail::CycleMesh old_mesh = mesh_;
    const int old_m = m_;
    const Evaluated kept_cache = cache_, kept_plain = plain_;
    mesh_ = mesh;
    m_ = m;
    cache_.u.resize(0);
    plain_.u.resize(0);
    sampled_u_.resize(0);
    const Evaluated& e = residual_at(v);
    if (e.ok && e.residual.cwiseAbs().maxCoeff() <= 1e3 * o_.rtol) {
      const Evaluated& full = at(v);  // accurate: v is a converged orbit
      if (full.ok && cache_accurate_) {
        t = arclength::tangent(*this, full.jacobian, previous);
        u = v;
        kept_count_ = 1;
        kept_.back() = kept_at(v, full.jacobian);
        set_phase(u);
        ++remeshes_;
        return;
      }
    }
    mesh_ = old_mesh;  // the new points did not make an orbit at the noise level: the old mesh stays
    m_ = old_m;
    cache_ = kept_cache;
    plain_ = kept_plain;
  }

  // The chord corrector's Newton matrix at a predicted orbit u from the last accepted
  // orbits' accurate ones (model.md §17.7): the Lagrange quadratic through the last three
  // (linear through two), in the distance along the branch, u projected on the last secant.
  // Its error, O(ds^3), sets only the chord's contraction rate, not the orbit. The first
  // matrix since the last accepted orbit only: a correction that failed with it (or a step
  // retried) integrates the next one.
  bool can_extrapolate() const {
    return Chord && o_.extrapolate_newton_matrix && !radau_ && kept_count_ >= 2 && !extrapolated_since_commit_;
  }
  const Evaluated& extrapolated(const Vec& u) const {
    extrapolated_since_commit_ = true;
    ++extrapolations_;
    const Kept &a = kept_[0], &b = kept_[1], &c = kept_[2];  // a only with three kept
    // Positions along the branch: the chord lengths between kept orbits, u projected on the last.
    const Vec secant = c.u - b.u;
    const double s0 = 0, s1 = kept_count_ == 3 ? (b.u - a.u).norm() : 0.0, s2 = s1 + secant.norm();
    const double x = s2 + (secant.norm() > 0 ? (u - c.u).dot(secant) / secant.norm() : 0.0);
    Evaluated& e = extrapolation_;
    if (kept_count_ == 3 && s1 > 0 && s2 > s1) {  // quadratic (Lagrange)
      const double w0 = (x - s1) * (x - s2) / ((s0 - s1) * (s0 - s2));
      const double w1 = (x - s0) * (x - s2) / ((s1 - s0) * (s1 - s2));
      const double w2 = (x - s0) * (x - s1) / ((s2 - s0) * (s2 - s1));
      const Jacobian ja = shifted(a, u), jb = shifted(b, u), jc = shifted(c, u);
      e.jacobian = Jacobian::combination(w0, ja, w1, jb, w2, &jc);
    } else {
      const double theta = s2 > s1 ? (x - s2) / (s2 - s1) : 0.0;
      e.jacobian = Jacobian::combination(1 + theta, shifted(c, u), -theta, shifted(b, u));
    }
    return finish_estimate(e, u);
  }
  // An estimated Newton matrix at u completed: the phase row exact (the current reference
  // orbit, set_phase at the last commit), the transition matrices from its blocks.
  const Evaluated& finish_estimate(Evaluated& e, const Vec& u) const {
    const int n = size();
    e.u = u;
    e.ok = true;
    e.why = {};
    e.residual = Vec::Zero(n - 1);  // unused: the chord corrector's residuals are state passes
    e.jacobian.phase = f_ref_ / mesh_.weight(0);
    e.transitions.resize(std::size_t(m_));
    for (int j = 0; j < m_; ++j) e.transitions[std::size_t(j)] = e.jacobian.diag[std::size_t(j)] * mesh_.weight(j);
    return e;
  }
  // While a special point is located within a step: the Newton matrix at u linear between
  // the step's two accurate ones (u projected on the chord), O(ds^2) (model.md §17.5).
  const Evaluated& interpolated(const Vec& u) const {
    const Kept &a = segment_ends_->first, &b = segment_ends_->second;
    const Vec chord = b.u - a.u;
    const double length2 = chord.squaredNorm();
    const double theta = length2 > 0 ? (u - a.u).dot(chord) / length2 : 0.0;
    Evaluated& e = extrapolation_;
    e.jacobian = Jacobian::combination(1 - theta, a.jacobian, theta, b.jacobian);
    return finish_estimate(e, u);
  }

  // The unknowns of the orbit through x(0) = state0 (SI) with period T at parameter p:
  // its M points from a state-only integration of one period.
  bool unknowns_from(const std::vector<double>& state0, double T, double p, Vec& u) const {
    if (state0.size() != std::size_t(kDim) || !(T > 0)) return false;
    u.resize(size());
    u(period_index()) = T / period_h_;
    u(param_index()) = (p - from_) / (to_ - from_);
    ctx_.variational = false;
    ctx_.radau_step = T / m_ / steps_;
    set(ctx_.p, ctx_.ref, p);
    double y[kDim];
    for (int i = 0; i < kDim; ++i) y[i] = state0[std::size_t(i)] / ctx_.scale(i);
    std::vector<double> targets;
    for (int j = 1; j <= m_; ++j) targets.push_back(mesh_.is_uniform() ? T * j / m_ : T * mesh_.node(j));
    int j = 0;
    for (int i = 0; i < kDim; ++i) u(i) = mesh_.weight(0) * y[i];
    std::string_view why;
    return state_.run(ctx_, y, T, targets, [&](const double* s) {
      if (++j < m_)
        for (int i = 0; i < kDim; ++i) u(kDim * j + i) = mesh_.weight(j) * s[i];
    }, why);
  }

  std::vector<CycleOrbit> orbits_;
  std::vector<CycleSpecial> specials_;
  long flows() const { return flows_; }
  long state_flows() const { return state_flows_; }
  long state_steps() const { return state_.steps(); }
  long newton_steps() const { return newton_.steps(); }
  long floquet_steps() const { return floquet_.steps(); }
  long extrapolations() const { return extrapolations_; }
  long remeshes() const { return remeshes_; }
  const FlowContext& context() const { return ctx_; }

 private:
  // The stops of interval j's flow (`targets`, from its start, the last its end) and which of
  // them are samples: the samples are k M uniform times over the period (k =
  // samples_per_interval; the amplitude's cyclic_max wants them uniform), those in (theta_j,
  // theta_{j+1}]; the interval's end is a stop, and a sample only where it is one of those times.
  void sample_plan(const Vec& u, int j, std::vector<double>& targets, std::vector<char>& is_sample) const {
    const int k = o_.samples_per_interval;
    const double h = interval_length(u, j);
    targets.clear();
    is_sample.clear();
    if (mesh_.is_uniform()) {  // k per interval, h i / k, the last exactly h
      for (int i = 1; i < k; ++i) targets.push_back(h * i / k);
      targets.push_back(h);
      is_sample.assign(targets.size(), 1);
      return;
    }
    const long total = long(k) * m_;
    const double T = period(u);
    const long first = long(std::floor(mesh_.node(j) * double(total) + 1e-9)) + 1;
    const long last = j + 1 == m_ ? total : long(std::floor(mesh_.node(j + 1) * double(total) + 1e-9));
    for (long s = first; s <= last; ++s) {
      targets.push_back(std::min(T * double(s) / double(total) - T * mesh_.node(j), h));
      is_sample.push_back(1);
    }
    if (targets.empty() || targets.back() < h) {
      targets.push_back(h);
      is_sample.push_back(0);
    } else {
      targets.back() = h;
    }
  }
  void clear_samples() const {
    sampled_u_.resize(0);
    qabs_.clear(), b1_.clear(), b2_.clear(), samples_.clear();
    qabs_rate_.clear(), b1_rate_.clear(), b2_rate_.clear();
  }
  void keep_sample(const double* s) const {
    const double q1 = s[0] * ctx_.scale(0), q2 = s[1] * ctx_.scale(1), q = std::hypot(q1, q2);
    qabs_.push_back(q);
    // d|q|/dt = q . q' / |q| and beta_i' from the state (the quintic peak of cyclic_max).
    qabs_rate_.push_back(q > 0 ? (q1 * s[4] * ctx_.scale(4) + q2 * s[5] * ctx_.scale(5)) / q : 0.0);
    b1_rate_.push_back(s[6] * ctx_.scale(6));
    b2_rate_.push_back(s[7] * ctx_.scale(7));
    if (radau_) samples_.push_back(ctx_.unscale(s));
    b1_.push_back(s[2]);
    b2_.push_back(s[3]);
  }
  bool sampled_for(const Vec& u) const { return sampled_u_.size() == u.size() && sampled_u_ == u; }

  // Samples the orbit uniformly (samples_per_interval per interval): max |q| and the
  // ball angles' extremes, each refined by a parabola through its neighbours. The samples
  // of the corrector's last residual pass are reused when they are u's.
  bool sample(const Vec& u, CycleOrbit& orbit) {
    const int k = o_.samples_per_interval;
    if (!sampled_for(u)) {
      ctx_.variational = false;
      ctx_.radau_step = period(u) / m_ / steps_;
      clear_samples();
      set(ctx_.p, ctx_.ref, parameter(u));
      std::vector<double> targets;
      std::vector<char> is_sample;
      for (int j = 0; j < m_; ++j) {
        sample_plan(u, j, targets, is_sample);
        double y[kDim];
        const Eigen::Matrix<double, kDim, 1> yj = point(u, j);
        for (int i = 0; i < kDim; ++i) y[i] = yj(i);
        std::size_t at_target = 0;
        std::string_view why;
        state_.run(ctx_, y, interval_length(u, j), targets, [&](const double* s) {
          if (is_sample[at_target++]) keep_sample(s);
        }, why);
      }
    }
    if (qabs_.size() != std::size_t(m_ * k)) return false;
    std::vector<double> b1 = b1_, b2 = b2_, r1 = b1_rate_, r2 = b2_rate_;
    const double dt = period(u) / (m_ * k);
    orbit.amplitude = cyclic_max(qabs_, qabs_rate_, dt);
    orbit.ball_max = {cyclic_max(b1, r1, dt), cyclic_max(b2, r2, dt)};
    for (auto* v : {&b1, &b2, &r1, &r2})
      for (double& x : *v) x = -x;
    orbit.ball_min = {-cyclic_max(b1, r1, dt), -cyclic_max(b2, r2, dt)};
    return true;
  }

  CycleOptions o_;
  double from_, to_, period_h_;
  int m_;
  detail::CycleMesh mesh_;
  mutable FlowContext ctx_;
  mutable Integrator newton_, floquet_;
  mutable Integrator state_;
  mutable Evaluated cache_, plain_;
  mutable bool cache_accurate_ = false;
  mutable long flows_ = 0, state_flows_ = 0;
  Eigen::Matrix<double, kDim, 1> y_ref_ = Eigen::Matrix<double, kDim, 1>::Zero();
  Eigen::Matrix<double, kDim, 1> f_ref_ = Eigen::Matrix<double, kDim, 1>::Zero();
  CycleOrbit pending_, last_;
  std::size_t pending_trivial_ = 0, last_trivial_ = 0;  // the trivial multiplier's index
  std::array<double, 3> pending_tests_{}, last_tests_{};
  bool pending_pair_ = false;
  bool radau_ = false;
  int steps_ = 1;
  mutable std::vector<Eigen::VectorXd> samples_;  // the stiff route: the SI states at the samples
  mutable std::vector<double> qabs_, b1_, b2_;     // |q| and the ball angles at the samples
  mutable std::vector<double> qabs_rate_, b1_rate_, b2_rate_;  // their rates (d/dt)
  mutable Vec sampled_u_;                          // the orbit they belong to (empty: none)
  // The last two accepted orbits' accurate Newton matrices (extrapolated()).
  struct Kept {
    Vec u;
    Jacobian jacobian;
    std::vector<double> lengths;          // its intervals' lengths h_j [s]
    std::vector<Generator> generators;    // at its intervals' ends (cycle_period_shift.hpp)
  };
  // An accepted orbit's Newton matrix with what moves it to another period.
  Kept kept_at(const Vec& u, const Jacobian& J) const {
    Kept k{u, J, {}, {}};
    ctx_.variational = false;
    set(ctx_.p, ctx_.ref, parameter(u));
    for (int j = 0; j < m_; ++j) {
      k.lengths.push_back(interval_length(u, j));
      k.generators.push_back(period_shift_generator(ctx_, point(u, (j + 1) % m_)));
    }
    return k;
  }
  // Kept k's Newton matrix at the intervals' lengths of u.
  Jacobian shifted(const Kept& k, const Vec& u) const {
    std::vector<double> dh(static_cast<std::size_t>(m_));
    for (int j = 0; j < m_; ++j)
      dh[std::size_t(j)] = o_.shift_newton_matrix ? interval_length(u, j) - k.lengths[std::size_t(j)] : 0.0;
    return shift_periods(k.jacobian, k.generators, dh);
  }
  std::array<Kept, 3> kept_;
  int kept_count_ = 0;
  mutable Evaluated extrapolation_;
  std::optional<std::pair<Kept, Kept>> segment_ends_;  // while locating within a step (root_on_branch)
  mutable bool extrapolated_since_commit_ = false;
  mutable long extrapolations_ = 0;
  long remeshes_ = 0;
};

static_assert(arclength::Problem<CycleProblem<true>>);
static_assert(arclength::Problem<CycleProblem<false>>);

}  // namespace abu::cycle_problem
