// Cost per equilibrium against the number of balls (n = 2, 3, 4, 6, 11, 12 by default):
// the ring scene data/scenes/ring11.toml (the default scene's rotor, coulomb friction
// kappa = 1e3, mu = 0.002, omega = 900 rad/s, equal balls 3.3e-5 kg at 0.018 m) with its
// ball count set by abu::set_ball_count. Single thread; each figure is the median over R
// repeats of (time of a block) / (equilibria in it), a block repeated until it lasts
// --min-ms so that small n are not timer-bound.
//
//   bench_n SCENE OUT.bin OUT.csv [--repeat R] [--min-ms T] [--cap C] [--counts 2,3,4,6,11,12]
//
// Timed per n:
//   analyze      abu::analyze(p) (find_equilibria + equilibrium_spectrum of each), / count
//   equilibria   find_equilibria(p) alone, / count
//   refined      equilibrium_spectrum(p, e) on each equilibrium (linearization included),
//                aligned and balanced samples apart, and apart again by whether the
//                refinement converged; on at most C (default 512) equilibria of each kind,
//                evenly spread over the list (every one up to n = 10; at n = 11, 12 a
//                spectrum costs ~1.5 ms and all of them, 5 times, would take minutes)
//   linearize    linearize(p.cast<long double>(), e.state()) alone
//   structured   the same spectrum with SpectrumMethod::structured (its QRs without the
//                long-double Newton refinement), to split the refined spectrum's time;
//                on the same equilibria as refined
//   map cell     abu::CellAnalyzerN::analyze, one cell of an n-ball map at the scene's
//                parameters (the same equilibria and spectra, rows stored in the
//                cell's reused storage), / cell: what `map` costs per cell at this n on
//                a friction axis (y = mu: the column keeps its equilibria, model.md §13.9)
//   map cell, general axis   the same with y = U, two values 1e-9 apart analysed in
//                turn: every cell finds its equilibria and their classes again (any axis
//                that moves them: omega, U, k, c, ...)
//   dense QR     Eigen::EigenSolver (eigenvalues only, no balancing) on the double
//                Jacobian jacobian(p, at_rest(position)), precomputed: the same matrices
//                as the numpy baseline's
// OUT.csv has one row of these (us per equilibrium) per n; OUT.bin has, per n, the
// matrices and eigenvalues for tests/benchmarks/bench_n_numpy.py (which prints the
// table), little-endian:
//   int64 n, count, dim (= 2 n + 4), 0
//   int64 meta[count][4]     aligned (1) or balanced sample (0), analyzer verdict
//                            (0 stable, 1 unstable, 2 marginal), n_structural, converged
//   float64 J[count][dim][dim]      row-major
//   float64 eig[count][dim][2]      the analyzer's (refined) eigenvalues, re, im
//   int64 structural[count][dim]    1 where the analyzer's eigenvalue is a structural zero
//   float64 qr[count][dim][2]       the dense QR's eigenvalues (Eigen), re, im
#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "abu/equilibria/equilibria_n.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/map.hpp"
#include "abu/scan/scan.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using abu::any_balls;
using Matrix = abu::StateMatrix<double, any_balls>;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Seconds per call of `block`, repeated until `min_s` has passed (at least once).
double per_call(const std::function<void()>& block, double min_s) {
  int calls = 0;
  const auto t0 = Clock::now();
  double elapsed = 0;
  do {
    block();
    ++calls;
    elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
  } while (elapsed < min_s);
  return elapsed / calls;
}

template <class T>
void put(std::ofstream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}

int code(abu::Stability s) {
  switch (s) {
    case abu::Stability::stable: return 0;
    case abu::Stability::unstable: return 1;
    case abu::Stability::marginal: return 2;
  }
  return 2;
}

