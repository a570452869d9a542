// gnuplot, found and run (gnuplot.hpp).
#include "abu/output/gnuplot.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/output/format.hpp"
#include "chart_registry.hpp"

extern char** environ;

namespace abu {

namespace fs = std::filesystem;

namespace {
std::atomic<int> g_chart_failures{0};
std::atomic<pid_t> g_chart_pid{0};
}  // namespace

// The one place that decides where the gnuplot scripts are (docs/install.md):
//   1. $ABU_PLOTS_DIR, if set and not empty (taken as given: an explicit choice);
//   2. next to the running program as installed: <dir of /proc/self/exe>/ABU_PLOTS_FROM_BINDIR
//      (../share/abu/plots under GNUInstallDirs), so an installed tree can be moved;
//   3. the source tree's plots/ (the build tree's binary, and programs linked against a
//      library built from a tree that still exists);
//   4. the configured install prefix's copy (a program linked against the installed
//      library, run from anywhere).
// If none exists, the source tree's path is returned and run_gnuplot says it is missing.
fs::path plots_dir() {
  if (const char* env = std::getenv("ABU_PLOTS_DIR"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = (exe.parent_path() / ABU_PLOTS_FROM_BINDIR).lexically_normal();
    if (fs::is_directory(installed, ec)) return installed;
  }
  const fs::path source(ABU_SOURCE_PLOTS_DIR);
  if (fs::is_directory(source, ec)) return source;
  const fs::path prefix(ABU_INSTALL_PLOTS_DIR);
  if (fs::is_directory(prefix, ec)) return prefix;
  return source;
}

int chart_failures() { return g_chart_failures.load(); }
void kill_running_chart() noexcept {
  if (const pid_t pid = g_chart_pid.load(); pid > 0) ::kill(pid, SIGTERM);
}

namespace {
// gnuplot on PATH (or $ABU_GNUPLOT), located when a chart is drawn.
std::optional<fs::path> find_gnuplot() {
  if (const char* env = std::getenv("ABU_GNUPLOT"); env && *env) {
    if (::access(env, X_OK) == 0) return fs::path(env);
    return std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "/usr/bin:/bin";
  while (true) {
    const auto colon = rest.find(':');
    const std::string_view dir = rest.substr(0, colon);
    const fs::path candidate = fs::path(dir.empty() ? "." : std::string(dir)) / "gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate;
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 1);
  }
  return std::nullopt;
}

// Runs gnuplot with `args`; returns its exit status (-1 if it did not exit normally),
// its standard error in `messages`.
int spawn_gnuplot(const fs::path& gnuplot, std::vector<std::string> args, std::string& messages) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error(fmt::format("pipe: {}", std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);  // the CLI blocks SIGINT/SIGTERM in its threads
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, gnuplot.c_str(), &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  ::close(pipe_fds[1]);
  if (spawned != 0) {
    ::close(pipe_fds[0]);
    messages = std::strerror(spawned);
    return -1;
  }
  g_chart_pid = pid;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    if (messages.size() < 65536) messages.append(buffer, std::size_t(n));
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  g_chart_pid = 0;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// gnuplot's message, shortened to its last lines and escaped for one terminal line each.
std::string gnuplot_cause(const std::string& messages) {
  std::vector<std::string> lines, located;  // located: gnuplot's `"script" line N: ...` messages
  for (std::size_t start = 0; start < messages.size();) {
    const std::size_t end = std::min(messages.find('\n', start), messages.size());
    const std::string line = messages.substr(start, end - start);
    if (line.find_first_not_of(" \t^") != std::string::npos) lines.push_back(line);
    if (line.rfind("\"", 0) == 0 && line.find("\" line ") != std::string::npos) located.push_back(line);
    start = end + 1;
  }
  if (!located.empty()) lines = located;  // not the echoed command
  std::string cause;
  const std::size_t from = lines.size() > 3 ? lines.size() - 3 : 0;
  for (std::size_t i = from; i < lines.size(); ++i) cause += (cause.empty() ? "" : " | ") + escaped(lines[i]);
  return cause.empty() ? std::string("no message") : cause;
}

// gnuplot's words for data it cannot draw: nothing plottable, or a range of one value.
bool degenerate_data(const std::string& messages) {
  for (const char* pattern : {"all points", "range is invalid", "empty x range", "empty y range", "empty z range",
                              "empty cb range", "no valid points", "No data in plot", "undefined value",
                              "Skipping data file with no valid points", "No valid data points", "undefined variable: STATS_",
                              "Can't calculate", "not enough"})
    if (messages.find(pattern) != std::string::npos) return true;
  return false;
}

std::string gnuplot_string(const std::string& text) {
  std::string out;
  for (const char c : escaped(text)) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

// gnuplot's messages without the script's path and line ("warning: No valid data points
// found in file"), one per line, for a note on a chart.
std::vector<std::string> plain_messages(const std::string& messages) {
  std::vector<std::string> out;
  for (std::size_t start = 0; start < messages.size();) {
    const std::size_t end = std::min(messages.find('\n', start), messages.size());
    std::string line = messages.substr(start, end - start);
    start = end + 1;
    const bool is_located = line.rfind("\"", 0) == 0 && line.find("\" line ") != std::string::npos;
    if (!is_located && messages.find("\" line ") != std::string::npos) continue;  // the echoed command
    if (const auto colon = line.find(": "); is_located && colon != std::string::npos) line = line.substr(colon + 2);
    if (line.find_first_not_of(" \t^") == std::string::npos) continue;
    if (std::find(out.begin(), out.end(), line) == out.end()) out.push_back(line.substr(0, 90));
  }
  if (out.size() > 3) out.resize(3);
  return out;
}

// An empty chart carrying `title` and the note "no data to draw" with gnuplot's reasons,
// in the format of `output`'s target (png or svg).
bool draw_note_chart(const fs::path& gnuplot, const std::string& output, const std::string& title,
                     const std::string& messages) {
  const bool svg = output.find(".svg.") != std::string::npos;
  std::string text = "no data to draw";
  for (const auto& m : plain_messages(messages)) text += "\\n(" + gnuplot_string(m) + ")";
  std::string script = fmt::format(
      "set terminal {} size 900,600; set output '{}'; unset border; unset xtics; unset ytics; unset key; "
      "set title \"{}\" noenhanced; set label 1 \"{}\" at graph 0.5, 0.55 center font ',14' noenhanced; "
      "plot [0:1][0:1] NaN notitle",
      svg ? "svg" : "pngcairo", output, gnuplot_string(title), text);
  std::string ignored;
  return spawn_gnuplot(gnuplot, {"gnuplot", "-e", script}, ignored) == 0;
}
}  // namespace

bool run_gnuplot(const fs::path& script, const std::vector<std::pair<std::string, std::string>>& variables) {
  std::vector<std::string> outputs;  // the reserved temporaries this chart writes
  {
    std::lock_guard lock(detail::chart_mutex());
    for (const auto& [name, value] : variables)
      if (detail::reserved_outputs().count(value)) outputs.push_back(value);
  }
  const std::string chart = script.stem().string();
  const auto fail = [&](const std::string& cause) {
    ++g_chart_failures;
    std::lock_guard lock(detail::chart_mutex());
    for (const auto& o : outputs) detail::failed_chart_outputs().insert(o);
    fmt::print(stderr, "stability-scan: warning: chart '{}' not drawn: {}; the CSVs are written (exit code 4)\n",
               chart, cause);
    return false;
  };
  if (!fs::exists(script)) return fail(fmt::format("gnuplot script {} not found (set ABU_PLOTS_DIR)", escaped(script.string())));
  const auto gnuplot = find_gnuplot();
  if (!gnuplot)
    return fail("gnuplot not found on PATH (install it, e.g. Debian package gnuplot-nox, set ABU_GNUPLOT, or pass "
                "--no-chart)");
  std::string assignments;
  for (const auto& [name, value] : variables) {
    if (value.find('\'') != std::string::npos || value.find('\n') != std::string::npos)
      return fail(fmt::format("'{}' contains a quote or a newline; gnuplot cannot be given it", escaped(value)));
    assignments += fmt::format("{}='{}';", name, value);
  }
  std::string messages;
  const int status = spawn_gnuplot(*gnuplot, {"gnuplot", "-e", assignments, script.string()}, messages);
  if (stop_requested()) throw Interrupted(stop_signal(), fmt::format("chart '{}'", chart));
  if (status == 0) {
    // gnuplot's warnings pass through; an output it left empty is a failure.
    fmt::print(stderr, "{}", messages);
    for (const auto& o : outputs) {
      std::error_code ec;
      if (fs::file_size(o, ec) == 0 || ec) return fail(fmt::format("gnuplot wrote nothing to {}", escaped(o)));
    }
    return true;
  }
  const std::string cause =
      status < 0 ? fmt::format("gnuplot did not run ({})", gnuplot_cause(messages))
                 : fmt::format("gnuplot exited with status {}: {}", status, gnuplot_cause(messages));
  if (status > 0 && degenerate_data(messages)) {
    bool drawn = !outputs.empty();
    std::string title = chart;
    for (const auto& [name, value] : variables)
      if (name == "title") title = value;
    for (const auto& o : outputs) drawn = drawn && draw_note_chart(*gnuplot, o, title, messages);
    if (drawn) {
      fmt::print(stderr, "stability-scan: warning: chart '{}' has no drawable data ({}); drawn empty with that note\n",
                 chart, gnuplot_cause(messages));
      return false;
    }
  }
  return fail(cause);
}


}  // namespace abu
