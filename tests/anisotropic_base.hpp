// BASE of docs/model.md §10.8 for the anisotropic-support tests and benchmarks: two rolling
// balls on the §10.8 rotor, the friction law given (kappa = 1e5 s/rad for coulomb: ball
// rates ~1e7-1e8 1/s), and §10.8's anisotropy times `scale` around the mean support.
#pragma once

#include "abu/core/params.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu::testing {

inline ParamsN anisotropic_base(FrictionLaw law) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = law;
  p.kappa = 1e5;
  p.balls.resize(2);
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-3, 0.001, 0.003, 0.1};
  return p;
}

/// dk = 375 N/m, k_xy = 150 N/m, dc = 0.3 N s/m, c_xy = 0.1 N s/m, times `scale`.
inline AnisotropicSupport anisotropic_base_support(const ParamsN& p, double scale) {
  const double k = p.rotor.stiffness, c = p.rotor.damping;
  return {k + 375.0 * scale, k - 375.0 * scale, 150.0 * scale, c + 0.3 * scale, c - 0.3 * scale, 0.1 * scale};
}

}  // namespace abu::testing
