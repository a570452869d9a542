// The vector field of the balancer on an unround race for integration (model.md §11.3 at
// constant speed, §15.6 with the Euler terms of a run-up), its analytic Jacobian and its
// derivative in omega (model.md §15.6), in double on the bounded any-ball storage (no
// allocation per call: the path points live in a fixed array).
//
//   abu::State<double, abu::any_balls> f = abu::unround_vector_field(p, race, x, omega_dot);
//   abu::StateMatrix<double, abu::any_balls> J = abu::unround_jacobian(p, race, x, omega_dot);
#pragma once

#include "abu/model/model.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// l'''(beta) of the path radius (11.1.1): with l, l', l'' of path_point the third
/// derivative the Jacobian off equilibrium needs (model.md (15.6.3)). Exact.
double path_third_derivative(const RaceHarmonics& h, double l, double beta);

/// f(x) = (s', A(beta)^-1 b(s, s')) of model.md (11.3.3)-(11.3.4), with the Euler terms
/// of the run-up (15.6.1) when omega_dot != 0; p.omega is omega(t).
State<double, any_balls> unround_vector_field(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x,
                                              double omega_dot = 0.0);

/// df/dx at any state (model.md (15.6.2)-(15.6.4)): A^-1 (db/ds - (dA/ds) s''), A^-1 db/ds'.
StateMatrix<double, any_balls> unround_jacobian(const ParamsN& p, const RaceShape& race,
                                                const State<double, any_balls>& x, double omega_dot = 0.0);

/// df/domega at fixed x and omega_dot (model.md (15.6.5)): the run-up's df/dt is
/// omega_dot times this inside a segment of the speed profile.
State<double, any_balls> unround_omega_derivative(const ParamsN& p, const RaceShape& race,
                                                  const State<double, any_balls>& x);

}  // namespace abu
