// A flexible rotor (docs/model.md §18): a finite-element shaft with discs and
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
//   abu::ShaftSpec spec = abu::shaft_spec_of(scene);                // input/scene.hpp
//   abu::ShaftMatrices m = abu::assemble_shaft(spec);               // fixed-frame M, G, K, C
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "abu/model/anisotropic_support.hpp"

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

/// A bearing at a node: translational spring and damper to ground, and an optional tilt
/// spring (model.md §18.3). Isotropic (k, c), or anisotropic: the fixed-frame matrices K_f,
/// C_f on the fixed axes (n1, n2) of model.md §10.1 (§18.19); the tilt spring is isotropic.
struct ShaftBearing {
  int node{};
  double stiffness{};        ///< k [N/m]; an anisotropic bearing: its mean (k_x + k_y)/2
  double damping{};          ///< c [N s/m]; an anisotropic bearing: its mean (c_x + c_y)/2
  double tilt_stiffness{};   ///< k_psi [N m/rad]
  double tilt_damping{};     ///< c_psi [N m s/rad]
  /// K_f and C_f of an anisotropic bearing (stiffness, damping are then their means, which
  /// assemble_shaft puts in K and C); none: the isotropic k I, c I. Given in the matrix form it
  /// counts as anisotropic even if K_f = k I, as the rigid [rotor]'s support does.
  std::optional<AnisotropicSupport> anisotropic{};
};

/// The whole shaft. Invariant (checked by the scene reader, input/scene.cpp): every node
/// index in [0, elements.size()], the balancer node carries a disc.
struct ShaftSpec {
  std::vector<ShaftElement> elements;
  std::vector<ShaftDisc> discs;
  std::vector<ShaftBearing> bearings;
  int balancer_node{};

  int nodes() const { return int(elements.size()) + 1; }
  int dofs() const { return 4 * nodes(); }
};

/// Whether a bearing of `spec` is given by fixed-frame matrices (ShaftBearing::anisotropic):
/// the rotating-frame equations are then pi/omega-periodic (model.md §18.19).
bool has_anisotropic_bearings(const ShaftSpec& spec);

/// Fixed-frame structural matrices of the non-rotating-frame equation
///     M u'' + (C + Omega G) u' + K u = f        (model.md §18.4)
/// with u in the fixed frame, the same dof order as above. M, K symmetric; G skew.
struct ShaftMatrices {
  Eigen::SparseMatrix<double> mass, stiffness, damping, gyroscopic;
};

/// An anisotropic bearing enters with its mean stiffness and damping (ShaftBearing::stiffness,
/// damping); its deviatoric part is bearing_deviator's (shaft_bearings.hpp, model.md §18.19).
ShaftMatrices assemble_shaft(const ShaftSpec& spec);

/// The matrices of one element in ONE bending plane (model.md §18.1), dofs
/// (w_k, theta_k, w_{k+1}, theta_{k+1}): deflection and section rotation, theta = w' for
/// Euler–Bernoulli. Plane 1 is (u1, psi2), plane 2 is (u2, -psi1) (model.md §18.4). The
/// element's gyroscopic matrix is 2 x rotary_mass placed between the planes (§18.4).
struct BeamElementMatrices {
  Eigen::Matrix4d translational_mass;  ///< int rho A N_w^T N_w dz
  Eigen::Matrix4d rotary_mass;         ///< int rho I N_theta^T N_theta dz
  Eigen::Matrix4d stiffness;           ///< bending (+ shear for Timoshenko)
  double shear_parameter = 0;          ///< Phi = 12 E I / (kappa_s G A L^2); 0 for Euler–Bernoulli
};
BeamElementMatrices beam_element_matrices(const ShaftElement& e);

/// Cowper's (1966) shear coefficient of a hollow circular section, with Poisson's ratio
/// nu = E / (2 G) - 1 (model.md §18.1). 0 when shear_modulus is 0.
double shear_coefficient(const ShaftElement& e);

/// The first rule `spec` breaks, as a sentence naming the element, disc, bearing or node
/// (node index out of range, non-positive length or diameter, inner >= outer diameter,
/// negative modulus, density, mass, inertia, stiffness or damping, E = 0, a dof without
/// mass: model.md §18.9; an anisotropic bearing's K_f not positive definite, C_f not positive
/// semidefinite, or stiffness, damping not their means: §18.19), or nullopt. The scene reader checks these with file and line;
/// this is the model's own guard (make_shaft_system throws on it).
std::optional<std::string> shaft_spec_violation(const ShaftSpec& spec);

/// Every number of the shaft, one line per element, disc and bearing, each starting with
/// `prefix`: what a map's tiles were computed for (their manifest), and its provenance.
std::string describe_shaft(const ShaftSpec& spec, std::string_view prefix);

}  // namespace abu
