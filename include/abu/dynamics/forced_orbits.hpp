// The non-balanced states on an anisotropic support (docs/model.md §10.14): each aligned
// equilibrium of the mean (isotropic) system becomes a pi/omega-periodic orbit of the
// rotating-frame system, which is non-autonomous. The orbit is continued from the
// equilibrium in the homotopy parameter delta of model/machine_field.hpp (delta = 0:
// the mean support, delta = 1: the scene's), by multiple shooting over the fixed period
// pi/omega with the project's pseudo-arclength engine, and its 2n + 4 Floquet multipliers
// come from the product of the short-interval transition matrices (linear/floquet.hpp).
//
// Unknowns (scaled, model.md (10.14.3)): the states y_1..y_M at t_j = (j - 1) pi/(omega M)
// (y = D^-1 x, D = diag(L, L, 1.., L omega, L omega, omega..)) and delta / delta_end.
// Equations: phi(t_j, t_j + h; y_j) - y_{j+1} = 0, cyclic. No phase condition and no
// trivial multiplier: the period is the forcing's, and a time shift of an orbit is not
// an orbit (the support turns in the rotating frame).
//
//   abu::ForcedOrbit o = abu::forced_orbit(p, support, aligned_equilibrium, {});
//   if (o.status.ok()) ... o.q_abs_max, o.multipliers, o.verdict ...
#pragma once

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "abu/continuation/arclength.hpp"
#include "abu/core/params.hpp"
#include "abu/core/status.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/model/machine_field.hpp"
#include "abu/model/unround_race.hpp"

namespace abu {

/// The machine at one value of a physical parameter: its parameters with the mean support
/// (k_bar, c_bar) and the race's paths at that value.
struct MachineAtValue {
  ParamsN params;
  RaceShape race;
};
/// The machine along the parameter. Called also a little beyond the interval's ends (a
/// continuation's predictor, a difference quotient): it must not refuse such values.
using MachineFamily = std::function<MachineAtValue(double value)>;

struct ForcedOrbitOptions {
  int intervals = 8;  ///< M shooting intervals per pi/omega; default 8
  /// Radau IIA steps per interval (model.md §10.18); doubled while the multipliers'
  /// discretization error exceeds `accuracy`, up to max_steps_per_interval. |q| and the ball
  /// angles are sampled at the step points. Defaults 16, 256.
  int steps_per_interval = 16;
  int max_steps_per_interval = 256;
  /// Target on the multipliers' discretization error (relative to max(|rho|, 1e-6), estimated
  /// by halving the steps); default 1e-10.
  double accuracy = 1e-10;
  double delta_end = 1.0;         ///< continue to this delta (1: the scene's support); default 1
  /// In delta / delta_end (the orbit moves O(|kappa| / |K|) per unit delta, scaled O(1)): a first step of 0.1,
  /// ds_min 1e-4 (a family that needs shorter steps is in trouble: stick-slip of coulomb balls), 400 attempts.
  ContinuationOptions continuation{0.1, 1e-4, 0.5, 400, 1};
};

struct ForcedOrbit {
  // The aligned equilibrium of the mean system it continues (model.md §13.2).
  Family family = Family::aligned;
  unsigned pattern = 0;
  int member = 1;
  std::string kind;  ///< e.g. "together 1", "aligned ++- 2"
  double delta = 0;  ///< the last delta reached (delta_end when converged)
  double period = 0;  ///< pi / omega [s]
  double q_abs_max = 0, q_abs_mean = 0;  ///< over the period [m] (rotating frame; fixed-frame whirl radius, §2)
  double q_abs_min = 0;                  ///< the least |q| over the period [m] (trigonometric interpolation, as q_abs_max)
  std::vector<double> ball_min, ball_max;  ///< range of each beta_i over the period [rad]
  /// All 2n + 4 multipliers over pi/omega, modulus descending; log_moduli keeps those below 1e-308.
  std::vector<std::complex<double>> multipliers;
  std::vector<double> log_moduli;
  std::vector<std::complex<double>> exponents;  ///< (omega/pi) ln rho [1/s, rotating frame], Im in (-omega, omega]
  /// The verdict: stable if ln max|rho| < -band, unstable if > band, else marginal;
  /// band = discretization_error + 64 eps M steps (model.md §10.18).
  Stability verdict = Stability::marginal;
  double band = 0;
  int steps_per_interval = 0;       ///< Radau steps per interval of the final discretization
  double discretization_error = 0;  ///< max |rho_S - rho_{S/2}| / max(|rho|, 1e-6) over the resolved multipliers
  /// The stiff multipliers (coulomb ball rates): their ln|rho| is the period average of the
  /// fast eigenvalues of J(x(t)) along the orbit, not the discrete map's (model.md §10.18).
  int unresolved_multipliers = 0;
  std::vector<double> state0;     ///< x(0) SI (model.md (2.2)): the orbit at t = 0
  double periodicity = 0;         ///< max |x(pi/omega) - x(0)| / D (scaled), integrated from state0 in one run
  Status status;                  ///< converged, or the kind of failure (see reason)
  std::string reason;             ///< where and why it failed; empty when converged
  long steps = 0, newton_iterations = 0;
  bool stable() const { return verdict == Stability::stable; }
};

/// Continues the aligned equilibrium `e` of `p` (which must carry the mean support
/// k_bar, c_bar; e an equilibrium of it with q != 0) to delta_end.
ForcedOrbit forced_orbit(const ParamsN& p, const AnisotropicSupport& support, const EquilibriumN& e,
                         const ForcedOrbitOptions& options = {});

/// The same from any equilibrium `start` (at rest, SI) of the machine at delta = 0 — the mean
/// support with `machine.race` (model.md §20: an equilibrium of the unround race, §11.4) —
/// labelled `kind`. `machine.support` must be set; its delta is ignored (the continuation's).
ForcedOrbit forced_orbit(const ParamsN& p, const RigidMachine& machine, const State<double, any_balls>& start,
                         std::string kind, const ForcedOrbitOptions& options = {});

/// The orbit of `machine` at delta_end near `guess` (an orbit of a neighbouring parameter value,
/// e.g. the previous value of a sweep, model.md §20.6): Newton on the shooting equations from
/// the states one run from guess.state0 reaches, with guess's step count, then the same
/// a-posteriori refinement as forced_orbit. status not converged (with the reason) where Newton
/// fails: the neighbouring orbit does not continue to this value within Newton's reach.
ForcedOrbit forced_orbit_near(const ParamsN& p, const RigidMachine& machine, const ForcedOrbit& guess, std::string kind,
                              const ForcedOrbitOptions& options = {});

}  // namespace abu
