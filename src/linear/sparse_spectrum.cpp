// Shift-invert ARPACK on a sparse pencil; see include/abu/linear/sparse_spectrum.hpp and
// docs/model.md §19 (method §19.1, the rightmost ladder and its coverage §19.2, the
// residual §19.3): the nearest eigenvalues of given shifts and the rightmost ladder, each
// shift's run in shift_invert.cpp.
#include "abu/linear/sparse_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "shift_invert.hpp"

namespace abu {

namespace {

using shift_invert::cplx;
using shift_invert::make_pencil;
using shift_invert::Pencil;
using shift_invert::run_shift;
using shift_invert::ShiftResult;

void sort_pairs(std::vector<SparseEigenpair>& pairs) {
  std::stable_sort(pairs.begin(), pairs.end(), [](const SparseEigenpair& l, const SparseEigenpair& r) {
    if (l.value.real() != r.value.real()) return l.value.real() > r.value.real();
    return l.value.imag() > r.value.imag();
  });
}

// Two computed values are one eigenvalue when they agree to 1e-9 of their modulus: ARPACK's
// values at tol 1e-12 differ between shifts by ~1e-12 x a condition number; distinct
// eigenvalues closer than 1e-9 relative are beyond what double shift-invert separates anyway.
bool same_value(cplx a, cplx b) {
  return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)) + 1e-300;
}

// A value counts as real (its conjugate is itself) when |Im| <= 1e-10 |lambda|: complex
// arithmetic leaves ~1e-16 |lambda| x condition in the imaginary part of a real eigenvalue.
bool is_real(cplx a) { return std::abs(a.imag()) <= 1e-10 * std::abs(a); }

// The covered band at depth d: the discs (centre frequency omega_j on Re = shift_real,
// radius r_j) cut the vertical line at distance d from the centres in intervals of
// half-width sqrt(r_j^2 - d^2); the band [0, Y] is their contiguous union from 0 (the disc
// at omega = 0 also covers its mirror; the pencil is real).
double covered_band(const std::vector<std::pair<double, double>>& discs, double d) {
  double reach = -1.0;
  for (const auto& [omega, r] : discs) {
    if (r <= d) return reach;
    const double h = std::sqrt(r * r - d * d);
    if (reach < 0.0) {
      if (omega - h > 0.0) return -1.0;
      reach = omega + h;
    } else {
      if (omega - h >= reach) return reach;  // a gap: open discs must overlap
      reach = std::max(reach, omega + h);
    }
  }
  return reach;
}

}  // namespace

SparseSpectrum eigenvalues_near(const SparseRealMatrix& A, const SparseRealMatrix& B,
                                std::span<const std::complex<double>> shifts, int k,
                                const SparseSpectrumOptions& options, ShiftFactorizations* cache) {
  const Pencil p = make_pencil(A, B, k);
  SparseSpectrum out;
  // Repeated shifts in one call reuse their LU even without a caller's cache.
  ShiftFactorizations local;
  ShiftFactorizations* c = cache ? cache : &local;
  for (cplx sigma : shifts) {
    ShiftResult s = run_shift(p, sigma, k, options, c, options.keep_vectors);
    out.factorizations += s.factorized ? 1 : 0;
    out.status.merge(s.run.status);
    out.shifts.push_back(s.run);
    for (auto& e : s.pairs) out.eigenpairs.push_back(std::move(e));
  }
  sort_pairs(out.eigenpairs);
  return out;
}

