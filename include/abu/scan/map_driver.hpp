// Running a stability map: the grid cut into tiles of whole columns, tiles computed on
// all threads (and, in an MPI build, on all ranks: map_mpi.hpp), each tile written to
// disk atomically as it finishes, the CSVs assembled from the tiles in order.
//
// Determinism: a tile's text depends only on the job and the tile index (CellAnalyzer
// starts every column afresh), and the files are the tiles concatenated in index order,
// so 1 thread, N threads, N ranks and an interrupted-then-resumed run give the same bytes.
//
//   abu::MapJob job;   // io builds it from a scene: map_setup.hpp, map_job()
//   abu::TileStore store(dir / abu::tile_directory_name(job), job, abu::TileStore::Mode::fresh);
//   abu::MapRunStats stats = abu::compute_tiles(job, store.missing(), options,
//       [&](int tile, abu::TileText&& text) { store.put(tile, text); });
//   abu::assemble(job, store, long_csv_stream, summary_csv_stream, &grid_stream);
#pragma once

#include "abu/model/shaft.hpp"
#include "abu/model/unround_race.hpp"

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "abu/continuation/boundaries.hpp"

#include "abu/continuation/boundaries_n.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/scan/map.hpp"

namespace abu {

/// Columns (x values) per tile: small enough for progress and resume, large enough that
/// a tile (8 x ny cells) dwarfs the cost of writing it.
inline constexpr int kTileColumns = 8;
/// Text per tile above which a tile gets fewer columns: what an MPI rank other than 0
/// holds per tile to send it (rank 0 and single-process maps stream, kTileSpillBytes).
inline constexpr long kTileBudgetBytes = 32L << 20;
/// A worker's text buffers (rows, summary) are written to the tile's temporaries when
/// one passes this: a streamed worker holds about 3 x (this + one cell's text).
inline constexpr std::size_t kTileSpillBytes = std::size_t(1) << 20;
/// Allowance for a worker's analyzers and equilibria (fixed size, well below this).
inline constexpr std::size_t kWorkerBaseBytes = std::size_t(16) << 20;
/// Bytes of CSV per cell of a two-ball map (long rows and summary, measured on the default
/// scene, rounded up): the up-front disk and memory estimate (docs/robustness.md).
inline constexpr std::size_t kMapBytesPerCell = 900;
/// The same without the long rows: the summary row and the grid block (map --long not given).
inline constexpr std::size_t kSummaryBytesPerCell = 160;

/// Everything that determines a map's output.
struct MapJob {
  Params params;  ///< two balls (any_balls false)
  Axis x, y;
  CellMethod method = CellMethod::fast;
  /// Provenance comment block ("# " lines) on top of both CSVs: output/map_files.hpp,
  /// map_provenance(), writes it from the two fields below and the parameters.
  std::string provenance;
  /// The command line the provenance names (the request's, with the options the job adds).
  std::string command_line;
  /// Comment lines after the provenance block (the ball-count axis, lugre).
  std::string provenance_notes;
  /// Any ball count: a scene with n != 2 balls, or the ball count as an axis. Cells by
  /// CellAnalyzerN (model.md §13.8), the n-ball CSV columns; `method` is not used.
  bool any_balls = false;
  ParamsN params_n;               ///< the scene (any_balls)
  std::vector<ParamsN> by_count;  ///< ball-count axis: the ring with x/y.from + k balls
  BalancedSampling sampling;      ///< of the balanced set (model.md §13.5)
  /// coulomb-set friction (model.md §14): every cell is the stick set of `params_n` at the
  /// cell's parameters with resolution `stick` (stick_map.hpp), not equilibria; one ball
  /// count (no ball-count axis), any_balls false, `method` and `sampling` not used.
  bool stick_set = false;
  StickSetOptions stick;
  /// coulomb-set on an unround race (model.md §20.5): the stick set on its paths per cell.
  RaceShape race;
  /// coulomb-set on a flexible shaft (model.md §18.17): per cell the stick set of the rigid
  /// balancer the balls see through this shaft (`params_n` then gives omega, U and the balls).
  std::shared_ptr<const ShaftSpec> shaft;
  /// The long CSV's rows (a row per equilibrium per cell, ~0.8 kB a cell) are formatted
  /// and kept in the tiles only when asked for (`map --long`); part of the tiles' manifest.
  bool long_rows = false;
  /// An anisotropic support (model.md §10): `params_n` carries its mean, `any_balls` is set,
  /// cells hold the balanced states judged by Floquet multipliers (§10.12), the summary
  /// gains rho_abs_max, and there are no fold/Hopf boundaries (they are the mean system's).
  std::optional<AnisotropicSupport> support;
  /// The most balls of any cell: the number of beta columns of the n-ball long CSV.
  int max_balls_in_map() const;
  /// Columns per tile: kTileColumns for two balls; 1 for n balls, whose cells cost up to
  /// seconds each (n = 12), so that a map a few columns wide still keeps every thread busy.
  int tile_columns() const;
};

int tile_count(const MapJob& job);

/// One thread's analyzers and cell storage for a job (reused over its tiles).
struct CellWorkspace {
  explicit CellWorkspace(const MapJob& job);
  std::optional<CellAnalyzer> two_balls;
  std::optional<CellAnalyzerN> any_balls;
  MapCell cell;
  MapCellN cell_n;
};

/// What the charts and the speed ranges need of one cell (two-ball and n-ball maps; a
/// stick-set map has none), in a tile's grid block: three float64 per cell in the summary's
/// order (ix outer, iy inner), the same values the summary writes, in this machine's byte
/// order.
struct MapCellFacts {
  /// 0 no balanced state, 1 exists but unstable, 2 partly stable (n balls: some samples
  /// of the balanced set), 3 stable (two balls: balanced_stable = 1; n balls: every sample)
  double category = 0;
  double best_q_abs = 0;  ///< |q| of the stable state of least |q| [m]; NaN: nothing is stable
  double balanced_stable_fraction = 0;  ///< n balls; NaN: two balls, or no samples
};
static_assert(sizeof(MapCellFacts) == 3 * sizeof(double));

/// The computed text of one tile: its rows of the long CSV (empty unless job.long_rows),
/// of the summary CSV, and its grid block (MapCellFacts per cell, as bytes).
struct TileText {
  std::string rows, summary, grid;
  long cells = 0, equilibria = 0, fallbacks = 0;
};

/// Computes tile `tile` with `workspace` (one per thread). Throws NumericalError naming
/// the cell if a value is not finite.
TileText compute_tile(const MapJob& job, int tile, CellWorkspace& workspace);

class TileStore;
/// As compute_tile, but the text goes to the tile's file in `store` as it is made (1 MB
/// buffers: a worker's memory does not grow with the y axis), renamed into place at the
/// end; the returned TileText has the counts only. Same bytes as put(compute_tile(...)).
TileText compute_tile_into(const MapJob& job, int tile, CellWorkspace& workspace, const TileStore& store);

/// Comment block and column names of the long CSV (one row per equilibrium per cell) and
/// of the summary CSV (one row per cell).
std::string map_csv_header(const MapJob& job);
std::string summary_csv_header(const MapJob& job);
/// "map_X_Y.csv", "summary_X_Y.csv", ".map_X_Y.tiles".
std::string map_file_name(const MapJob& job);
std::string summary_file_name(const MapJob& job);
std::string tile_directory_name(const MapJob& job);
/// Bytes of CSV text per cell, an upper estimate (long rows and summary).
std::size_t map_bytes_per_cell(const MapJob& job);

/// The tiles of one map on disk: a directory holding a manifest (the job's headers: a
/// resumed run must be the same map) and one file per finished tile, each written under a
/// temporary name and renamed, so a present tile is complete. Thread-safe. The directory
/// is locked (flock on its file "lock", holding the writer's PID) for the store's life: a
/// second writer is refused, naming the holder.
class TileStore {
 public:
  enum class Mode {
    fresh,   ///< the directory must not exist (an interrupted run is not discarded silently)
    resume,  ///< keep the tiles of an interrupted run of the same map
    discard  ///< remove an earlier run's tiles, start over
  };
  /// Throws InputError (origin "--resume" / "-o") when the mode's rule is broken.
  TileStore(std::filesystem::path directory, const MapJob& job, Mode mode);
  /// The same for any tiled job (`basin`, basin.hpp): `manifest` is everything that
  /// determines its bytes, `tiles` how many tiles it has.
  TileStore(std::filesystem::path directory, const std::string& manifest, int tiles, Mode mode);
  ~TileStore();
  TileStore(const TileStore&) = delete;
  TileStore& operator=(const TileStore&) = delete;
  bool has(int tile) const;
  /// Tiles not on disk yet, ascending.
  std::vector<int> missing() const;
  void put(int tile, const TileText& text) const;
  /// Appends tile `tile`'s long rows to `rows`, its summary rows to `summary` and its grid
  /// block to `grid` (if not null).
  void append(int tile, std::ostream& rows, std::ostream& summary, std::ostream* grid = nullptr) const;
  /// Removes the directory (after the assembled files are in place).
  void remove() const;
  const std::filesystem::path& directory() const { return directory_; }
  std::filesystem::path tile_path(int tile) const;

