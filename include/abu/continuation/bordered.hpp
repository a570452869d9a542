// The linear algebra of pseudo-arclength continuation, generic over the problem: Newton
// on the bordered system [F(u); d . (u - u_pred)] = 0 (the corrector), the unit tangent
// (the null vector of F_u) and det [F_u; t^T] (which changes sign at a branch point).
//
// A System supplies its unknowns' type Vec (n + 1 of them: the state and the
// parameter), the n x (n + 1) Jacobian type, F and F_u at a point, the size of the part
// of F that has to vanish to rounding, and its Newton tolerances. The types are Eigen
// fixed-size, or bounded-dynamic (Matrix<long double, Dynamic, 1, 0, 31, 1>) for
// problems whose size is known only at run time: every matrix here then lives on the
// stack (no heap allocation per step).
//
//   struct Circle { using Vec = Eigen::Vector2d ... };   // see tests/test_arclength.cpp
//   auto c = abu::arclength::correct(system, u + ds * t, t);
//   if (c.converged()) t = abu::arclength::tangent(c.jacobian, t);
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <concepts>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>

#include "abu/core/small_lu.hpp"
#include "abu/core/status.hpp"

namespace abu::arclength {

/// How a solve ended: converged; not converged (out of iterations, stalled above the
/// tolerance, residual too large); or a numerical issue (a non-finite or diverging step).
/// The library's one outcome type (core/status.hpp); its to_string is abu::to_string.
using Status = abu::Outcome;
using abu::to_string;

/// Newton's stopping rules. A run stops at a step of max-norm <= step_tolerance, or, from
/// the third step on, at one that did not halve (the rounding level reached): converged
/// if that step is <= stall_tolerance and the system's residual_size <= residual_tolerance.
struct NewtonSettings {
  int max_iterations = 12;
  long double step_tolerance = 1e-15L;
  long double stall_tolerance = 1e-12L;
  long double residual_tolerance = 1e-15L;
  long double divergence = 1;  ///< a longer step: diverging (the unknowns are O(1) scaled)
  /// The chord corrector converges linearly, so after a step of size s that followed one of
  /// size s' the remaining error is about s^2 / s'. With this > 0 it also stops when that
  /// prediction is <= predicted_tolerance (saving the step that would only confirm it); the
  /// residual_size check still decides convergence. 0: off.
  long double predicted_tolerance = 0;
};

template <class S>
concept System = requires(const S& s, const typename S::Vec& u) {
  typename S::Vec;       // n + 1 unknowns, scaled to O(1)
  typename S::Jacobian;  // n x (n + 1)
  { s.residual(u) };     // F(u), n entries
  { s.jacobian(u) } -> std::convertible_to<typename S::Jacobian>;
  { s.residual_size(u) } -> std::convertible_to<typename S::Vec::Scalar>;  // what must reach rounding
  { s.newton() } -> std::convertible_to<NewtonSettings>;
};

/// The (n + 1) x (n + 1) matrix type of the bordered systems for unknowns `Vec`.
template <class Vec>
using Square = Eigen::Matrix<typename Vec::Scalar, Vec::RowsAtCompileTime, Vec::RowsAtCompileTime, 0,
                             Vec::MaxRowsAtCompileTime, Vec::MaxRowsAtCompileTime>;

/// The LU factorization of a bordered matrix: for fixed sizes in double SmallLu (the same
/// bits as Eigen's PartialPivLU, 25-30 % faster: core/small_lu.hpp), else PartialPivLU.
/// (In long double, x87 code, Eigen's kernel is the faster one: 200 against 340 ns for
/// 5 x 5, measured; both give the same bits.)
template <class M>
auto factor(const M& B) {
  if constexpr (std::is_same_v<typename M::Scalar, double> && M::RowsAtCompileTime != Eigen::Dynamic &&
                M::RowsAtCompileTime <= 16) {
    return SmallLu<M>(B);
  } else {
    return B.partialPivLu();
  }
}

/// [J; d^T].
template <class Vec, class Jacobian>
Square<Vec> bordered(const Jacobian& J, const Vec& d) {
  const Eigen::Index n = d.size() - 1;
  Square<Vec> M(n + 1, n + 1);
  if constexpr (Vec::RowsAtCompileTime != Eigen::Dynamic) {
    M.template topRows<Vec::RowsAtCompileTime - 1>() = J;
  } else {
    M.topRows(n) = J;
  }
  M.row(n) = d.transpose();
  return M;
}

/// The factorization of [J; d^T] for the system s: its own where it has one
/// (`s.factor_bordered(J, d)`, an object with solve(Vec): a structured solver for a sparse
/// F_u, e.g. the block-cyclic Newton matrix of multiple shooting), else the dense LU.
template <class S, class Jacobian, class Vec>
auto factor_bordered(const S& s, const Jacobian& J, const Vec& d) {
  if constexpr (requires { s.factor_bordered(J, d); }) {
    return s.factor_bordered(J, d);
  } else {
    return factor(bordered(J, d));
  }
}

/// The result of a corrector run.
template <class S>
struct Correction {
  typename S::Vec u;
  /// F_u at the last iterate the step was computed from: within one (rounding-level)
  /// Newton step of u, so reusable for the tangent where F_u is analytic.
  typename S::Jacobian jacobian;
  Status status = Status::not_converged;
  std::string_view reason;  ///< why it did not converge (empty if it did)
  int iterations = 0;       ///< steps taken
  bool converged() const { return status == Status::converged; }
};

/// Newton on [F(u); d . (u - u_pred)] = 0 from u_pred: the pseudo-arclength corrector with
/// d the tangent, or with d = e_k the solution at a fixed value of u_k.
///
/// A system that declares `static constexpr bool chord_corrector = true` gets the chord
/// method: F_u of the first iterate is kept for every step (linear convergence at a rate of
/// order |F_u(u_pred) - F_u(u)| / |F_u|, i.e. of the step ds), for systems whose F_u costs
/// many times F (the periodic orbits' variational equations). The returned `jacobian` is
/// then that of u_pred: such a system wants `tangent_at_solution` too.
template <System S>
Correction<S> correct(const S& s, const typename S::Vec& u_pred, const typename S::Vec& d) {
  using Vec = typename S::Vec;
  using Scalar = typename Vec::Scalar;
  const NewtonSettings rules = s.newton();
  Correction<S> c;
  c.u = u_pred;
  c.jacobian = s.jacobian(u_pred);
  Scalar last = std::numeric_limits<Scalar>::infinity();
  constexpr bool chord = requires { requires S::chord_corrector; };
  using Factors = decltype(factor_bordered(s, c.jacobian, d));
  std::optional<Factors> kept;  // the chord method's one factorization
  if constexpr (chord) kept.emplace(factor_bordered(s, c.jacobian, d));
  for (int it = 0; it < rules.max_iterations; ++it) {
    if constexpr (!chord) {
      if (it > 0) c.jacobian = s.jacobian(c.u);
    }
    Vec r(u_pred.size());
    r << s.residual(c.u), d.dot(c.u - u_pred);
    Vec step;
    if constexpr (chord) {
      step = kept->solve(Vec(-r));
    } else {
      step = factor_bordered(s, c.jacobian, d).solve(Vec(-r));
    }
    if (!step.allFinite()) {
      c.status = Status::numerical_issue;
      c.reason = "a Newton step was not finite (singular bordered system)";
      return c;
    }
    c.u += step;
    c.iterations = it + 1;
    const Scalar size = step.cwiseAbs().maxCoeff();
    const bool stalled = it >= 2 && size > last / 2;  // no longer converging quadratically
    const bool predicted = chord && rules.predicted_tolerance > 0 && it >= 1 && size < last / 2 &&
                           size * (size / last) <= rules.predicted_tolerance;
    if (size <= rules.step_tolerance || stalled || predicted) {
      if (!predicted && size > rules.stall_tolerance) {
        c.reason = "Newton stopped converging above the rounding level";
      } else if (s.residual_size(c.u) > rules.residual_tolerance) {
        c.reason = "the steps converged but the residual did not reach the rounding level";
      } else {
        c.status = Status::converged;
      }
      return c;
    }
    if (size > rules.divergence) {
      c.status = Status::numerical_issue;
      c.reason = "Newton diverged (a step longer than the scaled unknowns)";
      return c;
    }
    last = size;
  }
  c.reason = "Newton ran out of iterations";
  return c;
}

/// The unit tangent at a point where F_u = J: the null vector of J, from the bordered
/// system with `previous` as the border (well-conditioned while the curve turns by less
/// than 90 degrees per step), oriented along `previous`.
template <class Vec, class Jacobian>
Vec tangent(const Jacobian& J, const Vec& previous) {
  Vec e = Vec::Zero(previous.size());
  e(previous.size() - 1) = 1;
  Vec t = factor(bordered(J, previous)).solve(e);
  t.normalize();
  if (t.dot(previous) < 0) t = -t;
  return t;
}

/// The same for the system s: its own bordered solver where it has one (factor_bordered).
template <class S, class Vec, class Jacobian>
Vec tangent(const S& s, const Jacobian& J, const Vec& previous) {
  Vec e = Vec::Zero(previous.size());
  e(previous.size() - 1) = 1;
  Vec t = factor_bordered(s, J, previous).solve(e);
  t.normalize();
  if (t.dot(previous) < 0) t = -t;
  return t;
}

/// det [J; t^T]: of one sign along a regular branch, through folds included; it changes
/// sign where two branches cross (a branch point).
template <class Vec, class Jacobian>
typename Vec::Scalar bordered_determinant(const Jacobian& J, const Vec& t) {
  return factor(bordered(J, t)).determinant();
}

}  // namespace abu::arclength
