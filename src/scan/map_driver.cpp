#include "abu/scan/map_driver.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <cmath>
#include <exception>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <thread>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/temp_files.hpp"
#include "abu/scan/stick_map.hpp"
#include "map_rows.hpp"

namespace abu {

using map_rows::AxisText;
using map_rows::TileBuffers;

namespace fs = std::filesystem;

// A worker holds one tile's text in memory: with a long y axis fewer columns per tile keep
// that under kTileBudgetBytes (the maps of up to ~5000 rows keep kTileColumns).
int MapJob::tile_columns() const {
  if (any_balls || stick_set) return 1;  // cells of up to seconds each
  const long per_column = long(y.count) * long(map_bytes_per_cell(*this));
  return int(std::clamp<long>(kTileBudgetBytes / std::max(per_column, 1L), 1, kTileColumns));
}

std::size_t map_bytes_per_cell(const MapJob& job) {
  if (job.stick_set) return stick_map_bytes_per_cell(job);
  if (!job.any_balls) return job.long_rows ? kMapBytesPerCell : kSummaryBytesPerCell;
  // n balls: up to 2^n aligned rows and the balanced samples, each with n angle columns.
  const int n = job.max_balls_in_map();
  return job.long_rows ? std::size_t((64 + (1 << n)) * (100 + 25 * n)) : std::size_t(kSummaryBytesPerCell + 50 * n);
}

int tile_count(const MapJob& job) { return (job.x.count + job.tile_columns() - 1) / job.tile_columns(); }

std::string map_file_name(const MapJob& job) {
  return fmt::format("map_{}_{}.csv", job.x.name(), job.y.name());
}
std::string summary_file_name(const MapJob& job) {
  return fmt::format("summary_{}_{}.csv", job.x.name(), job.y.name());
}
std::string tile_directory_name(const MapJob& job) {
  return fmt::format(".map_{}_{}.tiles", job.x.name(), job.y.name());
}

int MapJob::max_balls_in_map() const {
  if (x.ball_count) return int(x.to);
  if (y.ball_count) return int(y.to);
  return any_balls || stick_set ? params_n.n_balls() : 2;
}

CellWorkspace::CellWorkspace(const MapJob& job) {
  if (job.stick_set) return;  // stick_set() keeps no state between cells
  if (job.any_balls)
    any_balls.emplace(job.params_n, job.by_count, job.x, job.y, job.sampling, job.support);
  else
    two_balls.emplace(job.params, job.x, job.y, job.method);
}

namespace {

// Text buffered per worker before it goes to the tile's temporaries (streamed tiles): the
// worker's memory does not grow with the y axis (2 GB at 8 threads, N_y = 20,000).
constexpr std::size_t kSpillBytes = kTileSpillBytes;

// The cells of `tile` into `out`. With `spill` set, whenever a buffer passes kSpillBytes
// its contents go to `spill` and the buffers are emptied; without, everything stays in
// the buffers. The bytes are the same either way.
using Spill = std::function<void(TileBuffers& out)>;
TileText compute_tile_text(const MapJob& job, int tile, CellWorkspace& workspace, TileBuffers& out,
                           const Spill& spill) {
  TileText text;
  const int first = tile * job.tile_columns(), last = std::min(job.x.count, first + job.tile_columns());
  const auto maybe_spill = [&] {
    if (spill && out.largest() >= kSpillBytes) spill(out);
  };
  const AxisText xs(job.x, first, last), ys(job.y);
  if (job.stick_set) {  // coulomb-set: the stick set of every cell (stick_map.hpp); no grid block
    for (int ix = first; ix < last; ++ix)
      for (int iy = 0; iy < job.y.count; ++iy) {
        throw_if_stopped("a map tile");
        ++text.cells;
        text.equilibria += write_stick_cell(job, ix, iy, xs[ix], ys[iy], out.rows, out.summary);
        if (!job.long_rows) out.rows.clear();
        maybe_spill();
      }
    return text;
  }
  if (job.any_balls) {
    for (int ix = first; ix < last; ++ix)
      for (int iy = 0; iy < job.y.count; ++iy) {
        throw_if_stopped("a map tile");  // the tile under way is not written; --resume redoes it
        workspace.any_balls->analyze(ix, iy, workspace.cell_n);
        ++text.cells;
        text.equilibria += long(workspace.cell_n.equilibria.size());
        text.fallbacks += long(workspace.cell_n.equilibria.size());  // every one by full eigenvalues
        map_rows::write_cell_n(job, ix, iy, xs[ix], ys[iy], workspace.cell_n, out);
        maybe_spill();
      }
    return text;
  }
  CellAnalyzer& analyzer = *workspace.two_balls;
  MapCell& cell = workspace.cell;
  for (int ix = first; ix < last; ++ix) {
    for (int iy = 0; iy < job.y.count; ++iy) {
      throw_if_stopped("a map tile");  // the tile under way is not written; --resume redoes it
      analyzer.analyze(ix, iy, cell);
      ++text.cells;
      text.equilibria += cell.count;
      text.fallbacks += cell.fallbacks;
      map_rows::write_cell(job, ix, iy, xs[ix], ys[iy], cell, out);
      maybe_spill();
    }
  }
  return text;
}

}  // namespace

TileText compute_tile(const MapJob& job, int tile, CellWorkspace& workspace) {
  // Compiled formats into fmt's buffers: half the cost of a map's cells is writing them,
  // and a format string parsed per row would be most of that.
  TileBuffers out;
  TileText text = compute_tile_text(job, tile, workspace, out, {});
  text.rows.assign(out.rows.data(), out.rows.size());
  text.summary.assign(out.summary.data(), out.summary.size());
  text.grid.assign(out.grid.data(), out.grid.size());
  return text;
}

// ---------------------------------------------------------------------------------------
// Tiles on disk

namespace {

// The job's headers without the lines that only spell the request (the command line as
// typed, the scene's path): a resumed run is the same map when the parameters, axes,
// method and program are, however the scene path or the options were written.
std::string manifest_of(const MapJob& job) {
  std::string out = fmt::format("abu map tiles v3: {} columns per tile, {} tiles, {}\n", job.tile_columns(),
                                tile_count(job), job.long_rows ? "with the long rows (--long)" : "without the long rows");
  std::istringstream headers(map_csv_header(job) + summary_csv_header(job));
  for (std::string line; std::getline(headers, line);)
    if (line.rfind("# command:", 0) != 0 && line.rfind("# scene:", 0) != 0) out += line + '\n';
  return out;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string content(fs::file_size(path), '\0');
  in.read(content.data(), std::streamsize(content.size()));
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read", path.string()));
  return content;
}

// Writes under an exclusively created temporary (random name, registered so that a stop
// removes it) and renames: a reader sees the whole file or none. Errors name errno.
void write_atomically(const fs::path& path, std::string_view a, std::string_view b = {}, std::string_view c = {},
                      std::string_view d = {}) {
  int fd = -1;
  const fs::path part = create_temporary_next_to(path, "part", fd);
  const auto fail = [&](const char* what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(part.c_str());
    unregister_temporary(part);
    throw std::runtime_error(fmt::format("{}: cannot {}: {}", path.string(), what, std::strerror(err)));
  };
  for (std::string_view piece : {a, b, c, d}) {
    while (!piece.empty()) {
      const ssize_t n = ::write(fd, piece.data(), piece.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) fail("write", n < 0 ? errno : ENOSPC);
      piece.remove_prefix(std::size_t(n));
    }
  }
  if (::close(fd) != 0) {
    fd = -1;
    fail("write", errno);
  }
  fd = -1;
  if (::rename(part.c_str(), path.c_str()) != 0) fail("rename into place", errno);
  unregister_temporary(part);
}

}  // namespace

// The directory's lock: flock on DIR/lock, the holder's PID inside. A lock file that was
// removed (a finished map removes its directory) while we waited is not ours: retry.
void TileStore::lock() {
  const fs::path path = directory_ / "lock";
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
      throw std::runtime_error(fmt::format("{}: cannot open the tile lock: {}", path.string(), std::strerror(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      char buffer[32] = {};
      const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
      ::close(fd);
      if (err != EWOULDBLOCK)
        throw std::runtime_error(fmt::format("{}: cannot lock: {}", path.string(), std::strerror(err)));
      const std::string holder = n > 0 ? std::string(buffer, std::size_t(n)) : std::string("unknown");
      throw InputError("-o", 0, directory_.string(),
                       fmt::format("another map (PID {}) is writing these tiles; wait for it to finish or stop it",
                                   holder.substr(0, holder.find_first_not_of("0123456789"))));
    }
    struct stat by_fd {}, by_path {};
    if (::fstat(fd, &by_fd) == 0 && ::stat(path.c_str(), &by_path) == 0 && by_fd.st_ino == by_path.st_ino &&
        by_fd.st_dev == by_path.st_dev) {
      const std::string pid = std::to_string(::getpid());
      if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
        // The lock holds without the PID; the message of a second writer says "unknown".
      }
      lock_fd_ = fd;
      return;
    }
    ::close(fd);
    fs::create_directories(directory_);
  }
  throw std::runtime_error(fmt::format("{}: cannot take the tile lock", path.string()));
}

TileStore::TileStore(fs::path directory, const MapJob& job, Mode mode)
    : TileStore(std::move(directory), manifest_of(job), tile_count(job), mode) {}

TileStore::TileStore(fs::path directory, const std::string& manifest, int tiles, Mode mode)
    : directory_(std::move(directory)), tiles_(tiles) {
  const fs::path manifest_path = directory_ / "manifest";
  std::error_code ec;
  const bool existed = fs::exists(directory_, ec);
  if (existed && !fs::is_directory(directory_, ec))
    throw InputError("-o", 0, directory_.string(), "exists and is not a tile directory");
  fs::create_directories(directory_);
  lock();  // before looking at anything inside: another writer may be changing it
  // A directory without a manifest holds no tiles of any map (a first write that failed,
  // or only the lock of a finished run): it counts as absent.
  const bool has_map = fs::exists(manifest_path, ec);
  if (has_map && mode == Mode::fresh)
    throw InputError("-o", 0, directory_.string(),
                     "holds the tiles of an interrupted map; continue it with --resume or start over with --fresh");
  if (has_map && mode == Mode::resume) {
    if (read_file(manifest_path) != manifest)
      throw InputError("--resume", 0, directory_.string(),
                       "these tiles belong to a different map (scene content, --set, axes, method or program version "
                       "differ); run with --fresh to start over");
    // Temporaries of tiles whose writing was cut short.
    for (const auto& entry : fs::directory_iterator(directory_))
      if (entry.path().filename().string().find(".part") != std::string::npos) fs::remove(entry.path());
    return;
  }
  // Start over: everything but the lock goes.
  for (const auto& entry : fs::directory_iterator(directory_))
    if (entry.path().filename() != "lock") fs::remove_all(entry.path());
  try {
    write_atomically(manifest_path, manifest);
  } catch (...) {
    // No manifest (and, if we made it, no directory) is left to make the next run refuse.
    if (!existed) fs::remove_all(directory_, ec);
    throw;
  }
}

TileStore::~TileStore() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

fs::path TileStore::tile_path(int tile) const { return directory_ / fmt::format("tile{:06}", tile); }

bool TileStore::has(int tile) const {
  std::error_code ec;
  return fs::exists(tile_path(tile), ec);
}

std::vector<int> TileStore::missing() const {
  std::vector<int> out;
  for (int t = 0; t < tiles_; ++t)
    if (!has(t)) out.push_back(t);
  return out;
}

// A tile file: "<rows bytes> <summary bytes> <grid bytes>\n" (each 20 digits, so that a
// streamed tile can write it last, at the start), the rows, the summary rows, the grid block.
namespace {
std::string tile_header(std::size_t rows, std::size_t summary, std::size_t grid) {
  return fmt::format("{:020} {:020} {:020}\n", rows, summary, grid);
}

void write_all(int fd, std::string_view piece, const fs::path& path) {
  while (!piece.empty()) {
    const ssize_t n = ::write(fd, piece.data(), piece.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error(fmt::format("{}: cannot write: {}", path.string(), std::strerror(n < 0 ? errno : ENOSPC)));
    piece.remove_prefix(std::size_t(n));
  }
}

// The temporaries of a streamed tile (rows; summary rows and grid block, appended at the
// end). On any exit but commit() (a stop, an error) all are closed and removed.
class StreamedTile {
 public:
  explicit StreamedTile(fs::path path) : path_(std::move(path)) {
    part_[0] = create_temporary_next_to(path_, "part", fd_[0]);
    part_[1] = create_temporary_next_to(path_, "summary.part", fd_[1]);
    part_[2] = create_temporary_next_to(path_, "grid.part", fd_[2]);
    write_all(fd_[0], tile_header(0, 0, 0), part_[0]);  // a placeholder, rewritten by commit()
  }
  ~StreamedTile() {
    for (int k = 0; k < 3; ++k) {
      if (fd_[k] >= 0) ::close(fd_[k]);
      if (part_[k].empty()) continue;
      ::unlink(part_[k].c_str());
      unregister_temporary(part_[k]);
    }
  }
  StreamedTile(const StreamedTile&) = delete;
  StreamedTile& operator=(const StreamedTile&) = delete;
  void write(TileBuffers& out) {
    fmt::memory_buffer* buffers[3] = {&out.rows, &out.summary, &out.grid};
    for (int k = 0; k < 3; ++k) {
      write_all(fd_[k], std::string_view(buffers[k]->data(), buffers[k]->size()), part_[k]);
      bytes_[k] += buffers[k]->size();
      buffers[k]->clear();
    }
  }
  void commit() {
    // The summary rows and the grid block after the rows, through a fixed buffer; then the
    // sizes at the start.
    std::vector<char> buffer(kSpillBytes);
    for (int k = 1; k < 3; ++k) copy_back(k, buffer);
    const std::string header = tile_header(bytes_[0], bytes_[1], bytes_[2]);
    if (::pwrite(fd_[0], header.data(), header.size(), 0) != ssize_t(header.size())) fail("write", part_[0]);
    const int fd = fd_[0];
    fd_[0] = -1;
    if (::close(fd) != 0) fail("write", part_[0]);
    if (::rename(part_[0].c_str(), path_.c_str()) != 0) fail("rename into place", path_);
    unregister_temporary(part_[0]);
    part_[0].clear();
  }

 private:
  // Appends temporary k to the rows' temporary. (It was opened write-only: read it through
  // a second descriptor, checked to be the same file.)
  void copy_back(int k, std::vector<char>& buffer) {
    const int reader = ::open(part_[k].c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    struct stat written {}, read_back {};
    if (reader < 0) fail("read back", part_[k]);
    if (::fstat(reader, &read_back) != 0 || ::fstat(fd_[k], &written) != 0 || read_back.st_ino != written.st_ino ||
        read_back.st_dev != written.st_dev) {
      ::close(reader);
      errno = errno ? errno : EIO;
      fail("read back", part_[k]);
    }
    std::size_t copied = 0;
    for (;;) {
      const ssize_t n = ::read(reader, buffer.data(), buffer.size());
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int err = errno;
        ::close(reader);
        errno = err;
        fail("read back", part_[k]);
      }
      if (n == 0) break;
      try {
        write_all(fd_[0], std::string_view(buffer.data(), std::size_t(n)), part_[0]);
      } catch (...) {
        ::close(reader);
        throw;
      }
      copied += std::size_t(n);
    }
    ::close(reader);
    if (copied != bytes_[k]) {
      errno = EIO;
      fail("read back", part_[k]);
    }
  }
  [[noreturn]] static void fail(const char* what, const fs::path& path) {
    throw std::runtime_error(fmt::format("{}: cannot {}: {}", path.string(), what, std::strerror(errno)));
  }
  fs::path path_, part_[3];
  int fd_[3] = {-1, -1, -1};
  std::size_t bytes_[3] = {0, 0, 0};
};
}  // namespace

void TileStore::put(int tile, const TileText& text) const {
  write_atomically(tile_path(tile), tile_header(text.rows.size(), text.summary.size(), text.grid.size()), text.rows,
                   text.summary, text.grid);
}

TileText compute_tile_into(const MapJob& job, int tile, CellWorkspace& workspace, const TileStore& store) {
  StreamedTile file(store.tile_path(tile));
  TileBuffers out;
  TileText text = compute_tile_text(job, tile, workspace, out, [&file](TileBuffers& b) { file.write(b); });
  file.write(out);
  file.commit();
  return text;
}

void TileStore::append(int tile, std::ostream& rows, std::ostream& summary, std::ostream* grid) const {
  // Through a fixed buffer: assembling holds no tile in memory.
  const fs::path path = tile_path(tile);
  std::ifstream in(path, std::ios::binary);
  std::string first;
  std::getline(in, first);
  std::size_t n_rows = 0, n_summary = 0, n_grid = 0;
  std::istringstream sizes(first);
  sizes >> n_rows >> n_summary >> n_grid;
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (!in || !sizes || ec || first.size() + 1 + n_rows + n_summary + n_grid != size)
    throw std::runtime_error(fmt::format("{}: damaged tile file; rerun with --fresh", path.string()));
  std::vector<char> buffer(std::min<std::size_t>(kSpillBytes, std::max({n_rows, n_summary, n_grid}) + 1));
  for (auto [out, left] : {std::pair<std::ostream*, std::size_t>{&rows, n_rows}, {&summary, n_summary}, {grid, n_grid}}) {
    if (!out) break;  // the grid block is last
    while (left > 0) {
      const std::size_t n = std::min(left, buffer.size());
      if (!in.read(buffer.data(), std::streamsize(n)))
        throw std::runtime_error(fmt::format("{}: cannot read", path.string()));
      out->write(buffer.data(), std::streamsize(n));
      left -= n;
    }
  }
}

void TileStore::remove() const { fs::remove_all(directory_); }

// ---------------------------------------------------------------------------------------
// Progress

ProgressMeter::ProgressMeter(int total, int before, bool enabled)
    : total_(total), done_(before), before_(before), enabled_(enabled), terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_print_(start_) {}

void ProgressMeter::tile_done(long cells) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  ++done_;
  cells_ += cells;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_print_).count();
  if (since >= (terminal_ ? 0.2 : 5.0)) {
    last_print_ = now;
    print_locked(false);
  }
}

