// coulomb-set balls on a flexible shaft (docs/model.md §18.17): the stick set of the rigid
// balancer the balls see through the shaft, and what it means for the whole shaft.
//
// Stuck balls are a static load omega^2 W(beta) at the balancer node; the node answers by its
// receptance, q = h omega^2 W(beta), so the stick condition (14.2) is that of a rigid rotor
// with the dynamic stiffness K_eff + i C_eff = 1/h (18.8.1): the shaft's stick set IS the
// equivalent rigid balancer's (18.17.1). Every other node deflects by H_k omega^2 W(beta), so
// over any part of the set its largest deflection is |H_k| / |h| times the node's |q|
// (18.17.2): the worst deflection along the shaft over E_B is max_k |H_k| / |h| times V.
//
//   abu::ShaftSystem sys = abu::stuck_balls_shaft(spec, params);   // params.law: coulomb-set
//   abu::ShaftStickSet s = abu::shaft_stick_set(sys, {});
//   fmt::print("{} {} at node {}\n", s.set.worst_q_abs, s.shaft.worst_deflection, s.shaft.worst_node);
#pragma once

#include <complex>
#include <vector>

#include "abu/equilibria/stick_set.hpp"
#include "abu/model/shaft_system.hpp"

namespace abu {

/// The shaft's figures of a stick set (model.md §18.17).
struct ShaftStickFigures {
  std::complex<double> dynamic_stiffness;  ///< K_eff + i C_eff at the balancer node [N/m] (18.8.1)
  /// |H_k| / |h| per node: its deflection per unit deflection of the balancer node (18.17.2)
  std::vector<double> deflection_ratio;
  int worst_node = 0;             ///< the node of the largest ratio (0-based, as [[disc]] node)
  double worst_deflection = 0.0;  ///< its deflection where V is attained: ratio x V [m]
  double worst_deflection_any = 0.0;  ///< ratio x V_E [m]
};

/// The stick set of a shaft's balls (of equivalent_rigid_params, with their law's mu_i) and
/// the shaft's figures.
struct ShaftStickSet {
  ParamsN equivalent;  ///< the rigid balancer the balls see (18.8.2)
  StickSet set;
  ShaftStickFigures shaft;
};

/// The shaft system of balls with a set-valued law: make_shaft_system takes the smooth laws
/// only (its field reads the law); the receptance of (18.8.1) reads none, so the system is made
/// under `none` and `balls.law` put back. Use it for static questions only (no shaft_field).
ShaftSystem stuck_balls_shaft(const ShaftSpec& spec, const ParamsN& balls);

/// Throws what shaft_stick_set would throw before it computes anything (NotSupportedError: an
/// undamped critical speed, where the node's deflection under stuck balls is undefined; mu_i <= 0).
void check_shaft_stick_set_defined(const ShaftSystem& sys);

/// Throws NotSupportedError where the set is not defined: an undamped critical speed or
/// mu_i <= 0 (stick_set's rule).
ShaftStickSet shaft_stick_set(const ShaftSystem& sys, const StickSetOptions& options = {});

}  // namespace abu
