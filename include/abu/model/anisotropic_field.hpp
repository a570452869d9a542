// The vector field of the balancer on an anisotropic support (docs/model.md §10.2, §10.14),
// away from the balanced states: time-periodic with period pi/omega in the rotating frame,
// with the support's anisotropy scaled by a homotopy parameter delta in [0, 1],
//     K_f(delta) = k_bar I + delta (K_f - k_bar I),   C_f(delta) = c_bar I + delta (C_f - c_bar I),
// so that delta = 0 is the isotropic model at the mean support and delta = 1 the scene.
//
//     f(x, t; delta) = f_mean(x) + (0, A(beta)^-1 (delta g(q, q', t), 0))              (10.14.1)
//     g = -(K_rot(t) - k_bar I) q - (C_rot(t) - c_bar I) (q' + omega J2 q)
//
// f_mean the field of model.md (3.10) at (k_bar, c_bar). The Jacobian adds to the mean one
// A^-1 (d(delta g)/ds - (dA/ds) A^-1 delta g) in the lower block rows (model.md (10.14.2)).
//
//   abu::ParamsN p = ...;  // p.rotor.stiffness = s.mean_stiffness(), p.rotor.damping = s.mean_damping()
//   abu::AnisotropicFieldValue v;
//   abu::anisotropic_field(p, s, x, t, 1.0, v, true);   // v.field, v.jacobian, v.delta_derivative, v.time_derivative
#pragma once

#include "abu/core/params.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/model/model.hpp"

namespace abu {

/// f, df/dx, df/ddelta and df/dt at one (x, t, delta) [SI, state order of model.md §2].
struct AnisotropicFieldValue {
  State<double, any_balls> field;
  StateMatrix<double, any_balls> jacobian;
  State<double, any_balls> delta_derivative;  ///< df/ddelta: the full anisotropy's force through A^-1
  State<double, any_balls> time_derivative;   ///< df/dt (explicit time only)
};

/// (10.14.1) at x, t, delta; the derivatives only when `derivatives` (the field alone
/// otherwise). `p` must carry the mean support (k_bar, c_bar). No allocation: bounded types.
void anisotropic_field(const ParamsN& p, const AnisotropicSupport& s, const State<double, any_balls>& x, double t,
                       double delta, AnisotropicFieldValue& out, bool derivatives);

}  // namespace abu
