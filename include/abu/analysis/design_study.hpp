// Design studies (docs/model.md §22): which balancer works. Design variables (the ball count,
// any scene parameter, the run-up rate and the hold) on a grid, then NLopt from the grid's best
// design; constraints from the linear analysis (a stable balanced state over a speed range at
// every unbalance of its range), from the machine (total ball mass, capacity over the
// unbalance) and from the runs (stalls); objectives from the outcome study (analysis/outcomes.hpp,
// the same starts and inputs for every design: common random numbers) or a design variable
// itself. The result states the recommended design, its figures, the binding constraint and
// how much better it is than the scene's own design.
//
//   abu::DesignOptions o;
//   o.variables = {abu::parse_design_variable("k=2000:12000:6")};
//   o.objective = abu::parse_design_objective("max:k");
//   o.constraints = {abu::parse_design_constraint("stable=300:2000")};
//   abu::DesignStudy s = abu::run_design_study(scene, speed, o);
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "abu/analysis/outcomes.hpp"
#include "abu/core/status.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/speed_profile.hpp"

namespace abu {

/// A design variable: a `--set` symbol, `n` (the ball count of a [balls] ring: every integer in
/// [low, high]), `alpha` (the run-up's acceleration, rad/s^2: the profile must be a ramp) or
/// `hold` (the time held after the speed change, s). `levels` grid values, evenly spaced
/// (`log`: in log), both ends included.
struct DesignVariable {
  std::string name;
  double low = 0, high = 0;
  int levels = 5;
  bool log = false;
  bool discrete() const { return name == "n"; }
  std::vector<double> grid() const;
};
/// "NAME=LOW:HIGH[:LEVELS[:log]]" (the --vary option). Throws InputError naming `origin`.
DesignVariable parse_design_variable(const std::string& text, const std::string& origin = "--vary");

/// What the study optimizes (docs/model.md §22.2).
struct DesignObjective {
  enum class Kind { below, median, p90, worst, maximize, minimize };
  Kind kind = Kind::below;
  std::string variable;  ///< maximize / minimize: a design variable's name
  bool needs_runs() const { return kind != Kind::maximize && kind != Kind::minimize; }
  bool larger_is_better() const { return kind == Kind::below || kind == Kind::maximize; }
};
/// "below" | "median" | "p90" | "worst" | "max:NAME" | "min:NAME". Throws InputError.
DesignObjective parse_design_objective(const std::string& text, const std::string& origin = "--objective");
std::string describe(const DesignObjective& o);

/// A constraint g <= 0 (docs/model.md §22.3).
struct DesignConstraint {
  enum class Kind {
    stable,    ///< the balanced state stable at every speed of [low, high] and every unbalance of U's range: g = max abscissa [1/s]
    capacity,  ///< sum m_i l_i >= value * U_max: g = value * U_max - capacity [kg m]
    mass,      ///< total ball mass <= value: g = mass - value [kg]
    stall,     ///< fraction of runs that stall <= value: g = fraction - value
  };
  Kind kind = Kind::stable;
  double value = 0, low = 0, high = 0;
  bool needs_runs() const { return kind == Kind::stall; }
};
/// "stable=W_LO:W_HI" | "capacity=FACTOR" | "mass=KG" | "stall=FRACTION". Throws InputError.
DesignConstraint parse_design_constraint(const std::string& text, const std::string& origin = "--constraint");
std::string describe(const DesignConstraint& c);

struct DesignOptions {
  std::vector<DesignVariable> variables;
  DesignObjective objective;
  std::vector<DesignConstraint> constraints;
  OutcomeOptions outcomes;  ///< samples, seed, design, uncertain inputs, limit, threads (the runs of every design)
  bool optimize = true;     ///< NLopt (COBYLA) from the grid's best design, per ball count
  int max_evaluations = 60; ///< of the optimizer, per ball count
  double xtol_rel = 1e-9;   ///< the optimizer's relative step tolerance on the continuous variables
  int speed_points = 41;    ///< speeds of the `stable` constraint's grid (log-spaced, both ends), then the worst refined
  /// Called after each design evaluated, with the designs evaluated, the grid's size and the runs so far.
  std::function<void(int designs, int grid, int runs)> progress;
};

/// One evaluated design.
struct DesignPoint {
  std::vector<double> values;     ///< per variable
  std::string origin;             ///< "scene", "grid" or "optimizer"
  bool feasible = false;
  std::vector<double> constraints;  ///< g_i, per constraint (<= 0 met)
  std::optional<double> objective;  ///< in the objective's own units (probability, m, or the variable's)
  std::optional<OutcomeSummary> outcomes;  ///< when the design was run
  double ball_mass = 0;           ///< total [kg]
  double capacity = 0;            ///< sum m_i l_i [kg m]
  std::string note;               ///< why not run, or infeasible
};

struct DesignStudy {
  Status status;
  std::vector<DesignPoint> points;  ///< the scene's own design first, then the grid, then the optimizer's
  int best = -1;                    ///< index of the recommended design (-1: none feasible)
  int baseline = 0;                 ///< the scene's own design
  std::string binding;              ///< the constraint that binds at the best (or "none")
  std::vector<int> pareto;          ///< feasible designs on the front of (objective, total ball mass)
  std::string speed;                ///< the profile, described
  double omega_final = 0;
  DesignOptions options;
  int runs = 0;                     ///< machine runs done
};

/// Runs the study (docs/model.md §22). Throws InputError before any run for an empty design
/// space, a variable the scene cannot take, a variable that is also uncertain, constraints no
/// design of the box can meet by the machine's own figures (mass, capacity) or by the linear
/// analysis on the grid, and a study too large for the memory; NotSupportedError as
/// analyze_outcomes.
DesignStudy run_design_study(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o);

/// The scene and speed profile of a design (its values applied in order, `n` first).
struct DesignedMachine {
  Scene scene;
  SpeedProfile speed;
  double t_end = 0;
};
DesignedMachine designed_machine(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o,
                                 const std::vector<double>& values);

/// The `stable` constraint's value (docs/model.md §22.3): the largest spectral abscissa of the
/// balanced states over the speeds of [low, high] and the unbalances of U's range [1/s]; +1e3
/// where no balanced state exists.
double balanced_abscissa_over(const Scene& scene, double low, double high, const std::vector<double>& unbalances,
                              int speed_points);

}  // namespace abu
