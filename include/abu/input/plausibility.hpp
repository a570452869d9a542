// Values a ball balancer does not have: warnings, not errors (the model holds for them,
// and a study may want them), each naming the parameter by its model.md symbol, the
// scene key it comes from, and the unit slip that most likely produced it.
//
//   for (const auto& w : abu::implausible_values(scene)) fmt::print(stderr, "warning: {}\n", w);
//
// The checks and their bounds (each a factor of 10 to 1000 beyond any balancer we know
// of, so that a real design does not trip them):
//   m_i > M_r                        ball heavier than the rotor: grams typed as kilograms?
//   m_i / (4/3 pi r_i^3) outside 300 .. 30000 kg/m^3
//                                    a ball of no material: mass in g or radius in mm?
//   l_i > 1 m, l_i < 1 mm            race radius: millimetres typed as metres / a value in mm?
//   r_i > 0.1 m                      ball radius: millimetres typed as metres?
//   M_r > 1000 kg                    rotor mass: grams typed as kilograms?
//   omega_n < 1 rad/s                omega_n = sqrt(k / (M_r + sum m)): stiffness in kN/m, N/mm?
//   U > 10 sum m_i l_i               unbalance far beyond what the balls can cancel: g mm?
//   omega > 100 omega_n              speed: rpm typed as rad/s?
//   mu, mu_c, mu_s > 0.5             mu = f / r is a rolling-resistance ratio (1e-4 .. 1e-2)
#pragma once

#include <string>
#include <vector>

#include "abu/input/scene.hpp"

namespace abu {

/// One message per implausible value (per distinct value for the balls), in the order
/// of the table above; empty for a plausible scene.
std::vector<std::string> implausible_values(const Scene& scene);

}  // namespace abu
