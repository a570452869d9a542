#include "abu/io/io.hpp"

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "abu/core/errors.hpp"

extern char** environ;

namespace abu {

namespace fs = std::filesystem;

std::string format_number(double value, std::string_view what) {
  if (!std::isfinite(value)) throw NumericalError(fmt::format("non-finite {} ({}) would be written", what, value));
  return fmt::format("{}", value);
}

fs::path OutputTransaction::temporary_for(const fs::path& target) {
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::exists(dir)) {
    // Remember which directories we create, outermost first, to undo them on failure.
    std::vector<fs::path> missing;
    for (fs::path d = dir; !d.empty() && !fs::exists(d); d = d.parent_path()) missing.push_back(d);
    fs::create_directories(dir);
    created_dirs_.insert(created_dirs_.end(), missing.begin(), missing.end());
  }
  fs::path tmp = dir / fmt::format(".{}.tmp-{}", target.filename().string(), ::getpid());
  staged_.emplace_back(tmp, target);
  return tmp;
}

fs::path OutputTransaction::stage(const fs::path& target, std::string_view content) {
  const fs::path tmp = temporary_for(target);
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  out.write(content.data(), std::streamsize(content.size()));
  out.close();
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
  return tmp;
}

fs::path OutputTransaction::reserve(const fs::path& target) { return temporary_for(target); }

void OutputTransaction::commit() {
  for (const auto& [tmp, target] : staged_) {
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) throw std::runtime_error(fmt::format("cannot move {} into place: {}", target.string(), ec.message()));
  }
  committed_ = true;
}

OutputTransaction::~OutputTransaction() {
  if (committed_) return;
  std::error_code ec;
  for (const auto& staged : staged_) fs::remove(staged.first, ec);
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

void run_gnuplot(const fs::path& script, const std::vector<std::pair<std::string, std::string>>& variables) {
  if (!fs::exists(script)) throw std::runtime_error(
        fmt::format("gnuplot script {} not found (set ABU_PLOTS_DIR to the directory of the scripts)", script.string()));
  std::string assignments;
  for (const auto& [name, value] : variables) {
    if (value.find('\'') != std::string::npos)
      throw std::runtime_error(fmt::format("path {} contains a quote; gnuplot cannot be given it", value));
    assignments += fmt::format("{}='{}';", name, value);
  }
  std::vector<std::string> args{"gnuplot", "-e", assignments, script.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, "gnuplot", nullptr, nullptr, argv.data(), environ) != 0)
    throw std::runtime_error("gnuplot not found on PATH (Debian package gnuplot-nox)");
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("gnuplot failed on {}", script.string()));
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
    switch (p.law) {
      case FrictionLaw::none: break;
      case FrictionLaw::viscous: s += fmt::format(" d{}={}", n, b.d); break;
      case FrictionLaw::coulomb: s += fmt::format(" mu{}={}", n, b.mu); break;
      case FrictionLaw::stribeck:
        s += fmt::format(" mu_c{}={} mu_s{}={} v_s{}={}", n, b.mu_c, n, b.mu_s, n, b.v_s);
        break;
    }
  }
  return s;
}

template <int N>
std::string provenance_header(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p) {
  const double M = p.total_mass();
  return fmt::format(
      "# stability-scan {} (abu-stability)\n# command: {}\n# scene: {}\n# parameters (SI): {}\n"
      "# derived: M={} kg, omega_n=sqrt(k/M)={} rad/s\n",
      ABU_VERSION, command_line, scene_file, describe_parameters(p), M, std::sqrt(p.rotor.stiffness / M));
}

template std::string describe_parameters<2>(const Params&);
template std::string describe_parameters<any_balls>(const ParamsN&);
template std::string provenance_header<2>(std::string_view, std::string_view, const Params&);
template std::string provenance_header<any_balls>(std::string_view, std::string_view, const ParamsN&);

}  // namespace abu
