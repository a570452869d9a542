#include "abu/analysis/map_setup.hpp"

#include "abu/input/shaft_scene.hpp"

#include "abu/input/race_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>


#include "abu/core/errors.hpp"
#include "abu/core/escaped.hpp"
#include "abu/core/resources.hpp"
#include "abu/core/suggest.hpp"
#include "abu/input/ranges.hpp"
#include "abu/scan/map_mpi.hpp"
#include "abu/scan/stick_map.hpp"

namespace abu {

namespace {

// True if setting `a` changes a value `b` also sets (m and m1, or m2 and m2): two axes or
// continuation parameters that overlap are one parameter, refused (docs/robustness.md).
bool params_overlap(ParamRef a, ParamRef b) {
  return a.quantity == b.quantity && (a.ball < 0 || b.ball < 0 || a.ball == b.ball);
}

std::vector<std::string> split_fields(std::string_view spec) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= spec.size(); ++i)
    if (i == spec.size() || spec[i] == ':') {
      parts.emplace_back(spec.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}

}  // namespace

std::optional<double> finite_number(std::string_view text) {
  double v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

namespace {

std::optional<long> integer(const std::string& s) {
  long n = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), n);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return n;
}

// "n:FROM:TO:COUNT": the ball count of a ring (model.md §13.8).
Axis parse_ball_count_axis(const std::vector<std::string>& parts, const Scene& scene, const std::string& origin,
                           const std::string& text) {
  const auto fail = [&](const std::string& rule) -> Axis { throw InputError(origin, 0, text, rule); };
  if (!scene.ring)
    return fail("the ball count is an axis only for a [balls] ring scene (this scene lists [[ball]] tables)");
  if (parts.size() == 5) return fail("the ball-count axis takes every integer: no 'log'");
  if (parts.size() != 4) return fail("expected n:FROM:TO:COUNT");
  const auto from = integer(parts[1]), to = integer(parts[2]), count = integer(parts[3]);
  if (!from) return fail(fmt::format("FROM '{}' is not an integer ball count", parts[1]));
  if (!to) return fail(fmt::format("TO '{}' is not an integer ball count", parts[2]));
  if (!count) return fail(fmt::format("COUNT '{}' is not an integer", parts[3]));
  if (*from < kSceneMinBalls || *to > kSceneMaxBalls || *from > *to)
    return fail(fmt::format("the ball count runs over {} <= FROM <= TO <= {} (got {} .. {})", kSceneMinBalls,
                            kSceneMaxBalls, *from, *to));
  if (*count != *to - *from + 1)
    return fail(fmt::format("COUNT must be TO - FROM + 1 = {}: every integer in between (got {})", *to - *from + 1,
                            *count));
  Axis axis;
  axis.ball_count = true;
  axis.from = double(*from);
  axis.to = double(*to);
  axis.count = int(*count);
  for (long n = *from; n <= *to; ++n) {  // every count's ring must be a valid scene
    Scene probe = scene;
    set_ball_count(probe, int(n), origin);
  }
  return axis;
}

}  // namespace

