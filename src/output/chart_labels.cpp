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
// What the chart varies, by the symbols the subtitle shows.
class Varied {
 public:
  Varied(const std::vector<ChartAxis>& axes, const Scene& scene) : axes_(axes) {
    for (const auto& b : scene.balls) derived_ |= b.specified;
  }
  // "varies", "follows r", or empty (the scene's value holds on the whole chart). m, mu and l
  // follow a varied r, rho, f or R_s only where a ball is given through them (model.md §1.1).
  std::string of(std::string_view symbol) const {
    const std::uint8_t bit = symbol == "m" ? specified::density : symbol == "mu" ? specified::rolling_length
                             : symbol == "l"                    ? specified::surface_radius
                                                                : 0;
    for (const auto& a : axes_) {
      const std::string base = a.name.substr(0, a.name.find_last_not_of("0123456789") + 1);
      if (base == symbol) return a.name == symbol ? "varies" : fmt::format("{} varies", a.name);
      const std::uint8_t moves = base == "r"     ? specified::density | specified::rolling_length | specified::surface_radius
                                 : base == "rho" ? specified::density
                                 : base == "f"   ? specified::rolling_length
                                 : base == "R_s" ? specified::surface_radius
                                                 : 0;
      if (bit & moves & derived_) return "follows " + a.name;
    }
    return {};
  }
  // "varies: omega = 100 .. 1000 rad/s (x axis)|", or empty.
  std::string line() const {
    std::string out;
    for (const auto& a : axes_)
      out += fmt::format("{}{} = {:.6g} .. {:.6g}{} ({})", out.empty() ? "varies: " : ";  ", a.name, a.from, a.to,
                         a.unit.empty() || a.unit == "-" ? std::string() : " " + a.unit, a.axis);
    return out.empty() ? out : out + "|";
  }

 private:
  const std::vector<ChartAxis>& axes_;
  std::uint8_t derived_ = 0;  // the specified bits of any ball
};

// "m = 3.3e-05 kg" if every ball has the value, else "m = 3.3e-05 .. 4e-05 kg"; "m varies".
template <class Get>
std::string ball_range(const Scene& scene, const Varied& varied, const char* symbol, const char* unit, Get get) {
  if (const std::string v = varied.of(symbol); !v.empty()) return fmt::format("{} {}", symbol, v);
  double lo = get(scene.balls.front()), hi = lo;
  for (const auto& b : scene.balls) lo = std::min(lo, get(b)), hi = std::max(hi, get(b));
  const std::string u = *unit ? fmt::format(" {}", unit) : std::string();
  return lo == hi ? fmt::format("{} = {:.4g}{}", symbol, lo, u) : fmt::format("{} = {:.4g} .. {:.4g}{}", symbol, lo, hi, u);
}
// "k = 7500 N/m", or "k varies".
std::string global(const Varied& varied, const char* symbol, double value, const char* unit) {
  if (const std::string v = varied.of(symbol); !v.empty()) return fmt::format("{} {}", symbol, v);
  return fmt::format("{} = {:.4g}{}{}", symbol, value, *unit ? " " : "", unit);
}
}  // namespace

