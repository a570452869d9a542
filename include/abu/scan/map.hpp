// Stability maps over two parameters: for every cell of an x-y grid and every
// equilibrium, whether it exists, its stability, number of unstable eigenvalues,
// spectral abscissa, residual vibration |q| and ball angles.
//
// The per-cell work is CellAnalyzer's; it is allocation-free and keeps per-column state
// (a map is processed column by column: x fixed, y varying), which lets it exploit that
// friction parameters do not move equilibria (model.md §4): with a friction coefficient
// on the y axis the equilibria and most of the linearization are computed once per
// column. Tiling, threads, resume and MPI live in the map driver (map_driver.hpp); axes
// are parsed and checked against a scene in io (map_setup.hpp).
//
// Two balls take CellAnalyzer (the degree-8 characteristic polynomial, Routh); any other
// count, and the ball count as an axis, take CellAnalyzerN: the full n-ball analysis of
// every cell (model.md §13.8).
//
//   abu::Axis x = abu::parse_axis("omega:50:2000:1000", scene, "--x");   // map_setup.hpp
//   abu::CellAnalyzer cells(params, x, y);
//   abu::MapCell cell;
//   cells.analyze(ix, iy, cell);
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <vector>

#include "abu/equilibria/ball_permutations.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/aligned_reduced.hpp"
#include "abu/linear/characteristic.hpp"
#include "abu/model/anisotropic_support.hpp"

namespace abu {

/// One axis of a map: `count` values from `from` to `to` (both included), evenly spaced
/// or evenly spaced in log; or the ball count (`ball_count`: the integers from .. to,
/// count = to - from + 1, `param` unused).
struct Axis {
  ParamRef param;
  double from = 0, to = 0;
  int count = 0;
  bool logarithmic = false;
  bool ball_count = false;
  /// The i-th value (i in [0, count)); the ends are exact.
  double value(int i) const;
  /// The column name and file-name part: the parameter's symbol, or "n".
  std::string name() const;
};

inline constexpr int kMaxAxisCount = 20000;
/// Maps larger than this many cells are refused (memory and time), whatever the axes.
inline constexpr long kMaxCells = 100'000'000;

/// One equilibrium of a cell.
struct MapEquilibrium {
  Family family = Family::balanced;
  std::int8_t member = 1;
  std::int8_t n_unstable = 0;
  /// Eigenvalues within their error bound of the imaginary axis that neither the refined
  /// spectrum nor the certified Routh count could place: the verdict is undecided (stable
  /// is then false and n_unstable a lower bound).
  std::int8_t n_undecided = 0;
  bool stable = false;
  double abscissa = 0;  ///< spectral abscissa [1/s]
  double q_abs = 0;     ///< |q| [m]: the rotor's whirl radius, the same in the fixed frame
  double beta1 = 0, beta2 = 0;
};

/// Everything computed for one cell, a plain fixed-size value.
struct MapCell {
  std::array<MapEquilibrium, 6> equilibria{};
  std::uint8_t count = 0;
  unsigned degeneracy = degeneracy_none;
  std::uint8_t fallbacks = 0;  ///< eigenproblems decided by the full eigensolver
  /// The stable equilibrium with the smallest |q| (index into equilibria), -1 if none.
  int best_stable() const;
};

/// How a cell's stability is decided (benchmarks compare them; `fast` is the default).
enum class CellMethod {
  full,  ///< refined eigenvalues of every equilibrium (spectrum.hpp)
  fast,  ///< characteristic polynomial: Routh-Hurwitz / Lienard-Chipart, full near the boundary
};

/// Per-thread analyzer for one map; holds per-column state, no allocation per cell.
class CellAnalyzer {
 public:
  CellAnalyzer(const Params& base, const Axis& x, const Axis& y, CellMethod method = CellMethod::fast);
  void analyze(int ix, int iy, MapCell& out);

 private:
  // What is known of one equilibrium in the current column.
  struct Tracked {
    Equilibrium equilibrium;
    Linearization<long double, 2> linearization;  // at the last cell (y-dependent part aside)
    FrictionSplit split;                          // friction on y: the column's polynomials
    std::complex<double> rightmost{};             // at the previous cell, for Newton
    bool have_roots = false;
  };
  void start_column(int ix);
  void fill(MapEquilibrium& m, const Equilibrium& e) const;
  // Stability, n_unstable and abscissa of tracked equilibrium t for polynomial p; falls
  // back to the full spectrum of `lin` when the fast decision is not certain.
  void decide(Tracked& t, const Polynomial& p, const Linearization<long double, 2>& lin, MapEquilibrium& m,
              MapCell& cell);

