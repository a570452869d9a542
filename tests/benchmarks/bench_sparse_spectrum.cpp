// Benchmark (not a test) of the large sparse spectra (linear/sparse_spectrum.hpp,
// docs/model.md §19): the rightmost 10 eigenvalues of the gyroscopic chain pencil
// (sparse_chain.hpp) against the number of states, time and peak memory. Driven by
// tests/benchmarks/sparse_spectrum_scipy.py, which runs scipy.sparse.linalg.eigs on the same
// matrices (written here as Matrix Market) in the same run:
//
//   bench_sparse_spectrum --states N --dir DIR [--k 10] [--dense]
//
// writes DIR/A_N.mtx, DIR/B_N.mtx and DIR/abu_N.csv (the eigenvalues with residuals) and
// prints one JSON line: seconds (wall) of rightmost_eigenvalues, the peak resident memory
// of the solve (VmHWM after resetting it through /proc/self/clear_refs, minus the resident
// memory before), and with --dense the time of a dense Eigen solver on B^-1 A.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <unsupported/Eigen/SparseExtra>

#include "abu/linear/sparse_spectrum.hpp"
#include "sparse_chain.hpp"

namespace {

// Resident memory in kB: "VmRSS" (now) or "VmHWM" (peak since the last reset).
long status_kb(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key, 0) == 0) return std::strtol(line.c_str() + std::string(key).size() + 1, nullptr, 10);
  return -1;
}
void reset_peak() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";  // Linux >= 4.0: resets VmHWM to the current resident size
}

}  // namespace

int main(int argc, char** argv) {
  long states = 1000;
  int k = 10;
  bool dense = false;
  std::string dir = ".";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--states" && i + 1 < argc) states = std::strtol(argv[++i], nullptr, 10);
    else if (a == "--k" && i + 1 < argc) k = int(std::strtol(argv[++i], nullptr, 10));
    else if (a == "--dir" && i + 1 < argc) dir = argv[++i];
    else if (a == "--dense") dense = true;
    else {
      fmt::print(stderr, "usage: bench_sparse_spectrum --states N --dir DIR [--k 10] [--dense]\n");
      return 2;
    }
  }
  abu::testing::ChainSpec spec;
  spec.masses = int(states / 4);
  const auto p = abu::testing::chain_pencil(spec);
  const long n = long(p.A.rows());
  Eigen::saveMarket(p.A, fmt::format("{}/A_{}.mtx", dir, n));
  Eigen::saveMarket(p.B, fmt::format("{}/B_{}.mtx", dir, n));

  // The rightmost 10: one real shift at 0 (the chain's dampers are stiffness-proportional,
  // so the rightmost modes are the slowest), its disc's inscribed square as the coverage.
  abu::RightmostOptions o;
  const long rss_before = status_kb("VmRSS");
  reset_peak();
  const auto t0 = std::chrono::steady_clock::now();
  const auto s = abu::rightmost_eigenvalues(p.A, p.B, k, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const long peak = status_kb("VmHWM");
  double worst_residual = 0.0;
  {
    std::ofstream csv(fmt::format("{}/abu_{}.csv", dir, n));
    csv << "re,im,residual\n";
    for (const auto& e : s.eigenpairs) {
      csv << fmt::format("{:.17g},{:.17g},{:.3e}\n", e.value.real(), e.value.imag(), e.residual);
      worst_residual = std::max(worst_residual, e.residual);
    }
  }
  double dense_seconds = -1.0, dense_worst = -1.0;
  if (dense) {
    const auto d0 = std::chrono::steady_clock::now();
    const Eigen::MatrixXd op = Eigen::MatrixXd(p.B).partialPivLu().solve(Eigen::MatrixXd(p.A));
    Eigen::EigenSolver<Eigen::MatrixXd> es(op, false);
    dense_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - d0).count();
    // The dense values nearest the sparse ones: the worst relative difference.
    dense_worst = 0.0;
    for (const auto& e : s.eigenpairs) {
      double best = 1e300;
      for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i)
        best = std::min(best, std::abs(es.eigenvalues()[i] - e.value) / std::abs(e.value));
      dense_worst = std::max(dense_worst, best);
    }
  }
  fmt::print(
      "{{\"states\": {}, \"nnz_A\": {}, \"nnz_B\": {}, \"seconds\": {:.6g}, \"peak_kb\": {}, \"rss_before_kb\": {}, "
      "\"status\": \"{}\", \"found\": {}, \"shifts\": {}, \"operator_applications\": {}, \"worst_residual\": {:.3e}, "
      "\"abscissa\": {:.17g}, \"coverage\": \"{}\", \"dense_seconds\": {:.6g}, \"dense_worst_rel\": {:.3e}}}\n",
      n, p.A.nonZeros(), p.B.nonZeros(), seconds, peak - rss_before, rss_before,
      s.status.ok() ? "converged" : std::string(s.status.reason), s.eigenpairs.size(), s.shifts.size(),
      s.shifts.empty() ? 0 : s.shifts[0].operator_applications, worst_residual,
      s.eigenpairs.empty() ? 0.0 : s.eigenpairs[0].value.real(), s.coverage.how, dense_seconds, dense_worst);
  return s.status.ok() ? 0 : 3;
}
