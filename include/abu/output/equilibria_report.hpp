// The outputs of `equilibria` (analysis/equilibria.hpp), whatever the machine: the table,
// CSV or JSON text, the warnings for stderr, and the files some states add (mode shapes, the
// stick set's boundary and chart). The one place of the output layer that chooses a writer by
// the kind of states.
//
//   abu::EquilibriaReport r = abu::analyze_equilibria(scene);
//   std::string text = abu::equilibria_text(r, "csv", {command_line, scene.file, unit});
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "abu/analysis/equilibria.hpp"
#include "abu/core/speed_units.hpp"
#include "abu/output/files.hpp"

namespace abu {

/// Who asked, for the provenance every output starts with, and the unit speeds are shown in.
struct OutputContext {
  std::string command_line;  ///< the command line as typed
  std::string scene_file;    ///< the scene's path as given
  SpeedUnit unit = SpeedUnit::rad_per_s;
};

/// `format` is "table", "csv" or "json".
std::string equilibria_text(const EquilibriaReport& r, std::string_view format, const OutputContext& context);

/// What equilibria_text writes per state [bytes], an upper bound (measured 8.6-10.8 kB of JSON,
/// 1.4-2 kB of table and under 1 kB of CSV per balanced state, 3 to 12 balls), for the memory
/// and disk estimates made before the work.
double equilibria_text_bytes_per_state(std::string_view format);

/// What to say on stderr: the analysis' own warnings, polishes or refinements that did not
/// converge, ill-conditioned spectra, LuGre's route deviations.
std::string equilibria_warnings(const EquilibriaReport& r);

/// DIR/modes.csv (every mode of every equilibrium) and, with `chart`, DIR/modes.png (the best
/// stable state's modes): rigid rotors only (the analysis refuses the others).
void stage_mode_shapes(OutputTransaction& out, const std::filesystem::path& dir, const EquilibriaReport& r,
                       const OutputContext& context, bool chart);

/// DIR/stick_set.csv and, for two balls, DIR/stick_boundary.csv, DIR/stick_raster.dat and with
/// `chart` DIR/stick_set.png: coulomb-set scenes only (nothing for the others).
void stage_stick_set_files(OutputTransaction& out, const std::filesystem::path& dir, const EquilibriaReport& r,
                           const OutputContext& context, bool chart);

}  // namespace abu