Axis parse_axis(std::string_view spec, const Scene& scene, const std::string& origin) {
  const std::string text(spec);
  const std::vector<std::string> parts = split_fields(spec);
  const auto fail = [&](const std::string& rule) -> Axis { throw InputError(origin, 0, text, rule); };
  if (!parts.empty() && parts[0] == "n") return parse_ball_count_axis(parts, scene, origin, text);
  if (parts.size() != 4 && parts.size() != 5) return fail("expected NAME:FROM:TO:N or NAME:FROM:TO:N:log");
  Axis axis;
  const auto ref = parse_param(parts[0], int(scene.balls.size()));
  if (!ref) return fail(unknown_name_rule(fmt::format("unknown parameter '{}'", parts[0]), closest_param(parts[0], true),
                                          "known", fmt::format("{}, or n (a ring's ball count)", param_symbols_help())));
  if (ref->quantity == Quantity::ball_radius)
    return fail("the ball radius does not enter the equations of motion (model.md §3)");
  axis.param = *ref;
  const auto number = [&](const std::string& s, const char* what) {
    const auto v = finite_number(s);
    if (!v) fail(fmt::format("{} '{}' is not a finite number", what, s));
    return *v;
  };
  axis.from = number(parts[1], "FROM");
  axis.to = number(parts[2], "TO");
  {
    const auto n = integer(parts[3]);
    if (!n) return fail(fmt::format("N '{}' is not an integer", parts[3]));
    if (*n < 1 || *n > kMaxAxisCount) return fail(fmt::format("N must be in [1, {}] (got {})", kMaxAxisCount, *n));
    axis.count = int(*n);
  }
  if (parts.size() == 5) {
    if (parts[4] != "log") return fail(fmt::format("the fifth field must be 'log' (got '{}')", parts[4]));
    if (!(axis.from > 0 && axis.to > 0))
      return fail(fmt::format("a log axis needs both ends > 0 (got {} .. {})", axis.from, axis.to));
    axis.logarithmic = true;
  }
  if (axis.count > 1 && axis.from == axis.to) return fail("FROM and TO are equal but N > 1");
  // The axis is an interval; the physical range and the scene's rules hold at both ends.
  Scene probe = scene;
  set_checked(probe, axis.param, axis.from, origin);
  check_numerical_range(probe, origin, fmt::format("at {}={}", to_string(axis.param), axis.from));
  set_checked(probe, axis.param, axis.to, origin);
  check_numerical_range(probe, origin, fmt::format("at {}={}", to_string(axis.param), axis.to));
  return axis;
}

