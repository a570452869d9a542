// The vector field of a rigid-rotor balancer composed from its parts (docs/model.md §20):
// the rotor on an isotropic or anisotropic support, each ball on a round or unround race,
// each ball with its smooth friction law, at constant speed or during a run-up. One state
// layout (model.md §2), one field, its analytic Jacobian and its derivatives in the spin
// speed, in the support's angle and in the anisotropy homotopy parameter:
//
//     A(beta) s'' = b(s, s'; omega, omega') + delta (g(q, q', theta), 0)           (20.1)
//
// A and b those of the unround race (model.md (11.3.3)-(11.3.4), with the run-up's Euler
// terms (15.6.1)) at the mean support (k_bar, c_bar) — for a round race model.md §3's, by
// model.hpp's code — and g the support's anisotropic force on the rotating axes (10.14.1) at
// the spin angle theta: g = -(K_rot(theta) - k_bar I) q - (C_rot(theta) - c_bar I) (q' +
// omega J2 q). A part that is absent costs nothing: a round race on an isotropic support is
// model.md §3's field (model.hpp) itself.
//
//   abu::RigidMachine m{&race, &support};          // either may be null
//   abu::MachineFieldValue v;
//   abu::machine_field(p, m, x, theta, omega_dot, v, true);   // v.field, v.jacobian, ...
#pragma once

#include "abu/core/params.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/model/model.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// The parts of a rigid-rotor machine beyond model.md §3 (not owned; null: the base part).
/// `p` (ParamsN) carries the rest: masses, radii, friction per ball, the isotropic or mean
/// support (k_bar, c_bar when `support` is set), omega.
struct RigidMachine {
  const RaceShape* race = nullptr;              ///< unround centre paths (model.md §11); null or round(): circles
  const AnisotropicSupport* support = nullptr;  ///< anisotropic support (model.md §10); null or isotropic(): p.rotor
  double delta = 1.0;  ///< the anisotropy's homotopy scale in (20.1) (1: the scene's support)

  bool unround() const;
  /// An anisotropic support, whatever delta (at delta = 0 the field is the mean support's,
  /// its delta derivative A^-1 (g, 0) is not zero).
  bool anisotropic() const;
  /// Neither part: model.md §3's field applies as it is.
  bool base() const { return !unround() && !anisotropic(); }
};

/// f and its derivatives at one (x, theta) [SI, state order of model.md §2]. No allocation.
struct MachineFieldValue {
  State<double, any_balls> field;             ///< f(x)
  StateMatrix<double, any_balls> jacobian;    ///< df/dx
  State<double, any_balls> omega_derivative;  ///< df/domega at fixed x, theta, omega'
  State<double, any_balls> angle_derivative;  ///< df/dtheta (zero without anisotropy)
  State<double, any_balls> delta_derivative;  ///< df/ddelta: A^-1 (g, 0) (zero without anisotropy)
};

/// (20.1) at x with the support's spin angle theta [rad] (theta = omega t at constant speed,
/// the integral of omega during a run-up) and the angular acceleration omega_dot; the
/// derivatives only when `derivatives`. Along a run omega(t), theta(t):
/// df/dt = omega' df/domega + omega df/dtheta.
void machine_field(const ParamsN& p, const RigidMachine& m, const State<double, any_balls>& x, double theta,
                   double omega_dot, MachineFieldValue& out, bool derivatives);

/// The balls' share of (20.1) in the rigid layout s = (q1, q2, beta_1..beta_n), q the
/// translation the balls ride on: every term model.md (11.3.3)-(11.3.4) and (15.6.2)-(15.6.4)
/// owe to the balls except their translating mass on q (which the rotor's M includes) — their
/// coupling and inertia in A, their forces in b, Bs = db/ds - (dA/ds) s'' with s'' = `acc`,
/// and Bv = db/ds'. A flexible shaft adds it at its balancer node (model.md §18.18); the rigid
/// field is it plus the rotor's M, k, c and U.
struct BallShare {
  DofMatrix<double, any_balls> mass;            ///< A's ball terms (zero on the q-q block)
  Coordinates<double, any_balls> force;         ///< b's ball terms
  DofMatrix<double, any_balls> force_position;  ///< Bs's ball terms
  DofMatrix<double, any_balls> force_velocity;  ///< Bv's ball terms
};
BallShare ball_share(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x,
                     const Coordinates<double, any_balls>& acc, double omega_dot = 0.0);

/// The share's A and b terms alone (BallShare::mass, ::force; no derivatives, so no third path
/// derivative): what a field evaluation on a flexible shaft needs per step (model.md §18.20).
/// Writes into `mass` and `force` (bounded storage: no allocation).
void ball_share_terms(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x, double omega_dot,
                      DofMatrix<double, any_balls>& mass, Coordinates<double, any_balls>& force);

}  // namespace abu
