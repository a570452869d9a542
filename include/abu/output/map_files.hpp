// The files of a stability map (analysis/map_setup.hpp runs it): the provenance block,
// the CSVs assembled from the tiles, the boundary CSV and the heat maps, written together
// (OutputTransaction) or not at all. The charts are drawn from a compact binary grid
// (plots/map.gp, grid_file: four float64 per cell), not from the summary CSV.
//
//   job.provenance = abu::map_provenance(job, scene.file);
//   const abu::MapRunReport r = abu::run_map(job, output);
//   const abu::MapFilesReport f = abu::write_map_files(job, r, {dir, true, scene.file, &stop});
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <string_view>

#include "abu/analysis/map_setup.hpp"
#include "abu/output/report_views.hpp"

namespace abu {

/// The comment block on top of a map's CSVs: provenance_header of the job's command line
/// and parameters (two balls or n balls), then the job's notes.
std::string map_provenance(const MapJob& job, std::string_view scene_file);

struct MapFilesOptions {
  std::filesystem::path directory;
  bool chart = true;
  std::string title;                        ///< the charts' subtitle (the scene file)
  const std::atomic<bool>* stop = nullptr;  ///< set by a signal: nothing is committed
};

struct MapFilesReport {
  bool written = false;  ///< false: stopped while writing (the tiles stay for --resume)
  MapVerdicts verdicts;  ///< two-ball maps with an omega axis: the speed ranges' input
};

/// Writes summary_X_Y.csv (and map_X_Y.csv if job.long_rows), boundary_X_Y.csv (if the
/// run has boundaries) and the heat maps (options.chart), then removes the tiles. Throws
/// std::runtime_error naming the tile directory when a file cannot be written.
MapFilesReport write_map_files(const MapJob& job, const MapRunReport& run, const MapFilesOptions& options);

}  // namespace abu
