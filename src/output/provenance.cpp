// Provenance headers (provenance.hpp).
#include "abu/output/provenance.hpp"

#include <fmt/format.h>

#include "abu/output/format.hpp"

namespace abu {

template <int N>
std::string describe_parameters(const ParamsT<double, N>& p) {
  std::string s = fmt::format("M_r={} k={} c={} U={} omega={} law={}", p.rotor.mass, p.rotor.stiffness,
                              p.rotor.damping, p.rotor.unbalance, p.omega, to_string(p.law));
  if (p.law == FrictionLaw::coulomb || p.law == FrictionLaw::stribeck) s += fmt::format(" kappa={}", p.kappa);
  for (std::size_t i = 0; i < p.balls.size(); ++i) {
    const auto& b = p.balls[i];
    const auto n = i + 1;
    s += fmt::format(" m{}={} l{}={} r{}={} j{}={}", n, b.mass, n, b.race_radius, n, b.radius, n, b.inertia_factor);
    if (b.specified & specified::density) s += fmt::format(" rho{}={}", n, b.density);
    if (b.specified & specified::surface_radius) s += fmt::format(" R_s{}={}", n, b.surface_radius);
    switch (p.law) {
      case FrictionLaw::none: break;
      case FrictionLaw::viscous: s += fmt::format(" d{}={}", n, b.d); break;
      case FrictionLaw::coulomb:
      case FrictionLaw::coulomb_set:
        s += fmt::format(" mu{}={}", n, b.mu);
        if (b.specified & specified::rolling_length) s += fmt::format(" f{}={}", n, b.rolling_length);
        break;
      case FrictionLaw::stribeck:
        s += fmt::format(" mu_c{}={} mu_s{}={} v_s{}={}", n, b.mu_c, n, b.mu_s, n, b.v_s);
        break;
      case FrictionLaw::lugre:
        s += fmt::format(" sigma0_{}={} sigma1_{}={} sigma2_{}={} mu_c{}={} mu_s{}={} v_s{}={}", n, b.sigma0, n,
                         b.sigma1, n, b.sigma2, n, b.mu_c, n, b.mu_s, n, b.v_s);
        break;
    }
  }
  return s;
}

template <int N>
std::string describe_specification(const ParamsT<double, N>& p) {
  std::string s;
  for (std::size_t i = 0; i < p.balls.size(); ++i) {
    const auto& b = p.balls[i];
    const auto n = i + 1;
    auto add = [&](const std::string& text) {
      if (!s.empty()) s += ' ';
      s += text;
    };
    if (b.specified & specified::density) add(fmt::format("m{}=rho{}*pi*(2*r{})^3/6={} kg", n, n, n, b.mass));
    if (b.specified & specified::rolling_length) add(fmt::format("mu{}=f{}/r{}={}", n, n, n, b.mu));
    if (b.specified & specified::surface_radius) add(fmt::format("l{}=R_s{}-r{}={} m", n, n, n, b.race_radius));
  }
  return s;
}

template <int N>
std::string provenance_header(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p) {
  const double M = p.total_mass();
  std::string out = fmt::format(
      "# stability-scan {} (abu-stability)\n# command: {}\n# scene: {}\n# parameters (SI): {}\n"
      "# derived: M={} kg, omega_n=sqrt(k/M)={} rad/s\n",
      ABU_VERSION, escaped(command_line), escaped(scene_file), describe_parameters(p), M, std::sqrt(p.rotor.stiffness / M));
  if (const std::string spec = describe_specification(p); !spec.empty())
    out += fmt::format("# derived from the specification (model.md §1.1): {}\n", spec);
  return out;
}

template std::string describe_parameters<2>(const Params&);
template std::string describe_parameters<any_balls>(const ParamsN&);
template std::string describe_specification<2>(const Params&);
template std::string describe_specification<any_balls>(const ParamsN&);
template std::string provenance_header<2>(std::string_view, std::string_view, const Params&);
template std::string provenance_header<any_balls>(std::string_view, std::string_view, const ParamsN&);

}  // namespace abu
