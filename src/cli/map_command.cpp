// `stability-scan map SCENE --x NAME:FROM:TO:N[:log] --y ...`: a stability map over two
// parameters (or a parameter and a ring's ball count, `n:FROM:TO:COUNT`), every
// equilibrium of every cell; tiles on all threads (and MPI ranks), resumable; CSVs, heat
// maps and the fold/Hopf boundaries drawn on top. The work is the library's
// (analysis/map_setup.hpp runs it, output/map_files.hpp writes it); this file is options,
// signals and messages.
#include <fmt/format.h>

#include <thread>

#include <unistd.h>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/output/format.hpp"
#include "abu/output/files.hpp"
#include "abu/analysis/map_setup.hpp"
#include "abu/output/map_files.hpp"
#include "abu/scan/map_driver.hpp"
#include "abu/scan/map_mpi.hpp"
#include "cli.hpp"
#include "commands.hpp"
#include "composed_commands.hpp"
#include "shaft_commands.hpp"
#include "stick_options.hpp"
#include "unround_commands.hpp"
#include "views.hpp"

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
  bool long_csv = false;
  BalancedSampling sampling;
  StickSetOptions stick;  // coulomb-set scenes
  ShaftSpectrumOptions shaft;  // a flexible shaft (model.md §18.13)
};

