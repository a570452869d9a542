#include "abu/scan/map_mpi.hpp"

#include <fmt/format.h>

#include <condition_variable>
#include <deque>
#include <sstream>

#include "abu/core/errors.hpp"

#ifdef ABU_MPI
#include <mpi.h>
#endif

namespace abu {

namespace {

MapRunStats compute_local(const MapJob& job, const std::vector<int>& missing, const MapRunOptions& options,
                          const TileStore* store) {
  MapRunOptions streamed = options;
  streamed.stream_to = store;
  return compute_tiles(job, missing, streamed, [store](int tile, TileText&& text) { store->put(tile, text); });
}

}  // namespace

#ifndef ABU_MPI

MpiSession::MpiSession(int&, char**&) {}
MpiSession::~MpiSession() = default;
int mpi_rank() { return 0; }
int mpi_size() { return 1; }
std::optional<std::vector<int>> share_missing_tiles(const std::optional<std::vector<int>>& root_missing) {
  return root_missing;
}
MapRunStats compute_distributed(const MapJob& job, const std::vector<int>& missing, const MapRunOptions& options,
                                const TileStore* store) {
  return compute_local(job, missing, options, store);
}

#else

namespace {

constexpr int kTagTile = 1, kTagDone = 2;

// A tile on the wire: "tile rows summary grid cells equilibria fallbacks\n" + rows + summary
// + grid block.
std::string encode(int tile, const TileText& t) {
  return fmt::format("{} {} {} {} {} {} {}\n", tile, t.rows.size(), t.summary.size(), t.grid.size(), t.cells,
                     t.equilibria, t.fallbacks) +
         t.rows + t.summary + t.grid;
}

int decode(const std::string& message, TileText& t) {
  const auto newline = message.find('\n');
  std::istringstream head(message.substr(0, newline));
  int tile = -1;
  std::size_t rows = 0, summary = 0, grid = 0;
  head >> tile >> rows >> summary >> grid >> t.cells >> t.equilibria >> t.fallbacks;
  if (newline == std::string::npos || !head || newline + 1 + rows + summary + grid != message.size())
    throw std::runtime_error("MPI: damaged tile message");
  t.rows = message.substr(newline + 1, rows);
  t.summary = message.substr(newline + 1 + rows, summary);
  t.grid = message.substr(newline + 1 + rows + summary, grid);
  return tile;
}

std::string receive(int& source, int& tag) {
  MPI_Status status;
  MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
  int n = 0;
  MPI_Get_count(&status, MPI_CHAR, &n);
  std::string buffer(std::size_t(n), '\0');
  MPI_Recv(buffer.data(), n, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  source = status.MPI_SOURCE;
  tag = status.MPI_TAG;
  return buffer;
}

void send(const std::string& message, int tag) {
  MPI_Send(message.data(), int(message.size()), MPI_CHAR, 0, tag, MPI_COMM_WORLD);
}

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
}

MpiSession::~MpiSession() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

int mpi_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int mpi_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

std::optional<std::vector<int>> share_missing_tiles(const std::optional<std::vector<int>>& root_missing) {
  if (mpi_size() == 1) return root_missing;
  int count = root_missing ? int(root_missing->size()) : -1;
  MPI_Bcast(&count, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (count < 0) return std::nullopt;
  std::vector<int> tiles = root_missing ? *root_missing : std::vector<int>(std::size_t(count));
  MPI_Bcast(tiles.data(), count, MPI_INT, 0, MPI_COMM_WORLD);
  return tiles;
}

MapRunStats compute_distributed(const MapJob& job, const std::vector<int>& missing, const MapRunOptions& options,
                                const TileStore* store) {
  const int rank = mpi_rank(), size = mpi_size();
  if (size == 1) return compute_local(job, missing, options, store);
  std::vector<int> mine;
  for (int t : missing)
    if (t % size == rank) mine.push_back(t);

  if (rank == 0) {
    // The main thread receives the other ranks' tiles while the workers compute ours.
    MapRunStats remote;
    std::vector<std::string> failures;
    const auto receive_all = [&](const std::function<bool()>&) {
      for (int finished = 0; finished < size - 1;) {
        int source = 0, tag = 0;
        const std::string message = receive(source, tag);
        if (tag == kTagTile) {
          TileText text;
          const int tile = decode(message, text);
          store->put(tile, text);
          if (options.progress) options.progress->tile_done(text.cells);
          ++remote.tiles;
          remote.cells += text.cells;
          remote.equilibria += text.equilibria;
          remote.fallbacks += text.fallbacks;
        } else {
          ++finished;
          if (message != "ok") failures.push_back(fmt::format("rank {}: {}", source, message));
        }
      }
    };
    MapRunOptions streamed = options;
    streamed.stream_to = store;
    MapRunStats stats = compute_tiles(
        job, mine, streamed, [store](int tile, TileText&& text) { store->put(tile, text); }, receive_all);
    for (const auto& f : failures)
      if (f.find("interrupted") == std::string::npos) throw NumericalError(f);
    stats.tiles += remote.tiles;
    stats.cells += remote.cells;
    stats.equilibria += remote.equilibria;
    stats.fallbacks += remote.fallbacks;
    stats.interrupted = stats.tiles < int(missing.size());
    return stats;
  }

  // Other ranks: workers queue finished tiles, the main thread sends them to rank 0.
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<std::string> queue;
  const auto enqueue = [&](int tile, TileText&& text) {
    std::string message = encode(tile, text);
    std::lock_guard lock(mutex);
    queue.push_back(std::move(message));
    ready.notify_one();
  };
  const auto send_all = [&](const std::function<bool()>& done) {
    for (;;) {
      std::unique_lock lock(mutex);
      ready.wait_for(lock, std::chrono::milliseconds(20), [&] { return !queue.empty(); });
      if (queue.empty()) {
        if (done()) return;
        continue;
      }
      std::string message = std::move(queue.front());
      queue.pop_front();
      lock.unlock();
      send(message, kTagTile);
    }
  };
  try {
    MapRunStats stats = compute_tiles(job, mine, options, enqueue, send_all);
    for (auto& message : queue) send(message, kTagTile);  // finished after the last check
    send(stats.interrupted ? "interrupted" : "ok", kTagDone);
    return stats;
  } catch (const std::exception& e) {
    send(e.what(), kTagDone);
    throw;
  }
}

#endif

}  // namespace abu
