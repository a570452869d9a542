#include "tiled_run.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <sstream>

#include "abu/core/cancel.hpp"
#include "abu/output/format.hpp"
#include "cli.hpp"

namespace abu::cli {

TileStore::Mode tile_store_mode(const TiledRunFlags& flags) {
  return flags.resume ? TileStore::Mode::resume : flags.fresh ? TileStore::Mode::discard : TileStore::Mode::fresh;
}

std::optional<FinishedTiles> run_missing_tiles(const TileStore& store, const std::filesystem::path& tiles_dir, int tiles,
                                               const TiledRunFlags& flags, const TileComputation& compute) {
  const std::vector<int> missing = store.missing();
  ProgressMeter meter(tiles, tiles - int(missing.size()), !flags.quiet && (flags.progress || isatty(STDERR_FILENO)));
  MapRunOptions run;
  run.threads = flags.threads;
  run.stop = &stop_flag();
  run.progress = &meter;
  set_interrupt_note(fmt::format("the finished tiles are kept in {}; rerun the same command with --resume",
                                 escaped(tiles_dir.string())));
  const MapRunStats stats = compute(missing, run, [&store](int tile, TileText&& text) { store.put(tile, text); });
  meter.finish();
  set_interrupt_note({});
  if (!stats.interrupted && !stop_requested()) {
    std::ostringstream rows, summary;
    for (int t = 0; t < tiles; ++t) store.append(t, rows, summary);
    return FinishedTiles{stats, rows.str(), summary.str()};
  }
  fmt::print(stderr, "stability-scan: interrupted: {} of {} tiles are kept in {}; run the same command with --resume\n",
             tiles - int(store.missing().size()), tiles, tiles_dir.string());
  return std::nullopt;
}

}  // namespace abu::cli
