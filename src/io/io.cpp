#include "abu/io/io.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/temp_files.hpp"

extern char** environ;

namespace abu {

namespace fs = std::filesystem;

std::string format_number(double value, std::string_view what) {
  if (!std::isfinite(value)) throw NumericalError(fmt::format("non-finite {} ({}) would be written", what, value));
  // +-DBL_MAX is the stand-in of a value that was not computed (an infinite inverse
  // eigenvalue), never a result.
  if (std::abs(value) == std::numeric_limits<double>::max())
    throw NumericalError(fmt::format("{} is the stand-in DBL_MAX (not computed) and would be written", what));
  return fmt::format("{}", value);
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += fmt::format("\\u{:04x}", int(c));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string escaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\r') out += "\\r";
    else if (c < 0x20 || c == 0x7f) out += fmt::format("\\x{:02x}", c);
    else out += ch;
  }
  return out;
}

namespace {
// Commits are atomic with respect to the signal thread: it waits for a commit under way.
std::mutex g_commit_mutex;

// Test hook (tests/cli/check_robustness.sh): the K-th rename into place fails, to check
// that the old files come back.
int failing_rename() {
  const char* env = std::getenv("ABU_TEST_FAIL_RENAME");
  return env ? std::atoi(env) : 0;
}

std::mutex g_chart_mutex;
std::set<std::string>& failed_chart_outputs() {
  static std::set<std::string> paths;
  return paths;
}
std::set<std::string>& reserved_outputs() {
  static std::set<std::string> paths;
  return paths;
}
std::atomic<int> g_chart_failures{0};
std::atomic<pid_t> g_chart_pid{0};
}  // namespace

TargetKind check_output_target(const fs::path& target, std::string_view option) {
  struct stat st {};
  if (::lstat(target.c_str(), &st) != 0) {
    if (errno == ENOENT) return TargetKind::absent;
    throw InputError(std::string(option), 0, escaped(target.string()),
                     fmt::format("cannot inspect the output: {}", std::strerror(errno)));
  }
  if (S_ISREG(st.st_mode)) return TargetKind::regular;
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return TargetKind::in_place;
  const char* what = S_ISDIR(st.st_mode)   ? "a directory"
                     : S_ISLNK(st.st_mode) ? "a symbolic link (give the path it points to)"
                                           : "neither a regular file, a character device nor a FIFO";
  throw InputError(std::string(option), 0, escaped(target.string()),
                   fmt::format("the output exists and is {}: it is not replaced", what));
}

void check_output_directory(const fs::path& dir, std::string_view option) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    throw InputError(std::string(option), 0, escaped(dir.string()),
                     fmt::format("cannot inspect the output directory: {}", std::strerror(errno)));
  }
  if (!S_ISDIR(st.st_mode))
    throw InputError(std::string(option), 0, escaped(dir.string()), "the output directory exists and is not a directory");
}

fs::path OutputTransaction::temporary_for(const fs::path& target) {
  const TargetKind kind = check_output_target(target);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  check_output_directory(dir);
  if (!fs::exists(dir)) {
    // Remember which directories we create, outermost first, to undo them on failure.
    std::vector<fs::path> missing;
    for (fs::path d = dir; !d.empty() && !fs::exists(d); d = d.parent_path()) missing.push_back(d);
    fs::create_directories(dir);
    created_dirs_.insert(created_dirs_.end(), missing.begin(), missing.end());
  }
  fs::path tmp = create_temporary_next_to(target, "tmp");
  staged_.push_back({tmp, target, kind});
  return tmp;
}

namespace {
// Opens `path` with `flags` (no O_CREAT: the file exists, created exclusively or a device)
// and writes all of `content`, retrying interrupted and partial writes; throws with errno's
// message naming the file.
void write_all(const fs::path& path, int flags, std::string_view content) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw std::runtime_error(fmt::format("cannot write {}: {}", escaped(path.string()), std::strerror(errno)));
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      ::close(fd);
      throw std::runtime_error(fmt::format("cannot write {}: {}", escaped(path.string()), std::strerror(err)));
    }
    done += std::size_t(n);
  }
  if (::close(fd) != 0)
    throw std::runtime_error(fmt::format("cannot write {}: {}", escaped(path.string()), std::strerror(errno)));
}
}  // namespace

