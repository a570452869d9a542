// How an equilibrium is named and measured in every report (report.cpp, report_views.cpp,
// report_campbell.cpp): its |q|, its sign pattern and its label ("balanced 1", "aligned +-+ 2").
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"

namespace abu::detail {

template <int N>
double q_abs(const EquilibriumT<N>& e) {
  return std::hypot(double(e.position(0)), double(e.position(1)));
}

/// The sign of each ball along the line of q (`+-+`); empty for balanced states.
template <int N>
std::string pattern_of(const EquilibriumT<N>& e) {
  return e.family == Family::balanced ? std::string() : pattern_string(e.pattern, e.n_balls());
}

template <int N>
std::string state_label(const EquilibriumT<N>& e) {
  if (e.family == Family::aligned) return fmt::format("aligned {} {}", pattern_of(e), e.member);
  return fmt::format("{} {}", to_string(e.family), e.member);
}

}  // namespace abu::detail
