// The Newton matrices a cycle branch keeps (docs/model.md §17.5, §17.7, §17.9): the accepted
// orbits' accurate ones, extrapolated to a predicted orbit or interpolated within a step for
// the chord corrector, and the new mesh of an accepted orbit, which starts them again. Members
// of CycleProblem (cycle_problem.hpp); internal to src/dynamics.
#pragma once

#include "cycle_problem.hpp"

namespace abu::cycle_problem {

// A new mesh for the orbit just accepted where its transition matrices' growth is spread
// unevenly, or over too few or too many intervals (model.md §17.9): its points from state
// flows of the accepted orbit, the Newton matrix there integrated (its multipliers are
// those already found), the tangent from it. u and t change size; the Newton matrices kept
// for the extrapolation start again with this one.
template <bool Chord>
inline void CycleProblem<Chord>::remesh(Vec& u, Vec& t) {
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
template <bool Chord>
inline bool CycleProblem<Chord>::can_extrapolate() const {
  return Chord && o_.extrapolate_newton_matrix && !radau_ && kept_count_ >= 2 && !extrapolated_since_commit_;
}

template <bool Chord>
inline const Evaluated& CycleProblem<Chord>::extrapolated(const Vec& u) const {
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
template <bool Chord>
inline const Evaluated& CycleProblem<Chord>::finish_estimate(Evaluated& e, const Vec& u) const {
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
template <bool Chord>
inline const Evaluated& CycleProblem<Chord>::interpolated(const Vec& u) const {
  const Kept &a = segment_ends_->first, &b = segment_ends_->second;
  const Vec chord = b.u - a.u;
  const double length2 = chord.squaredNorm();
  const double theta = length2 > 0 ? (u - a.u).dot(chord) / length2 : 0.0;
  Evaluated& e = extrapolation_;
  e.jacobian = Jacobian::combination(1 - theta, a.jacobian, theta, b.jacobian);
  return finish_estimate(e, u);
}

// An accepted orbit's Newton matrix with what moves it to another period.
template <bool Chord>
inline auto CycleProblem<Chord>::kept_at(const Vec& u, const Jacobian& J) const -> Kept {
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
template <bool Chord>
inline auto CycleProblem<Chord>::shifted(const Kept& k, const Vec& u) const -> Jacobian {
  std::vector<double> dh(static_cast<std::size_t>(m_));
  for (int j = 0; j < m_; ++j)
    dh[std::size_t(j)] = o_.shift_newton_matrix ? interval_length(u, j) - k.lengths[std::size_t(j)] : 0.0;
  return shift_periods(k.jacobian, k.generators, dh);
}
}  // namespace abu::cycle_problem
