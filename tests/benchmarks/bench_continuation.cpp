// A full omega continuation of every branch of a scene from 0.2 omega_n to 8 omega_n with
// the special points located, against finding the same points on plain sweep grids:
// speed against error.
//
//   bench_continuation SCENE [--repeat R] [--max-grid N] [--process BINARY]... [--launches L]
//
// Prints the continuation's median wall time (library call, one thread and one per core),
// its steps and Newton iterations, then for sweep grids of increasing size the time and the
// relative error of each special point located between grid values (midpoint of the
// bracket). With --process, the whole process: `BINARY continue SCENE --set omega=FROM
// --param omega --to TO --no-chart -o DIR [EXTRA]` (--process "BINARY EXTRA", e.g.
// "build/stability-scan --threads 1") launched L times per binary (interleaved, so that
// two binaries, e.g. before and after a change, see the same machine), median wall time
// and median CPU time (user + system, from wait4) per launch. --max-grid 0 skips the grids.
#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <spawn.h>
#include <sys/resource.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/scan/scan.hpp"
#include "abu/input/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Located {
  abu::Label label;
  double parameter;
};

// Special points on a grid: a fold where the number of together equilibria changes, a
// Hopf point where the balanced state's count of unstable eigenvalues changes by two.
std::vector<Located> grid_points(const abu::SweepResult& s) {
  std::vector<Located> out;
  const auto count = [](const abu::Analysis& a, abu::Family f) {
    int n = 0;
    for (const auto& e : a.equilibria.points()) n += e.family == f;
    return n;
  };
  const auto balanced_unstable = [](const abu::Analysis& a) {
    const auto pts = a.equilibria.points();
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (pts[i].family == abu::Family::balanced) return a.spectra[i].n_unstable;
    return -1;
  };
  for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
    const double mid = (s.values[i] + s.values[i + 1]) / 2;
    if (count(s.points[i], abu::Family::together) != count(s.points[i + 1], abu::Family::together))
      out.push_back({abu::Label::LP, mid});
    const int a = balanced_unstable(s.points[i]), b = balanced_unstable(s.points[i + 1]);
    if (a >= 0 && b >= 0 && std::abs(a - b) == 2) out.push_back({abu::Label::HB, mid});
  }
  return out;
}

struct Launch {
  double wall = 0, cpu = 0;  // s
};

