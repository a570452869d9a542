#include "abu/output/chart_labels.hpp"
#include "abu/model/shaft.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace abu {

double natural_frequency(const Scene& scene) {
  double mass = scene.rotor.mass;
  for (const auto& b : scene.balls) mass += b.mass;
  return std::sqrt(scene.rotor.stiffness / mass);
}

std::string format_omega_n(const Scene& scene) { return fmt::format("{}", natural_frequency(scene)); }

namespace {
// "m = 3.3e-05 kg" if every ball has the value, else "m = 3.3e-05 .. 4e-05 kg".
template <class Get>
std::string ball_range(const Scene& scene, const char* symbol, const char* unit, Get get) {
  double lo = get(scene.balls.front()), hi = lo;
  for (const auto& b : scene.balls) lo = std::min(lo, get(b)), hi = std::max(hi, get(b));
  const std::string u = *unit ? fmt::format(" {}", unit) : std::string();
  return lo == hi ? fmt::format("{} = {:.4g}{}", symbol, lo, u) : fmt::format("{} = {:.4g} .. {:.4g}{}", symbol, lo, hi, u);
}
}  // namespace

std::string chart_subtitle(const Scene& scene, const std::vector<std::string>& overrides) {
  std::string out;
  for (const auto& s : overrides) out += fmt::format("--set {}  ", s);
  if (!overrides.empty()) out += "|";
  const auto& r = scene.rotor;
  if (scene.shaft)  // the rotor's k, c, M_r are not used: the shaft's discs and bearings replace them (model.md §18.10)
    out += fmt::format("flexible shaft: {} nodes, {} bearings, balancer at node {}, U = {:.4g} kg m;  {} balls: ",
                       scene.shaft->nodes(), scene.shaft->bearings.size(), scene.shaft->balancer_node, r.unbalance,
                       scene.balls.size());
  else
    out += fmt::format("rotor M_r = {:.4g} kg, k = {:.4g} N/m, c = {:.4g} N s/m, U = {:.4g} kg m;  {} balls: ", r.mass,
                       r.stiffness, r.damping, r.unbalance, scene.balls.size());
  out += fmt::format("{}, {}", ball_range(scene, "m", "kg", [](const auto& b) { return b.mass; }),
                     ball_range(scene, "l", "m", [](const auto& b) { return b.race_radius; }));
  double capacity = 0;
  for (const auto& b : scene.balls) capacity += b.mass * b.race_radius;
  out += fmt::format(" (capacity sum m l = {:.4g} kg m)|friction {}", capacity, to_string(scene.law));
  switch (scene.law) {
    case FrictionLaw::none: break;
    case FrictionLaw::viscous:
      out += fmt::format(" {}", ball_range(scene, "d", "N s/m", [](const auto& b) { return b.d; }));
      break;
    case FrictionLaw::coulomb:
      out += fmt::format(" {}, kappa = {:.4g} s/rad", ball_range(scene, "mu", "", [](const auto& b) { return b.mu; }),
                         scene.kappa);
      break;
    case FrictionLaw::coulomb_set:
      out += fmt::format(" {} (set-valued)", ball_range(scene, "mu", "", [](const auto& b) { return b.mu; }));
      break;
    case FrictionLaw::stribeck:
      out += fmt::format(" {}, {}, v_s = {:.4g} rad/s, kappa = {:.4g} s/rad",
                         ball_range(scene, "mu_c", "", [](const auto& b) { return b.mu_c; }),
                         ball_range(scene, "mu_s", "", [](const auto& b) { return b.mu_s; }),
                         scene.balls.front().v_s, scene.kappa);
      break;
    case FrictionLaw::lugre:
      out += fmt::format(" {}, {}, {}, {}, {}, v_s = {:.4g} rad/s",
                         ball_range(scene, "sigma0", "1/rad", [](const auto& b) { return b.sigma0; }),
                         ball_range(scene, "sigma1", "s/rad", [](const auto& b) { return b.sigma1; }),
                         ball_range(scene, "sigma2", "s/rad", [](const auto& b) { return b.sigma2; }),
                         ball_range(scene, "mu_c", "", [](const auto& b) { return b.mu_c; }),
                         ball_range(scene, "mu_s", "", [](const auto& b) { return b.mu_s; }), scene.balls.front().v_s);
      break;
  }
  if (!scene.shaft)
    out += fmt::format(";  omega_n = sqrt(k / (M_r + sum m)) = {:.5g} rad/s ({:.5g} rpm)", natural_frequency(scene),
                       natural_frequency(scene) * 30 / 3.14159265358979323846);
  std::replace(out.begin(), out.end(), '\'', '"');
  return out;
}

}  // namespace abu
