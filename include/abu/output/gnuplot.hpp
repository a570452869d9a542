// Charts: gnuplot scripts run on staged CSVs. A chart that fails never loses results: the
// CSVs are committed, the chart's outputs are not, and the process exits with 4.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace abu {

/// Directory of the gnuplot scripts: $ABU_PLOTS_DIR; else ../share/abu/plots next to the
/// running program (an installed tree); else the source tree's plots/; else the configured
/// install prefix's share/abu/plots (docs/install.md).
std::filesystem::path plots_dir();

/// Runs `gnuplot -e "name='value';..." script` (gnuplot found on PATH at run time, or
/// $ABU_GNUPLOT). Results are never lost to a chart: a failure does not throw. It is
/// reported on stderr with its cause, the outputs gnuplot was to write (variables whose
/// value is a reserved temporary) are not committed, and chart_failures() counts it (the
/// CLI then exits 4). A chart whose data are empty or degenerate (gnuplot: "all points
/// undefined", "range is invalid", ...) is drawn as an empty chart with that note instead
/// (a warning, not a failure). Returns true if the script's own chart was drawn.
bool run_gnuplot(const std::filesystem::path& script,
                 const std::vector<std::pair<std::string, std::string>>& variables);
/// Charts that could not be drawn in this process (exit code 4, docs/robustness.md).
int chart_failures();
/// Kills a running gnuplot (the signal thread).
void kill_running_chart() noexcept;

}  // namespace abu
