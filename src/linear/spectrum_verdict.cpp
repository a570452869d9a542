// The verdict of a spectrum with Newton refinement only where it matters
// (spectrum_verdict.hpp). The refinements that are done are compute_spectrum's own calls
// (same starts, same start vectors, same acceptance), so the abscissa has its bits.
#include "abu/linear/spectrum_verdict.hpp"

#include <cmath>
#include <limits>

#include "spectrum_starts.hpp"

namespace abu {

namespace {

using ld = long double;
constexpr int N = any_balls;
constexpr std::size_t kCap = SpectrumN::capacity;
constexpr double kClearRelative = 1e-5;  // (header)
constexpr double kClearBound = 64e4;

SpectrumVerdict from_full(const Linearization<ld, N>& lin, int structural_zeros) {
  const SpectrumN sp = compute_spectrum(lin, SpectrumMethod::refined, structural_zeros);
  return {sp.stability, sp.n_unstable, sp.n_structural, sp.abscissa, sp.count, sp.converged};
}

// Which estimates need Newton: not clear of the axis, possibly the rightmost, and every
// start within 1e-3 of one that does (copies of a multiple eigenvalue, as the grouping of
// spectrum.cpp), conjugate partners alike. False if there is no rightmost start.
bool select(const spectrum_detail::Starts<N>& starts, std::size_t m, std::array<double, kCap>& radius,
            std::array<bool, kCap>& need) {
  const auto& start = starts.estimates;
  std::size_t top = m;
  for (std::size_t i = 0; i < m; ++i) {
    radius[i] = kClearBound * spectrum_detail::apriori_error(start[i]);
    if (!std::isfinite(radius[i]) || !std::isfinite(std::abs(start[i].value))) return false;
    if (top == m || start[i].value.real() > start[top].value.real()) top = i;
  }
  if (top == m) return false;
  for (std::size_t i = 0; i < m; ++i) {
    const auto z = start[i].value;
    const bool clear = std::abs(z.real()) > kClearRelative * std::abs(z) && std::abs(z.real()) > radius[i];
    // A start with another within 1e-3 of it (a cluster: nearly multiple eigenvalues, where
    // Newton can stall and compute_spectrum regroups or retries) is refined as there.
    bool cluster = false;
    for (std::size_t j = 0; j < m && !cluster; ++j)
      cluster = j != i && start[j].value != std::conj(z) && std::abs(start[j].value - z) <= 1e-3 * std::abs(z);
    need[i] = !clear || cluster || z.real() + radius[i] >= start[top].value.real() - radius[top];
  }
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < m && need[i]; ++j) {
        const bool near = std::abs(start[j].value - start[i].value) <= 1e-3 * std::abs(start[i].value) ||
                          start[j].value == std::conj(start[i].value);
        if (!need[j] && near) need[j] = grew = true;
      }
  }
  return true;
}

}  // namespace

SpectrumVerdict spectrum_verdict(const Linearization<ld, N>& lin, int structural_zeros) {
  using namespace spectrum_detail;
  if (structural_zeros > 0) return from_full(lin, structural_zeros);
  Starts<N> starts;
  starting_values(lin, SpectrumMethod::refined, starts);
  const std::size_t m = eigen_count<N>(starts.count);
  std::array<double, kCap> radius{};
  std::array<bool, kCap> need{};
  if (!starts.status.ok() || !select(starts, m, radius, need)) return from_full(lin, structural_zeros);
  // compute_spectrum's refinements (the same calls, acceptance and grouping) for these.
  SpectrumN sp;
  sp.count = starts.count;
  std::array<ld, kCap> band{};
  std::array<bool, kCap> failed{};
  const VectorSource<N> vector_of = [](const Estimate<N>& e, bool complex) {
    return complex ? position_vector<std::complex<double>, N>(e) : position_vector<double, N>(e);
  };
  assemble_spectrum(lin, starts, SpectrumMethod::refined, vector_of, sp, band, &failed, &need);
  // A failed one: compute_spectrum retries from shifted inverses; leave that to it.
  for (std::size_t i = 0; i < m; ++i)
    if (failed[i]) return from_full(lin, structural_zeros);
  // Classify as sort_and_classify does, on the double values; the QR values of the
  // others by their sign (clear of the axis by selection).
  SpectrumVerdict v;
  v.abscissa = -std::numeric_limits<double>::infinity();
  int marginal = 0;
  double unrefined_right = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < m; ++i) {
    const double re = sp.eigenvalues[i].real();
    if (need[i]) {
      ++v.refined;
      v.abscissa = std::max(v.abscissa, re);
      if (std::abs(re) <= double(band[i])) {
        ++marginal;
      } else if (re > 0) {
        ++v.n_unstable;
      }
    } else {
      unrefined_right = std::max(unrefined_right, re + radius[i]);
      if (re > 0) ++v.n_unstable;
    }
  }
  // The abscissa must be a refined eigenvalue's, with room to spare.
  if (!(unrefined_right < v.abscissa)) return from_full(lin, structural_zeros);
  v.stability = v.n_unstable > 0 ? Stability::unstable : marginal > 0 ? Stability::marginal : Stability::stable;
  v.converged = sp.converged;
  return v;
}

}  // namespace abu