int run(const std::string& scene_path, const std::string& bin_path, const std::string& csv_path, int repeats,
        double min_s, std::size_t cap, const std::vector<int>& counts) {
  const abu::Scene ring = abu::load_scene(scene_path);
  std::ofstream bin(bin_path, std::ios::binary);
  std::ofstream csv(csv_path);
  csv << "n,aligned,balanced,grid_points,repeats,analyze_us,equilibria_us,refined_us,refined_aligned_us,"
         "refined_balanced_us,linearize_us,structured_us,qr_us,qr_aligned_us,qr_balanced_us,not_converged,"
         "ill_conditioned,marginal,spectrum_not_converged,timed_aligned,timed_balanced,refined_aligned_conv_us,"
         "refined_aligned_nconv_us,refined_balanced_conv_us,refined_balanced_nconv_us,nconv_aligned,nconv_balanced,"
         "map_cell_us,map_cell_general_us\n";
  volatile double sink = 0;
  fmt::print("{:>3} {:>6} {:>6} {:>11} {:>11} {:>11} {:>11} {:>11} {:>11} {:>11}   (us per equilibrium, median of {})\n",
             "n", "align.", "bal.", "analyze", "find_eq", "refined", "ref.align", "ref.bal", "linearize",
             "dense QR", repeats);
  for (const int n : counts) {
    abu::Scene scene = ring;
    abu::set_ball_count(scene, n, "bench_n");
    const abu::ParamsN p = abu::params_of<any_balls>(scene);
    const abu::ParamsT<long double, any_balls> pl = p.cast<long double>();

    // One analysis as the reference of everything below (and a warm-up).
    const abu::AnalysisN a = abu::analyze(p);
    const auto points = a.equilibria.points();
    const std::size_t count = points.size();
    std::vector<std::size_t> aligned, balanced;
    for (std::size_t i = 0; i < count; ++i)
      (points[i].family == abu::Family::balanced ? balanced : aligned).push_back(i);
    std::vector<Matrix> jac(count);
    for (std::size_t i = 0; i < count; ++i)
      jac[i] = abu::jacobian(p, abu::at_rest<double, any_balls>(points[i].position_si()));
    const int dim = 2 * n + 4;

    // The refined (and structured) spectrum alone: on at most `cap` equilibria of each
    // kind, evenly spread over the list (all of them up to n = 10 with the default cap),
    // each call timed on its own so that its time can be split by kind and by whether
    // the refinement converged.
    const auto spread = [cap](const std::vector<std::size_t>& v) {
      if (v.size() <= cap) return v;
      std::vector<std::size_t> out(cap);
      for (std::size_t k = 0; k < cap; ++k) out[k] = v[k * v.size() / cap];
      return out;
    };
    const std::vector<std::size_t> sub_al = spread(aligned), sub_bal = spread(balanced);
    std::vector<std::size_t> sub_all = sub_al;
    sub_all.insert(sub_all.end(), sub_bal.begin(), sub_bal.end());
    // seconds[kind][converged], calls[kind][converged] of one timed block
    struct Split {
      double seconds[2][2] = {};
      double calls[2][2] = {};
    };
    const auto refined_block = [&](double min_time) {
      Split s;
      const auto t_block = Clock::now();
      do {
        for (const std::size_t i : sub_all) {
          const auto t0 = Clock::now();
          sink = sink + abu::equilibrium_spectrum(p, points[i]).abscissa;
          const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
          const int kind = points[i].family == abu::Family::balanced ? 1 : 0;
          const int conv = a.spectra[i].converged ? 1 : 0;
          s.seconds[kind][conv] += dt;
          s.calls[kind][conv] += 1;
        }
      } while (std::chrono::duration<double>(Clock::now() - t_block).count() < min_time);
      return s;
    };
    const auto qr_of = [&](const std::vector<std::size_t>& which) {
      Eigen::EigenSolver<Matrix> solver(dim);
      for (const std::size_t i : which) {
        solver.compute(jac[i], false);
        sink = sink + solver.eigenvalues()(0).real();
      }
    };
    const double c = double(count);
    const auto per = [](double seconds, std::size_t k) { return k == 0 ? 0.0 : seconds / double(k) * 1e6; };
    const auto us = [](double seconds, double calls) { return calls == 0 ? 0.0 : seconds / calls * 1e6; };
    std::vector<double> t_an, t_find, t_ref_al, t_ref_bal, t_lin, t_struct, t_qr_al, t_qr_bal;
    std::vector<double> t_conv[2], t_nconv[2], t_cell;
    // One map cell at the scene's parameters (1 x 1 map: omega and mu at their values).
    abu::Axis ax, ay;
    ax.param = *abu::parse_param("omega", n);
    ax.from = ax.to = p.omega;
    ax.count = 1;
    ay.param = *abu::parse_param("mu", n);
    ay.from = ay.to = p.balls[0].mu;
    ay.count = 1;
    abu::CellAnalyzerN cells(p, {}, ax, ay, abu::BalancedSampling{});
    abu::MapCellN cell;
    cells.analyze(0, 0, cell);  // warm-up: the cell's storage grows once
    abu::Axis au = ay;
    au.param = *abu::parse_param("U", n);
    au.from = p.rotor.unbalance;
    au.to = p.rotor.unbalance * (1 + 1e-9);
    au.count = 2;
    abu::CellAnalyzerN moving(p, {}, ax, au, abu::BalancedSampling{});
    moving.analyze(0, 0, cell);
    moving.analyze(0, 1, cell);
    int next_row = 0;
    std::vector<double> t_general;
    for (int r = 0; r < repeats; ++r) {
      t_an.push_back(per(per_call([&] { sink = sink + double(abu::analyze(p).spectra.size()); }, min_s), count));
      t_find.push_back(
          per(per_call([&] { sink = sink + double(abu::find_equilibria(p).list.size()); }, min_s), count));
      const Split s = refined_block(min_s);
      t_ref_al.push_back(us(s.seconds[0][0] + s.seconds[0][1], s.calls[0][0] + s.calls[0][1]));
      t_ref_bal.push_back(us(s.seconds[1][0] + s.seconds[1][1], s.calls[1][0] + s.calls[1][1]));
      for (int conv = 0; conv < 2; ++conv) {
        (conv ? t_conv : t_nconv)[0].push_back(us(s.seconds[0][conv], s.calls[0][conv]));
        (conv ? t_conv : t_nconv)[1].push_back(us(s.seconds[1][conv], s.calls[1][conv]));
      }
      t_lin.push_back(per(per_call(
                              [&] {
                                for (const auto& e : points)
                                  sink = sink + double(abu::linearize(pl, e.state()).stiffness(0, 0));
                              },
                              min_s),
                          count));
      t_struct.push_back(per(per_call(
                                 [&] {
                                   for (const std::size_t i : sub_all)
                                     sink = sink +
                                            abu::equilibrium_spectrum(p, points[i], abu::SpectrumMethod::structured)
                                                .abscissa;
                                 },
                                 min_s),
                             sub_all.size()));
      t_cell.push_back(per_call([&] { cells.analyze(0, 0, cell); sink = sink + double(cell.equilibria.size()); }, min_s) * 1e6);
      t_general.push_back(per_call(
                              [&] {
                                moving.analyze(0, next_row, cell);
                                next_row = 1 - next_row;
                                sink = sink + double(cell.equilibria.size());
                              },
                              min_s) *
                          1e6);
      t_qr_al.push_back(per(per_call([&] { qr_of(aligned); }, min_s), aligned.size()));
      t_qr_bal.push_back(per(per_call([&] { qr_of(balanced); }, min_s), balanced.size()));
    }
    const double ref_al = median(t_ref_al), ref_bal = median(t_ref_bal);
    const double qr_al = median(t_qr_al), qr_bal = median(t_qr_bal);
    const double refined = (ref_al * double(aligned.size()) + ref_bal * double(balanced.size())) / c;
    const double qr = (qr_al * double(aligned.size()) + qr_bal * double(balanced.size())) / c;
    int not_converged = 0, ill = 0, marginal = 0, spec_nc = 0, nconv_al = 0, nconv_bal = 0;
    for (std::size_t i = 0; i < count; ++i) {
      not_converged += points[i].converged ? 0 : 1;
      ill += a.spectra[i].ill_conditioned ? 1 : 0;
      marginal += a.spectra[i].stability == abu::Stability::marginal ? 1 : 0;
      spec_nc += a.spectra[i].converged ? 0 : 1;
      if (!a.spectra[i].converged) ++(points[i].family == abu::Family::balanced ? nconv_bal : nconv_al);
    }
    fmt::print("{:>3} {:>6} {:>6} {:>11.2f} {:>11.2f} {:>11.2f} {:>11.2f} {:>11.2f} {:>11.2f} {:>11.2f}\n", n,
               aligned.size(), balanced.size(), median(t_an), median(t_find), refined, ref_al, ref_bal, median(t_lin),
               qr);
    std::fflush(stdout);
    if (cell.equilibria.size() != count)
      throw std::runtime_error(fmt::format("n = {}: the map cell has {} equilibria, analyze {}", n, cell.equilibria.size(), count));
    csv << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", n, aligned.size(), balanced.size(),
                       a.equilibria.balanced_set.grid_points, repeats, median(t_an), median(t_find), refined, ref_al,
                       ref_bal, median(t_lin), median(t_struct), qr, qr_al, qr_bal, not_converged, ill, marginal,
                       spec_nc, sub_al.size(), sub_bal.size(), median(t_conv[0]), median(t_nconv[0]),
                       median(t_conv[1]), median(t_nconv[1]), nconv_al, nconv_bal, median(t_cell),
                       median(t_general));

    // Matrices and eigenvalues for the numpy script.
    for (const std::int64_t v : {std::int64_t(n), std::int64_t(count), std::int64_t(dim), std::int64_t(0)}) put(bin, v);
    for (std::size_t i = 0; i < count; ++i) {
      const auto& s = a.spectra[i];
      if (s.count != dim) throw std::runtime_error(fmt::format("n = {}: spectrum of {} eigenvalues", n, s.count));
      for (const std::int64_t v : {std::int64_t(points[i].family == abu::Family::balanced ? 0 : 1),
                                   std::int64_t(code(s.stability)), std::int64_t(s.n_structural),
                                   std::int64_t(s.converged && points[i].converged ? 1 : 0)})
        put(bin, v);
    }
    for (std::size_t i = 0; i < count; ++i)
      for (int r = 0; r < dim; ++r)
        for (int k = 0; k < dim; ++k) put(bin, jac[i](r, k));
    for (std::size_t i = 0; i < count; ++i)
      for (int k = 0; k < dim; ++k) {
        put(bin, a.spectra[i].eigenvalues[std::size_t(k)].real());
        put(bin, a.spectra[i].eigenvalues[std::size_t(k)].imag());
      }
    for (std::size_t i = 0; i < count; ++i)
      for (int k = 0; k < dim; ++k) put(bin, std::int64_t(a.spectra[i].structural[std::size_t(k)] ? 1 : 0));
    Eigen::EigenSolver<Matrix> solver(dim);
    for (std::size_t i = 0; i < count; ++i) {
      solver.compute(jac[i], false);
      for (int k = 0; k < dim; ++k) {
        put(bin, solver.eigenvalues()(k).real());
        put(bin, solver.eigenvalues()(k).imag());
      }
    }
  }
  return sink == 12345.678 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() < 3) {
    fmt::print(stderr, "usage: bench_n SCENE OUT.bin OUT.csv [--repeat R] [--min-ms T] [--cap C] [--counts 2,3,4,6,11,12]\n");
    return 2;
  }
  int repeats = 5;
  double min_ms = 20;
  std::size_t cap = 512;
  std::vector<int> counts{2, 3, 4, 6, 11, 12};
  for (std::size_t i = 3; i + 1 < args.size(); i += 2) {
    if (args[i] == "--repeat") repeats = std::max(1, std::stoi(args[i + 1]));
    if (args[i] == "--min-ms") min_ms = std::stod(args[i + 1]);
    if (args[i] == "--cap") cap = std::size_t(std::max(1, std::stoi(args[i + 1])));
    if (args[i] == "--counts") {
      counts.clear();
      std::stringstream list(args[i + 1]);
      for (std::string item; std::getline(list, item, ',');) counts.push_back(std::stoi(item));
    }
  }
  return run(args[0], args[1], args[2], repeats, min_ms * 1e-3, cap, counts);
}
