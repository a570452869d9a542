// Files of `simulate` on a flexible shaft (report_shaft_simulation.hpp, model.md §18.16).
#include "abu/output/report_shaft_simulation.hpp"

#include <fmt/format.h>

#include "abu/output/format.hpp"
#include "abu/output/report_simulation.hpp"

namespace abu {

std::string shaft_simulation_csv(const ShaftSimulationResult& r, const ShaftSystem& sys, const SpeedProfile& speed,
                                 std::string_view header) {
  std::string base = simulation_csv(r.run, sys.balancer, speed, header);
  if (const std::size_t at = base.find("# method: "); at != std::string::npos)  // the shaft's stiffness probe
    base.replace(at, base.find('\n', at) - at,
                 fmt::format("# method: {} (stiffness ratio max|Re lambda(J)| / max(omega_max + omega_n, the fastest underdamped "
                             "|Im lambda|) = {:.4g}, max|Re lambda| = {:.4g} 1/s; model.md §18.16)",
                             to_string(r.run.method), r.run.stiffness_ratio, r.run.spectral_radius));
  // The rigid route's derived M and omega_n (of k = 0 on a shaft): the summary's rigid view instead.
  if (const std::size_t at = base.find("# derived: "); at != std::string::npos)
    base.replace(at, base.find('\n', at) - at,
                 fmt::format("# derived: the summary's rigid view of the shaft (model.md §18.16): M_r = {} kg (the "
                             "balancer disc), k_static = {} N/m at the balancer node, omega_n = sqrt(k_static / (M_r + "
                             "sum m)) = {} rad/s (the stall test's estimate, not a critical speed), L = {} m",
                             format_number(r.view.rotor.mass, "M_r"), format_number(r.view.rotor.stiffness, "k"),
                             format_number(r.run.summary.omega_n, "omega_n"),
                             format_number(r.run.displacement_scale, "L")));
  std::string shaft = fmt::format(
      "# flexible shaft (model.md §18.16): {} nodes, {} states; q1 q2 dq1 dq2 are the balancer node's ({}) u1 u2 "
      "and their rates; max_deflection [m] = max over the nodes of |(u1_k, u2_k)| at the sample, at node "
      "max_deflection_node (0-based)\n",
      sys.nodes(), sys.state_size(), sys.spec.balancer_node);
  for (const ShaftBearing& b : sys.spec.bearings)  // the pi/omega-periodic field's bearings (model.md §18.19)
    if (const auto& a = b.anisotropic)
      shaft += fmt::format("# anisotropic bearing at node {} (model.md §18.19): K_f [[{}, {}], [{}, {}]] N/m, C_f [[{}, {}], "
                           "[{}, {}]] N s/m on the fixed axes n1, n2 (a1, a2 at t = 0)\n",
                           b.node, format_number(a->k_x, "k_x"), format_number(a->k_xy, "k_xy"),
                           format_number(a->k_xy, "k_xy"), format_number(a->k_y, "k_y"), format_number(a->c_x, "c_x"),
                           format_number(a->c_xy, "c_xy"), format_number(a->c_xy, "c_xy"), format_number(a->c_y, "c_y"));
  return with_columns(
      base, shaft,
      ",max_deflection,max_deflection_node",
      [&](std::size_t row, std::string& out) {
        out += ',';
        out += format_number(r.deflection.at(row), "max_deflection");
        out += fmt::format(",{}", r.deflection_node.at(row));
      });
}

std::string shaft_simulation_json(const ShaftSimulationResult& r, const ShaftSystem& sys, const SpeedProfile& speed,
                                  std::string_view command_line, std::string_view scene_file) {
  std::string out = simulation_json(r.run, sys.balancer, speed, command_line, scene_file);
  std::string x_end = "[";
  for (Eigen::Index i = 0; i < r.x_end.size(); ++i) x_end += (i ? ", " : "") + format_number(r.x_end(i), "x_end");
  x_end += "]";
  const std::string block = fmt::format(
      "  \"shaft\": {{\"nodes\": {}, \"balancer_node\": {}, \"state_size\": {}, \"max_deflection\": {}, "
      "\"max_deflection_node\": {}, \"t_max_deflection\": {}, \"static_stiffness\": {}, \"balancer_mass\": {}, "
      "\"note\": {}, \"x_end\": {}}},\n",
      sys.nodes(), sys.spec.balancer_node, sys.state_size(), format_number(r.max_deflection, "max_deflection"),
      r.max_deflection_node, format_number(r.t_max_deflection, "t_max_deflection"),
      format_number(r.view.rotor.stiffness, "static stiffness"), format_number(r.view.rotor.mass, "balancer mass"),
      json_string("q and state_end are the balancer node's u1, u2 and the balls (model.md (2.2)); omega_n is "
                  "sqrt(static_stiffness / (balancer_mass + sum m_i)), the rigid estimate the stall test uses, not a "
                  "critical speed of the shaft; x_end is the whole state (u per node: u1, u2, psi1, psi2; beta; their "
                  "rates), model.md §18.16"),
      x_end);
  const std::size_t at = out.rfind("  \"units\"");
  out.insert(at == std::string::npos ? out.size() : at, block);
  return out;
}

std::string shaft_simulation_text(const ShaftSimulationResult& r, const ShaftSystem& sys, const SpeedProfile& speed) {
  std::string out = simulation_text(r.run, speed);
  out += fmt::format("  flexible shaft: {} nodes, {} states; |q| above is the balancer node's (node {})\n", sys.nodes(),
                     sys.state_size(), sys.spec.balancer_node);
  out += fmt::format("  largest node deflection: {:.6g} m at node {}, t = {:.6g} s\n", r.max_deflection,
                     r.max_deflection_node, r.t_max_deflection);
  return out;
}

}  // namespace abu
