// The Campbell view of an omega sweep on an anisotropic support (docs/model.md §10.15,
// docs/views.md): campbell_omega.csv and campbell_omega.png from the balanced states'
// Floquet modes, staged in the sweep's transaction; the critical speeds on stderr.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "abu/analysis/floquet_sweep.hpp"
#include "abu/output/files.hpp"
#include "abu/input/scene.hpp"
#include "cli.hpp"

namespace abu::cli {

/// Nothing unless s.param is omega. Returns the files staged.
std::vector<std::filesystem::path> stage_floquet_campbell(OutputTransaction& out, const FloquetSweep& s,
                                                          const ParamsN& base, const Scene& scene,
                                                          const SceneOptions& options, const std::filesystem::path& dir,
                                                          const std::string& header, bool chart);

}  // namespace abu::cli
