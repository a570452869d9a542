// Running the analysis over parameter points: the per-point pipeline (equilibria +
// spectra) and one-parameter sweeps on a plain grid. Continuation (continuation.hpp)
// follows branches instead; maps cover two parameters.
//
//   abu::Analysis a = abu::analyze(p);                  // one parameter point (two balls)
//   abu::AnalysisN an = abu::analyze(pn);               // any number of balls
//   auto values = abu::grid_values(100, 2000, 190, false);
//   abu::SweepResult s = abu::sweep(p, *abu::parse_param("omega", 2), values);
#pragma once

#include <array>
#include <vector>

#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/spectrum.hpp"

namespace abu {

/// Every equilibrium of one parameter point with its spectrum (spectra[i] belongs to
/// equilibria.points()[i]).
struct Analysis {
  EquilibriumSet equilibria;
  std::array<Spectrum, 6> spectra{};
};

Analysis analyze(const Params& p, SpectrumMethod method = SpectrumMethod::refined);

/// The same for any number of balls (spectra[i] belongs to equilibria.points()[i]).
struct AnalysisN {
  EquilibriumSetN equilibria;
  std::vector<SpectrumN> spectra;
  /// representative[i]: the equilibrium whose spectrum spectra[i] copies (model.md §13.9:
  /// equal balls' permutation images; i itself where computed), always <= i. Anything
  /// computed from a spectrum and invariant under permuting equal balls can be shared too.
  std::vector<int> representative;
  double capacity = 0;   ///< sum m_i l_i [kg m], what the balls can cancel
  double unbalance = 0;  ///< U [kg m]
};
AnalysisN analyze(const ParamsN& p, const BalancedSampling& sampling = {},
                  SpectrumMethod method = SpectrumMethod::refined);

/// Spectrum at an equilibrium (linearized in long double at its exact position); on the
/// balanced set of n >= 3 balls the tangent directions are deflated (structural zeros,
/// normal stability: spectrum.hpp, compute_normal_spectrum).
Spectrum equilibrium_spectrum(const Params& p, const Equilibrium& e, SpectrumMethod method = SpectrumMethod::refined);
SpectrumN equilibrium_spectrum(const ParamsN& p, const EquilibriumN& e, SpectrumMethod method = SpectrumMethod::refined);

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

/// What a two-ball sweep of `values` values and its CSV and Campbell text hold [bytes], an
/// upper bound: twice an Analysis (its own size and what it holds) and twice the ~12.5 kB of
/// text a value writes (the text grows by doubling), plus 20 MB. Measured 28 kB a value
/// (5,000 and 40,000 values of the default scene, /usr/bin/time) against 37 kB.
double sweep_memory_estimate(std::size_t values);

}  // namespace abu
