// Cost of one equilibrium (closed form + Newton polish + Jacobian + eigenvalues) and
// the price of accurate eigenvalues against a plain dense eigensolver.
//
//   bench_equilibria timing SCENE [--points N] [--repeat R]
//       single thread; an omega grid 0.2..8 omega_n of N points; per phase the median
//       over R repeats of ns per equilibrium, and ratios taken within one run.
//   bench_equilibria eigenvalues OUT.csv SCENE...
//       every equilibrium's eigenvalues by every method, for tests/benchmarks/bench_errors.py
//       to score against the 40-digit reference.
#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "abu/scan/scan.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/spectrum.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using abu::Params;

// What an engineer writes first: J in double, Eigen's dense QR, no balancing.
std::array<std::complex<double>, 8> plain_dense(const Params& p, const abu::Equilibrium& e) {
  const abu::State<double, 2> x = abu::at_rest<double, 2>(e.position_si());
  const Eigen::Matrix<double, 8, 8> J = abu::jacobian(p, x);
  Eigen::EigenSolver<Eigen::Matrix<double, 8, 8>> solver(J, false);
  std::array<std::complex<double>, 8> out{};
  for (int i = 0; i < 8; ++i) out[std::size_t(i)] = solver.eigenvalues()(i);
  return out;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int timing(const std::string& scene_path, int points, int repeats) {
  const abu::Scene scene = abu::load_scene(scene_path);
  const Params base = abu::params_of<2>(scene);
  const double omega_n = std::sqrt(base.rotor.stiffness / base.total_mass());
  std::vector<Params> grid(std::size_t(points), base);
  for (int i = 0; i < points; ++i)
    grid[std::size_t(i)].omega = omega_n * (0.2 + 7.8 * double(i) / double(points - 1));

  // Inputs of each phase, prepared once so that every phase is timed alone.
  std::vector<std::pair<std::size_t, abu::Equilibrium>> closed, polished;
  std::vector<std::pair<std::size_t, abu::Linearization<long double, 2>>> lins;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const abu::EquilibriumSet set = abu::closed_form_equilibria(grid[i]);
    for (const auto& e : set.points()) {
      closed.emplace_back(i, e);
      polished.emplace_back(i, abu::polish_equilibrium(grid[i], e));
      lins.emplace_back(i, abu::linearize(grid[i].cast<long double>(), polished.back().second.state()));
    }
  }
  const double n = double(closed.size());
  volatile double sink = 0;
  std::vector<double> t_closed, t_polish, t_jac, t_dense, t_structured, t_refined, t_plain, t_total;
  for (int r = 0; r < repeats; ++r) {
    auto t0 = Clock::now();
    for (const auto& p : grid) {
      const abu::EquilibriumSet set = abu::closed_form_equilibria(p);
      sink = sink + double(set.points().size());
    }
    t_closed.push_back(seconds_since(t0) / n);
    t0 = Clock::now();
    for (const auto& [i, e] : closed) sink = sink + abu::polish_equilibrium(grid[i], e).residual;
    t_polish.push_back(seconds_since(t0) / n);
    t0 = Clock::now();
    for (const auto& [i, e] : polished)
      sink = sink + double(abu::linearize(grid[i].cast<long double>(), e.state()).stiffness(0, 0));
    t_jac.push_back(seconds_since(t0) / n);
    for (auto [method, out] : {std::pair{abu::SpectrumMethod::dense_qr, &t_dense},
                               std::pair{abu::SpectrumMethod::structured, &t_structured},
                               std::pair{abu::SpectrumMethod::refined, &t_refined}}) {
      t0 = Clock::now();
      for (const auto& [i, lin] : lins) sink = sink + abu::compute_spectrum(lin, method).abscissa;
      out->push_back(seconds_since(t0) / n);
    }
    t0 = Clock::now();
    for (const auto& [i, e] : polished) sink = sink + plain_dense(grid[i], e)[0].real();
    t_plain.push_back(seconds_since(t0) / n);
    // The whole pipeline as the CLI runs it.
    t0 = Clock::now();
    for (const auto& p : grid) {
      const abu::EquilibriumSet set = abu::find_equilibria(p);
      for (const auto& e : set.points()) sink = sink + abu::equilibrium_spectrum(p, e).abscissa;
    }
    t_total.push_back(seconds_since(t0) / n);
  }
  const auto ns = [](const std::vector<double>& v) { return median(v) * 1e9; };
  fmt::print("scene {}: {} omega values in [0.2, 8] omega_n, {} equilibria, median of {} runs, 1 thread\n",
             scene_path, points, closed.size(), repeats);
  fmt::print("{:<48} {:>12}\n", "phase", "ns/equilib.");
  fmt::print("{:<48} {:>12.0f}\n", "closed forms (long double)", ns(t_closed));
  fmt::print("{:<48} {:>12.0f}\n", "Newton polish (long double)", ns(t_polish));
  fmt::print("{:<48} {:>12.0f}\n", "linearization A, C, K (long double)", ns(t_jac));
  fmt::print("{:<48} {:>12.0f}\n", "eigenvalues: refined (analyzer)", ns(t_refined));
  fmt::print("{:<48} {:>12.0f}\n", "eigenvalues: structured QR only", ns(t_structured));
  fmt::print("{:<48} {:>12.0f}\n", "eigenvalues: balanced dense QR (numpy's way)", ns(t_dense));
  fmt::print("{:<48} {:>12.0f}\n", "plain: double J + unbalanced dense QR", ns(t_plain));
  fmt::print("{:<48} {:>12.0f}\n", "whole pipeline (find_equilibria + spectrum)", ns(t_total));
  const double pipeline = ns(t_closed) + ns(t_polish) + ns(t_jac) + ns(t_refined);
  fmt::print("split of the pipeline: closed form {:.0f}%, polish {:.0f}%, linearization {:.0f}%, eigenvalues {:.0f}%\n",
             100 * ns(t_closed) / pipeline, 100 * ns(t_polish) / pipeline, 100 * ns(t_jac) / pipeline,
             100 * ns(t_refined) / pipeline);
  fmt::print("cost of accuracy: refined / balanced dense QR = {:.2f}x, refined / plain = {:.2f}x, "
             "whole pipeline / plain = {:.2f}x\n",
             median(t_refined) / median(t_dense), median(t_refined) / median(t_plain),
             median(t_total) / median(t_plain));
  return sink == 12345.678 ? 1 : 0;
}

