// A flexible rotor (issue 11, docs/model.md §18): a finite-element shaft with discs and
// bearings, the balancer's race and balls at one disc node. A scene without `[shaft]` is
// the rigid Jeffcott rotor of model.hpp; nothing here runs for it.
//
// Degrees of freedom, node by node (node k = 0 … elements.size()):
//     (u1_k, u2_k, psi1_k, psi2_k)
// translations of the shaft centre line and small rotations (tilts) of its cross-section
// about a1 and a2, in the frame rotating with the shaft (model.md §2), SI units (m, rad).
// The first-order state of the shaft with n balls at the balancer node is
//     x = (u (4 N_nodes), beta_1 … beta_n, u', beta_1' … beta_n')     dimension 2 (4 N_nodes + n)
// i.e. model.md (2.2) with (q1, q2) replaced by the whole shaft's u; the balancer node's
// (u1, u2) is the q of the rigid model.
//
//   abu::ShaftSpec spec = abu::shaft_spec_of(scene);                // io/scene.hpp
//   abu::ShaftMatrices m = abu::assemble_shaft(spec);               // fixed-frame M, G, K, C
#pragma once

#include <vector>

#include <Eigen/SparseCore>

namespace abu {

/// One beam element between nodes k and k + 1 (model.md §18.1).
struct ShaftElement {
  double length{};          ///< [m]
  double outer_diameter{};  ///< [m]
  double inner_diameter{};  ///< [m], 0 for a solid shaft
  double youngs_modulus{};  ///< E [Pa]
  double density{};         ///< rho [kg/m^3]; 0 for a massless shaft
  double shear_modulus{};   ///< G [Pa]; 0: Euler–Bernoulli, > 0: Timoshenko with shear
};

/// A rigid disc at a node (model.md §18.2).
struct ShaftDisc {
  int node{};
  double mass{};                ///< [kg]
  double polar_inertia{};       ///< I_p [kg m^2]
  double transverse_inertia{};  ///< I_d [kg m^2]
};

/// An isotropic bearing at a node: translational spring and damper to ground, and an
/// optional tilt spring (model.md §18.3).
struct ShaftBearing {
  int node{};
  double stiffness{};        ///< k [N/m]
  double damping{};          ///< c [N s/m]
  double tilt_stiffness{};   ///< k_psi [N m/rad]
  double tilt_damping{};     ///< c_psi [N m s/rad]
};

/// The whole shaft. Invariant (checked by the scene reader, io/scene.cpp): every node
/// index in [0, elements.size()], the balancer node carries a disc.
struct ShaftSpec {
  std::vector<ShaftElement> elements;
  std::vector<ShaftDisc> discs;
  std::vector<ShaftBearing> bearings;
  int balancer_node{};

  int nodes() const { return int(elements.size()) + 1; }
  int dofs() const { return 4 * nodes(); }
};

/// Fixed-frame structural matrices of the non-rotating-frame equation
///     M u'' + (C + Omega G) u' + K u = f        (model.md §18.4)
/// with u in the fixed frame, the same dof order as above. M, K symmetric; G skew.
struct ShaftMatrices {
  Eigen::SparseMatrix<double> mass, stiffness, damping, gyroscopic;
};

ShaftMatrices assemble_shaft(const ShaftSpec& spec);

}  // namespace abu
