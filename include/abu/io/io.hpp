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

/// `s` as a JSON string literal: quotes, `"` and `\\` escaped, \n and \t, every other control
/// character as \u00XX, so that a scene path or command line with any byte is valid JSON.
std::string json_string(std::string_view s);

/// `text` with every control character (and DEL) written as an escape (\n, \t, \xHH), for
/// terminal messages and CSV comment lines: a scene string or path cannot start a line.
std::string escaped(std::string_view text);

/// How an output target that already exists is written (docs/robustness.md):
/// a regular file is replaced atomically; a character device or FIFO (/dev/null, a pipe)
/// is written in place; anything else (a directory, a symbolic link, a socket, a block
/// device) is refused with an InputError (exit 2) before anything is written.
enum class TargetKind { absent, regular, in_place };
/// Checks `target` by the rule above (`option` names the command-line option in the message).
TargetKind check_output_target(const std::filesystem::path& target, std::string_view option = "-o");
/// Checks an output directory up front: it is a directory (a link to one is fine) or absent.
void check_output_directory(const std::filesystem::path& dir, std::string_view option = "-o");

/// Files written together or not at all. Each is first written next to its target under
/// an exclusively created temporary (random name, O_EXCL|O_NOFOLLOW); commit() checks every
/// target, moves the old files aside, renames the new ones in and removes the old ones, or
/// on any failure puts the old ones back. An uncommitted transaction removes its
/// temporaries (and the directories it created) when destroyed.
class OutputTransaction {
 public:
  OutputTransaction() = default;
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;
  ~OutputTransaction();

  /// Writes `content` to a temporary next to `target`; returns the temporary's path
  /// (readable until commit, e.g. by gnuplot).
  std::filesystem::path stage(const std::filesystem::path& target, std::string_view content);
  /// An (empty, exclusively created) temporary next to `target` for another program
  /// (gnuplot) or a stream to write. A chart that failed is not committed (run_gnuplot).
  std::filesystem::path reserve(const std::filesystem::path& target);
  void commit();

 private:
  struct Entry {
    std::filesystem::path temporary, target;
    TargetKind kind;
  };
  std::filesystem::path temporary_for(const std::filesystem::path& target);
  std::vector<Entry> staged_;
  std::vector<std::filesystem::path> created_dirs_;
  bool committed_ = false;
};

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
/// Waits for a commit under way and blocks every later one (the signal thread, before it
/// removes the temporaries and ends the process: no commit is cut in the middle).
void hold_output_commits() noexcept;

/// Charts that could not be drawn in this process (exit code 4, docs/robustness.md).
int chart_failures();
/// Kills a running gnuplot (the signal thread).
void kill_running_chart() noexcept;

/// "key=value" list of every parameter in model.md symbols (N = 2 or any_balls). A ball
/// given by its specification (model.md §1.1) adds what was specified: rho_i, f_i, R_s_i.
template <int N>
std::string describe_parameters(const ParamsT<double, N>& p);

/// How the specified balls' model values were derived, "m1=rho1*pi*(2*r1)^3/6=... kg
/// mu1=f1/r1=... l1=R_s1-r1=... m ..." (model.md (1.1.1)-(1.1.3)); empty if no ball is
/// specified that way (the outputs of such scenes keep their bytes).
template <int N>
std::string describe_specification(const ParamsT<double, N>& p);

/// The comment block on top of every output file: program and version, the command
/// line, the scene and every parameter value used, and how specified balls' values were
/// derived (describe_specification). Lines start with "# ".
template <int N>
std::string provenance_header(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p);

}  // namespace abu
