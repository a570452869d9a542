// A flexible shaft whose balls roll on an unround race (docs/model.md §18.18): the shaft's
// rotating-frame rows of §18.5 and, at the balancer node, the balls' share of the composed
// rigid machine (machine_field.hpp, model.md §20.1): their couplings and forces on their race's
// paths. Static questions (equilibria, their spectra); the whole machine at rest, s' = 0.
//
//   Eigen::VectorXd b = abu::shaft_race_static_forces(sys, race, s);   // b(s, 0), size 4 N + n
//   abu::ShaftLinearization lin = abu::linearize_shaft_on_race(sys, race, s);  // at an equilibrium
#pragma once

#include <Eigen/Core>

#include "abu/model/shaft_system.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// b(s, 0) of (18.18.1): the shaft rows -K_r u + omega^2 U e_b plus the balls' centrifugal pull
/// at their path points, the ball rows of (11.3.4) with q the balancer node's translation.
Eigen::VectorXd shaft_race_static_forces(const ShaftSystem& sys, const RaceShape& race, const Eigen::VectorXd& s);

/// A ds'' + C ds' + K ds = 0 at rest with s'' = 0 (an equilibrium; (18.18.2)): the shaft's
/// rotating-frame matrices plus the balls' share scattered onto (u1_b, u2_b, beta).
ShaftLinearization linearize_shaft_on_race(const ShaftSystem& sys, const RaceShape& race, const Eigen::VectorXd& s);

}  // namespace abu
