// Files that appear complete or not at all (docs/robustness.md): output targets checked up
// front, every file of a result staged under an exclusive temporary and renamed into place
// together by commit(), or removed.
//
//   abu::OutputTransaction out;
//   out.stage("out/sweep_omega.csv", csv);
//   abu::run_gnuplot(abu::plots_dir() / "sweep.gp", {{"csv", ...}, {"png", out.reserve("out/x.png")}});
//   out.commit();   // if anything threw before, the destructor removes the temporaries
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace abu {

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
  /// The same for a data file a stream writes here (a CSV): never taken for a chart's
  /// output, so a chart that fails to draw from it does not keep it from being committed.
  std::filesystem::path reserve_data(const std::filesystem::path& target);
  /// An earlier run's output at `target` that this one supersedes but may not write (a map's
  /// long CSV without --long, its charts with --no-chart): removed by the commit unless a
  /// file is committed there, restored with the rest if the commit fails. Regular files only.
  void retire(const std::filesystem::path& target);
  void commit();

 private:
  struct Entry {
    std::filesystem::path temporary, target;
    TargetKind kind;
  };
  std::filesystem::path temporary_for(const std::filesystem::path& target);
  std::vector<Entry> staged_;
  std::vector<std::filesystem::path> retired_;
  std::vector<std::filesystem::path> created_dirs_;
  bool committed_ = false;
};

/// Waits for a commit under way and blocks every later one (the signal thread, before it
/// removes the temporaries and ends the process: no commit is cut in the middle).
void hold_output_commits() noexcept;

}  // namespace abu
