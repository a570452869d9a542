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

std::complex<double> stuck_balls_dynamic_stiffness(const ShaftSystem& sys) {
  const std::optional<std::complex<double>> z = balancer_dynamic_stiffness(sys);
  if (!z)
    throw NotSupportedError(fmt::format(
        "at omega = {} rad/s the shaft's rotating-frame stiffness is singular (an undamped critical speed): the "
        "balancer node's deflection under stuck balls, and so the stick set, is not defined (model.md §18.17)",
        sys.balancer.omega));
  return *z;
}

ShaftStickSet shaft_stick_set(const ShaftSystem& sys, const StickSetOptions& options) {
  const std::complex<double> z = stuck_balls_dynamic_stiffness(sys);
  const std::optional<Eigen::VectorXcd> h = node_receptances(sys);
  if (!h) throw NotSupportedError(fmt::format("at omega = {} rad/s: no receptance (model.md §18.17)", sys.balancer.omega));
  ShaftStickSet out;
  out.equivalent = equivalent_rigid_params(sys, z);
  out.set = stick_set(out.equivalent, options);
  ShaftStickFigures& f = out.shaft;
  f.dynamic_stiffness = z;
  const double hb = std::abs((*h)(sys.spec.balancer_node));
  f.deflection_ratio.resize(std::size_t(sys.nodes()));
  for (int k = 0; k < sys.nodes(); ++k) {
    f.deflection_ratio[std::size_t(k)] = std::abs((*h)(k)) / hb;
    if (f.deflection_ratio[std::size_t(k)] > f.deflection_ratio[std::size_t(f.worst_node)]) f.worst_node = k;
  }
  // (18.17.2): every node's deflection is its ratio times the balancer node's, at every beta.
  const double ratio = f.deflection_ratio[std::size_t(f.worst_node)];
  f.worst_deflection = ratio * out.set.worst_q_abs;
  f.worst_deflection_any = ratio * out.set.worst_q_abs_any;
  return out;
}

}  // namespace abu
