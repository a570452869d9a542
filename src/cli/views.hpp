// The rotordynamics views a sweep or continuation writes besides its own outputs
// (docs/views.md): the Campbell CSV and chart of an omega run, the stability ranges and
// critical speeds in summary_NAME.json and on stderr.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "abu/output/files.hpp"
#include "abu/output/report_views.hpp"
#include "cli.hpp"

namespace abu::cli {

/// What one run hands to stage_views.
struct ViewsInput {
  std::filesystem::path dir;
  std::string param, param_unit;  ///< the swept/continued parameter and its unit
  double from = 0, to = 0;        ///< its interval [SI]
  std::vector<CampbellSample> samples;  ///< empty unless the parameter is omega
  StabilityRanges ranges;
  std::string header;  ///< provenance header of the run
  std::string title;   ///< chart title
  bool chart = true;
};

/// Stages campbell_<param>.csv (+ .png) when there are samples and summary_<param>.json,
/// and prints the ranges and critical speeds to stderr. Returns the files staged.
template <int N>
std::vector<std::filesystem::path> stage_views(OutputTransaction& out, const ViewsInput& in, const ParamsT<double, N>& p,
                                               const Scene& scene, const SceneOptions& options);

/// A map axis `omega:FROM:TO:N[:log]` typed in the command's --units, rewritten in rad/s
/// (any other axis, or a malformed one for the map's own checks, unchanged).
std::string omega_axis_input(const SceneOptions& options, const std::string& axis);

/// After a map: summary_<x>_<y>.json with the omega ranges per value of the other axis,
/// from the map's verdicts (output/map_files.hpp; nothing when no axis is omega or the map
/// has no verdicts); the ranges on stderr unless `quiet`. `command`: the map's canonical
/// command line (the same bytes for any thread or rank count).
void write_map_ranges(const std::filesystem::path& dir, const std::string& x, const std::string& y,
                      const MapVerdicts& verdicts, const Scene& scene, const SceneOptions& options,
                      const std::string& command, bool quiet);

}  // namespace abu::cli