 private:
  void lock();
  std::filesystem::path directory_;
  int tiles_ = 0;
  int lock_fd_ = -1;
};

/// Progress and ETA of a map on stderr: one '\r'-updated line on a terminal, a line every
/// few seconds otherwise. Thread-safe; silent when disabled.
class ProgressMeter {
 public:
  /// `total` tiles in the map, `before` of them already done (resumed).
  ProgressMeter(int total, int before, bool enabled);
  void tile_done(long cells);
  /// Ends the line (terminal) after the last update.
  void finish();

 private:
  void print_locked(bool final_line);
  std::mutex mutex_;
  int total_, done_, before_;
  long cells_ = 0;
  bool enabled_, terminal_;
  std::chrono::steady_clock::time_point start_, last_print_;
};

struct MapRunOptions {
  int threads = 1;
  /// Set from a signal handler: workers stop after their current tile.
  const std::atomic<bool>* stop = nullptr;
  ProgressMeter* progress = nullptr;
  /// If set, tiles are streamed into this store (compute_tile_into) and `sink` is not called.
  const TileStore* stream_to = nullptr;
};

struct MapRunStats {
  int tiles = 0;  ///< computed in this call
  long cells = 0, equilibria = 0, fallbacks = 0;
  double seconds = 0;
  bool interrupted = false;
};

/// Called from worker threads with each finished tile; must be thread-safe.
using TileSink = std::function<void(int tile, TileText&& text)>;

/// What one worker thread does with a tile: computes it (and hands it on), returning the
/// tile's counts. Built once per thread by the pool, so it may own per-thread workspace.
using TileWork = std::function<MapRunStats(int tile)>;

/// The thread pool of maps and basins: an atomic counter hands out `tiles` to
/// options.threads threads, each running its own `make_work()`; the counts are summed and
/// progress is reported per tile. An `Interrupted` inside a tile drops that tile only;
/// any other exception stops every worker and is rethrown after all joined. `wait` (if
/// set) runs on the calling thread while the workers run, and must return once `done()`
/// is true (MPI uses it to receive other ranks' tiles).
MapRunStats run_tile_pool(const std::vector<int>& tiles, const MapRunOptions& options,
                          const std::function<TileWork()>& make_work,
                          const std::function<void(const std::function<bool()>& done)>& wait = {});

/// run_tile_pool for tiles computed as text by `compute` (thread-safe; the unround race's,
/// the shaft's and the basin's tiles): each finished tile goes to `sink`, its cells and
/// equilibria counted.
MapRunStats run_text_tiles(const std::vector<int>& tiles, const MapRunOptions& options, const TileSink& sink,
                           const std::function<TileText(int tile)>& compute);

/// Computes `tiles` on options.threads threads (an atomic counter hands out tiles, one
/// CellAnalyzer per thread) and passes each to `sink`. `wait` (if set) runs on the
/// calling thread while the workers run, and must return once `done()` is true (MPI uses
/// it to receive other ranks' tiles). Rethrows a worker's exception after all stopped.
MapRunStats compute_tiles(const MapJob& job, const std::vector<int>& tiles, const MapRunOptions& options,
                          const TileSink& sink, const std::function<void(const std::function<bool()>& done)>& wait = {});

/// The fold and Hopf curves in the map's plane (two balls): every fold and Hopf point of
/// a continuation in x along the bottom and the top edge, continued in y across the map.
/// A curve that meets neither edge is not found (a note of the run says so). nullopt
/// for maps of n != 2 balls (map_boundaries_n) and ball-count axes.
std::optional<BoundaryRun> map_boundaries(const MapJob& job);
/// The same for a map of n >= 3 balls (neither axis the ball count): the n-ball branches
/// (branches_n.hpp) along the bottom and top edges, their folds and the Hopf points of
/// their aligned branches and balanced samples continued across (boundaries_n.hpp).
/// Empty for two-ball jobs and ball-count axes.
std::optional<BoundaryRunN> map_boundaries_n(const MapJob& job);

/// Writes the two CSVs: headers, then every tile's rows in tile order; and, if `grid` is
/// not null, every tile's grid block (the MapCellFacts of every cell, in the summary's order).
void assemble(const MapJob& job, const TileStore& store, std::ostream& map_csv, std::ostream& summary_csv,
              std::ostream* grid = nullptr);

}  // namespace abu
