// Parts of the flexible-rotor tests (model.md §18): a steel tube element, a small flexible
// rotor and a rigid rotor's balls (tests/test_shaft.cpp, tests/test_shaft_matrices.cpp).
#pragma once

#include <cstddef>

#include "abu/core/params.hpp"
#include "abu/model/shaft.hpp"

namespace abu::testing {

// A steel tube: E 2.1e11 Pa, rho 7800 kg/m^3, G = E / (2 (1 + 0.3)).
inline ShaftElement steel(double length, double outer, double inner, bool timoshenko) {
  const double E = 2.1e11;
  return {length, outer, inner, E, 7800.0, timoshenko ? E / 2.6 : 0.0};
}

// The default scene's rotor with n balls, every ball different (index mix-ups cannot cancel).
// Not inlined: inlined into the tests' loops over n, GCC 12 -O3 reports a false
// -Wstringop-overflow in BoundedBalls::resize.
[[gnu::noinline]] inline ParamsN balls(int n, FrictionLaw law, double omega) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = omega;
  p.law = law;
  p.kappa = 1e2;
  p.balls.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const double f = 1 + 0.07 * i;
    p.balls[std::size_t(i)] = {3.3e-5 * f, 0.018 * (1 + 0.01 * i), 1e-3, 1.4, 0.002 * f, 1e-4 * f, 0.001 * f,
                               0.003 * f, 0.1 * f};
  }
  return p;
}

// A small flexible rotor: 4 hollow steel elements, discs at nodes 2 (the balancer) and 4,
// bearings at nodes 0 and 3 (overhung disc at 4). Scaled so that its first critical
// speeds lie near the default scene's (a few hundred rad/s).
inline ShaftSpec small_rotor(bool timoshenko) {
  ShaftSpec s;
  for (int i = 0; i < 4; ++i) s.elements.push_back(steel(0.1, 0.012, 0.004, timoshenko));
  s.discs = {{2, 0.12, 2.0e-4, 1.0e-4}, {4, 0.3, 6.0e-4, 3.2e-4}};
  s.bearings = {{0, 2e5, 20.0, 0.0, 0.0}, {3, 3e5, 30.0, 5.0, 0.01}};
  s.balancer_node = 2;
  return s;
}

}  // namespace abu::testing