  Params base_;
  Axis x_, y_;
  CellMethod method_;
  bool friction_y_ = false;  // y only changes the balls' friction: equilibria fixed per column
  int column_ = -1;
  Params column_params_;
  std::array<Tracked, 6> tracked_{};
  int tracked_count_ = 0;
  unsigned column_degeneracy_ = degeneracy_none;
};

/// One equilibrium of an n-ball cell (CellAnalyzerN).
struct MapEquilibriumN {
  Family family = Family::balanced;
  unsigned pattern = 0;  ///< aligned: the sign pattern (equilibria_n.hpp); 0 for balanced
  int member = 1;        ///< root of the pattern (1, 2) or the balanced sample's index
  int n_unstable = 0;
  int n_structural = 0;  ///< zero by construction (model.md §13.4), left out of the verdict
  bool stable = false;
  double abscissa = 0;   ///< spectral abscissa [1/s]; on the balanced set the normal one;
                         ///< anisotropic support: the Floquet decay rate (omega/pi) ln max|rho|
  double rho_abs_max = 0;  ///< anisotropic support: max |rho| over pi/omega (model.md §10.12); else 0
  double q_abs = 0;      ///< |q| [m]
  std::array<double, max_balls> beta{};
};

/// Everything computed for one cell of an n-ball map. `equilibria` keeps its storage
/// from cell to cell (one MapCellN per thread), so a cell does not allocate once it has
/// grown to the map's largest count.
struct MapCellN {
  int n_balls = 0;
  double capacity = 0;     ///< sum m_i l_i [kg m]
  double unbalance = 0;    ///< U [kg m]
  bool balanced_exists = false;  ///< the polygon inequality (model.md §13.4.2)
  int balanced_samples = 0, balanced_stable = 0;
  double normal_abscissa_max = 0;  ///< over the balanced samples (meaningful if balanced_samples > 0)
  int aligned = 0, aligned_stable = 0;
  unsigned degeneracy = degeneracy_none;
  std::vector<MapEquilibriumN> equilibria;  ///< balanced samples, then aligned (equilibria_n.hpp order)
  /// The stable equilibrium with the smallest |q| (first in list order on ties), -1 if none.
  int best_stable() const;
};

/// Per-thread analyzer of an n-ball map (any 2 <= n <= 12, also the ball count as an
/// axis): every cell by the full analysis of model.md §13.8, which is what
/// `equilibria` computes at the cell's parameters (scan.hpp, analyze). Reuses its
/// equilibrium list and the cell's storage; the spectra are fixed-capacity values.
class CellAnalyzerN {
 public:
  /// `base`: the scene's parameters; with a ball-count axis `by_count[k]` are those of
  /// the scene's ring with from + k balls (io builds them: scan does not know scenes).
  /// With `support` (the scene's anisotropic support, `base` its mean), a cell holds only its
  /// balanced states, judged by their Floquet multipliers (model.md §10.12); the others are
  /// periodic orbits, not equilibria, and are left out.
  CellAnalyzerN(const ParamsN& base, std::vector<ParamsN> by_count, const Axis& x, const Axis& y,
                const BalancedSampling& sampling, std::optional<AnisotropicSupport> support = std::nullopt);
  void analyze(int ix, int iy, MapCellN& out);
  /// The parameters of cell (ix, iy).
  ParamsN cell_params(int ix, int iy) const;

 private:
  void analyze_floquet_cell(const ParamsN& p, std::span<const EquilibriumN> points, MapCellN& out);
  // Equilibrium k by §13.10 (equal balls, aligned), its pencil made at first need.
  AlignedVerdict aligned_cell_verdict(const ParamsT<long double, any_balls>& pl, std::size_t k);

  ParamsN base_;
  std::vector<ParamsN> by_count_;
  Axis x_, y_;
  BalancedSampling sampling_;
  std::optional<AnisotropicSupport> support_;
  // The cell's equilibria and their classes, kept while the next cell's statics are the
  // same (friction coefficients do not move equilibria, model.md §4: a friction axis
  // finds them once per column; the balls' kinds and whether any has a friction slope,
  // which sets the structural zeros, must not change either).
  EquilibriumSetN set_;
  PermutationClasses classes_;  // equal balls: one verdict per class (model.md §13.9)
  ParamsN set_params_{};
  bool have_set_ = false;
  std::vector<int> source_;  // per class: the member whose verdict the others copy
  // Per equilibrium of set_: g of a balanced sample (model.md (13.9.4)), the sides of an
  // aligned one (§13.10); its pencil's rightmost root along the column, once found.
  struct PencilRoot {
    std::complex<double> root{};
    bool tracked = false;
  };
  std::vector<long double> sample_g_;
  std::vector<AlignedReduction> sides_;
  std::vector<PencilRoot> aligned_roots_;
  std::vector<int> pencil_of_;           // index in pencils_, -1 not made yet
  std::vector<AlignedPencil> pencils_;   // of the aligned classes' computed members
  std::optional<ReducedSplits> reduced_splits_;  // the balanced corners', made at first need
  // The reduced problem's rightmost root along the column (cells iy = 0, 1, .. of one ix,
  // in that order whatever the threads: the same bytes), the start of the next sample's.
  int column_ = -1;
  std::complex<double> reduced_root_{};
  bool reduced_tracked_ = false;
};

}  // namespace abu
