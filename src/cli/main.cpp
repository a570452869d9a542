#include "cli.hpp"
#include "abu/scan/map_mpi.hpp"

int main(int argc, char** argv) {
  abu::MpiSession mpi(argc, argv);  // a no-op unless built with -DABU_MPI=ON
  return abu::cli::run(argc, argv);
}
