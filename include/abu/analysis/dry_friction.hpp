// Dry friction as it is, next to a smooth coulomb or stribeck law (docs/model.md §14.10): the
// smooth laws regularize the stick (arctan in kappa); their verdict is that of creeping balls.
// The set-valued law with the same coefficients (stribeck: the breakaway level mu_s) says where
// the balls really stop, and the worst vibration they leave there.
//
//   abu::DryFrictionVerdict d = abu::dry_friction_verdict(p);   // p: a coulomb scene
//   if (d.set) ... d.set->worst_q_abs, d.set->area ...
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>

#include "abu/continuation/branches_n.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/equilibria/shaft_stick_set.hpp"
#include "abu/equilibria/stick_set.hpp"

namespace abu {

struct DryFrictionVerdict {
  bool applies = false;         ///< the law is coulomb or stribeck
  std::string which;            ///< "the same mu_i" (coulomb) or "mu_i = mu_s" (stribeck)
  std::optional<StickSet> set;  ///< the stick set; absent where it is not defined
  std::string not_defined;      ///< why not (the set's NotSupportedError), when absent
  /// On a flexible shaft (model.md §18.17): the set of the rigid balancer the balls see through
  /// the shaft's receptance, and the shaft's figures of it.
  std::optional<ShaftStickFigures> shaft;
};

/// What a verdict leaves, as the figures a row of a sweep or a branch carries (model.md §14.10).
struct DryFigures {
  bool defined = false;           ///< the set is defined (mu_i > 0, K, C not both 0) and computed
  bool balanced_exists = false;   ///< a balanced point lies in the set (else V is not defined)
  double worst_q_abs = 0.0;       ///< V: max |q| over the components holding a balanced point [m]
  double whole_set_q_abs = 0.0;   ///< V_E: max |q| over the whole set [m]
  double bare_rotor_q_abs = 0.0;  ///< the rotor without balls at this speed [m]
  double area_fraction = 0.0;     ///< the set's share of the torus of arrangements
};
DryFigures dry_figures(const DryFrictionVerdict& d);

/// When a sweep's or a branch's rows carry the dry figures: always, never, or (automatic) when
/// few of the values need a scan of the torus — a set that the bound (14.10.1) shows to be the
/// whole torus is free, any other costs 0.3–2 s (two balls) or 0.2–1.5 s (3–12 balls; model.md
/// §14.10), which for many values would dwarf the study itself.
enum class DryRows { automatic, on, off };
/// The most values needing a scan that `automatic` computes: about half a minute at most.
inline constexpr std::size_t kDryAutomaticScans = 24;
inline constexpr std::size_t kDryAutomaticScansN = 12;  ///< 3 to 12 balls
struct DryRequest {
  DryRows rows = DryRows::automatic;
  StickSetOptions stick;  ///< the sets' resolution
  int threads = 1;        ///< the values shared among them, 0 one per core (the same figures on any number)
};

/// The dry figures along one parameter of a smooth `coulomb` / `stribeck` scene, each distinct
/// value's set once (a branch's rows repeat values); `skipped` when the law has them but the
/// request leaves them out (then `values` and `scans` say how many there were).
using DryFiguresAlong = std::map<double, DryFigures>;
struct DryAlong {
  DryFiguresAlong figures;  ///< empty: not computed
  std::string which;        ///< dry_coefficients of the law; empty: the law has no dry verdict
  std::size_t values = 0;   ///< distinct values
  std::size_t scans = 0;    ///< of them, the sets the bound (14.10.1) does not decide
  std::size_t scan_limit = 0;  ///< what `automatic` computes at most
  bool computed() const { return !figures.empty(); }
  bool skipped() const { return !which.empty() && figures.empty(); }
};
/// At `values[k]` the scene `params[k]` (a sweep's values, any parameter or the ball count).
DryAlong dry_figures_along(std::span<const double> values, std::span<const ParamsN> params,
                           const DryRequest& request = {});
/// `smooth` with `param` set to each value.
DryAlong dry_figures_along(const ParamsN& smooth, ParamRef param, std::span<const double> values,
                           const DryRequest& request = {});
/// The same at every row's parameter value of a continuation run (its special rows included:
/// pass the run with_special_rows gives).
DryAlong dry_figures_along(const Params& smooth, const ContinuationRun& run, const DryRequest& request = {});
DryAlong dry_figures_along(const ParamsN& smooth, const ContinuationRunN& run, const DryRequest& request = {});
/// Whether `law` has a resting counterpart whose stick set the dry verdict is (coulomb, stribeck).
bool has_dry_verdict(FrictionLaw law);
/// The resting law's coefficients in words ("the same mu_i", "mu_i = mu_s"); empty without one.
std::string dry_coefficients(FrictionLaw law);

/// The stick set of coulomb-set friction with the smooth law's coefficients (no boundary
/// tracing: the verdict needs the area and the worst vibration only), on the race's paths when
/// `race` is unround (model.md §20.5). Empty (applies = false) for the other laws.
DryFrictionVerdict dry_friction_verdict(const ParamsN& smooth, const StickSetOptions& options = {},
                                        const RaceShape* race = nullptr);
/// The same for the balls of a flexible shaft (model.md §18.17): the set through the shaft's
/// receptance, not defined at an undamped critical speed.
DryFrictionVerdict dry_friction_verdict(const ShaftSystem& smooth, const StickSetOptions& options = {});

}  // namespace abu
