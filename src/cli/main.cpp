#include "abu/cli.hpp"
#include "abu/map_mpi.hpp"

int main(int argc, char** argv) {
  abu::MpiSession mpi(argc, argv);  // a no-op unless built with -DABU_MPI=ON
  return abu::cli::run(argc, argv);
}
