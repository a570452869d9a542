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

/// What a two-ball sweep of `values` values holds [bytes], an upper bound, its rows streamed
/// (output/sweep_stream.hpp): over omega, what a value keeps for the Campbell view (six
/// equilibria's samples and their text), bounded by twice an Analysis and 25 kB; over another
/// parameter 2 kB (its comments and stability flags); plus 20 MB. Measured (/usr/bin/time,
/// default scene): 5,001 values over omega 110 MB (22 kB a value); 100,001 over mu 12 MB.
double sweep_memory_estimate(std::size_t values, bool omega);

}  // namespace abu
