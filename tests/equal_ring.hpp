// A ring of n equal balls on the default scene's rotor (M_r 0.12 kg, k 7500 N/m, c 2 N s/m):
// m 3.3e-5 kg at l 0.018 m, r 1e-3 m, rolling (j 1.4), rolling resistance mu, d 1e-4, stribeck
// 0.001 / 0.003 / 0.1, kappa 1e3 — the ring of data/scenes/ring11.toml with the speed, unbalance
// and law given. Shared by the tests of the equal-ball reductions (model.md §13.9, §13.10).
#pragma once

#include "abu/model/model.hpp"

namespace abu::test {

inline ParamsN equal_ring(int n, FrictionLaw law, double omega, double unbalance, double mu = 0.002) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, unbalance};
  p.omega = omega;
  p.law = law;
  p.kappa = 1e3;
  p.balls.resize(std::size_t(n));
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, mu, 1e-4, 0.001, 0.003, 0.1};
  return p;
}

}  // namespace abu::test
