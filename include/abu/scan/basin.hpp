// Basins of attraction (model.md §15.5): from a grid of initial ball positions (rotor at
// rest, balls at rest in the rotor frame) every cell's trajectory is integrated until it
// enters the neighbourhood of a stable equilibrium of the final speed (the settle test),
// or to t_end, and classified by what it ended in (the outcomes of model.md §15.2).
//
// The grid: ball 1 x ball 2 over [0, 2 pi)^2, cells1 x cells2 cells, beta = 2 pi k / cells;
// balls 3..n (if any) start at the fixed angles `fixed`. Tiles are whole columns (one
// beta1 value each) and go through the map's TileStore (map_driver.hpp), so a basin is
// threaded, resumable and locked like a map, with the same bytes whatever the thread count.
//
//   abu::BasinJob job;  job.params = p;  job.speed = abu::SpeedProfile::constant(400);
//   job.sim.t_end = 20;  job.cells1 = job.cells2 = 16;
//   const auto targets = abu::basin_targets(job);
//   abu::BasinCell c = abu::compute_basin_cell(job, targets, 3, 5);   // beta = (3, 5) * 2 pi / 16
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "abu/core/params.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/model/anisotropic_support.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/model/speed_profile.hpp"
#include "abu/linear/unround_spectrum.hpp"
#include "abu/model/unround_race.hpp"
#include "abu/scan/basin_certificate.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

struct BasinJob {
  Params params;            ///< two balls (any_balls false)
  ParamsN params_n;         ///< n >= 3 balls (any_balls true)
  bool any_balls = false;
  SpeedProfile speed;       ///< constant or a run-up; the attractors are those of its final speed
  SimulationOptions sim;    ///< t_end, every (the settle test looks at every sample), rtol, method
  int cells1 = 24, cells2 = 24;  ///< grid of beta1 x beta2 over [0, 2 pi)^2
  std::vector<double> fixed;     ///< start angles of balls 3..n [rad] (every cell; empty: `others`)
  /// Start angles of balls 3..n per cell when `fixed` is empty (n >= 3): cell (i, j) holds
  /// (i cells2 + j)'s point of a Sobol sequence (set_sobol_starts), so that every ball's start
  /// angle is sampled, not only balls 1 and 2's; [rad], (n - 2) per cell, row-major.
  std::vector<double> others;
  /// An unround race (model.md §11, §15.7): the balls run on its paths (any_balls true), and
  /// the attractors are its stable equilibria at the final speed; empty or round: the round race.
  RaceShape race;
  /// The race's equilibria at the final speed (model.md §11.4), found once for every cell's end
  /// (set_basin_race fills it); empty on a round race.
  std::shared_ptr<const UnroundResult> race_equilibria;
  /// An anisotropic support (model.md §10, §20; any_balls true, params_n carrying its mean): the
  /// cells integrate the composed field, the support turning with the spin angle. Its targets
  /// are the balanced states the Floquet multipliers call stable and, with an unround race, the
  /// race's states continued to pi/omega-periodic orbits that they call stable (§20.8;
  /// analysis/basin_targets.hpp); the other states are judged at t_end by §15.2 (`periodic`).
  std::optional<AnisotropicSupport> support;
  /// A flexible shaft (model.md §18.16, §18.21; any_balls true): the cells integrate the whole
  /// shaft (simulate_shaft, with `race` on it if unround), the settle test and the outcome judged
  /// on the balancer's view; params_n is then that view (shaft_summary_params: its L, U and balls).
  std::shared_ptr<const ShaftSystem> shaft;
  /// Settle test (model.md §15.5): scaled distance to a stable equilibrium (or to the
  /// balanced set, n >= 3) at most settle_radius for settle_samples samples in a row.
  double settle_radius = 1e-2;
  int settle_samples = 5;
  std::string provenance;   ///< "# " lines on top of the CSV (also the resume manifest's)
  int n_balls() const;
  double beta1(int i) const;
  double beta2(int j) const;
  /// Balls 3..n's start angles in cell (i, j) [rad] (empty for two balls).
  std::vector<double> start_of_others(int i, int j) const;
  double final_omega() const { return speed.omega(sim.t_end); }
};

/// Fills job.others (n >= 3, job.fixed empty): balls 3..n of cell (i, j) start at 2 pi times
/// point k = i cells2 + j of the Sobol sequence in n - 2 dimensions (GSL's gsl_qrng_sobol, its
/// points 1, 2, ... in order): a low-discrepancy sample of their angles over the whole grid,
/// the same whatever the thread count. Needs job.cells1, cells2 and the ball count set.
void set_sobol_starts(BasinJob& job);

/// A stable pi/omega-periodic orbit of the final speed as an attractor (model.md §20.8): on an
/// unround race with an anisotropic support no state is at rest in the rotating frame, and the
/// field depends on the spin angle theta only through 2 theta, so the orbit's state is a
/// function of theta mod pi. Sampled at `phases` equally spaced spin angles.
struct BasinOrbit {
  double omega = 0;  ///< the final speed [rad/s]
  int dim = 0;       ///< 2n + 4
  /// phases x dim, SI (model.md (2.2)): row k is the state at spin angle theta = k pi / phases.
  std::vector<double> states;
  int phases() const { return dim == 0 ? 0 : int(states.size()) / dim; }
  /// The state at spin angle theta [rad] (any real; taken mod pi) into x (dim values): linear
  /// interpolation between the two neighbouring rows, ball angles along their short arc.
  void at(double theta, double* x) const;
  /// The scaled distance of state x to the orbit's state at spin angle theta, in the settle
  /// test's scaling (model.md §15.5, (20.8)): max of |q - q*| / L, |beta - beta*| (mod 2 pi),
  /// |q' - q*'| / (L omega), |beta' - beta*'| / omega. L the displacement scale [m].
  double distance(const double* x, double theta, double L) const;
};

