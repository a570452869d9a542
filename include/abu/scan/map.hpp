// Stability maps over two parameters: for every cell of an x-y grid and every
// equilibrium, whether it exists, its stability, number of unstable eigenvalues,
// spectral abscissa, residual vibration |q| and ball angles.
//
// The per-cell work is CellAnalyzer's; it is allocation-free and keeps per-column state
// (a map is processed column by column: x fixed, y varying), which lets it exploit that
// friction parameters do not move equilibria (model.md §4): with a friction coefficient
// on the y axis the equilibria and most of the linearization are computed once per
// column. Tiling, threads, resume and MPI live in the map driver (map_driver.hpp).
//
//   abu::Axis x = abu::parse_axis("omega:50:2000:1000", scene, "--x");
//   abu::CellAnalyzer cells(params, x, y);
//   abu::MapCell cell;
//   cells.analyze(ix, iy, cell);
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "abu/linear/characteristic.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/io/scene.hpp"

namespace abu {

/// One axis of a map: `count` values from `from` to `to` (both included), evenly spaced
/// or evenly spaced in log.
struct Axis {
  ParamRef param;
  double from = 0, to = 0;
  int count = 0;
  bool logarithmic = false;
  /// The i-th value (i in [0, count)); the ends are exact.
  double value(int i) const;
};

/// Parses "NAME:FROM:TO:N[:log]" and checks it against the scene (the parameter exists
/// and its law uses it, both ends in its physical range, N in [1, kMaxAxisCount], log
/// needs positive ends). Throws InputError with file `origin` (e.g. "--x").
Axis parse_axis(std::string_view spec, const Scene& scene, const std::string& origin);
inline constexpr int kMaxAxisCount = 20000;
/// Maps larger than this many cells are refused (memory and time), whatever the axes.
inline constexpr long kMaxCells = 100'000'000;

/// One equilibrium of a cell.
struct MapEquilibrium {
  Family family = Family::balanced;
  std::int8_t member = 1;
  std::int8_t n_unstable = 0;
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

}  // namespace abu
