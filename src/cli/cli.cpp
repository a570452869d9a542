#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "cli.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/params.hpp"
#include "abu/core/temp_files.hpp"
#include "abu/output/format.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/input/ranges.hpp"
#include "abu/core/suggest.hpp"
#include "abu/input/plausibility.hpp"
#include "abu/input/shaft_scene.hpp"
#include "commands.hpp"

namespace abu::cli {

namespace {
std::string g_command_line;
std::mutex g_note_mutex;
std::string g_interrupt_note;

// How long a computation may take to notice a stop request before the signal thread
// removes the temporaries itself and ends the process (docs/robustness.md "Signals").
constexpr auto kStopGrace = std::chrono::milliseconds(1000);

void write_stderr(const std::string& text) noexcept {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + done, text.size() - done);
    if (n <= 0) return;
    done += std::size_t(n);
  }
}

// SIGINT and SIGTERM are blocked in every thread (the mask is inherited) and taken here
// by sigwait: the stop flag is set, a running gnuplot is ended, and if the command has
// not finished within kStopGrace (a computation that does not poll the flag), the
// temporaries are removed and the process ends with 128 + signal. A second signal ends
// it at once the same way.
void signal_thread(sigset_t set) {
  int signal = 0;
  if (sigwait(&set, &signal) != 0) return;
  request_stop(signal);
  kill_running_chart();
  const auto deadline = std::chrono::steady_clock::now() + kStopGrace;
  sigset_t pending;
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (sigpending(&pending) == 0 && (sigismember(&pending, SIGINT) || sigismember(&pending, SIGTERM))) break;
  }
  hold_output_commits();  // a commit under way finishes; none starts
  const int removed = remove_registered_temporaries();
  std::string note;
  {
    std::lock_guard lock(g_note_mutex);
    note = g_interrupt_note;
  }
  write_stderr(fmt::format("stability-scan: stopped by {} ({} temporar{} removed){}{}\n",
                           signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal", removed,
                           removed == 1 ? "y" : "ies", note.empty() ? "" : "; ", note));
  ::_exit(128 + signal);
}

void start_signal_thread() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  if (pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return;
  std::thread(signal_thread, set).detach();
}

// Standard output flushed and checked: a full disk or a closed pipe is an I/O failure.
int checked_stdout(int code) {
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    fmt::print(stderr, "stability-scan: failed: cannot write standard output: {}\n",
               errno ? std::strerror(errno) : "write error");
    return code == exit_ok || code == exit_chart_failed ? exit_failure : code;
  }
  return code;
}
}  // namespace

int interrupted_exit_code() { return 128 + (stop_signal() > 0 ? stop_signal() : SIGINT); }

void set_interrupt_note(std::string note) {
  std::lock_guard lock(g_note_mutex);
  g_interrupt_note = std::move(note);
}

const std::string& command_line() { return g_command_line; }

SpeedUnit SceneOptions::speed_unit() const { return speed_unit_from_string(units).value_or(SpeedUnit::rad_per_s); }

double omega_input(const SceneOptions& options, double typed) { return to_rad_per_s(typed, options.speed_unit()); }

SpeedProfile run_speed(const SceneOptions& options, const std::string& ramp, const std::string& profile_file,
                       const Scene& scene) {
  if (options.speed_unit() != SpeedUnit::rad_per_s && !profile_file.empty())
    throw InputError("--speed-profile", 0, "units",
                     "a speed profile file is in rad/s; --units applies to --set omega and --ramp (drop --units)");
  if (!ramp.empty()) return SpeedProfile::parse_ramp(ramp, "--ramp", to_rad_per_s(1.0, options.speed_unit()));
  if (!profile_file.empty()) return SpeedProfile::load(profile_file);
  if (scene.simulate && scene.simulate->speed) return *scene.simulate->speed;
  return SpeedProfile::constant(scene.omega, scene.file, "speed.omega");
}

namespace {
// `--set omega=V` in the command's --units: rewritten to rad/s before the scene's rules
// check it (a value that is not a number is left for apply_override to report).
std::string in_si(const SceneOptions& options, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (options.speed_unit() == SpeedUnit::rad_per_s || eq == std::string::npos) return assignment;
  std::string name = assignment.substr(0, eq);
  name.erase(0, name.find_first_not_of(" \t"));
  name.erase(name.find_last_not_of(" \t") + 1);
  if (name != "omega") return assignment;
  std::string text = assignment.substr(eq + 1);
  text.erase(0, text.find_first_not_of(" \t"));
  text.erase(text.find_last_not_of(" \t") + 1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(v)) return assignment;
  return fmt::format("omega={}", omega_input(options, v));
}
}  // namespace

// The overrides do not depend on their order for being accepted: a rule between two
// values (r < l) is judged on the final scene. They are applied in the given order; one
// refused only because of a value a later override changes is applied again after the
// others; at the end every override is checked once more against the final scene.
Scene load(const SceneOptions& options) {
  Scene scene = load_scene(options.scene);
  std::vector<std::string> pending = options.overrides;
  while (!pending.empty()) {
    std::vector<std::string> refused;
    std::optional<InputError> first;
    for (const auto& assignment : pending) {
      try {
        apply_override(scene, in_si(options, assignment));
      } catch (const InputError& e) {
        if (!first) first = e;
        refused.push_back(assignment);
      }
    }
    if (refused.size() == pending.size()) throw *first;
    pending = std::move(refused);
  }
  for (const auto& assignment : options.overrides) apply_override(scene, in_si(options, assignment));
  if (scene.shaft) {  // a flexible rotor: its own ranges and warnings (shaft_scene.hpp)
    check_shaft_range(scene, options.overrides.empty() ? scene.file : "--set");
    for (const auto& w : shaft_warnings(scene)) fmt::print(stderr, "stability-scan: warning: {}\n", w);
    return scene;
  }
  check_numerical_range(scene, options.overrides.empty() ? scene.file : "--set");
  for (const auto& w : implausible_values(scene)) fmt::print(stderr, "stability-scan: warning: {}\n", w);
  return scene;
}

