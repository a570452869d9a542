// The equations of a fold curve (N = 6 unknowns y = (z, p2)) or a Hopf curve (N = 7:
// y = (z, p2, w / w0)) in two parameters, as a System of the pseudo-arclength engine
// (bordered.hpp): F = 0 plus the fold (one) or Hopf (two) condition of bifurcation.hpp,
// z the scaled unknowns of static_equations.hpp and the second parameter scaled like the
// first (0 at its start value, 1 at its end value). The residuals are analytic, the
// Jacobian central differences in long double.
#pragma once

#include <complex>
#include <optional>

#include <Eigen/Core>

#include "abu/continuation/bifurcation.hpp"
#include "abu/continuation/bordered.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/model/static_equations.hpp"

namespace abu {

template <int N>
class CurveSystem {
 public:
  using ld = long double;
  using Vec = Eigen::Matrix<ld, N, 1>;
  using Res = Eigen::Matrix<ld, N - 1, 1>;
  using Jacobian = Eigen::Matrix<ld, N - 1, N>;
  using Vec5 = StaticEquations::Vec5;
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
  const Params& base() const { return base_; }

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
  Jacobian jacobian(const Vec& y) const {
    constexpr ld h = 1e-7L;
    Jacobian D;
    for (int k = 0; k < N; ++k) {
      Vec yp = y, ym = y;
      yp(k) += h;
      ym(k) -= h;
      D.col(k) = (residual(yp) - residual(ym)) / (2 * h);
    }
    return D;
  }

  // The equilibrium rows F are scaled to O(1) and have to reach rounding level; the
  // condition's rows (whose size depends on the borders) are held to Newton's step
  // tolerance only.
  ld residual_size(const Vec& y) const { return at(y).residual(z(y)).cwiseAbs().maxCoeff(); }
  static arclength::NewtonSettings newton() { return {12, 1e-14L, 1e-12L, 1e-14L, 1}; }
  // The finite-difference Jacobian's noise (~1e-12) exceeds the last Newton step: the
  // tangent is taken from F_u at the corrected point itself.
  static constexpr bool tangent_at_solution = true;

 private:
  Params base_;
  const ContinuationRun& run_;
  ParamRef param2_;
  ld from2_, span2_, omega0_;
  std::optional<FoldCondition> fold_;
  std::optional<HopfCondition> hopf_;
};

}  // namespace abu
