// `stability-scan map SCENE --x NAME:FROM:TO:N[:log] --y ...`: a stability map over two
// parameters, every equilibrium of every cell; tiles on all threads (and MPI ranks),
// resumable; CSVs, heat maps and the fold/Hopf boundaries drawn on top.
#include <fmt/format.h>

#include <csignal>
#include <fstream>
#include <thread>

#include <unistd.h>

#include "abu/continuation/boundaries.hpp"
#include "cli.hpp"
#include "abu/core/errors.hpp"
#include "abu/io/io.hpp"
#include "abu/scan/map_driver.hpp"
#include "abu/scan/map_mpi.hpp"
#include "abu/io/report.hpp"
#include "commands.hpp"

namespace abu::cli {

namespace {

struct MapOptions {
  SceneOptions scene;
  std::string x, y;
  std::string output_dir = "out";
  std::string method = "fast";
  int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  bool resume = false, fresh = false, progress = false, quiet = false;
  bool chart = true, boundaries = true;
};

std::atomic<bool> g_interrupted{false};
extern "C" void on_interrupt(int) { g_interrupted = true; }

// SIGINT/SIGTERM stop the workers after their current tile (the tiles written so far
// stay for --resume); the previous handlers come back when the map is done.
class InterruptGuard {
 public:
  InterruptGuard() {
    g_interrupted = false;
    previous_int_ = std::signal(SIGINT, on_interrupt);
    previous_term_ = std::signal(SIGTERM, on_interrupt);
  }
  ~InterruptGuard() {
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  void (*previous_int_)(int) = SIG_DFL;
  void (*previous_term_)(int) = SIG_DFL;
};

// The command line that determines the output: thread count, progress, resume and the
// output directory are left out, so that the files of any such runs compare equal.
std::string canonical_command_line(const MapOptions& o) {
  std::string line = fmt::format("stability-scan map {} --x {} --y {}", o.scene.scene, o.x, o.y);
  for (const auto& s : o.scene.overrides) line += " --set " + s;
  return line + " --method " + o.method;
}

// The fold and Hopf curves in the map's plane: every fold and Hopf point of a
// continuation in x along the bottom and the top edge, continued in y across the map.
// A curve that meets neither edge is not found (said in the CSV).
std::string boundary_overlay(const MapJob& job) {
  BoundaryRun all;
  all.param = job.x.param;
  all.param2 = job.y.param;
  all.from = job.x.from, all.to = job.x.to, all.from2 = job.y.from, all.to2 = job.y.to;
  ContinuationOptions options;
  for (const auto& [at, to] : {std::pair{job.y.from, job.y.to}, std::pair{job.y.to, job.y.from}}) {
    Params p = job.params;
    set(p, job.x.param, job.x.from);
    set(p, job.y.param, at);
    const ContinuationRun run = continue_branches(p, job.x.param, job.x.to, options, StartSelection{});
    BoundaryRun part = continue_boundaries(p, run, job.y.param, to, options);
    for (auto& c : part.curves) all.curves.push_back(std::move(c));
    for (auto& n : part.notes) all.notes.push_back(std::move(n));
  }
  all.notes.push_back(
      "curves found from the fold and Hopf points on the bottom and top edges of the map; a closed curve "
      "inside the map touching neither edge is not drawn");
  return boundary_csv(all, job.provenance);
}

}  // namespace

Action add_map_command(CLI::App& app) {
  auto o = std::make_shared<MapOptions>();
  CLI::App* sub = app.add_subcommand(
      "map",
      "Stability map over two parameters: every equilibrium of every cell (exists, stable, unstable count, "
      "spectral abscissa, |q|, ball angles), a per-cell summary, heat maps with the fold/Hopf boundaries. "
      "Resumable (--resume), multi-threaded, and across MPI ranks in an -DABU_MPI=ON build.");
  add_scene_options(*sub, o->scene);
  sub->add_option("--x", o->x, "x axis NAME:FROM:TO:N[:log], e.g. omega:50:2000:1000")->required();
  sub->add_option("--y", o->y, "y axis NAME:FROM:TO:N[:log], e.g. mu:1e-4:0.1:1000:log")->required();
  sub->add_option("-o,--output-dir", o->output_dir, "Directory for map_X_Y.csv, summary_X_Y.csv and the charts")
      ->capture_default_str();
  sub->add_option("--method", o->method, "Stability decision: fast (characteristic polynomial, full near the "
                                         "boundary) or full (refined eigenvalues everywhere)")
      ->check(CLI::IsMember({"fast", "full"}))
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "Worker threads (the output does not depend on it)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  auto* resume = sub->add_flag("--resume", o->resume, "Continue an interrupted map from its tiles");
  auto* fresh = sub->add_flag("--fresh", o->fresh, "Discard the tiles of an interrupted map and start over");
  resume->excludes(fresh);
  auto* progress = sub->add_flag("--progress", o->progress, "Show progress and ETA on stderr even if not a terminal");
  auto* quiet = sub->add_flag("--quiet", o->quiet, "No progress and no summary on stderr");
  progress->excludes(quiet);
  sub->add_flag("!--no-chart", o->chart, "Skip the PNG/SVG heat maps");
  sub->add_flag("!--no-boundaries", o->boundaries, "Skip the fold/Hopf boundary curves (continuation)");
  return [o]() -> int {
    // Everything is checked before any work (exit 2, nothing written).
    const Scene scene = load(o->scene);
    MapJob job;
    job.x = parse_axis(o->x, scene, "--x");
    job.y = parse_axis(o->y, scene, "--y");
    if (job.x.param == job.y.param) throw InputError("--y", 0, o->y, "the y parameter must differ from the x one");
    if (long(job.x.count) * long(job.y.count) > kMaxCells)
      throw InputError("--y", 0, o->y,
                       fmt::format("the map would have {} x {} cells; at most {} are allowed (memory and time)",
                                   job.x.count, job.y.count, kMaxCells));
    job.params = params_of<2>(scene);
    job.method = o->method == "full" ? CellMethod::full : CellMethod::fast;
    job.provenance = provenance_header(canonical_command_line(*o), scene.file, job.params);
    const std::filesystem::path dir(o->output_dir);
    const bool root = mpi_rank() == 0;

    std::optional<TileStore> store;
    std::optional<std::vector<int>> missing;
    {
      std::exception_ptr failure;
      try {
        if (root) {
          store.emplace(dir / tile_directory_name(job), job,
                        o->resume  ? TileStore::Mode::resume
                        : o->fresh ? TileStore::Mode::discard
                                   : TileStore::Mode::fresh);
          missing = store->missing();
        }
      } catch (...) {
        failure = std::current_exception();
      }
      missing = share_missing_tiles(missing);
      if (failure) std::rethrow_exception(failure);
      if (!missing) return exit_bad_input;  // rank 0 refused the input and said why
    }

    const int total = tile_count(job);
    const bool show = root && !o->quiet && (o->progress || isatty(STDERR_FILENO));
    ProgressMeter meter(total, total - int(missing->size()), show);
    InterruptGuard guard;
    MapRunOptions run_options;
    run_options.threads = o->threads;
    run_options.stop = &g_interrupted;
    run_options.progress = &meter;
    const MapRunStats stats = compute_distributed(job, *missing, run_options, store ? &*store : nullptr);
    meter.finish();
    if (stats.interrupted || g_interrupted) {
      if (root)
        fmt::print(stderr,
                   "stability-scan: interrupted: {} of {} tiles are kept in {}; run the same command with --resume "
                   "to finish the map\n",
                   total - int(store->missing().size()), total, store->directory().string());
      return exit_interrupted;
    }
    if (!root) return exit_ok;

    OutputTransaction out;
    const auto map_path = out.reserve(dir / map_file_name(job));
    const auto summary_path = out.reserve(dir / summary_file_name(job));
    {
      std::ofstream map_csv(map_path, std::ios::binary), summary_csv(summary_path, std::ios::binary);
      assemble(job, *store, map_csv, summary_csv);
      map_csv.close();
      summary_csv.close();
      if (!map_csv || !summary_csv) throw std::runtime_error(fmt::format("{}: cannot write the map", dir.string()));
    }
    const std::string x = to_string(job.x.param), y = to_string(job.y.param);
    std::filesystem::path curves;
    if (o->boundaries) {
      const auto started = std::chrono::steady_clock::now();
      curves = out.stage(dir / fmt::format("boundary_{}_{}.csv", x, y), boundary_overlay(job));
      if (!o->quiet)
        fmt::print(stderr, "boundaries: {:.2f} s\n",
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    }
    if (o->chart) {
      const auto name = [&](const char* kind, const char* ext) {
        return out.reserve(dir / fmt::format("{}_{}_{}.{}", kind, x, y, ext)).string();
      };
      run_gnuplot(plots_dir() / "map.gp", {{"summary", summary_path.string()},
                                           {"curves", curves.string()},
                                           {"png_stability", name("stability", "png")},
                                           {"svg_stability", name("stability", "svg")},
                                           {"png_vibration", name("vibration", "png")},
                                           {"svg_vibration", name("vibration", "svg")},
                                           {"xname", x},
                                           {"xunit", std::string(unit(job.x.param.quantity))},
                                           {"yname", y},
                                           {"yunit", std::string(unit(job.y.param.quantity))},
                                           {"logx", job.x.logarithmic ? "1" : "0"},
                                           {"logy", job.y.logarithmic ? "1" : "0"},
                                           {"title", scene.file}});
    }
    if (g_interrupted) {
      fmt::print(stderr, "stability-scan: interrupted while writing; the tiles are kept in {}; rerun with --resume\n",
                 store->directory().string());
      return exit_interrupted;  // `out` removes its temporaries
    }
    out.commit();
    store->remove();
    if (!o->quiet)
      fmt::print(stderr,
                 "{} cells, {} equilibria ({} decided by full eigenvalues), {} tiles computed in {:.2f} s "
                 "({:.3g} cells/s) -> {}\n",
                 stats.cells, stats.equilibria, stats.fallbacks, stats.tiles, stats.seconds,
                 stats.seconds > 0 ? double(stats.cells) / stats.seconds : 0.0, dir.string());
    return exit_ok;
  };
}

}  // namespace abu::cli
