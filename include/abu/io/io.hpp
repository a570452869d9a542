// Writing results: numbers in shortest round-trip form, files that appear complete or
// not at all, the provenance header every output file starts with, and gnuplot.
//
//   abu::OutputTransaction out;
//   out.stage("out/sweep_omega.csv", csv);
//   abu::run_gnuplot(abu::plots_dir() / "sweep.gp", {{"csv", ...}, {"png", out.reserve("out/x.png")}});
//   out.commit();   // if anything threw before, the destructor removes the temporaries
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "abu/core/params.hpp"

namespace abu {

/// Shortest decimal that reads back to the same double (fmt's "{}", locale-free).
/// Throws NumericalError naming `what` for a non-finite value: no NaN reaches a file.
std::string format_number(double value, std::string_view what = "value");

/// Files written together or not at all. Each is first written next to its target
/// under a temporary name; commit() renames them into place. An uncommitted
/// transaction removes its temporaries (and the directories it created) when destroyed.
class OutputTransaction {
 public:
  OutputTransaction() = default;
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;
  ~OutputTransaction();

  /// Writes `content` to a temporary next to `target`; returns the temporary's path
  /// (readable until commit, e.g. by gnuplot).
  std::filesystem::path stage(const std::filesystem::path& target, std::string_view content);
  /// A temporary path next to `target` for another program (gnuplot) to write.
  std::filesystem::path reserve(const std::filesystem::path& target);
  void commit();

 private:
  std::filesystem::path temporary_for(const std::filesystem::path& target);
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // temp, target
  std::vector<std::filesystem::path> created_dirs_;
  bool committed_ = false;
};

/// Directory of the gnuplot scripts: $ABU_PLOTS_DIR; else ../share/abu/plots next to the
/// running program (an installed tree); else the source tree's plots/; else the configured
/// install prefix's share/abu/plots (docs/install.md).
std::filesystem::path plots_dir();

/// Runs `gnuplot -e "name='value';..." script`; throws std::runtime_error if gnuplot is
/// missing or fails.
void run_gnuplot(const std::filesystem::path& script,
                 const std::vector<std::pair<std::string, std::string>>& variables);

/// "key=value" list of every parameter in model.md symbols (N = 2 or any_balls).
template <int N>
std::string describe_parameters(const ParamsT<double, N>& p);

/// The comment block on top of every output file: program and version, the command
/// line, the scene and every parameter value used. Lines start with "# ".
template <int N>
std::string provenance_header(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p);

}  // namespace abu
