// Stability maps of a flexible rotor's balanced state (shaft_map.hpp, model.md §18.13).
#include "abu/scan/shaft_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/scan/summary_map_text.hpp"
#include "abu/equilibria/shaft_equilibria.hpp"

namespace abu {

ShaftVerdict shaft_verdict(const SparseSpectrum& s, int structural_zeros) {
  ShaftVerdict v;
  const auto& pairs = s.eigenpairs;
  // Structural zeros are directions along a set of equilibria (U = 0's circle, the balanced
  // set of n >= 3 balls, model.md §13.4), not modes: the |lambda|-smallest are set aside.
  v.structural.assign(pairs.size(), 0);
  std::vector<std::size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) {
    return std::abs(pairs[a].value) < std::abs(pairs[c].value);
  });
  for (int z = 0; z < structural_zeros && std::size_t(z) < order.size(); ++z) v.structural[order[std::size_t(z)]] = 1;
  // Beside a structural zero, a value whose relative residual is >= 1 cannot be told from 0: the
  // copy of that zero a retried shift returns (model.md §19.7), set aside with it and counted.
  if (structural_zeros > 0)
    for (std::size_t i = 0; i < pairs.size(); ++i)
      if (!v.structural[i] && pairs[i].residual >= 1.0) v.structural[i] = 1, ++v.zero_copies;
  // A real part decides only beyond its error bound: the relative residual r makes lambda exact
  // for a pencil perturbed by r |lambda| ||B v||, which moves an eigenvalue of condition c by
  // about c r |lambda| (model.md §18.12, §19.3). Within it the sign is not known; a condition
  // that could not be computed (0) leaves every sign near the axis unknown.
  bool certified_positive = false, uncertain = false;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (v.structural[i]) continue;
    ++v.found;
    const auto& l = pairs[i].value;
    // The first of equal real parts in the sorted list has Im >= 0 (sparse_spectrum.hpp's order).
    if (l.real() > v.abscissa) v.abscissa = l.real(), v.rightmost = {l.real(), std::abs(l.imag())};
    const double c = pairs[i].condition;
    const double bound = c > 0.0 ? c * pairs[i].residual * std::abs(l) : std::numeric_limits<double>::infinity();
    if (l.real() > bound) certified_positive = true;
    else if (std::abs(l.real()) <= bound && v.doubt.empty())
      v.doubt = fmt::format("the eigenvalue {:.6g}{:+.6g}i 1/s has |Re| within its error bound {:.3g} 1/s (condition "
                            "{:.3g} times relative residual {:.3g} times |lambda|): its sign is not known",
                            l.real(), l.imag(), bound, c, pairs[i].residual),
      uncertain = true;
  }
  const SpectrumCoverage& c = s.coverage;
  if (certified_positive)
    v.verdict = "unstable";
  else if (!uncertain && s.status.ok() && !c.empty() && c.real_max >= 0)
    v.verdict = "stable";
  else
    v.verdict = "undetermined";
  return v;
}

SparseSpectrum shaft_rightmost(const ShaftSystem& sys, const Eigen::VectorXd& x, int eigenvalues, double band,
                               bool vectors, int* merged) {
  return pencil_rightmost(shaft_pencil(linearize_shaft(sys, x)), sys.balancer.omega, eigenvalues, band, vectors, merged);
}

SparseSpectrum pencil_rightmost(const ShaftPencil& pencil, double omega, int eigenvalues, double band, bool vectors,
                                int* merged) {
  RightmostOptions ro;
  ro.max_frequency = band > 0 ? band : 10.0 * omega;
  ro.arpack.keep_vectors = vectors;
  const int k = std::max(1, std::min(eigenvalues, int(pencil.a.rows()) - 2));  // ARPACK: k < n - 1
  SparseSpectrum s = rightmost_eigenvalues(pencil.a, pencil.b, k, ro);
  // Copies from overlapping discs closer than 1e-6 of their modulus are one eigenvalue
  // (as `equilibria` on a shaft scene merges them).
  const int dropped = merge_shift_copies(s, 1e-6);
  if (merged) *merged = dropped;
  return s;
}

std::vector<ShaftEquilibrium> shaft_balanced_states(const ShaftSystem& sys, const BalancedSampling& sampling) {
  // W(beta) = 0 does not involve the support: any dynamic stiffness gives the same balanced
  // states (model.md §18.8); the aligned ones (which do) are not wanted here.
  const ParamsN rigid = equivalent_rigid_params(sys, {1.0, 0.0});
  const EquilibriumSetN set = find_equilibria(rigid, sampling);
  std::vector<ShaftEquilibrium> out;
  for (const EquilibriumN& e : set.points())
    if (e.family == Family::balanced) out.push_back(shaft_equilibrium_from_rigid(sys, e));
  return out;
}