MapJob map_job(const Scene& scene, const MapRequest& request) {
  MapJob job;
  job.x = parse_axis(request.x, scene, "--x");
  job.y = parse_axis(request.y, scene, "--y");
  if (job.x.ball_count && job.y.ball_count) throw InputError("--y", 0, request.y, "only one axis can be the ball count");
  if (!job.x.ball_count && !job.y.ball_count && params_overlap(job.x.param, job.y.param))
    throw InputError("--y", 0, escaped(request.y),
                     fmt::format("the y parameter must differ from the x one ({} and {} set the same value)",
                                 to_string(job.x.param), to_string(job.y.param)));
  if (long(job.x.count) * long(job.y.count) > kMaxCells)
    throw InputError("--y", 0, request.y,
                     fmt::format("the map would have {} x {} cells; at most {} are allowed (memory and time)",
                                 job.x.count, job.y.count, kMaxCells));
  job.method = request.method;
  job.sampling = request.sampling;
  job.long_rows = request.long_rows;
  if (scene.law == FrictionLaw::coulomb_set) {  // the stick set per cell (model.md §14, stick_map.hpp)
    if (job.x.ball_count || job.y.ball_count)
      throw InputError(job.x.ball_count ? "--x" : "--y", 0, "n",
                       "a coulomb-set map takes one ball count: the ball count is not an axis of a stick-set map");
    job.stick_set = true;
    job.stick = request.stick;
    job.race = race_shape(scene);
    if (!job.race.round()) job.provenance_notes += describe_race(job.race, "# ");
    if (scene.shaft) {  // through the shaft (model.md §18.17); its numbers in the tiles' manifest
      job.shaft = std::make_shared<const ShaftSpec>(shaft_spec_of(scene));
      job.provenance_notes += describe_shaft(*job.shaft, "# ");
    }
    job.params_n = params_of<any_balls>(scene);
    job.command_line =
        request.command_line + (scene.balls.size() == 2
                                    ? fmt::format(" --stick-columns {} --stick-area-tolerance {}", request.stick.columns,
                                                  request.stick.area_tolerance)
                                    : fmt::format(" --stick-grid {}", request.stick.grid_budget));
    // Every cell's set must be defined (mu > 0, not K = C = 0, no undamped critical speed of a
    // shaft) before any work.
    for (int ix = 0; ix < job.x.count; ++ix)
      for (int iy = 0; iy < job.y.count; ++iy) check_stick_cell_defined(job, ix, iy);
    return job;
  }
  const Axis* count_axis = job.x.ball_count ? &job.x : job.y.ball_count ? &job.y : nullptr;
  job.support = scene.support;  // cells by Floquet multipliers (model.md §10.12), the n-ball path
  // LuGre takes the n-ball cells too, which know its spectra (model.md §12.8).
  job.any_balls = count_axis || scene.balls.size() != 2 || scene.law == FrictionLaw::lugre || scene.support;
  if (!job.any_balls) {
    job.params = params_of<2>(scene);
    job.command_line = request.command_line;
    return job;
  }
  if (const auto rule = options_violation(request.sampling)) throw InputError("--set-samples", 0, "samples", *rule);
  job.params_n = params_of<any_balls>(scene);
  job.command_line = request.command_line + fmt::format(" --set-samples {}", request.sampling.samples_per_sheet);
  if (count_axis) {
    // The other axis must hold on every ball count (a per-ball symbol such as m3 needs 3
    // balls); each count's ring is the scene's, rebuilt (scene.hpp, set_ball_count).
    const bool other_is_x = count_axis == &job.y;
    const std::string& other_spec = other_is_x ? request.x : request.y;
    for (int k = 0; k < count_axis->count; ++k) {
      Scene s = scene;
      set_ball_count(s, int(count_axis->value(k)), other_is_x ? "--y" : "--x");
      parse_axis(other_spec, s, other_is_x ? "--x" : "--y");
      job.by_count.push_back(params_of<any_balls>(s));
    }
    job.provenance_notes =
        scene.ring->total_mass_held
            ? fmt::format("# ball-count axis: the ring's total mass {} kg held (m = total_mass / n)\n",
                          scene.ring->total_mass)
            : fmt::format("# ball-count axis: the ring's per-ball mass {} kg held\n", scene.ring->ball.mass);
  }
  if (scene.law == FrictionLaw::lugre)
    job.provenance_notes += "# friction lugre (model.md §12.8): the z = 0 equilibria (the frictionless model's), each judged by "
                      "the spectrum of (12.10) with c = 1, where both one-sided Jacobians coincide (never non-smooth); "
                      "the n zeros along the family are not counted\n";
  return job;
}

namespace {

// Refuses (exit 2) a map whose tiles and CSVs cannot fit on the disk, or whose workers'
// tiles cannot fit in memory, before any work (docs/robustness.md "Maps").
std::string check_map_fits(const MapJob& job, const MapOutput& output) {
  const double cells = double(job.x.count) * double(job.y.count);
  const double per_cell = double(map_bytes_per_cell(job));
  const double disk = 2 * cells * per_cell;  // the tiles, then the assembled CSVs
  if (const auto free = free_bytes(output.directory); free && disk > *free)
    throw InputError("-o", 0, escaped(output.directory.string()),
                     fmt::format("the map needs about {} of disk ({} cells: its tiles and CSVs), {} are free there; "
                                 "make the map smaller or write it elsewhere",
                                 gigabytes(disk), cells, gigabytes(*free)));
  const int workers = std::max(1, std::min(output.threads, tile_count(job)));
  // Each worker streams its tile (map_driver.hpp): two text buffers and a copy buffer of
  // kTileSpillBytes (each can pass it by one cell's text) and its analyzers; independent of
  // the axes' lengths.
  const double memory =
      double(workers) * (3.0 * (double(kTileSpillBytes) + per_cell) + double(kWorkerBaseBytes));
  if (const auto available = available_memory(); available && memory > *available)
    throw InputError("--threads", 0, std::to_string(output.threads),
                     fmt::format("{} workers would need about {} of memory, {} are available; use fewer threads",
                                 workers, gigabytes(memory), gigabytes(*available)));
  return fmt::format("map: {} cells, about {} of disk (tiles, then CSVs) and {} of memory ({} workers x {:.0f} MB)\n",
                     cells, gigabytes(disk), gigabytes(memory), workers, memory / workers / 1e6);
}
}  // namespace

