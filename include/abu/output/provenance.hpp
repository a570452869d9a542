// The provenance every output file starts with: program and version, command line, scene, and
// every parameter value used (model.md symbols).
#pragma once

#include <string>
#include <string_view>

#include "abu/core/params.hpp"

namespace abu {

/// "key=value" list of every parameter in model.md symbols (N = 2 or any_balls). A ball
/// given by its specification (model.md §1.1) adds what was specified: rho_i, f_i, R_s_i.
template <int N>
std::string describe_parameters(const ParamsT<double, N>& p);

/// How the specified balls' model values were derived, "m1=rho1*pi*(2*r1)^3/6=... kg
/// mu1=f1/r1=... l1=R_s1-r1=... m ..." (model.md (1.1.1)-(1.1.3)); empty if no ball is
/// specified that way (the outputs of such scenes keep their bytes).
template <int N>
std::string describe_specification(const ParamsT<double, N>& p);

/// The comment block on top of every output file: program and version, the command
/// line, the scene and every parameter value used, and how specified balls' values were
/// derived (describe_specification). Lines start with "# ".
template <int N>
std::string provenance_header(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p);

}  // namespace abu
