// Maps across MPI ranks (build with -DABU_MPI=ON, run under `mpirun -n N`). Rank 0 owns
// the tile store and the output; every rank computes the missing tiles t with
// t mod N = rank on its threads; the other ranks send their finished tiles to rank 0,
// which stores them as its own. Only rank 0's main thread and the other ranks' main
// threads call MPI (MPI_THREAD_FUNNELED). Without ABU_MPI everything here is a single
// process of rank 0.
//
//   abu::MpiSession mpi(argc, argv);          // in main()
//   if (abu::mpi_rank() == 0) ... else ...
#pragma once

#include <optional>
#include <vector>

#include "abu/scan/map_driver.hpp"

namespace abu {

/// MPI_Init_thread / MPI_Finalize in an MPI build, nothing otherwise.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

int mpi_rank();
int mpi_size();

/// Rank 0 passes the tiles still to compute (or nullopt when it failed before, e.g. bad
/// input); every rank returns rank 0's list, or nullopt if rank 0 failed.
std::optional<std::vector<int>> share_missing_tiles(const std::optional<std::vector<int>>& root_missing);

/// Computes `missing` across all ranks. Rank 0 passes its store (every tile ends up in it)
/// and its progress meter; the other ranks pass nullptr. Returns this rank's statistics
/// (rank 0: all ranks' tiles summed). A failure on any rank is rethrown on rank 0 as a
/// NumericalError naming the rank.
MapRunStats compute_distributed(const MapJob& job, const std::vector<int>& missing, const MapRunOptions& options,
                                const TileStore* store);

}  // namespace abu
