// Reports of the balanced states' Floquet stability on an anisotropic support
// (docs/model.md §10.5, §10.6).
#include "abu/output/report_floquet.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include "abu/output/format.hpp"

namespace abu {

namespace {

constexpr std::string_view kOrbitsNote =
    "the mean system's other equilibria become pi/omega-periodic orbits on an anisotropic support "
    "(docs/model.md §10.3); --no-periodic-orbits asked not to compute them (model.md §10.14), so none is reported";

}  // namespace

std::string floquet_table(const FloquetAnalysis& a, const ParamsN& p, const AnisotropicSupport& support) {
  std::string out = fmt::format("anisotropic support: {}\n", describe_support(support));
  out += fmt::format("omega = {} rad/s; the rotating-frame system is periodic with pi/omega = {:.6g} s: stability "
                     "from Floquet multipliers rho (|rho| < 1 decays), exponents lambda = (omega/pi) ln rho [1/s, "
                     "rotating frame, Im modulo 2 omega]\n\n",
                     p.omega, std::numbers::pi / p.omega);
  if (a.balanced.empty()) out += "no balanced state (the balls cannot cancel U, model.md §5/§13.4)\n";
  for (std::size_t i = 0; i < a.balanced.size(); ++i) {
    const EquilibriumN& e = a.balanced[i];
    const BalancedFloquet& f = a.floquet[i];
    out += fmt::format("balanced {}: beta =", e.member);
    for (Eigen::Index k = 2; k < e.position.size(); ++k) out += fmt::format(" {:.6f}", double(e.position(k)));
    out += fmt::format(" rad; {} (max |rho| = {:.12f}, decay rate {:.6g} 1/s)", to_string(f.verdict), f.max_modulus,
                       f.abscissa);
    if (f.deflated) out += fmt::format("; {} unit multiplier(s) along the balanced set deflated", f.deflated);
    out += fmt::format("\n  Hill N = {}, Magnus cross-check {:.2g}\n  {:>20}  {:>15}  {:>14}  {:>14}\n", f.harmonics,
                       f.monodromy_deviation, "|rho|", "arg rho [rad]", "Re lambda", "Im lambda");
    for (std::size_t k = 0; k < f.multipliers.size(); ++k)
      out += fmt::format("  {:>20.12e}  {:>15.10f}  {:>14.6g}  {:>14.6g}\n", std::abs(f.multipliers[k]),
                         std::arg(f.multipliers[k]), f.exponents[k].real(), f.exponents[k].imag());
  }
  if (a.periodic_orbits_not_computed > 0)
    out += fmt::format("\n{} other state(s): {}\n", a.periodic_orbits_not_computed, kOrbitsNote);
  return out;
}

std::string floquet_csv(const FloquetAnalysis& a, const ParamsN& p, const std::string& header) {
  std::string out = header;
  if (a.periodic_orbits_not_computed > 0)
    out += fmt::format("# anisotropic support: balanced states only; {} other state(s): {}\n",
                       a.periodic_orbits_not_computed, kOrbitsNote);
  const int n = p.n_balls();
  out += "state,member";
  for (int k = 1; k <= n; ++k) out += fmt::format(",beta{}", k);
  out += ",stability,max_modulus,decay_rate,deflated,harmonics,cross_check";
  const std::size_t count = a.floquet.empty() ? 0 : a.floquet.front().multipliers.size();
  for (std::size_t k = 1; k <= count; ++k) out += fmt::format(",rho{}_re,rho{}_im", k, k);
  out += "\n";
  for (std::size_t i = 0; i < a.balanced.size(); ++i) {
    const EquilibriumN& e = a.balanced[i];
    const BalancedFloquet& f = a.floquet[i];
    out += fmt::format("balanced,{}", e.member);
    for (Eigen::Index k = 2; k < e.position.size(); ++k) out += fmt::format(",{}", double(e.position(k)));
    out += fmt::format(",{},{},{},{},{},{}", to_string(f.verdict), f.max_modulus, f.abscissa, f.deflated, f.harmonics,
                       f.monodromy_deviation);
    for (const auto& rho : f.multipliers) out += fmt::format(",{},{}", rho.real(), rho.imag());
    out += "\n";
  }
  return out;
}

std::string floquet_json(const FloquetAnalysis& a, const ParamsN& p, const AnisotropicSupport& s,
                         std::string_view command_line, std::string_view scene_file,
                         std::string_view periodic_orbits) {
  std::string out = "{\n";
  out += fmt::format("  \"command\": {},\n  \"scene\": {},\n  \"balls\": {},\n  \"omega\": {},\n", json_string(command_line),
                     json_string(scene_file), p.n_balls(), p.omega);
  out += fmt::format(
      "  \"support\": {{\"frame\": \"fixed\", \"stiffness\": [[{}, {}], [{}, {}]], \"damping\": [[{}, {}], [{}, {}]], "
      "\"mean_stiffness\": {}, \"mean_damping\": {}, \"units\": \"N/m, N s/m\"}},\n",
      s.k_x, s.k_xy, s.k_xy, s.k_y, s.c_x, s.c_xy, s.c_xy, s.c_y, s.mean_stiffness(), s.mean_damping());
  out += fmt::format("  \"period\": {},\n  \"units\": {},\n", std::numbers::pi / p.omega,
                     json_string("beta [rad]; floquet_multipliers [re, im] over pi/omega, dimensionless, sorted by "
                                 "modulus descending; floquet_exponents [re, im] 1/s, rotating frame, im modulo 2 "
                                 "omega; decay_rate = (omega/pi) ln max |rho| [1/s]"));
  out += "  \"balanced_states\": [";
  for (std::size_t i = 0; i < a.balanced.size(); ++i) {
    const EquilibriumN& e = a.balanced[i];
    const BalancedFloquet& f = a.floquet[i];
    out += i ? ",\n    {" : "\n    {";
    out += fmt::format("\"member\": {}, \"on_balanced_set\": {}, \"beta\": [", e.member, e.on_balanced_set);
    for (Eigen::Index k = 2; k < e.position.size(); ++k) out += fmt::format("{}{}", k > 2 ? ", " : "", double(e.position(k)));
    out += fmt::format("], \"residual\": {}, \"stability\": \"{}\", \"max_modulus\": {}, \"decay_rate\": {}, "
                       "\"band\": {}, \"deflated_unit_multipliers\": {}, \"hill_harmonics\": {}, "
                       "\"magnus_cross_check\": {},\n     \"floquet_multipliers\": [",
                       e.residual, to_string(f.verdict), f.max_modulus, f.abscissa, f.band, f.deflated, f.harmonics,
                       f.monodromy_deviation);
    for (std::size_t k = 0; k < f.multipliers.size(); ++k)
      out += fmt::format("{}[{}, {}]", k ? ", " : "", f.multipliers[k].real(), f.multipliers[k].imag());
    out += "],\n     \"floquet_exponents\": [";
    for (std::size_t k = 0; k < f.exponents.size(); ++k)
      out += fmt::format("{}[{}, {}]", k ? ", " : "", f.exponents[k].real(), f.exponents[k].imag());
    out += "]}";
  }
  out += a.balanced.empty() ? "],\n" : "\n  ],\n";
  if (!periodic_orbits.empty()) return out + fmt::format("  {}\n}}\n", periodic_orbits);
  out += fmt::format("  \"periodic_orbits\": {{\"count\": {}, \"computed\": false, \"note\": {}}}\n}}\n",
                     a.periodic_orbits_not_computed, json_string(kOrbitsNote));
  return out;
}

}  // namespace abu