ShaftMapCell shaft_map_cell(const ShaftSystem& sys, const ShaftMapSpectrum& o) {
  ShaftMapCell cell;
  const std::vector<ShaftEquilibrium> states = shaft_balanced_states(sys, o.sampling);
  cell.balanced = int(states.size());
  if (states.empty()) {
    cell.state = "no_balanced_state";
    cell.reason = "U exceeds what the balls can balance (model.md §13.2)";
    return cell;
  }
  bool any_unstable = false, all_stable = true;
  Outcome worst = Outcome::converged;
  double abscissa = -std::numeric_limits<double>::infinity();
  for (const ShaftEquilibrium& e : states) {
    const SparseSpectrum s = shaft_rightmost(sys, e.state(), o.eigenvalues, o.band);
    const ShaftVerdict v = shaft_verdict(s, e.structural_zeros);
    any_unstable = any_unstable || v.verdict == "unstable";
    all_stable = all_stable && v.verdict == "stable";
    if (!s.status.ok() && worst == Outcome::converged) worst = s.status.outcome, cell.reason = s.status.reason;
    if (!v.doubt.empty() && cell.reason.empty()) cell.reason = v.doubt;  // why undetermined (the sign of a real part)
    cell.found += v.found;
    if (v.found > 0 && v.abscissa > abscissa) abscissa = v.abscissa, cell.frequency = v.rightmost.imag();
    const SpectrumCoverage& c = s.coverage;
    if (c.empty()) {
      cell.imag_max = -1.0;
    } else if (&e == &states.front()) {
      cell.real_min = c.real_min, cell.real_max = c.real_max, cell.imag_max = c.imag_max;
    } else if (cell.imag_max >= 0) {  // the rectangle every state's search covers
      cell.real_min = std::max(cell.real_min, c.real_min);
      cell.real_max = std::min(cell.real_max, c.real_max);
      cell.imag_max = std::min(cell.imag_max, c.imag_max);
    }
    for (std::size_t i = 0; i < s.eigenpairs.size(); ++i)
      if (!v.structural[i]) {
        cell.residual = std::max(cell.residual, s.eigenpairs[i].residual);
        cell.backward_error = std::max(cell.backward_error, s.eigenpairs[i].backward_error);
      }
    cell.shifts += int(s.shifts.size());
    cell.factorizations += s.factorizations;
  }
  if (cell.found > 0) cell.abscissa = abscissa;
  cell.verdict = any_unstable ? "unstable" : all_stable ? "stable" : "undetermined";
  if (worst != Outcome::converged) cell.state = std::string(to_string(worst));
  if (cell.found == 0 && cell.state == "converged") {
    cell.state = "no_eigenvalue";
    cell.reason = "ARPACK returned no eigenvalue";
  }
  return cell;
}

std::string shaft_map_manifest(const ShaftMapJob& job) {
  return summary_map_manifest(shaft_map_header(job) + fmt::format("eigenvalues {} band {} samples {}\n",
                                                                  job.spectrum.eigenvalues, job.spectrum.band,
                                                                  job.spectrum.sampling.samples_per_sheet),
                              job.xs, job.ys);
}

std::string shaft_map_header(const ShaftMapJob& job) {
  return job.provenance +
         fmt::format(
             "# flexible-shaft stability map (model.md §18.13): x = {} [{}], {} values; y = {} [{}], {} values; per "
             "cell the balanced states (u = 0, W(beta) = 0; balanced = how many, samples of the set for n >= 3 "
             "balls) and their {} rightmost eigenvalues with |Im| <= {} (ARPACK shift-invert, model.md §19). "
             "spectral_abscissa = max Re lambda found [1/s], frequency = |Im| of that eigenvalue [1/s, rotating "
             "frame]; verdict stable (every eigenvalue in the covered rectangle found, all Re < 0), unstable (one "
             "found with Re > 0), undetermined, none (no balanced state); covered rectangle coverage_* [1/s] (empty: "
             "nothing covered); state = converged, no_balanced_state, or the spectrum's outcome when ARPACK fell "
             "short (then the numbers are what it found); residual_max = largest ||A v - lambda B v|| / (|lambda| "
             "||B v||) and backward_error_max = largest ||A v - lambda B v|| / ((||A||_1 + |lambda| ||B||_1) ||v||) over the "
             "eigenvalues found (the relative residual of a slow ball mode near 0 is large by its small |lambda|); "
             "cells in order ix outer, iy inner\n"
             "{},{},balanced,state,verdict,spectral_abscissa,frequency,found,coverage_real_min,coverage_real_max,"
             "coverage_imag_max,residual_max,backward_error_max,shifts,factorizations\n",
             job.x_name, job.x_unit, job.xs.size(), job.y_name, job.y_unit, job.ys.size(), job.spectrum.eigenvalues,
             job.spectrum.band > 0 ? fmt::format("{} 1/s", job.spectrum.band) : std::string("10 omega"), job.x_name,
             job.y_name);
}

TileText compute_shaft_map_tile(const ShaftMapJob& job, int tile) {
  TileText text;
  const int ix = tile;
  for (int iy = 0; iy < int(job.ys.size()); ++iy) {
    const MapCellPlace cell{"shaft map", job.x_name, job.xs[std::size_t(ix)], job.y_name, job.ys[std::size_t(iy)]};
    throw_if_stopped("shaft map tile");
    const ShaftMapCell c = shaft_map_cell(job.cell_system(ix, iy), job.spectrum);
    const auto num = [&cell](double v, const char* what) { return cell_number(v, cell, what); };
    const bool found = c.found > 0, covered = c.imag_max >= 0;
    text.summary += fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", num(job.xs[std::size_t(ix)], "x"), num(job.ys[std::size_t(iy)], "y"),
        c.balanced, c.state, c.verdict, found ? num(c.abscissa, "spectral abscissa") : std::string(),
        found ? num(c.frequency, "frequency") : std::string(), c.found,
        covered ? num(c.real_min, "coverage") : std::string(), covered ? num(c.real_max, "coverage") : std::string(),
        covered ? num(c.imag_max, "coverage") : std::string(), found ? num(c.residual, "residual") : std::string(),
        found ? num(c.backward_error, "backward error") : std::string(),
        c.shifts, c.factorizations);
    ++text.cells;
    text.equilibria += c.balanced;
  }
  return text;
}

MapRunStats compute_shaft_map_tiles(const ShaftMapJob& job, const std::vector<int>& tiles,
                                    const MapRunOptions& options, const TileSink& sink) {
  return run_text_tiles(tiles, options, sink, [&](int tile) { return compute_shaft_map_tile(job, tile); });
}

}  // namespace abu
