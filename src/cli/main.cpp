#include "abu/cli.hpp"

int main(int argc, char** argv) { return abu::cli::run(argc, argv); }