SparseSpectrum rightmost_eigenvalues(const SparseRealMatrix& A, const SparseRealMatrix& B, int k,
                                     const RightmostOptions& options, ShiftFactorizations* cache) {
  const int per = options.per_shift > 0 ? options.per_shift : std::max(k, 6);
  const Pencil p = make_pencil(A, B, per);
  if (!(options.spacing > 0.0 && options.spacing < 2.0))
    throw std::invalid_argument("rightmost_eigenvalues: spacing must be in (0, 2) (consecutive discs must overlap)");
  if (!(options.max_frequency >= 0.0) || !std::isfinite(options.shift_real))
    throw std::invalid_argument("rightmost_eigenvalues: max_frequency must be >= 0 and shift_real finite");
  SparseSpectrum out;
  const double alpha = options.shift_real;
  std::vector<std::pair<double, double>> discs;  // (omega_j, r_j)
  // Distinct eigenvalues in the upper half-plane (Im >= 0), the lower half by conjugation.
  std::vector<SparseEigenpair> upper;
  double omega = 0.0;
  bool reached = false;
  for (int j = 0; j < std::max(1, options.max_shifts); ++j) {
    ShiftResult s = run_shift(p, cplx(alpha, omega), per, options.arpack, cache, true);
    out.factorizations += s.factorized ? 1 : 0;
    if (s.run.status.outcome == Outcome::numerical_issue) {
      // The shift lies on an eigenvalue (model.md §19.5: a structural zero at sigma = 0):
      // listed, then moved up the line Re = alpha by delta = 1e-6 of the pencil's scale
      // ||A||_1 / ||B||_1 (~1e10 times the zero's rounding). If that disc is too small to
      // reach back to the old shift (r < 2 delta: stiff structures, whose scale is far above
      // the spectrum near the axis), once more from the old shift by 1e-3 r. The disc stays
      // centred on the line, so (19.5) holds.
      const double base = omega;
      double delta = 1e-6 * p.norm1_a / p.norm1_b;
      for (int retry = 0; retry < 2; ++retry) {
        out.shifts.push_back(s.run);
        omega = base + delta;
        s = run_shift(p, cplx(alpha, omega), per, options.arpack, cache, true);
        out.factorizations += s.factorized ? 1 : 0;
        if (s.run.status.outcome == Outcome::numerical_issue || s.run.radius >= 2.0 * delta) break;
        delta = 1e-3 * s.run.radius;
      }
    }
    out.status.merge(s.run.status);
    out.shifts.push_back(s.run);
    // This shift's values folded into the upper half-plane; a conjugate pair that this
    // shift saw whole (the real shift sees both members) folds to one value.
    std::vector<SparseEigenpair> folded;
    std::vector<bool> from_lower;
    for (auto& e : s.pairs) {
      const bool lower = e.value.imag() < 0.0 && !is_real(e.value);
      if (lower) {
        e.value = std::conj(e.value);
        if (e.vector.size()) e.vector = e.vector.conjugate().eval();
      }
      bool dup = false;
      for (std::size_t i = 0; i < folded.size() && !dup; ++i)
        dup = from_lower[i] != lower && same_value(folded[i].value, e.value);
      if (dup) continue;
      folded.push_back(std::move(e));
      from_lower.push_back(lower);
    }
    // One-to-one merge with the values of earlier shifts: keep the smaller residual.
    const std::size_t earlier = upper.size();  // only earlier shifts' values are candidates
    std::vector<bool> used(earlier, false);
    for (auto& e : folded) {
      bool merged = false;
      for (std::size_t i = 0; i < earlier && !merged; ++i) {
        if (used[i] || !same_value(upper[i].value, e.value)) continue;
        used[i] = merged = true;
        if (e.residual < upper[i].residual) upper[i] = std::move(e);
      }
      if (!merged) upper.push_back(std::move(e));
    }
    if (s.run.radius <= 0.0) break;  // no disc to step from; the status says why
    discs.emplace_back(omega, s.run.radius);
    if (omega >= options.max_frequency) {
      reached = true;
      break;
    }
    omega += options.spacing * s.run.radius;
  }
  if (!reached && out.status.ok())
    out.status.merge(Outcome::not_converged, "the shift ladder stopped (max_shifts) below max_frequency");

  // Coverage: the deepest rectangle |Re - alpha| <= d, |Im| <= Y that the discs cover, with
  // Y the band asked for (or, with one real shift and no band, the inscribed square).
  if (!discs.empty()) {
    double rmin = discs.front().second;
    for (const auto& dr : discs) rmin = std::min(rmin, dr.second);
    const double y0 = covered_band(discs, 0.0);
    double target = options.max_frequency > 0.0 ? std::min(options.max_frequency, y0) : 0.0;
    if (options.max_frequency > 0.0 && y0 < options.max_frequency)
      out.status.merge(Outcome::not_converged, "the shifts' discs leave a gap below max_frequency");
    double lo = 0.0, hi = rmin;  // covered_band(lo) >= target; find the largest such d
    if (options.max_frequency <= 0.0) {
      lo = hi = rmin / std::sqrt(2.0);  // one disc: the square inscribed in it
      target = covered_band(discs, lo);
    } else {
      for (int it = 0; it < 100; ++it) {
        const double mid = 0.5 * (lo + hi);
        (covered_band(discs, mid) >= target ? lo : hi) = mid;
      }
    }
    // 1 - 1e-12: the bisection's last step and the discs being open.
    const double depth = lo * (1.0 - 1e-12);
    out.coverage.real_min = alpha - depth;
    out.coverage.real_max = alpha + depth;
    out.coverage.imag_max = target * (1.0 - 1e-12);
    out.coverage.how = fmt::format(
        "{} shift(s) sigma = {:.6g} + i omega, omega = 0 .. {:.6g} 1/s, {} nearest eigenvalues each; their "
        "discs |lambda - sigma| < r (r = {:.6g} .. {:.6g} 1/s) cover |Re - {:.6g}| <= {:.6g}, |Im| <= {:.6g} 1/s",
        discs.size(), alpha, discs.back().first, per, rmin,
        std::max_element(discs.begin(), discs.end(), [](auto& l, auto& r) { return l.second < r.second; })->second,
        alpha, depth, out.coverage.imag_max);
  }

  // Both halves, sorted; the k rightmost, a pair the k-th splits kept whole.
  std::vector<SparseEigenpair> all;
  for (auto& e : upper) {
    if (!is_real(e.value)) {
      SparseEigenpair c = e;
      c.value = std::conj(e.value);
      if (c.vector.size()) c.vector = c.vector.conjugate().eval();
      all.push_back(std::move(c));
    }
    all.push_back(std::move(e));
  }
  sort_pairs(all);
  const auto& cov = out.coverage;
  for (auto& e : all)
    e.covered = !cov.empty() && e.value.real() >= cov.real_min && e.value.real() <= cov.real_max &&
                std::abs(e.value.imag()) <= cov.imag_max;
  std::size_t keep = std::min(all.size(), std::size_t(k));
  if (keep > 0 && keep < all.size() && !is_real(all[keep - 1].value) &&
      same_value(all[keep].value, std::conj(all[keep - 1].value)))
    ++keep;
  all.resize(keep);
  if (!options.arpack.keep_vectors)
    for (auto& e : all) e.vector.resize(0);
  if (int(all.size()) < k || cov.empty() || all.back().value.real() < cov.real_min)
    out.status.merge(Outcome::not_converged,
                     "fewer than k eigenvalues lie in the covered region: the k-th rightmost is not certified");
  out.eigenpairs = std::move(all);
  return out;
}

// The ladder's discs overlap, and an eigenvalue inside two discs is returned by both
// shifts, the farther one's copy less accurate (measured on the flexible spindle:
// -4.038060958 1/s from sigma = 0 and -4.0380599 +- 1.3e-6 i from sigma = 8893 i, 1e-7
// apart).
int merge_shift_copies(SparseSpectrum& s, double relative) {
  std::vector<SparseEigenpair>& v = s.eigenpairs;
  std::vector<char> drop(v.size(), 0);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j) {
      if (drop[i] || drop[j] || v[i].shift == v[j].shift) continue;
      const double scale = std::max(std::abs(v[i].value), std::abs(v[j].value));
      if (!(std::abs(v[i].value - v[j].value) <= relative * scale)) continue;
      const bool i_nearer = std::abs(v[i].value - v[i].shift) <= std::abs(v[j].value - v[j].shift);
      drop[i_nearer ? j : i] = 1;
    }
  int dropped = 0;
  std::vector<SparseEigenpair> kept;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (drop[i]) ++dropped;
    else kept.push_back(std::move(v[i]));
  v = std::move(kept);
  return dropped;
}

}  // namespace abu
