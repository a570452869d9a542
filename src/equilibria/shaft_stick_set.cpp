// coulomb-set balls on a flexible shaft (shaft_stick_set.hpp, model.md §18.17).
#include "abu/equilibria/shaft_stick_set.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "abu/core/errors.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"

namespace abu {

ShaftSystem stuck_balls_shaft(const ShaftSpec& spec, const ParamsN& balls) {
  ParamsN smooth = balls;
  smooth.law = FrictionLaw::none;
  ShaftSystem sys = make_shaft_system(spec, smooth);
  sys.balancer.law = balls.law;
  return sys;
}

namespace {
// Every node's receptance (one sparse solve) and K_eff + i C_eff = 1/h from it; NotSupportedError
// at an undamped critical speed (the rotating-frame stiffness singular: no static response).
struct StuckBallsResponse {
  Eigen::VectorXcd receptances;
  std::complex<double> dynamic_stiffness;
};
StuckBallsResponse stuck_balls_response(const ShaftSystem& sys) {
  const std::optional<Eigen::VectorXcd> h = node_receptances(sys);
  const std::complex<double> hb = h ? (*h)(sys.spec.balancer_node) : 0.0;
  const std::complex<double> z = hb != 0.0 ? 1.0 / hb : 0.0;
  if (!h || hb == 0.0 || !std::isfinite(z.real()) || !std::isfinite(z.imag()))
    throw NotSupportedError(fmt::format(
        "at omega = {} rad/s the shaft's rotating-frame stiffness is singular (an undamped critical speed): the "
        "balancer node's deflection under stuck balls, and so the stick set, is not defined (model.md §18.17)",
        sys.balancer.omega));
  return {*h, z};
}
}  // namespace

void check_shaft_stick_set_defined(const ShaftSystem& sys) {
  check_stick_set_defined(equivalent_rigid_params(sys, stuck_balls_response(sys).dynamic_stiffness));
}

ShaftStickSet shaft_stick_set(const ShaftSystem& sys, const StickSetOptions& options) {
  const StuckBallsResponse response = stuck_balls_response(sys);
  const Eigen::VectorXcd& h = response.receptances;
  ShaftStickSet out;
  out.equivalent = equivalent_rigid_params(sys, response.dynamic_stiffness);
  out.set = stick_set(out.equivalent, options);
  ShaftStickFigures& f = out.shaft;
  f.dynamic_stiffness = response.dynamic_stiffness;
  const double hb = std::abs(h(sys.spec.balancer_node));
  f.deflection_ratio.resize(std::size_t(sys.nodes()));
  for (int k = 0; k < sys.nodes(); ++k) {
    f.deflection_ratio[std::size_t(k)] = std::abs(h(k)) / hb;
    if (f.deflection_ratio[std::size_t(k)] > f.deflection_ratio[std::size_t(f.worst_node)]) f.worst_node = k;
  }
  // (18.17.2): every node's deflection is its ratio times the balancer node's, at every beta.
  const double ratio = f.deflection_ratio[std::size_t(f.worst_node)];
  f.worst_deflection = ratio * out.set.worst_q_abs;
  f.worst_deflection_any = ratio * out.set.worst_q_abs_any;
  return out;
}

}  // namespace abu
