// A stability map of a flexible rotor's balanced state (docs/model.md §18.13):
// over two parameters (omega, a bearing's k or c, mu, m, U, kappa, ...) per cell the
// balanced states of the shaft (u = 0, the balls at W(beta) = 0, model.md §18.8), the
// rightmost eigenvalues of each by ARPACK shift-invert (sparse_spectrum.hpp, §19), the
// spectral abscissa and its frequency (rotating frame), the verdict and the rectangle of
// the complex plane the search covered. Tiles are columns (one x value each) through the
// map's TileStore and thread pool (map_driver.hpp): threads, --resume, the same bytes
// whatever the thread count (each cell is computed from its parameters alone).
//
//   abu::ShaftMapJob job{...};                    // the CLI builds cell_system from the scene
//   abu::ShaftMapCell c = abu::shaft_map_cell(sys, job.spectrum);
//   abu::compute_shaft_map_tiles(job, store.missing(), options, sink);
#pragma once

#include <complex>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/linear/sparse_spectrum.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

/// What each cell's spectrum search asks for.
struct ShaftMapSpectrum {
  int eigenvalues = 10;  ///< k rightmost per balanced state
  double band = 0.0;     ///< |Im lambda| <= band [1/s, rotating frame]; 0: 10 omega of the cell
  BalancedSampling sampling;  ///< samples of the balanced set (n >= 3 balls)
};

/// One cell. `state` says what was computed:
///   "converged"          every balanced state's spectrum converged over its band
///   "no_balanced_state"  U exceeds the balls' capacity (model.md §13.2): nothing to judge
///   otherwise            the outcome of the worst spectrum (to_string(Outcome)), e.g.
///                        "not_converged" when ARPACK fell short; `reason` says why
/// The numbers are meaningful only when `found` > 0.
struct ShaftMapCell {
  int balanced = 0;             ///< balanced states judged (samples of the set for n >= 3)
  std::string state = "converged";
  std::string reason;           ///< why, when state is not "converged"
  std::string verdict = "none"; ///< stable / unstable / undetermined / none (no balanced state)
  int found = 0;                ///< eigenvalues found (structural zeros excluded), all states
  /// max Re lambda over the non-structural eigenvalues found [1/s] (the spectral abscissa
  /// as far as covered) and |Im| of that eigenvalue [1/s, rotating frame]
  double abscissa = 0.0, frequency = 0.0;
  /// The covered rectangle, the intersection over the balanced states: every eigenvalue with
  /// real_min <= Re <= real_max, |Im| <= imag_max is among those found. imag_max < 0: none.
  double real_min = 0.0, real_max = 0.0, imag_max = -1.0;
  double residual = 0.0;  ///< the largest eigenpair residual (sparse_spectrum.hpp)
  /// The largest normwise backward error: the measure that stays small for the slow ball
  /// modes near lambda = 0, whose relative residual scales like ||A|| eps / |lambda|.
  double backward_error = 0.0;
  int shifts = 0, factorizations = 0;
};

/// The verdict on one equilibrium's spectrum, as `equilibria` gives it on a shaft scene:
/// the |lambda|-smallest `structural_zeros` eigenvalues set aside (directions along a set
/// of equilibria, model.md §13.4); unstable if a found eigenvalue has Re > 0, stable if the
/// search converged and its covered rectangle reaches Re >= 0, else undetermined.
struct ShaftVerdict {
  std::string verdict;                 ///< stable / unstable / undetermined
  std::vector<char> structural;        ///< per eigenpair
  double abscissa = -std::numeric_limits<double>::infinity();  ///< max Re of the non-structural eigenpairs [1/s]
  std::complex<double> rightmost{};    ///< that eigenvalue (Im >= 0 of a pair)
  int found = 0;                       ///< non-structural eigenpairs
  /// Values set aside as copies of a structural zero: relative residual >= 1 (indistinguishable
  /// from 0) beside one (model.md §19.7); marked in `structural` too.
  int zero_copies = 0;
  /// Why the verdict is undetermined although the search converged: an eigenvalue whose real
  /// part is within its error bound residual x |lambda| of 0 (its sign is not known).
  std::string doubt;
};
ShaftVerdict shaft_verdict(const SparseSpectrum& s, int structural_zeros);

/// The `eigenvalues` rightmost eigenvalues of `sys` linearized at the state x in the band
/// |Im lambda| <= band (0: 10 omega), copies from overlapping shifts merged at 1e-6
/// (`merged`, if given, gets how many were dropped).
SparseSpectrum shaft_rightmost(const ShaftSystem& sys, const Eigen::VectorXd& x, int eigenvalues, double band,
                               bool vectors = false, int* merged = nullptr);
/// The same for any linearization's pencil (18.7.3) at spin speed omega (the band's default).
SparseSpectrum pencil_rightmost(const ShaftPencil& pencil, double omega, int eigenvalues, double band,
                                bool vectors = false, int* merged = nullptr);

/// The balanced states of the shaft (u = 0; every sample of the set for n >= 3 balls):
/// they do not depend on the shaft's support (model.md §18.8), so no sparse solve is made.
std::vector<ShaftEquilibrium> shaft_balanced_states(const ShaftSystem& sys, const BalancedSampling& sampling = {});

/// One cell: the balanced states of `sys` and their spectra, merged as ShaftMapCell says.
ShaftMapCell shaft_map_cell(const ShaftSystem& sys, const ShaftMapSpectrum& o);

struct ShaftMapJob {
  std::string x_name, y_name, x_unit, y_unit;
  std::vector<double> xs, ys;
  /// The system of cell (ix, iy); thread-safe (called from the workers). May throw InputError.
  std::function<ShaftSystem(int ix, int iy)> cell_system;
  ShaftMapSpectrum spectrum;
  std::string provenance;  ///< "# " lines
};

/// What determines the map's bytes (the TileStore manifest).
std::string shaft_map_manifest(const ShaftMapJob& job);
/// Comment block and column names of shaft_map_X_Y.csv.
std::string shaft_map_header(const ShaftMapJob& job);
/// One tile: column ix = tile, its cells' rows in iy order (TileText::summary). Throws
/// NumericalError naming the cell if a number is not finite.
TileText compute_shaft_map_tile(const ShaftMapJob& job, int tile);
MapRunStats compute_shaft_map_tiles(const ShaftMapJob& job, const std::vector<int>& tiles,
                                    const MapRunOptions& options, const TileSink& sink);

}  // namespace abu
