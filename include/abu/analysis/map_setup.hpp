// A stability map from a scene: its axes parsed and checked against the scene's rules
// (the ball count as an axis on a [balls] ring), the job built (map_driver.hpp), and the
// run: tiles on every thread and MPI rank, resume, and the fold / Hopf boundaries. The
// files (the CSVs from the tiles, the boundary CSV, the heat maps) are the output layer's
// (output/map_files.hpp); the command line (src/cli/map_command.cpp) adds options and signals.
//
//   abu::MapJob job = abu::map_job(scene, request);
//   job.provenance = abu::map_provenance(job, scene.file);        // output/map_files.hpp
//   abu::MapRunReport r = abu::run_map(job, output);
//   if (r.outcome == abu::MapRunReport::Outcome::done) abu::write_map_files(job, r, files);
#pragma once

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "abu/input/scene.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

/// Parses "NAME:FROM:TO:N[:log]" and checks it against the scene (the parameter exists
/// and its law uses it, both ends in its physical range, N in [1, kMaxAxisCount], log
/// needs positive ends); or "n:FROM:TO:COUNT", the ball count of a [balls] ring scene
/// (integers 2 <= FROM <= TO <= 12, COUNT = TO - FROM + 1, no log, every count's ring
/// valid). Throws InputError with file `origin` (e.g. "--x").
Axis parse_axis(std::string_view spec, const Scene& scene, const std::string& origin);
/// One axis end ("FROM", "TO"): the whole text a finite number, else nothing.
std::optional<double> finite_number(std::string_view text);

struct MapRequest {
  std::string x, y;  ///< the axis specifications
  CellMethod method = CellMethod::fast;
  BalancedSampling sampling;
  StickSetOptions stick;  ///< coulomb-set scenes: the stick set's resolution per cell (stick_map.hpp)
  /// The command line that determines the output (without threads, resume, output
  /// directory), for the provenance header; n-ball maps get " --set-samples S" added.
  std::string command_line;
  bool long_rows = false;  ///< map_X_Y.csv, a row per equilibrium per cell (MapJob::long_rows)
};

/// The map's job: both axes checked (a per-ball axis on every ball count of a ball-count
/// axis), the cell limit, the parameters (two balls, n balls, or one ring per count), the
/// provenance's command line and notes (the block itself: output/map_files.hpp,
/// map_provenance). Throws InputError before any work.
MapJob map_job(const Scene& scene, const MapRequest& request);

struct MapOutput {
  std::filesystem::path directory;
  TileStore::Mode mode = TileStore::Mode::fresh;
  int threads = 1;
  const std::atomic<bool>* stop = nullptr;  ///< set by a signal: stop after the tiles in progress
  bool progress = false;                    ///< the progress line on stderr (rank 0)
  bool boundaries = true;                   ///< the fold/Hopf curves (continuation)
};

struct MapRunReport {
  enum class Outcome {
    done,         ///< every tile on disk (and the boundaries): the files can be written
    interrupted,  ///< stopped; the finished tiles stay in `tile_directory`
    refused,      ///< rank > 0: rank 0 refused the input (it says why)
    other_rank,   ///< rank > 0: done, rank 0 writes
  } outcome = Outcome::done;
  MapRunStats stats;
  int tiles_total = 0, tiles_kept = 0;
  std::filesystem::path tile_directory;
  std::shared_ptr<TileStore> store;           ///< done: the finished tiles (rank 0), locked
  std::optional<BoundaryRun> boundaries;      ///< two balls, when asked for
  std::optional<BoundaryRunN> boundaries_n;   ///< n >= 3 balls, when asked for
  double boundary_seconds = -1;  ///< < 0: no boundaries computed
  std::string boundary_note;     ///< why there are none, if not asked-for-and-done
};

/// Runs the map (every rank calls it in an MPI build): the tiles, then (rank 0, if asked
/// for) the boundaries. `job.provenance` must be set. Throws InputError (tile store rules),
/// NumericalError, std::runtime_error (I/O).
MapRunReport run_map(const MapJob& job, const MapOutput& output);

}  // namespace abu
