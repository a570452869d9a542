// Running the analysis over parameter points: the per-point pipeline (equilibria +
// spectra) and one-parameter sweeps on a plain grid. Continuation (continuation.hpp)
// follows branches instead; maps cover two parameters.
//
//   abu::Analysis a = abu::analyze(p);                  // one parameter point
//   auto values = abu::grid_values(100, 2000, 190, false);
//   abu::SweepResult s = abu::sweep(p, *abu::parse_param("omega", 2), values);
#pragma once

#include <array>
#include <vector>

#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/spectrum.hpp"

namespace abu {

/// Every equilibrium of one parameter point with its spectrum (spectra[i] belongs to
/// equilibria.points()[i]).
struct Analysis {
  EquilibriumSet equilibria;
  std::array<Spectrum, 6> spectra{};
};

Analysis analyze(const Params& p, SpectrumMethod method = SpectrumMethod::refined);

/// steps + 1 values from `from` to `to` (both included exactly), evenly spaced, or
/// evenly spaced in log if `logarithmic`.
std::vector<double> grid_values(double from, double to, int steps, bool logarithmic);

struct SweepResult {
  ParamRef param;
  std::vector<double> values;
  std::vector<Analysis> points;  ///< one per value
};

/// The analysis at every value of one parameter, the others as in `base`.
SweepResult sweep(const Params& base, ParamRef param, const std::vector<double>& values);

}  // namespace abu
