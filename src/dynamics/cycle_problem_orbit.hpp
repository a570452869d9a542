// The orbit at a solution of the cycle branch's shooting problem (docs/model.md §17.4-§17.6,
// §17.9, §17.13): its Floquet multipliers from the intervals' transition matrices, its
// amplitude and ball ranges from uniform samples, the test functions of LPC, PD and NS, and
// the unknowns of an orbit given by x(0) and T. Members of CycleProblem (cycle_problem.hpp);
// internal to src/dynamics.
#pragma once

#include "cycle_problem.hpp"

namespace abu::cycle_problem {

// The orbit at u: Floquet multipliers, amplitude, ball ranges; the test functions.
template <bool Chord>
inline arclength::Evaluation<double, 3> CycleProblem<Chord>::evaluate(const Vec& u, const Vec& t, const Jacobian&,
                                                                      arclength::Stage) {
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
  for (int j = 0; j < (o_.keep_profiles ? m_ : 0); ++j) {
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
template <bool Chord>
inline std::vector<std::complex<double>> CycleProblem<Chord>::nontrivial(std::vector<std::complex<double>> m,
                                                                        std::size_t trivial) {
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
template <bool Chord>
inline ProductEigenvalues CycleProblem<Chord>::multipliers(const Evaluated& e, const Vec& u,
                                                           std::size_t& trivial) const {
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

// The unknowns of the orbit through x(0) = state0 (SI) with period T at parameter p:
// its M points from a state-only integration of one period.
template <bool Chord>
inline bool CycleProblem<Chord>::unknowns_from(const std::vector<double>& state0, double T, double p, Vec& u) const {
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

// The stops of interval j's flow (`targets`, from its start, the last its end) and which of
// them are samples: the samples are k M uniform times over the period (k =
// samples_per_interval; the amplitude's cyclic_max wants them uniform), those in (theta_j,
// theta_{j+1}]; the interval's end is a stop, and a sample only where it is one of those times.
template <bool Chord>
inline void CycleProblem<Chord>::sample_plan(const Vec& u, int j, std::vector<double>& targets,
                                             std::vector<char>& is_sample) const {
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

template <bool Chord>
inline void CycleProblem<Chord>::clear_samples() const {
  sampled_u_.resize(0);
  qabs_.clear(), b1_.clear(), b2_.clear(), samples_.clear();
  qabs_rate_.clear(), b1_rate_.clear(), b2_rate_.clear();
}

template <bool Chord>
inline void CycleProblem<Chord>::keep_sample(const double* s) const {
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

// Samples the orbit uniformly (samples_per_interval per interval): max |q| and the
// ball angles' extremes, each refined by a parabola through its neighbours. The samples
// of the corrector's last residual pass are reused when they are u's.
template <bool Chord>
inline bool CycleProblem<Chord>::sample(const Vec& u, CycleOrbit& orbit) {
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
}  // namespace abu::cycle_problem