// The command line that determines the output: thread count, progress, resume and the
// output directory are left out, so that the files of any such runs compare equal.
std::string canonical_command_line(const MapOptions& o) {
  std::string line = fmt::format("stability-scan map {} --x {} --y {}", o.scene.scene, o.x, o.y);
  for (const auto& s : o.scene.overrides) line += " --set " + s;
  if (o.scene.units != "rad/s") line += " --units " + o.scene.units;  // omega is typed in that unit
  if (o.shaft.eigenvalues != ShaftSpectrumOptions{}.eigenvalues) line += fmt::format(" --eigenvalues {}", o.shaft.eigenvalues);
  if (o.shaft.band != ShaftSpectrumOptions{}.band) line += fmt::format(" --band {}", o.shaft.band);
  return line + " --method " + o.method;
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
  sub->add_option("--x", o->x, "x axis NAME:FROM:TO:N[:log], e.g. omega:50:2000:1000, or n:FROM:TO:COUNT (the "
                               "ball count of a [balls] ring scene, every integer)")->required();
  sub->add_option("--y", o->y, "y axis NAME:FROM:TO:N[:log], e.g. mu:1e-4:0.1:1000:log, or n:2:12:11")->required();
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
  sub->add_flag("--long", o->long_csv,
                "Also write map_X_Y.csv, one row per equilibrium per cell (~0.8 kB a cell: ~820 MB for 1000 x 1000); "
                "summary_X_Y.csv is always written");
  sub->add_option("--set-samples", o->sampling.samples_per_sheet,
                  "Samples per sheet of the balanced set (n >= 3 balls), as for `equilibria`")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  add_stick_resolution_options(*sub, o->stick);
  add_shaft_spectrum_options(*sub, o->shaft);
  return [o]() -> int {
    // Everything is checked before any work (exit 2, nothing written).
    const Scene scene = load(o->scene);
    if (scene.shaft && !set_valued_on_shaft(scene)) {  // the balanced state's stability (model.md §18.13)
      const bool race = unround_on_shaft(scene);           // or the race's equilibria on the shaft (§18.18)
      refuse_unmodelled(scene, "map", race ? Handles{.shaft_unround = true} : Handles{.shaft = true});
      check_output_directory(o->output_dir);
      return (race ? map_shaft_race : map_shaft)(scene, {omega_axis_input(o->scene, o->x), omega_axis_input(o->scene, o->y),
                               canonical_command_line(*o), o->scene.overrides, o->shaft, o->sampling, o->threads,
                               o->resume, o->fresh, o->progress, o->quiet, o->chart, o->output_dir});
    }
    if (o->shaft.eigenvalues != ShaftSpectrumOptions{}.eigenvalues || o->shaft.band != ShaftSpectrumOptions{}.band)
      throw InputError(o->shaft.band != ShaftSpectrumOptions{}.band ? "--band" : "--eigenvalues", 0, "shaft",
                       "ARPACK's eigenvalue count and band apply to a flexible shaft ([shaft]) only; a rigid "
                       "map computes every eigenvalue");
    const bool stick_on_race = set_valued_on_unround_race(scene);  // the stick set per cell (§20.5)
    if ((!scene.race.round() || o->x.rfind(kUnroundnessParam + ":", 0) == 0 ||
         o->y.rfind(kUnroundnessParam + ":", 0) == 0) && !stick_on_race) {  // model.md §11.10
      const bool on_support = unround_on_anisotropic_support(scene);  // periodic orbits per cell (§20.7)
      refuse_unmodelled(scene, "map", on_support ? Handles{.unround_anisotropic = true} : Handles{.unround = true});
      check_output_directory(o->output_dir);
      return (on_support ? map_composed : map_unround)(
          scene, o->scene,
          {omega_axis_input(o->scene, o->x), omega_axis_input(o->scene, o->y), canonical_command_line(*o), o->threads,
           o->resume, o->fresh, o->progress, o->quiet, o->chart, o->output_dir});
    }
    const bool stick = scene.law == FrictionLaw::coulomb_set;  // the stick set per cell (model.md §14)
    refuse_unmodelled(scene, "map",
                      {.lugre = true, .set_valued = true, .anisotropic = true, .unround_set_valued = true,
                       .shaft_set_valued = true});
    check_output_directory(o->output_dir);  // refused before any work
    MapRequest request;
    request.x = omega_axis_input(o->scene, o->x);
    request.y = omega_axis_input(o->scene, o->y);
    request.method = o->method == "full" ? CellMethod::full : CellMethod::fast;
    request.sampling = o->sampling;
    request.stick = stick_resolution(o->stick);
    request.command_line = canonical_command_line(*o);
    request.long_rows = o->long_csv;
    MapJob job = map_job(scene, request);
    job.provenance = map_provenance(job, scene.file);
    for (const Axis* a : {&job.x, &job.y})
      if (a->from > a->to && !o->quiet)
        fmt::print(stderr, "stability-scan: note: {} runs downward, from {} to {} (index 0 at {})\n",
                   a == &job.x ? "--x" : "--y", a->from, a->to, a->from);

    MapOutput output;
    output.directory = o->output_dir;
    output.mode = o->resume ? TileStore::Mode::resume : o->fresh ? TileStore::Mode::discard : TileStore::Mode::fresh;
    output.threads = o->threads;
    output.stop = &stop_flag();  // set by the CLI's signal thread (cli.cpp)
    output.progress = !o->quiet && (o->progress || isatty(STDERR_FILENO));
    output.boundaries = o->boundaries;
    set_interrupt_note(fmt::format("the finished tiles are kept in {}; rerun the same command with --resume",
                                   escaped((std::filesystem::path(o->output_dir) / tile_directory_name(job)).string())));
    MapRunReport r = run_map(job, output);
    MapFilesReport files;
    if (r.outcome == MapRunReport::Outcome::done) {
      files = write_map_files(job, r, {o->output_dir, o->chart, scene.file, &stop_flag()});
      if (!files.written) {
        r.outcome = MapRunReport::Outcome::interrupted;
        r.tiles_kept = r.tiles_total;
      }
    }
    set_interrupt_note({});
    switch (r.outcome) {
      case MapRunReport::Outcome::refused: return exit_bad_input;
      case MapRunReport::Outcome::other_rank: return exit_ok;
      case MapRunReport::Outcome::interrupted:
        if (mpi_rank() != 0) return interrupted_exit_code();
        if (r.tiles_kept == r.tiles_total)
          fmt::print(stderr, "stability-scan: interrupted while writing; the tiles are kept in {}; rerun with --resume\n",
                     r.tile_directory.string());
        else
          fmt::print(stderr,
                     "stability-scan: interrupted: {} of {} tiles are kept in {}; run the same command with --resume "
                     "to finish the map\n",
                     r.tiles_kept, r.tiles_total, r.tile_directory.string());
        return interrupted_exit_code();
      case MapRunReport::Outcome::done: break;
    }
    const MapRunStats& stats = r.stats;
    const std::filesystem::path dir(o->output_dir);
    // The stable speed ranges per value of the other axis (docs/views.md), from the summary.
    if (!stick)  // a stick-set map has no stability verdicts to turn into speed ranges
      write_map_ranges(dir, o->x.substr(0, o->x.find(':')), o->y.substr(0, o->y.find(':')), files.verdicts, scene,
                       o->scene, canonical_command_line(*o), o->quiet);
    if (!o->quiet && r.boundary_seconds >= 0) fmt::print(stderr, "boundaries: {:.2f} s\n", r.boundary_seconds);
    if (!o->quiet && !r.boundary_note.empty()) fmt::print(stderr, "{}\n", r.boundary_note);
    if (!o->quiet)
      fmt::print(stderr,
                 "{} cells, {} {}, {} tiles computed in {:.2f} s ({:.3g} cells/s) -> {}\n", stats.cells,
                 stats.equilibria,
                 stick ? "stick-set components"
                       : fmt::format("equilibria ({} decided by full eigenvalues)", stats.fallbacks),
                 stats.tiles, stats.seconds,
                 stats.seconds > 0 ? double(stats.cells) / stats.seconds : 0.0, dir.string());
    return exit_ok;
  };
}

}  // namespace abu::cli
