// A flexible-rotor scene (docs/model.md §18.10–§18.12): an optional `[shaft]`
// table turns the rigid Jeffcott rotor of model.md §1 into a finite-element shaft with
// discs and bearings; the balancer's race and balls sit at one disc (the balancer node).
//
//   [shaft]
//   balancer_node = 6            # the node whose disc carries the race and the balls
//   [[shaft.element]]            # in order along the shaft (left to right); none: one node 0,
//                                # a rigid disc on its bearing (the rigid rotor with tilt, model.md §18.9)
//   length = 0.5                 # [m], > 0: the section's length
//   outer_diameter = 0.03        # [m], > 0
//   inner_diameter = 0.0         # [m], optional (0: solid), 0 <= inner < outer
//   youngs_modulus = 2.1e11      # E [Pa], > 0
//   density = 7850.0             # rho [kg/m^3], >= 0 (0: a massless shaft)
//   shear_modulus = 8.1e10       # G [Pa], optional, > E/3 (Poisson's ratio < 0.5): Timoshenko (shear);
//                                # absent: Euler–Bernoulli
//   segments = 12                # optional integer 1..100000 (default 1): the section is cut into
//                                # `segments` equal elements, so a uniform shaft is one table
//   [[disc]]                     # a rigid disc at a node
//   node = 6  mass = 1.2  polar_inertia = 2.4e-3  transverse_inertia = 1.2e-3
//   [[bearing]]                  # an isotropic bearing (spring and damper to ground) at a node
//   node = 0  stiffness = 5e7  damping = 500.0
//   tilt_stiffness = 0.0         # [N m/rad], optional, >= 0
//   tilt_damping = 0.0           # [N m s/rad], optional, >= 0
//                                # or anisotropic (model.md §18.19): instead of stiffness, damping
//   stiffness_x = 5.2e7  stiffness_y = 4.8e7  stiffness_xy = 1e6     # K_f [N/m] on n1, n2 (xy optional)
//   damping_x = 500.0  damping_y = 400.0  damping_xy = 0.0           # C_f [N s/m] (xy optional)
//
// Nodes are numbered 0..E along the shaft, E the number of elements after `segments`:
// element e (0-based, in file order, each section's segments in turn) joins nodes e and
// e + 1; node 0 is the first section's left end. This is ShaftSpec's numbering
// (model/shaft.hpp) and ROSS's.
//
// In a shaft scene [rotor] gives only `unbalance` (U = m_u e [kg m], in the balancer
// disc's plane: the a1 axis points at it, model.md §2); its mass is the discs' and the
// shaft's, its support the bearings', so rotor.mass / stiffness / damping (and the
// anisotropic keys) are errors naming the table that replaces them. [[ball]] / [balls],
// [friction] and [speed] are as for the rigid rotor. [[disc]] and [[bearing]] without
// [shaft] are errors.
//
// Rules (each one InputError: file, line, key, rule; the first in the file wins, like
// every scene rule, scene.cpp): every key known, every number finite and in its range
// above; a bearing gives stiffness and damping or the matrix keys, never both, K_f positive
// definite, C_f positive semidefinite; node indices integers in 0..E (disc, bearing, balancer_node); every disc and
// bearing has a node; at most one disc per node (two on one node: give one with the summed
// mass and inertias); a disc's polar_inertia <= 2 transverse_inertia (the principal moments
// of a rigid body obey I_3 <= I_1 + I_2: swapped values are caught); the balancer node has a
// disc; at least one bearing, and the bearings hold the shaft: its rigid-body motions
// (translation and tilt, model.md §18.11) meet a spring, i.e. translational stiffness at two
// different positions, or at one position together with a tilt stiffness; every degree of
// freedom has inertia (a node of massless elements needs a disc with mass and
// transverse_inertia: massless nodes are not condensed, model.md §18.9). At most
// kMaxShaftElements elements in all. Two bearings on one node are allowed: they act in
// parallel (their stiffnesses and dampings add).
//
//   abu::Scene scene = abu::load_scene("data/scenes/shaft.toml");
//   const abu::ShaftSpec& spec = abu::shaft_spec_of(scene);   // NotSupportedError if rigid
//   std::vector<double> x = abu::node_positions(spec);         // [m], x[0] = 0
#pragma once

#include <string>
#include <vector>

#include "abu/model/shaft.hpp"

namespace abu {

struct Scene;

/// The bound on the elements of one shaft (after `segments`): 4 (E + 1) structural
/// degrees of freedom; 250000 elements are a million, beyond the sparse solvers' reach here.
inline constexpr int kMaxShaftElements = 250000;
/// The bound on one [[shaft.element]]'s `segments`.
inline constexpr int kMaxShaftSegments = 100000;

/// The scene's shaft; throws NotSupportedError if the scene is a rigid rotor (no [shaft]).
const ShaftSpec& shaft_spec_of(const Scene& scene);

/// Axial position of every node [m]: x_0 = 0, x_{k+1} = x_k + L_k.
std::vector<double> node_positions(const ShaftSpec& spec);

/// Mass of the shaft's elements and discs [kg]: sum rho A L + sum m_disc (the balls not included).
double shaft_mass(const ShaftSpec& spec);

/// Values far outside what a rotor has, as warnings (the scene is valid; cf. plausibility.hpp):
/// Euler–Bernoulli elements shorter than their diameter (shear matters: give shear_modulus),
/// a density below 100 kg/m^3 (g/cm^3 typed as kg/m^3?), E below 1e8 Pa (GPa typed as Pa?),
/// a diameter above 2 m (mm typed as m?).
std::vector<std::string> shaft_warnings(const Scene& scene);

/// The numerical range of a shaft scene (the rigid one is ranges.hpp's): U = 0 or
/// U >= 1e-12 of the balls' capacity. Throws InputError(origin, 0, "U", rule).
void check_shaft_range(const Scene& scene, const std::string& origin);

}  // namespace abu