/// A stable equilibrium of the final speed, the balanced set of n >= 3 balls, or a stable
/// periodic orbit (`orbit` set).
struct BasinTarget {
  std::string label;           ///< "balanced", "aligned:+-..." (ball 1 is +), "equilibrium" (an unround race's) or "orbit"
  int member = 0;              ///< 1-based among targets of the same label (0 for the balanced set); an
                               ///< unround race's: its number in the list `equilibria` prints
  std::vector<double> position;  ///< q1, q2, beta1.. [m, rad]; empty for the balanced set and an orbit
  bool balanced_set = false;   ///< n >= 3: the whole (normally stable) balanced set
  /// A periodic orbit (label "orbit", member = the race's equilibrium it continues, as
  /// `equilibria` numbers it): the settle test compares with its state at the run's spin angle.
  std::shared_ptr<const BasinOrbit> orbit;
  /// The Lyapunov region of model.md §15.8 (two balls): entering it decides the cell. Not
  /// certified (n >= 3, the balanced set): the settle radius test of §15.5 instead.
  BasinRegion region;
};

/// The attractors the settle test knows: the equilibria at the final speed whose spectrum
/// is stable (model.md §6), and for n >= 3 the balanced set if every sample of it is
/// normally stable (§13.5). Deterministic order (as the analysis lists them). Throws
/// std::invalid_argument for a job with an anisotropic support (its targets need Floquet
/// multipliers: analysis/basin_targets.hpp).
std::vector<BasinTarget> basin_targets(const BasinJob& job);

/// The balanced states as targets (label "balanced", member by order; for n >= 3 the set):
/// what basin_targets builds from any stability judgement, here from one flag per state.
/// `states` the balanced states at the final speed, `stable` one flag each; not certified,
/// `why` says what decides instead.
std::vector<BasinTarget> balanced_targets(const std::vector<EquilibriumN>& states, const std::vector<bool>& stable,
                                          const std::string& why);

/// Puts the balls on `race` (unround on a rigid rotor's isotropic support: job.race_equilibria
/// found at the final speed; job.params_n, job.speed, job.support and job.shaft must be set).
void set_basin_race(BasinJob& job, RaceShape race);

struct BasinCell {
  int i = 0, j = 0;
  double beta1 = 0, beta2 = 0;      ///< start angles [rad]
  std::vector<double> beta_others;  ///< start angles of balls 3..n [rad]
  std::string attractor;            ///< balanced | aligned:PATTERN | equilibrium | orbit | periodic | stuck | not_settled
  int member = 0;                   ///< which target of that label (settle test), 0 if by §15.2 only
  /// How the run ended: 0 at t_end (judged by §15.2), 1 by entering a target's certified
  /// Lyapunov region (§15.8), 2 by the settle radius test of a target without one (§15.5).
  int by_settle_test = 0;
  double t_settle = -1;             ///< [s]: entry time (settle test) or §15.2 settle time; -1 if none
  double t_end = 0;                 ///< [s]: the last time integrated
  double q_abs_end = 0, max_q_abs = 0;  ///< [m]
  std::vector<double> state_end;    ///< 2n + 4 values
  unsigned long steps = 0, rejected = 0;
  /// coulomb-set (model.md §14.8): max_i |s_i| at the end angles (-1 for the other laws) and
  /// whether every ball sticks there inside the stick set (1), outside it (0), or some slips (-1).
  double max_abs_s = -1;
  int in_stick_set = -1;
};

/// Length of the shortest arc of the circle that holds every angle [rad] (0 for one angle):
/// the angular spread of end points (model.md §14.8).
double shortest_arc(std::vector<double> angles);

BasinCell compute_basin_cell(const BasinJob& job, const std::vector<BasinTarget>& targets, int i, int j);

/// Long CSV: comment block, then `i,j,beta1_0,beta2_0,attractor,member,by_settle_test,
/// t_settle,t_end,q_abs_end,max_q_abs,beta1_end..betan_end,steps,rejected` (model.md §15.5),
/// for coulomb-set followed by `max_abs_s,in_stick_set` (model.md §14.8); for n >= 3 last the
/// start angles of balls 3..n, `beta3_0..betan_0`.
std::string basin_csv_header(const BasinJob& job);
std::string basin_row(const BasinCell& c);
/// The resume manifest: everything that determines the bytes.
std::string basin_manifest(const BasinJob& job);
/// One tile = one column (i fixed, j = 0..cells2-1).
TileText compute_basin_tile(const BasinJob& job, const std::vector<BasinTarget>& targets, int tile);

/// What a basin holds and writes at most [bytes]: each worker's recorded run
/// (simulation_memory_estimate of a cell's options) and the cells' text twice (600 bytes a cell
/// covers twelve balls' 22 angles), plus 20 MB; on disk the text twice (the tiles, then the CSV).
struct BasinEstimate {
  double runs = 0;    ///< the workers' recorded runs
  double cells = 0;   ///< the cells' text held
  double memory = 0;  ///< runs + cells + 20 MB
  double disk = 0;
};
BasinEstimate basin_estimate(const BasinJob& job, int threads);

/// Runs `tiles` on options.threads threads, each finished tile to `sink` (as compute_tiles
/// does for maps). Rethrows a worker's exception after all stopped.
MapRunStats compute_basin_tiles(const BasinJob& job, const std::vector<BasinTarget>& targets,
                                const std::vector<int>& tiles, const MapRunOptions& options, const TileSink& sink);

}  // namespace abu
