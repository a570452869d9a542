#pragma once
// The two-ball parameters in the any-ball-count type, for code that takes ParamsN
// (the n-ball analysis, the stick set) with a two-ball scene's fixed-size parameters.
#include "abu/core/params.hpp"

namespace abu {

inline ParamsN widen(const Params& p) {
  ParamsN q;
  q.rotor = p.rotor;
  q.omega = p.omega;
  q.law = p.law;
  q.kappa = p.kappa;
  q.balls.resize(2);
  q.balls[0] = p.balls[0];
  q.balls[1] = p.balls[1];
  return q;
}

}  // namespace abu