std::string chart_subtitle(const Scene& scene, const std::vector<std::string>& overrides,
                           const std::vector<ChartAxis>& varies) {
  const Varied varied(varies, scene);
  std::string out = varied.line();
  for (const auto& s : overrides) out += fmt::format("--set {}  ", s);
  if (!overrides.empty()) out += "|";
  const auto& r = scene.rotor;
  const std::string balls = varied.of("n").empty() ? fmt::format("{} balls", scene.balls.size()) : "n balls (varies)";
  if (scene.shaft)  // the rotor's k, c, M_r are not used: the shaft's discs and bearings replace them (model.md §18.10)
    out += fmt::format("flexible shaft: {} nodes, {} bearings, balancer at node {}, {};  {}: ", scene.shaft->nodes(),
                       scene.shaft->bearings.size(), scene.shaft->balancer_node,
                       global(varied, "U", r.unbalance, "kg m"), balls);
  else
    out += fmt::format("rotor {}, {}, {}, {};  {}: ", global(varied, "M_r", r.mass, "kg"),
                       global(varied, "k", r.stiffness, "N/m"), global(varied, "c", r.damping, "N s/m"),
                       global(varied, "U", r.unbalance, "kg m"), balls);
  // Over the ball count a [balls] ring holds either each ball's mass or their total (docs/cli.md, Scene files).
  const bool count_varies = !varied.of("n").empty();
  const bool total_held = count_varies && scene.ring && scene.ring->total_mass_held;
  const std::string mass = total_held ? fmt::format("m = sum m / n (sum m = {:.4g} kg held)", scene.ring->total_mass)
                                      : ball_range(scene, varied, "m", "kg", [](const auto& b) { return b.mass; });
  out += fmt::format("{}, {}", mass, ball_range(scene, varied, "l", "m", [](const auto& b) { return b.race_radius; }));
  double capacity = 0;
  for (const auto& b : scene.balls) capacity += b.mass * b.race_radius;
  const bool capacity_varies =
      !varied.of("m").empty() || !varied.of("l").empty() || (count_varies && !total_held);
  out += capacity_varies ? std::string(" (capacity sum m l varies)")
                         : fmt::format(" (capacity sum m l = {:.4g} kg m)", capacity);
  out += fmt::format("|friction {}", to_string(scene.law));
  const auto kappa = [&] { return global(varied, "kappa", scene.kappa, "s/rad"); };
  switch (scene.law) {
    case FrictionLaw::none: break;
    case FrictionLaw::viscous:
      out += fmt::format(" {}", ball_range(scene, varied, "d", "N s/m", [](const auto& b) { return b.d; }));
      break;
    case FrictionLaw::coulomb:
      out += fmt::format(" {}, {}", ball_range(scene, varied, "mu", "", [](const auto& b) { return b.mu; }), kappa());
      break;
    case FrictionLaw::coulomb_set:
      out += fmt::format(" {} (set-valued)", ball_range(scene, varied, "mu", "", [](const auto& b) { return b.mu; }));
      break;
    case FrictionLaw::stribeck:
      out += fmt::format(" {}, {}, {}, {}",
                         ball_range(scene, varied, "mu_c", "", [](const auto& b) { return b.mu_c; }),
                         ball_range(scene, varied, "mu_s", "", [](const auto& b) { return b.mu_s; }),
                         ball_range(scene, varied, "v_s", "rad/s", [](const auto& b) { return b.v_s; }), kappa());
      break;
    case FrictionLaw::lugre:
      out += fmt::format(" {}, {}, {}, {}, {}, {}",
                         ball_range(scene, varied, "sigma0", "1/rad", [](const auto& b) { return b.sigma0; }),
                         ball_range(scene, varied, "sigma1", "s/rad", [](const auto& b) { return b.sigma1; }),
                         ball_range(scene, varied, "sigma2", "s/rad", [](const auto& b) { return b.sigma2; }),
                         ball_range(scene, varied, "mu_c", "", [](const auto& b) { return b.mu_c; }),
                         ball_range(scene, varied, "mu_s", "", [](const auto& b) { return b.mu_s; }),
                         ball_range(scene, varied, "v_s", "rad/s", [](const auto& b) { return b.v_s; }));
      break;
  }
  constexpr double rpm_per_rad_s = 30 / 3.14159265358979323846;
  out += varied.of("omega").empty()
             ? fmt::format(";  speed omega = {:.6g} rad/s ({:.6g} rpm)", scene.omega, scene.omega * rpm_per_rad_s)
             : std::string(";  speed omega varies");
  const bool omega_n_varies = !varied.of("k").empty() || !varied.of("M_r").empty() || !varied.of("m").empty() ||
                              (count_varies && !total_held);
  if (!scene.shaft)
    out += omega_n_varies ? std::string(", omega_n varies")
                          : fmt::format(", omega_n = sqrt(k / (M_r + sum m)) = {:.5g} rad/s ({:.5g} rpm)",
                                        natural_frequency(scene), natural_frequency(scene) * rpm_per_rad_s);
  std::replace(out.begin(), out.end(), '\'', '"');
  return out;
}

}  // namespace abu