int eigenvalues(const std::string& out_path, const std::vector<std::string>& scenes) {
  std::ofstream out(out_path);
  out << "scene,index,family,member,q1,q2,beta1,beta2,method";
  for (int k = 1; k <= 8; ++k) out << ",re" << k << ",im" << k;
  out << "\n";
  for (const auto& path : scenes) {
    const Params p = abu::params_of<2>(abu::load_scene(path));
    const auto set = abu::find_equilibria(p);
    std::size_t index = 0;
    for (const auto& e : set.points()) {
      ++index;
      const auto row = [&](std::string_view method, const std::array<std::complex<double>, 8>& ev) {
        const auto s = e.position_si();
        out << fmt::format("{},{},{},{},{},{},{},{},{}", path, index, abu::to_string(e.family), e.member, s(0), s(1),
                           s(2), s(3), method);
        for (const auto& z : ev) out << fmt::format(",{},{}", z.real(), z.imag());
        out << "\n";
      };
      row("plain", plain_dense(p, e));
      for (auto m : {abu::SpectrumMethod::dense_qr, abu::SpectrumMethod::structured, abu::SpectrumMethod::refined})
        row(abu::to_string(m), abu::equilibrium_spectrum(p, e, m).eigenvalues);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() >= 2 && args[0] == "timing") {
    int points = 2000, repeats = 5;
    for (std::size_t i = 2; i + 1 < args.size(); i += 2) {
      if (args[i] == "--points") points = std::stoi(args[i + 1]);
      if (args[i] == "--repeat") repeats = std::stoi(args[i + 1]);
    }
    return timing(args[1], std::max(points, 2), std::max(repeats, 1));
  }
  if (args.size() >= 3 && args[0] == "eigenvalues")
    return eigenvalues(args[1], std::vector<std::string>(args.begin() + 2, args.end()));
  fmt::print(stderr, "usage: bench_equilibria timing SCENE [--points N] [--repeat R]\n"
                     "       bench_equilibria eigenvalues OUT.csv SCENE...\n");
  return 2;
}
