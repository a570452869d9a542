// The two kinds of n-ball equilibrium branch as Systems of the pseudo-arclength engine
// (bordered.hpp): aligned (all n + 2 static equations in the n + 3 scaled unknowns) and
// balanced samples with beta_3..beta_n held (model.md §13.7). Shared by the branches
// (branches_n.cpp) and the two-parameter curves (boundaries_n.cpp). Internal header.
#pragma once

#include <Eigen/Core>

#include "abu/continuation/bordered.hpp"
#include "abu/model/static_equations.hpp"

namespace abu {
namespace n_balls {

using ld = long double;
using Unknowns = StaticEquationsN::Unknowns;

// An aligned branch: all n + 2 equations in all n + 3 unknowns.
struct AlignedSystem {
  /// The branch in the full scaled unknowns z (static_equations.hpp).
  using Vec = Unknowns;
  using Jacobian = StaticEquationsN::JacobianMatrix;
  static constexpr bool balanced = false;
  const StaticEquationsN& eq;

  Unknowns full(const Vec& u) const { return u; }
  Vec reduced(const Unknowns& z) const { return z; }
  StaticEquationsN::Forces residual(const Vec& u) const { return eq.residual(u); }
  Jacobian jacobian(const Vec& u) const { return eq.jacobian(u); }
  ld residual_size(const Vec& u) const { return eq.residual(u).cwiseAbs().maxCoeff(); }
  static arclength::NewtonSettings newton() { return {}; }
  AlignedSystem on(const StaticEquationsN& other) const { return {other}; }
};

// A balanced sample with beta_3..beta_n held (model.md §13.7): unknowns (q / L, beta_1,
// beta_2, p), the rotor's equations and those of balls 1 and 2.
struct HeldSystem {
  using Vec = Eigen::Matrix<ld, 5, 1>;
  using Jacobian = Eigen::Matrix<ld, 4, 5>;
  static constexpr bool balanced = true;
  const StaticEquationsN& eq;
  Unknowns frame;  ///< the full unknowns, with the held angles
  /// A copy on other equations (the curves rebuild them at every second parameter).
  HeldSystem on(const StaticEquationsN& other) const { return {other, frame}; }

  Unknowns full(const Vec& u) const {
    Unknowns z = frame;
    z.head<4>() = u.head<4>();
    z(eq.dofs()) = u(4);
    return z;
  }
  Vec reduced(const Unknowns& z) const {
    Vec u;
    u << z.head<4>(), z(eq.dofs());
    return u;
  }
  Eigen::Matrix<ld, 4, 1> residual(const Vec& u) const { return eq.residual(full(u)).head<4>(); }
  Jacobian jacobian(const Vec& u) const {
    const StaticEquationsN::JacobianMatrix J = eq.jacobian(full(u));
    Jacobian out;
    out.leftCols<4>() = J.topLeftCorner<4, 4>();
    out.col(4) = J.col(eq.dofs()).head<4>();
    return out;
  }
  ld residual_size(const Vec& u) const { return residual(u).cwiseAbs().maxCoeff(); }
  static arclength::NewtonSettings newton() { return {}; }
};

}  // namespace n_balls
}  // namespace abu