fs::path OutputTransaction::stage(const fs::path& target, std::string_view content) {
  const fs::path tmp = temporary_for(target);
  // The temporary was created exclusively; O_NOFOLLOW again in case it was swapped.
  write_all(tmp, O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, content);
  return tmp;
}

fs::path OutputTransaction::reserve(const fs::path& target) {
  fs::path tmp = temporary_for(target);
  std::lock_guard lock(g_chart_mutex);
  reserved_outputs().insert(tmp.string());
  return tmp;
}

namespace {
// Copies a staged file into a target written in place (a character device or a FIFO).
void copy_in_place(const fs::path& from, const fs::path& to) {
  std::string content;
  {
    const int in = ::open(from.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (in < 0) throw std::runtime_error(fmt::format("cannot read {}: {}", escaped(from.string()), std::strerror(errno)));
    char buffer[65536];
    for (;;) {
      const ssize_t n = ::read(in, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      content.append(buffer, std::size_t(n));
    }
    ::close(in);
  }
  write_all(to, O_WRONLY | O_NOFOLLOW | O_CLOEXEC, content);
}
}  // namespace

void OutputTransaction::commit() {
  std::lock_guard commit_lock(g_commit_mutex);
  std::vector<Entry> entries;
  {
    std::lock_guard lock(g_chart_mutex);
    for (const auto& e : staged_) {
      if (failed_chart_outputs().count(e.temporary.string())) {
        std::error_code ec;
        fs::remove(e.temporary, ec);
        unregister_temporary(e.temporary);
        continue;
      }
      entries.push_back(e);
    }
  }
  // Every target checked before the first rename (it may have changed since staging).
  for (auto& e : entries) e.kind = check_output_target(e.target);
  // Old files aside, new ones in; on failure everything back as it was.
  std::vector<std::pair<fs::path, fs::path>> aside;  // old file's new name, target
  std::vector<fs::path> moved_in;
  const auto roll_back = [&] {
    for (const auto& target : moved_in) ::unlink(target.c_str());
    for (const auto& [old, target] : aside) rename_no_replace(old, target);
  };
  const int fail_at = failing_rename();
  int renames = 0;
  for (const auto& e : entries) {
    if (e.kind != TargetKind::regular) continue;
    fs::path old = e.target.parent_path() / fmt::format(".{}.old-{}", e.target.filename().string(), random_suffix());
    if (e.target.parent_path().empty()) old = old.filename();
    if (const int err = rename_no_replace(e.target, old)) {
      roll_back();
      throw std::runtime_error(
          fmt::format("cannot move the old {} aside: {}; nothing replaced", escaped(e.target.string()), std::strerror(err)));
    }
    aside.emplace_back(old, e.target);
  }
  for (const auto& e : entries) {
    if (e.kind == TargetKind::in_place) continue;
    ++renames;
    const int err = renames == fail_at ? EIO : rename_no_replace(e.temporary, e.target);
    if (err) {
      roll_back();
      throw std::runtime_error(fmt::format("cannot move {} into place: {}; the previous files are restored",
                                           escaped(e.target.string()), std::strerror(err)));
    }
    moved_in.push_back(e.target);
    unregister_temporary(e.temporary);
  }
  for (const auto& [old, target] : aside) ::unlink(old.c_str());
  committed_ = true;
  // Devices and FIFOs last: their writes cannot be undone.
  for (const auto& e : entries) {
    if (e.kind != TargetKind::in_place) continue;
    copy_in_place(e.temporary, e.target);
    ::unlink(e.temporary.c_str());
    unregister_temporary(e.temporary);
  }
}

OutputTransaction::~OutputTransaction() {
  std::error_code ec;
  for (const auto& staged : staged_) {
    {
      std::lock_guard lock(g_chart_mutex);
      reserved_outputs().erase(staged.temporary.string());
      failed_chart_outputs().erase(staged.temporary.string());
    }
    if (committed_) continue;
    fs::remove(staged.temporary, ec);
    unregister_temporary(staged.temporary);
  }
  if (committed_) {
    for (const auto& staged : staged_) {
      if (fs::exists(staged.temporary, ec) && staged.kind == TargetKind::in_place) fs::remove(staged.temporary, ec);
      unregister_temporary(staged.temporary);
    }
    return;
  }
  for (const auto& dir : created_dirs_) fs::remove(dir, ec);  // only if empty
}

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

void hold_output_commits() noexcept { g_commit_mutex.lock(); }  // never released: the process ends

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
    std::lock_guard lock(g_chart_mutex);
    for (const auto& [name, value] : variables)
      if (reserved_outputs().count(value)) outputs.push_back(value);
  }
  const std::string chart = script.stem().string();
  const auto fail = [&](const std::string& cause) {
    ++g_chart_failures;
    std::lock_guard lock(g_chart_mutex);
    for (const auto& o : outputs) failed_chart_outputs().insert(o);
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

template <int N>
std::string describe_parameters(const ParamsT<double, N>& p) {
  std::string s = fmt::format("M_r={} k={} c={} U={} omega={} law={}", p.rotor.mass, p.rotor.stiffness,
                              p.rotor.damping, p.rotor.unbalance, p.omega, to_string(p.law));
  if (p.law == FrictionLaw::coulomb || p.law == FrictionLaw::stribeck) s += fmt::format(" kappa={}", p.kappa);
  for (std::size_t i = 0; i < p.balls.size(); ++i) {
    const auto& b = p.balls[i];
    const auto n = i + 1;
    s += fmt::format(" m{}={} l{}={} r{}={} j{}={}", n, b.mass, n, b.race_radius, n, b.radius, n, b.inertia_factor);
    if (b.specified & specified::density) s += fmt::format(" rho{}={}", n, b.density);
    if (b.specified & specified::surface_radius) s += fmt::format(" R_s{}={}", n, b.surface_radius);
    switch (p.law) {
      case FrictionLaw::none: break;
      case FrictionLaw::viscous: s += fmt::format(" d{}={}", n, b.d); break;
      case FrictionLaw::coulomb:
      case FrictionLaw::coulomb_set:
        s += fmt::format(" mu{}={}", n, b.mu);
        if (b.specified & specified::rolling_length) s += fmt::format(" f{}={}", n, b.rolling_length);
        break;
      case FrictionLaw::stribeck:
        s += fmt::format(" mu_c{}={} mu_s{}={} v_s{}={}", n, b.mu_c, n, b.mu_s, n, b.v_s);
        break;
      case FrictionLaw::lugre:
        s += fmt::format(" sigma0_{}={} sigma1_{}={} sigma2_{}={} mu_c{}={} mu_s{}={} v_s{}={}", n, b.sigma0, n,
                         b.sigma1, n, b.sigma2, n, b.mu_c, n, b.mu_s, n, b.v_s);
        break;
    }
  }
  return s;
}

template <int N>
std::string describe_specification(const ParamsT<double, N>& p) {
  std::string s;
  for (std::size_t i = 0; i < p.balls.size(); ++i) {
    const auto& b = p.balls[i];
    const auto n = i + 1;
    auto add = [&](std::string text) { s += (s.empty() ? "" : " ") + std::move(text); };
    if (b.specified & specified::density) add(fmt::format("m{}=rho{}*pi*(2*r{})^3/6={} kg", n, n, n, b.mass));
    if (b.specified & specified::rolling_length) add(fmt::format("mu{}=f{}/r{}={}", n, n, n, b.mu));
    if (b.specified & specified::surface_radius) add(fmt::format("l{}=R_s{}-r{}={} m", n, n, n, b.race_radius));
  }
  return s;
}

template <int N>
std::string provenance_header(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p) {
  const double M = p.total_mass();
  std::string out = fmt::format(
      "# stability-scan {} (abu-stability)\n# command: {}\n# scene: {}\n# parameters (SI): {}\n"
      "# derived: M={} kg, omega_n=sqrt(k/M)={} rad/s\n",
      ABU_VERSION, escaped(command_line), escaped(scene_file), describe_parameters(p), M, std::sqrt(p.rotor.stiffness / M));
  if (const std::string spec = describe_specification(p); !spec.empty())
    out += fmt::format("# derived from the specification (model.md §1.1): {}\n", spec);
  return out;
}

template std::string describe_parameters<2>(const Params&);
template std::string describe_parameters<any_balls>(const ParamsN&);
template std::string describe_specification<2>(const Params&);
template std::string describe_specification<any_balls>(const ParamsN&);
template std::string provenance_header<2>(std::string_view, std::string_view, const Params&);
template std::string provenance_header<any_balls>(std::string_view, std::string_view, const ParamsN&);

}  // namespace abu