void ProgressMeter::finish() {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  print_locked(true);
}

void ProgressMeter::print_locked(bool final_line) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const int fresh = done_ - before_;
  std::string eta = "--";
  if (fresh > 0 && done_ < total_) {
    const double seconds = elapsed / fresh * (total_ - done_);
    eta = seconds < 120 ? fmt::format("{:.0f} s", seconds) : fmt::format("{:.1f} min", seconds / 60);
  } else if (done_ >= total_) {
    eta = "0 s";
  }
  fmt::print(stderr, "{}map: {}/{} tiles ({:.1f}%), {:.3g} cells/s, elapsed {:.1f} s, ETA {}{}",
             terminal_ ? "\r" : "", done_, total_, 100.0 * done_ / std::max(total_, 1),
             elapsed > 0 ? double(cells_) / elapsed : 0.0, elapsed, eta, terminal_ && !final_line ? "   " : "\n");
}

// ---------------------------------------------------------------------------------------
// Threads

MapRunStats run_tile_pool(const std::vector<int>& tiles, const MapRunOptions& options,
                          const std::function<TileWork()>& make_work,
                          const std::function<void(const std::function<bool()>& done)>& wait) {
  MapRunStats stats;
  const auto start = std::chrono::steady_clock::now();
  std::atomic<std::size_t> next{0};
  std::atomic<int> running{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::exception_ptr error;
  const auto stopped = [&] { return failed.load() || (options.stop && options.stop->load()); };
  const auto worker = [&] {
    try {
      const TileWork work = make_work();
      for (std::size_t i = next++; i < tiles.size() && !stopped(); i = next++) {
        const MapRunStats done = work(tiles[i]);
        {
          std::lock_guard lock(mutex);
          ++stats.tiles;
          stats.cells += done.cells;
          stats.equilibria += done.equilibria;
          stats.fallbacks += done.fallbacks;
        }
        if (options.progress) options.progress->tile_done(done.cells);
      }
    } catch (const Interrupted&) {
      // Stopped inside a tile: that tile is not written, the finished ones stay.
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
    --running;
  };
  const int n_threads = std::max(1, std::min<int>(options.threads, int(tiles.size())));
  running = n_threads;
  std::vector<std::thread> pool;
  pool.reserve(std::size_t(n_threads));
  for (int t = 0; t < n_threads; ++t) pool.emplace_back(worker);
  if (wait) {
    try {
      wait([&] { return running.load() == 0; });
    } catch (...) {
      failed = true;
      for (auto& th : pool) th.join();
      throw;
    }
  }
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.interrupted = stats.tiles < int(tiles.size());
  return stats;
}

MapRunStats run_text_tiles(const std::vector<int>& tiles, const MapRunOptions& options, const TileSink& sink,
                           const std::function<TileText(int tile)>& compute) {
  const auto make_work = [&]() -> TileWork {
    return [&](int tile) {
      TileText text = compute(tile);
      MapRunStats done;
      done.cells = text.cells;
      done.equilibria = text.equilibria;
      sink(tile, std::move(text));
      return done;
    };
  };
  return run_tile_pool(tiles, options, make_work);
}

MapRunStats compute_tiles(const MapJob& job, const std::vector<int>& tiles, const MapRunOptions& options,
                          const TileSink& sink, const std::function<void(const std::function<bool()>& done)>& wait) {
  const auto make_work = [&]() -> TileWork {
    // One workspace per thread, shared by its tiles (no allocation per cell).
    return [&job, &options, &sink, workspace = std::make_shared<CellWorkspace>(job)](int tile) {
      // Streamed into the store's tile (memory bounded) when there is one; in memory
      // for the sink otherwise (MPI ranks other than 0 send their tiles).
      TileText text = options.stream_to ? compute_tile_into(job, tile, *workspace, *options.stream_to)
                                        : compute_tile(job, tile, *workspace);
      MapRunStats done;
      done.cells = text.cells;
      done.equilibria = text.equilibria;
      done.fallbacks = text.fallbacks;
      if (!options.stream_to) sink(tile, std::move(text));
      return done;
    };
  };
  return run_tile_pool(tiles, options, make_work, wait);
}

void assemble(const MapJob& job, const TileStore& store, std::ostream& map_csv, std::ostream& summary_csv,
              std::ostream* grid) {
  map_csv << map_csv_header(job);
  summary_csv << summary_csv_header(job);
  for (int t = 0; t < tile_count(job); ++t) store.append(t, map_csv, summary_csv, grid);
}

}  // namespace abu
