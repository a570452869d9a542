// What a chart says about the scene it was drawn from: a subtitle with the key parameters
// and every --set, and the rotor's natural frequency to mark on speed axes.
//
//   run_gnuplot(script, {..., {"subtitle", abu::chart_subtitle(scene, overrides)},
//                             {"omega_n", abu::format_omega_n(scene)}});
#pragma once

#include <string>
#include <vector>

#include "abu/input/scene.hpp"

namespace abu {

/// omega_n = sqrt(k / (M_r + sum m_i)) [rad/s], the rotor's natural frequency with the
/// balls' mass (docs/model.md §5; it moves when the ball mass changes).
double natural_frequency(const Scene& scene);
/// natural_frequency in shortest round-trip form, for a gnuplot variable.
std::string format_omega_n(const Scene& scene);

/// A quantity a chart varies along one of its axes: the subtitle names its range there instead
/// of the scene's value.
struct ChartAxis {
  std::string name;  ///< as typed: omega, mu, mu1, m, r, n (the ball count), unroundness, ...
  double from = 0, to = 0;
  std::string unit;  ///< empty or "-": none
  std::string axis = "x axis";
};

/// Lines separated by '|' (the chart scripts break them there): what varies and over which
/// range (`varies`); every --set as typed; M_r k c U and the balls (count, m l, one value if all
/// balls share it, the capacity); the friction law and its coefficients; the speed and omega_n.
/// A quantity that varies is written "varies", one that follows it (m, l, mu through r, rho, f
/// or R_s, model.md §1.1) "follows NAME", never the scene's value. No single quote (gnuplot
/// variables are single-quoted strings).
std::string chart_subtitle(const Scene& scene, const std::vector<std::string>& overrides,
                           const std::vector<ChartAxis>& varies = {});

}  // namespace abu
