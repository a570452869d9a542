// The Campbell samples of an anisotropic omega sweep (docs/model.md §10.15).
#include "abu/output/report_campbell_aniso.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include "abu/linear/floquet_modes.hpp"
#include "equilibrium_text.hpp"

namespace abu {

std::vector<CampbellSample> floquet_campbell_samples(const FloquetSweep& s, const ParamsN& base,
                                                     const AnisotropicSupport& support) {
  std::vector<CampbellSample> out;
  if (s.param.quantity != Quantity::omega) return out;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    ParamsN p = base;
    set(p, s.param, s.values[i]);
    const FloquetAnalysis& a = s.points[i];
    for (std::size_t k = 0; k < a.balanced.size(); ++k) {
      const EquilibriumN& e = a.balanced[k];
      FloquetModes m = floquet_mode_views(p, support, e);
      if (!m.status.ok())
        throw NumericalError(fmt::format("omega={}: Campbell view of {}: {} (N = {})", s.values[i],
                                         detail::state_label(e), m.status.reason, m.harmonics));
      CampbellSample c;
      c.step = int(i);
      c.omega = p.omega;
      c.omega_n = natural_frequency(p);  // sqrt(k_bar / M)
      c.family = std::string(to_string(e.family));
      c.pattern = detail::pattern_of(e);
      c.member = e.member;
      c.stable = a.floquet[k].verdict == Stability::stable;
      c.series = detail::state_label(e);
      c.modes = std::move(m.modes);
      out.push_back(std::move(c));
    }
  }
  // Contiguous series (critical speeds are per series): stable sort keeps the speeds in order.
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.series < b.series; });
  return out;
}

std::string floquet_campbell_note(const AnisotropicSupport& support, const ParamsN& base) {
  const double M = base.total_mass();
  const double k1 = support.mean_stiffness() + support.stiffness_anisotropy();
  const double k2 = support.mean_stiffness() - support.stiffness_anisotropy();
  return fmt::format(
      "# anisotropic support (docs/model.md §10.15): the modes are the balanced states' Floquet modes over pi/omega "
      "(Hill's method); re_rotating, im_rotating = the Floquet exponent lambda [1/s, rotating frame], Im in [0, "
      "omega] (lambda is defined modulo 2 i omega);\n"
      "#   a mode's fixed-frame motion has the lines +-(Im lambda + omega + 2 k omega), k integer (10.15.2); "
      "whirl_frequency is the line pair with the largest mass-weighted amplitude, its sign that of the stronger "
      "line of the pair (ties forward); omega_n = sqrt(k_bar/M) with k_bar = (k_x + k_y)/2;\n"
      "#   the support's principal critical speeds sqrt((k_bar -+ |kappa|)/M) = {:.9g}, {:.9g} rad/s (M = M_r + "
      "sum m_i = {:.9g} kg): the rotor modes' whirl frequencies at low speed when the balls are light\n",
      std::sqrt(k2 / M), std::sqrt(k1 / M), M);
}

}  // namespace abu