// One launch of `argv` (stdout and stderr to /dev/null): wall time, and CPU time of the
// child alone (wait4's rusage).
Launch launch(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  const auto t0 = Clock::now();
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) {
    fmt::print(stderr, "cannot launch {}\n", args[0]);
    std::exit(2);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  Launch l;
  l.wall = std::chrono::duration<double>(Clock::now() - t0).count();
  posix_spawn_file_actions_destroy(&actions);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    fmt::print(stderr, "{} failed\n", args[0]);
    std::exit(2);
  }
  const auto seconds = [](timeval t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  l.cpu = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  return l;
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  if (argc < 2) {
    fmt::print(stderr,
               "usage: bench_continuation SCENE [--repeat R] [--max-grid N] [--process BINARY]... [--launches L]\n");
    return 2;
  }
  int repeats = 11, max_grid = 10000, launches = 21;
  std::vector<std::string> binaries;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--repeat") repeats = std::max(1, std::stoi(argv[i + 1]));
    if (std::string(argv[i]) == "--max-grid") max_grid = std::stoi(argv[i + 1]);
    if (std::string(argv[i]) == "--process") binaries.emplace_back(argv[i + 1]);
    if (std::string(argv[i]) == "--launches") launches = std::max(1, std::stoi(argv[i + 1]));
  }
  abu::Params p = abu::params_of<2>(abu::load_scene(argv[1]));
  const double omega_n = std::sqrt(p.rotor.stiffness / p.total_mass());
  const double from = 0.2 * omega_n, to = 8 * omega_n;
  p.omega = from;
  const abu::ParamRef omega = *abu::parse_param("omega", 2);

  std::vector<double> times, times_all;
  abu::ContinuationRun run;
  abu::ContinuationOptions all_cores;
  all_cores.threads = 0;
  for (int r = 0; r < repeats; ++r) {
    auto t0 = Clock::now();
    run = abu::continue_branches(p, omega, to, abu::ContinuationOptions{});
    times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    t0 = Clock::now();
    (void)abu::continue_branches(p, omega, to, all_cores);
    times_all.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::vector<Located> exact;
  for (const auto& b : run.branches)
    for (const auto& sp : b.specials) {
      bool seen = false;
      for (const auto& e : exact) seen = seen || (e.label == sp.label && std::abs(e.parameter - double(sp.parameter)) < 1e-9);
      if (!seen) exact.push_back({sp.label, double(sp.parameter)});
    }
  const auto& st = run.stats;
  fmt::print("scene {}: omega from {:.6g} to {:.6g} rad/s (0.2 .. 8 omega_n), median of {} runs, 1 thread\n", argv[1],
             from, to, repeats);
  fmt::print("continuation: {:.2f} ms (1 thread), {:.2f} ms (threads = 0: one per core, {} here); {} branches, {} steps "
             "({} retried), {} Newton iterations, {} spectra tracked, {} computed afresh; special points:",
             median(times) * 1e3, median(times_all) * 1e3, std::max(1u, std::thread::hardware_concurrency()),
             run.branches.size(), st.steps, st.rejected, st.newton_iterations, st.tracked_spectra, st.full_spectra);
  for (const auto& e : exact) fmt::print(" {} {:.17g}", abu::to_string(e.label), e.parameter);
  fmt::print("\n");
  if (!binaries.empty()) {
    // The whole process, each binary launched in turn (interleaved: the same machine state).
    const auto dir = std::filesystem::temp_directory_path() / fmt::format("bench_continuation.{}", ::getpid());
    std::vector<std::vector<Launch>> runs(binaries.size());
    for (int r = 0; r < launches; ++r)
      for (std::size_t b = 0; b < binaries.size(); ++b)
      {
        // "BINARY [EXTRA ARGS]": the binary, then the command, then the extra arguments.
        std::vector<std::string> words;
        for (std::size_t at = 0; at < binaries[b].size();) {
          const std::size_t space = std::min(binaries[b].find(' ', at), binaries[b].size());
          if (space > at) words.push_back(binaries[b].substr(at, space - at));
          at = space + 1;
        }
        std::vector<std::string> args{words[0], "continue", argv[1], "--set", fmt::format("omega={:.17g}", from),
                                      "--param", "omega", "--to", fmt::format("{:.17g}", to), "--no-chart", "-o",
                                      dir.string()};
        args.insert(args.end(), words.begin() + 1, words.end());
        runs[b].push_back(launch(args));
      }
    std::filesystem::remove_all(dir);
    fmt::print("whole process `continue --no-chart` (start-up, parse, all branches, special points, CSVs), median of {} "
               "launches each, interleaved:\n", launches);
    for (std::size_t b = 0; b < binaries.size(); ++b) {
      std::vector<double> wall, cpu;
      for (const auto& l : runs[b]) wall.push_back(l.wall), cpu.push_back(l.cpu);
      fmt::print("  {:<48} wall {:6.2f} ms   CPU {:6.2f} ms\n", binaries[b], median(wall) * 1e3, median(cpu) * 1e3);
    }
  }
  if (max_grid > 0) fmt::print("{:>10} {:>12} {:>26}\n", "sweep N", "time [ms]", "worst rel. error of a point");
  for (int n = 100; max_grid > 0 && n <= max_grid; n *= 10) {
    const auto values = abu::grid_values(from, to, n, false);
    const auto t0 = Clock::now();
    const abu::SweepResult s = abu::sweep(p, omega, values);
    const double ms = std::chrono::duration<double>(Clock::now() - t0).count() * 1e3;
    const auto found = grid_points(s);
    double worst = 0;
    int missed = 0;
    for (const auto& e : exact) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& f : found)
        if (f.label == e.label) best = std::min(best, std::abs(f.parameter - e.parameter) / e.parameter);
      if (!std::isfinite(best)) ++missed;
      else worst = std::max(worst, best);
    }
    fmt::print("{:>10} {:>12.1f} {:>26.2e}{}\n", n, ms, worst, missed ? fmt::format("  ({} missed)", missed) : "");
  }
  return 0;
}
