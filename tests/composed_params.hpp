// The viscous two-ball machine of tests/scenes/anisotropic/ref_viscous.toml and
// tests/scenes/composed/oval_anisotropic.toml at its mean support (k_bar = 10500, c_bar = 3.25),
// shared by the composed machine's tests.
#pragma once

#include "abu/core/params.hpp"

namespace abu::test {

inline ParamsN composed_mean_params() {
  ParamsN p;
  p.rotor = {0.2, 10500.0, 3.25, 8e-7};
  p.omega = 1100.0;
  p.law = FrictionLaw::viscous;
  p.balls.resize(2);
  p.balls[0] = {4e-5, 0.02, 1e-3, 1.4, 0, 2e-3, 0, 0, 0};
  p.balls[1] = {3e-5, 0.021, 1.2e-3, 1.0, 0, 2e-3, 0, 0, 0};
  return p;
}

}  // namespace abu::test
