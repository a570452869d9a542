// Balls with bit-identical parameters are interchangeable: permuting them maps an
// equilibrium onto one with the same spectrum at every parameter value (model.md §13.7).
// The n-ball continuation traces one of each set of images. Internal header.
#pragma once

#include <vector>

#include "abu/core/params.hpp"
#include "abu/model/model.hpp"

namespace abu::n_balls {

/// class_of[i]: the first ball whose parameters equal ball i's.
std::vector<int> ball_classes(const ParamsN& p);
/// The canonical image of s: among balls first_ball.., the angles of each class sorted
/// by wrapped value (ascending), the rest unchanged.
Coordinates<long double, any_balls> canonical(const Coordinates<long double, any_balls>& s,
                                              const std::vector<int>& class_of, int first_ball);
/// The sign pattern of an aligned configuration, ball 1 taken '+' (equilibria.hpp).
unsigned pattern_of(const Coordinates<long double, any_balls>& s);

}  // namespace abu::n_balls