MapRunReport run_map(const MapJob& job, const MapOutput& output) {
  if (job.provenance.empty())
    throw std::logic_error("run_map: the job has no provenance (output/map_files.hpp, map_provenance)");
  MapRunReport report;
  const std::filesystem::path& dir = output.directory;
  const bool root = mpi_rank() == 0;
  std::shared_ptr<TileStore> store;
  std::optional<std::vector<int>> missing;
  {
    std::exception_ptr failure;
    try {
      if (root) {
        const std::string estimate = check_map_fits(job, output);
        if (output.progress) std::fputs(estimate.c_str(), stderr);
        store = std::make_shared<TileStore>(dir / tile_directory_name(job), job, output.mode);
        missing = store->missing();
      }
    } catch (...) {
      failure = std::current_exception();
    }
    missing = share_missing_tiles(missing);
    if (failure) std::rethrow_exception(failure);
    if (!missing) {
      report.outcome = MapRunReport::Outcome::refused;  // rank 0 refused the input and said why
      return report;
    }
  }
  report.tiles_total = tile_count(job);
  ProgressMeter meter(report.tiles_total, report.tiles_total - int(missing->size()), root && output.progress);
  MapRunOptions run_options;
  run_options.threads = output.threads;
  run_options.stop = output.stop;
  run_options.progress = &meter;
  try {
    report.stats = compute_distributed(job, *missing, run_options, store.get());
  } catch (const InputError&) {
    throw;
  } catch (const NumericalError&) {
    throw;
  } catch (const std::exception& e) {
    // An I/O failure (a full disk): say so, and that the work done is not lost.
    if (!store) throw;
    throw std::runtime_error(fmt::format("{}; the finished tiles are kept in {}, rerun the same command with --resume",
                                         e.what(), escaped(store->directory().string())));
  }
  meter.finish();
  const auto stopped = [&] { return output.stop && output.stop->load(); };
  if (store) report.tile_directory = store->directory();
  if (report.stats.interrupted || stopped()) {
    report.outcome = MapRunReport::Outcome::interrupted;
    if (store) report.tiles_kept = report.tiles_total - int(store->missing().size());
    return report;
  }
  if (!root) {
    report.outcome = MapRunReport::Outcome::other_rank;
    return report;
  }
  report.store = store;
  const bool lugre = job.any_balls && job.params_n.law == FrictionLaw::lugre;
  if (output.boundaries && lugre) {
    report.boundary_note = "no fold/Hopf boundaries for friction law 'lugre': continuation of its z = 0 branches "
                           "with the spectra of (12.10) is not implemented (model.md §12.8)";
  } else if (output.boundaries) {
    const auto started = std::chrono::steady_clock::now();
    const auto seconds = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    };
    if ((report.boundaries = map_boundaries(job))) {
      report.boundary_seconds = seconds();
    } else if ((report.boundaries_n = map_boundaries_n(job))) {
      report.boundary_seconds = seconds();
    } else if (job.stick_set) {
      report.boundary_note = "no fold/Hopf boundaries: a coulomb-set map has stick sets, not isolated equilibria";
    } else {
      report.boundary_note = job.support ? "no fold/Hopf boundaries: the support is anisotropic (the boundaries "
                                           "would be the mean system's; model.md §10.12)"
                                         : "no fold/Hopf boundaries: the ball count is an axis of this map "
                                           "(continuation needs one ball count)";
    }
  }
  if (stopped()) {
    report.outcome = MapRunReport::Outcome::interrupted;
    report.tiles_kept = report.tiles_total;
    return report;
  }
  report.outcome = MapRunReport::Outcome::done;
  return report;
}

}  // namespace abu
