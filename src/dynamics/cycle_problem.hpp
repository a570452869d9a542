// The shooting problem of one cycle branch for the arclength engine (docs/model.md §17.2-§17.8,
// §17.11): the unknowns (M points, the period, the parameter), the residuals from state-only
// flows, the Newton matrix (integrated, or extrapolated along the branch, §17.7), the orbit's
// multipliers, amplitude and test functions, and the location of LPC, PD and NS on the branch
// (§17.5). Internal to src/dynamics (periodic_orbits.cpp). This header holds the class, its
// unknowns and its evaluations (residuals, Newton matrix); cycle_problem_orbit.hpp (the orbit
// at a solution), cycle_problem_specials.hpp (special points) and cycle_problem_matrices.hpp
// (the kept Newton matrices, the remeshing) define the other members.
#pragma once

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

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

  // The orbit at u: multipliers, amplitude, test functions (cycle_problem_orbit.hpp).
  arclength::Evaluation<double, 3> evaluate(const Vec& u, const Vec& t, const Jacobian&, arclength::Stage);
  static std::vector<std::complex<double>> nontrivial(std::vector<std::complex<double>> m, std::size_t trivial);
  ProductEigenvalues multipliers(const Evaluated& e, const Vec& u, std::size_t& trivial) const;

  // LPC, PD and NS located on the branch (cycle_problem_specials.hpp).
  void locate(unsigned changed, const arclength::Segment<Vec>& seg);
  double test_value(unsigned k, const Vec& u, const Vec& previous) const;
  bool on_branch(const Vec& from, const Vec& d, double sigma, Vec& u) const;
  bool root_on_branch(unsigned k, const arclength::Segment<Vec>& seg, CycleSpecial& out);

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

  // The Newton matrices kept along the branch: a new mesh that restarts them, their
  // extrapolation and interpolation (cycle_problem_matrices.hpp).
  void remesh(Vec& u, Vec& t);
  bool can_extrapolate() const;
  const Evaluated& extrapolated(const Vec& u) const;
  const Evaluated& finish_estimate(Evaluated& e, const Vec& u) const;
  const Evaluated& interpolated(const Vec& u) const;

  // The unknowns of a given orbit (cycle_problem_orbit.hpp).
  bool unknowns_from(const std::vector<double>& state0, double T, double p, Vec& u) const;

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
  // The orbit's samples: |q| and the ball angles (cycle_problem_orbit.hpp).
  void sample_plan(const Vec& u, int j, std::vector<double>& targets, std::vector<char>& is_sample) const;
  void clear_samples() const;
  void keep_sample(const double* s) const;
  bool sampled_for(const Vec& u) const { return sampled_u_.size() == u.size() && sampled_u_ == u; }
  bool sample(const Vec& u, CycleOrbit& orbit);

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
  Kept kept_at(const Vec& u, const Jacobian& J) const;     // cycle_problem_matrices.hpp
  Jacobian shifted(const Kept& k, const Vec& u) const;
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

// The members defined apart, one idea each (each of these includes this header first).
#include "cycle_problem_matrices.hpp"
#include "cycle_problem_orbit.hpp"
#include "cycle_problem_specials.hpp"
