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

/// Lines separated by '|' (the chart scripts break them there): every --set as typed;
/// M_r k c U and the balls (count, m l, one value if all balls share it, the capacity);
/// the friction law and its coefficients, omega_n. No single quote (gnuplot variables
/// are single-quoted strings).
std::string chart_subtitle(const Scene& scene, const std::vector<std::string>& overrides);

}  // namespace abu
