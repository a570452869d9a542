// The flexible rotor with its ball balancer in the frame rotating at omega (model.md
// §18.5–§18.7): the finite-element shaft of shaft.hpp, its discs and bearings, and the
// n balls of model.md §3 / §13 acting on the translation of the balancer node.
//
// Configuration and state (shaft.hpp):
//     s = (u (4 N_nodes), beta_1 … beta_n)                 size  4 N_nodes + n
//     x = (s, s')                                          size  2 (4 N_nodes + n)
// Second-order form, as model.hpp's (3.7) with the rigid rotor replaced by the shaft:
//     A(beta) s'' = b(s, s')
//     A = [ M_tot        B(beta) ]    M_tot = M (shaft, discs) + (sum m_i) at the balancer
//         [ B(beta)^T    diag(j_i m_i l_i^2) ]                 node's (u1, u2)
// The linearization keeps that form (A ds'' + C ds' + K ds = 0) and, for large spectra,
// the generalized first-order pencil
//     a v = lambda b v,   a = [[0, I], [-K, -C]],   b = [[I, 0], [0, A]]
// whose eigenvalues are those of J = df/dx (model.md §18.7): A is never inverted.
//
//   abu::ShaftSystem sys = abu::make_shaft_system(spec, balancer);   // balancer: abu::ParamsN
//   Eigen::VectorXd f = abu::shaft_field(sys, x);
//   abu::ShaftLinearization lin = abu::linearize_shaft(sys, x);
//   abu::ShaftPencil pencil = abu::shaft_pencil(lin);                  // for ARPACK shift-invert
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "abu/core/params.hpp"
#include "abu/model/shaft.hpp"

namespace abu {

/// Everything the rotating-frame equations depend on. `balancer` supplies the spin speed
/// omega, the unbalance U (rotor.unbalance, at the balancer node, along a1), the friction
/// law, kappa and the balls; its rotor.mass, rotor.stiffness and rotor.damping are NOT
/// used (the shaft, its discs and bearings replace the rigid rotor; the balancer disc's
/// mass plays M_r). `fixed` is assemble_shaft(spec), kept so that evaluations only add
/// the speed-dependent terms.
struct ShaftSystem {
  ShaftSpec spec;
  ParamsN balancer;
  ShaftMatrices fixed;

  int nodes() const { return spec.nodes(); }
  int shaft_dofs() const { return spec.dofs(); }                          ///< 4 N_nodes
  int n_balls() const { return balancer.n_balls(); }
  int configuration_size() const { return shaft_dofs() + n_balls(); }     ///< 4 N_nodes + n
  int state_size() const { return 2 * configuration_size(); }
  int balancer_dof() const { return 4 * spec.balancer_node; }            ///< index of u1 at the balancer node
  int ball_dof(int i) const { return shaft_dofs() + i; }                 ///< index of beta_{i+1} in s
};

/// Checks `spec` (shaft_spec_violation) and the balls (1 <= n <= max_balls; m_i, l_i > 0)
/// and assembles. Throws std::invalid_argument with the rule broken: the scene reader
/// checks the same rules first, with file and line.
ShaftSystem make_shaft_system(const ShaftSpec& spec, const ParamsN& balancer);

/// The speed-dependent linear part of the shaft rows in the rotating frame (model.md
/// §18.5), balls' translating mass included at the balancer node:
///     mass      = M_tot
///     damping   = C + omega G + 2 omega M_tot Jr
///     stiffness = K - omega^2 M_tot + omega C Jr + omega^2 G Jr
/// with Jr the rotation by +90° of every (u1, u2) and (psi1, psi2) pair. Size 4 N_nodes.
struct ShaftRotatingMatrices {
  Eigen::SparseMatrix<double> mass, damping, stiffness;
};
ShaftRotatingMatrices rotating_matrices(const ShaftSystem& sys);

/// A(beta) of the header comment, sparse, size 4 N_nodes + n (s: configuration).
Eigen::SparseMatrix<double> shaft_mass_matrix(const ShaftSystem& sys, const Eigen::VectorXd& s);

/// b(s, s'): rotating-frame generalized forces (model.md (18.5.x)), size 4 N_nodes + n.
Eigen::VectorXd shaft_generalized_forces(const ShaftSystem& sys, const Eigen::VectorXd& x);

/// x' = f(x) = (s', A^-1 b) by a sparse Cholesky factorization of A. Throws
/// NumericalError if A is not positive definite (cannot happen for a system that
/// make_shaft_system accepted).
Eigen::VectorXd shaft_field(const ShaftSystem& sys, const Eigen::VectorXd& x);

/// Second-order linearization at any state: A ds'' + C ds' + K ds = 0 with
/// C = -db/ds', K = -db/ds + (dA/ds) s'' (model.md (6.5) for the shaft).
struct ShaftLinearization {
  Eigen::SparseMatrix<double> mass;       ///< A(beta), symmetric positive definite
  Eigen::SparseMatrix<double> damping;    ///< C
  Eigen::SparseMatrix<double> stiffness;  ///< K
};
ShaftLinearization linearize_shaft(const ShaftSystem& sys, const Eigen::VectorXd& x);

/// The generalized eigenproblem a v = lambda b v of J = df/dx, v = (ds, lambda ds):
/// a = [[0, I], [-K, -C]], b = blkdiag(I, A). Both sparse, size 2 (4 N_nodes + n).
struct ShaftPencil {
  Eigen::SparseMatrix<double> a, b;
};
ShaftPencil shaft_pencil(const ShaftLinearization& lin);

/// J = df/dx = [[0, I], [-A^-1 K, -A^-1 C]] explicitly. A consistent mass matrix makes
/// A^-1 dense, so the lower half fills in: for small systems and checks only; large
/// spectra use shaft_pencil.
Eigen::SparseMatrix<double> shaft_jacobian(const ShaftSystem& sys, const Eigen::VectorXd& x);

}  // namespace abu