namespace {
// Integers on the command line are decimal: CLI11 reads "010" as octal 8 (strtoll base 0,
// also inside its range checks). An option's value of digits with leading zeros ("--steps
// 010", "--threads=007") loses the zeros before parsing: it is the decimal number.
std::string decimal(std::string text) {
  const std::size_t sign = (!text.empty() && (text[0] == '-' || text[0] == '+')) ? 1 : 0;
  if (text.size() < sign + 2 || text[sign] != '0' ||
      text.find_first_not_of("0123456789", sign) != std::string::npos)
    return text;
  const std::size_t first = std::min(text.find_first_not_of('0', sign), text.size() - 1);
  return text.substr(0, sign) + text.substr(first);
}
bool integer_option(std::string_view name) {
  for (const char* o : {"--steps", "--threads", "--max-steps", "--set-samples", "--stick-columns", "--stick-grid"})
    if (name == o) return true;
  return false;
}
std::vector<std::string> decimal_arguments(int argc, char** argv) {
  std::vector<std::string> args(argv, argv + argc);
  for (std::size_t i = 1; i < args.size(); ++i) {
    std::string& a = args[i];
    if (const auto eq = a.find('='); eq != std::string::npos && integer_option(std::string_view(a).substr(0, eq)))
      a = a.substr(0, eq + 1) + decimal(a.substr(eq + 1));
    else if (integer_option(args[i - 1]))
      a = decimal(a);
  }
  return args;
}
}  // namespace

void add_scene_options(CLI::App& sub, SceneOptions& options) {
  sub.add_option("scene", options.scene, "Scene file (TOML, SI units), e.g. data/scenes/default.toml")->required();
  sub.add_option("--set", options.overrides,
                 fmt::format("Override a parameter, NAME=VALUE (repeatable). Names: {}", param_symbols_help()))
      ->type_name("NAME=VALUE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub.add_option("--units", options.units,
                 "Unit of the speed omega as typed (--set omega=, --from/--to of omega) and displayed: rad/s, rpm or "
                 "hz; CSV columns named omega and JSON values stay in rad/s")
      ->check(CLI::IsMember({"rad/s", "rpm", "hz", "Hz"}))
      ->capture_default_str();
}

CLI::Validator tolerance_range(double lo, double hi) {
  const std::string bounds = fmt::format("[{:g}, {:g}]", lo, hi);
  return CLI::Validator(
      [lo, hi, bounds](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return fmt::format("'{}' is not a number", text);
        if (!(value >= lo && value <= hi)) return fmt::format("{} must be in {}", text, bounds);
        return {};
      },
      "in " + bounds);
}

int run_command(int argc, char** argv);

int run(int argc, char** argv) {
  for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + std::string(argv[i]);
  start_signal_thread();
  const int code = run_command(argc, argv);
  return checked_stdout(code == exit_ok && chart_failures() > 0 ? int(exit_chart_failed) : code);
}

int run_command(int argc, char** argv) {

  CLI::App app{"stability-scan: linear stability of the automatic ball balancer (model: docs model.md)"};
  app.name("stability-scan");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("stability-scan ") + ABU_VERSION);
  std::vector<std::pair<CLI::App*, Action>> commands;
  for (auto add : {add_equilibria_command, add_sweep_command, add_continue_command, add_map_command,
                    add_simulate_command, add_basin_command, add_outcomes_command, add_design_command}) {
    Action a = add(app);
    commands.emplace_back(app.get_subcommands({}).back(), a);
  }
  // An unknown word where the subcommand goes is named (CLI11 would say only that a
  // subcommand is required), with the nearest subcommand.
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string_view> names;
    for (const auto* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    const std::string_view word = argv[1];
    if (std::find(names.begin(), names.end(), word) == names.end()) {
      std::string list;
      for (auto n : names) list += fmt::format("{}{}", list.empty() ? "" : ", ", n);
      fmt::print(stderr, "stability-scan: unknown subcommand '{}'{} (subcommands: {})\nRun with --help for usage.\n",
                 word, did_you_mean(word, names), list);
      return exit_bad_input;
    }
  }
  std::vector<std::string> args = decimal_arguments(argc, argv);
  std::vector<char*> arg_pointers;
  for (auto& a : args) arg_pointers.push_back(a.data());
  try {
    app.parse(int(arg_pointers.size()), arg_pointers.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "stability-scan: {}\nRun with --help for usage.\n", escaped(e.what()));
    return exit_bad_input;
  }
  try {
    for (auto& [sub, action] : commands)
      if (sub->parsed()) return action();
    return exit_bad_input;
  } catch (const Interrupted& e) {
    fmt::print(stderr, "stability-scan: {}; no output written\n", escaped(e.what()));
    return interrupted_exit_code();
  } catch (const InputError& e) {
    fmt::print(stderr, "stability-scan: error: {}\n", escaped(e.what()));
    return exit_bad_input;
  } catch (const NotSupportedError& e) {
    fmt::print(stderr, "stability-scan: not supported yet: {}\n", escaped(e.what()));
    return exit_bad_input;
  } catch (const NumericalError& e) {
    fmt::print(stderr, "stability-scan: numerical failure: {}\n", escaped(e.what()));
    return exit_numerical;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stability-scan: failed: {}\n", escaped(e.what()));
    return exit_failure;
  }
}

}  // namespace abu::cli
