#include "abu/linear/spectrum.hpp"

#include "spectrum_starts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace abu {

namespace {

using ld = long double;
using cld = std::complex<ld>;
constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff 2^-53

// Sorts, and classifies each eigenvalue against its band; the `structural_zeros`
// eigenvalues of smallest modulus are exactly zero by construction and lie on the axis.
template <int N>
void sort_and_classify(SpectrumT<N>& sp, std::array<ld, SpectrumT<N>::capacity> band, int structural_zeros) {
  const std::size_t m = spectrum_detail::eigen_count<N>(sp.count);
  for (int z = 0; z < structural_zeros; ++z) {
    std::size_t smallest = 0;
    for (std::size_t i = 1; i < m; ++i)
      if (band[i] != std::numeric_limits<ld>::infinity() &&
          (band[smallest] == std::numeric_limits<ld>::infinity() ||
           std::abs(sp.eigenvalues[i]) < std::abs(sp.eigenvalues[smallest])))
        smallest = i;
    band[smallest] = std::numeric_limits<ld>::infinity();
  }
  std::array<int, SpectrumT<N>::capacity> order{};
  for (std::size_t i = 0; i < m; ++i) order[i] = int(i);
  std::sort(order.begin(), order.begin() + std::ptrdiff_t(m), [&](int a, int b) {
    const auto& x = sp.eigenvalues[std::size_t(a)];
    const auto& y = sp.eigenvalues[std::size_t(b)];
    return x.real() > y.real() || (x.real() == y.real() && x.imag() > y.imag());
  });
  SpectrumT<N> sorted = sp;
  for (std::size_t i = 0; i < m; ++i) {
    const auto k = std::size_t(order[i]);
    sorted.eigenvalues[i] = sp.eigenvalues[k];
    sorted.error[i] = sp.error[k];
    sorted.condition[i] = sp.condition[k];
    sorted.vectors[i] = sp.vectors[k];
    sorted.structural[i] = sp.structural[k];
    const double re = sp.eigenvalues[k].real();
    sorted.on_axis[i] = sp.structural[k] || std::abs(re) <= double(band[k]);
  }
  sp = sorted;
  sp.n_unstable = sp.n_marginal = sp.n_structural = 0;
  sp.abscissa = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < m; ++i) {
    if (sp.structural[i]) {
      ++sp.n_structural;
      continue;
    }
    sp.abscissa = std::max(sp.abscissa, sp.eigenvalues[i].real());
    if (sp.on_axis[i]) {
      ++sp.n_marginal;
    } else if (sp.eigenvalues[i].real() > 0) {
      ++sp.n_unstable;
    }
  }
  if (sp.n_structural == sp.count) sp.abscissa = 0;
  sp.stability = sp.n_unstable > 0 ? Stability::unstable : sp.n_marginal > 0 ? Stability::marginal : Stability::stable;
}

}  // namespace

std::string_view to_string(Stability s) {
  switch (s) {
    case Stability::stable: return "stable";
    case Stability::unstable: return "unstable";
    case Stability::marginal: return "marginal";
  }
  return "?";
}

std::string_view to_string(SpectrumMethod m) {
  switch (m) {
    case SpectrumMethod::dense_qr: return "dense-qr";
    case SpectrumMethod::structured: return "structured";
    case SpectrumMethod::refined: return "refined";
  }
  return "?";
}

namespace spectrum_detail {

template <int N>
void assemble_spectrum(const Linearization<ld, N>& qep, const Starts<N>& starts, SpectrumMethod method,
                       const VectorSource<N>& vector_of, SpectrumT<N>& sp, std::array<ld, SpectrumT<N>::capacity>& band,
                       std::array<bool, SpectrumT<N>::capacity>* failed_out,
                       const std::array<bool, SpectrumT<N>::capacity>* refine_only) {
  const auto& start = starts.estimates;
  const std::size_t m = eigen_count<N>(starts.count);  // eigenvalues to fill, from slot `first`
  const std::size_t first = eigen_count<N>(sp.count) - m;
  if (method != SpectrumMethod::refined) {
    // QR only: the a-priori bound eps |lambda| stands in for the error estimate.
    for (std::size_t i = 0; i < m; ++i) {
      sp.eigenvalues[first + i] = start[i].value;
      sp.error[first + i] = kEps * std::abs(start[i].value);
      sp.condition[first + i] = 1;
      band[first + i] = ld(8 * kEps * std::abs(start[i].value));
    }
    sp.converged = false;
    sp.status.merge(Outcome::not_converged, "QR values only: this method does not refine them");
    return;
  }
  std::array<bool, SpectrumT<N>::capacity> filled{};
  std::array<bool, SpectrumT<N>::capacity> converged_at{};
  std::array<cld, SpectrumT<N>::capacity> refined{};
  const auto fill = [&](std::size_t k, cld v, const RefinedEigenpair<N>& r) {
    const ld modulus = std::abs(v);
    refined[k] = v;
    sp.vectors[first + k] = v == r.value ? r.vector : QepVector<N>(r.vector.conjugate());
    sp.eigenvalues[first + k] = {double(v.real()), double(v.imag())};
    sp.error[first + k] = double(r.abs_condition * r.backward_error);
    sp.condition[first + k] =
        modulus > 0 ? double(r.abs_condition / modulus) : std::numeric_limits<double>::infinity();
    // Eight first-order error bounds, with every entry of A, C, K rounded to double.
    band[first + k] = 8 * r.abs_condition * (r.backward_error + ld(kEps));
    converged_at[k] = r.converged;
    filled[k] = true;
  };
  // Not to be refined (refine_only): the QR value, left out of every test below.
  std::array<bool, SpectrumT<N>::capacity> skipped{};
  if (refine_only)
    for (std::size_t i = 0; i < m; ++i)
      if (!(*refine_only)[i]) {
        skipped[i] = filled[i] = true;
        sp.eigenvalues[first + i] = start[i].value;
        sp.condition[first + i] = 1;
        sp.vectors[first + i] = QepVector<N>::Zero(qep.mass.rows());
      }
  for (std::size_t i = 0; i < m; ++i) {
    const auto z = start[i].value;
    if (filled[i] || z.imag() < 0) continue;  // lower half-plane: the conjugate partner
    if (z.imag() == 0) {
      const auto r = refine_eigenpair<ld, N>(qep, z, vector_of(start[i], false));
      fill(i, r.value, r);
      continue;
    }
    const auto r = refine_eigenpair<cld, N>(qep, z, vector_of(start[i], true));
    fill(i, r.value, r);
    for (std::size_t j = 0; j < m; ++j) {
      if (!filled[j] && start[j].value == std::conj(z)) {
        fill(j, std::conj(r.value), r);
        break;
      }
    }
  }
  for (std::size_t i = 0; i < m; ++i) {  // a lower-half value whose partner was not found
    if (filled[i]) continue;
    const auto r = refine_eigenpair<cld, N>(qep, start[i].value, vector_of(start[i], true));
    fill(i, r.value, r);
  }
  // Newton must stay in the basin of its starting value: a refined eigenvalue that moved
  // by more than half the distance to the nearest other starting value (which is also
  // how two starts would end on one eigenvalue) is not accepted.
  const auto as_ld = [](std::complex<double> z) { return cld(z.real(), z.imag()); };
  // Copies of one multiple eigenvalue (identical balls at one place: their relative
  // modes) converge to the same value from starts that the QR scattered; they do not
  // bound each other's basin.
  // Two starts on one simple eigenvalue converge to the same value with the same
  // eigenvector; copies of a semisimple multiple one keep independent vectors, or
  // already started together (the QR resolved no difference: closer than 1e-12, two
  // eigenvalues are one at the 1e-8 reported).
  // (Squared moduli, std::norm: hypotl made this pairwise test a fifth of the spectrum's
  // cost; decided once per pair.)
  std::array<std::array<bool, SpectrumT<N>::capacity>, SpectrumT<N>::capacity> copy{};
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j)
      copy[i][j] = j != i && converged_at[i] && converged_at[j] &&
                   std::norm(refined[i] - refined[j]) <= 1e-24L * std::norm(refined[i]) &&
                   (std::norm(sp.vectors[first + i].dot(sp.vectors[first + j])) < (1 - 1e-6) * (1 - 1e-6) ||
                    std::norm(start[i].value - start[j].value) <= 1e-24 * std::norm(start[i].value));
  const auto copies = [&](std::size_t i, std::size_t j) { return copy[i][j]; };
  const auto basin_radius = [&](std::size_t i, const std::array<bool, SpectrumT<N>::capacity>& group) {
    ld radius = std::numeric_limits<ld>::infinity();
    double radius_squared = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < m; ++j)
      if (start[j].value != start[i].value && !copies(i, j) && !group[j])
        radius_squared = std::min(radius_squared, std::norm(start[j].value - start[i].value) / 4);
    if (radius_squared < std::numeric_limits<double>::infinity()) radius = std::sqrt(ld(radius_squared));
    return radius;
  };
  std::array<bool, SpectrumT<N>::capacity> failed{};
  std::array<bool, SpectrumT<N>::capacity> none{};
  for (std::size_t i = 0; i < m; ++i)
    failed[i] = !skipped[i] && (!converged_at[i] || std::abs(refined[i] - as_ld(start[i].value)) > basin_radius(i, none));
  // Second chance for a multiple eigenvalue where the plain Newton stalled (its bordered
  // matrix is singular there, or it jumps to a neighbour): a failed start and every
  // start within 1e-3 of it that failed too (a semisimple cluster of a non-normal J
  // scatters by up to ~1e-5 in double) or that the QR did not tell apart from it (1e-12)
  // form a group of multiplicity k, refined once from their mean (refinement.hpp, the
  // rank-(k-1) update) and shared if that converges inside the group's basin.
  for (std::size_t i = 0; i < m; ++i) {
    if (!failed[i] || start[i].value.imag() < 0) continue;
    std::array<bool, SpectrumT<N>::capacity> group{};
    group[i] = true;
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t j = 0; j < m; ++j)
        for (std::size_t g = 0; g < m && !group[j]; ++g)
          if (group[g] && start[j].value.imag() >= 0 &&
              std::abs(start[j].value - start[g].value) <= 1e-3 * std::abs(start[g].value) &&
              (failed[j] || std::abs(start[j].value - start[g].value) <= 1e-12 * std::abs(start[g].value)))
            group[j] = grew = true;
    }
    int k = 0;
    std::complex<double> mean = 0;
    for (std::size_t j = 0; j < m; ++j)
      if (group[j]) ++k, mean += start[j].value;
    if (k < 2) continue;
    mean /= double(k);
    if (start[i].value.imag() == 0) mean.imag(0);
    Estimate<N> from = start[i];
    from.value = mean;
    const bool complex = mean.imag() != 0;
    const auto r = complex ? refine_eigenpair<cld, N>(qep, mean, vector_of(from, true), k)
                           : refine_eigenpair<ld, N>(qep, mean, vector_of(from, false), k);
    RefinedEigenpair<N> shared = r;
    if (!r.converged || std::abs(r.value - as_ld(mean)) > basin_radius(i, group)) {
      // Newton cannot certify this multiple eigenvalue: its QR copies, if they agree to
      // 1e-10 of their modulus within their own a-priori bounds (eps times the norm of the
      // matrix each came from, scaled back through the shift), give it, with their
      // spread plus that bound as the error estimate.
      double bound = 0;
      for (std::size_t j = 0; j < m; ++j) {
        if (!group[j]) continue;
        const auto& e = start[j];
        const double qr = apriori_error(e);
        bound = std::max(bound, std::abs(e.value - mean) + qr);
      }
      // 1e-10: copies of one eigenvalue agree to ~1e-15 here; two distinct eigenvalues
      // closer than that are indistinguishable at the 1e-8 the spectrum is reported to.
      if (!(bound <= 1e-10 * std::abs(mean))) continue;
      shared.value = as_ld(mean);
      shared.abs_condition = ld(std::abs(mean));
      shared.backward_error = ld(bound / std::abs(mean));
      shared.converged = true;
      shared.vector = vector_of(from, complex);
    }
    for (std::size_t j = 0; j < m; ++j) {
      if (!group[j]) continue;
      fill(j, shared.value, shared);
      failed[j] = false;
      if (!complex) continue;
      for (std::size_t c = 0; c < m; ++c)  // the conjugate copies
        if (start[c].value.imag() < 0 && std::abs(start[c].value - std::conj(start[j].value)) <=
                                             1e-12 * std::abs(start[j].value)) {
          fill(c, std::conj(shared.value), shared);
          failed[c] = false;
          break;
        }
    }
  }
  // Copies of one multiple eigenvalue share its error: the best-conditioned copy's bound
  // (a copy's y^H T' x can nearly vanish inside the eigenspace, which made a 1e16
  // "condition" and a band that swallowed the axis), the copies agreeing to 1e-12.
  for (std::size_t i = 0; i < m; ++i) {
    if (failed[i]) continue;
    for (std::size_t j = 0; j < m; ++j) {
      if (j == i || failed[j] || !copies(i, j) || !(band[first + j] < band[first + i])) continue;
      band[first + i] = band[first + j];
      sp.error[first + i] = sp.error[first + j];
      sp.condition[first + i] = sp.condition[first + j];
    }
  }
  for (std::size_t i = 0; i < m; ++i) sp.ill_conditioned = sp.ill_conditioned || !(sp.condition[first + i] * kEps <= 1e-8);
  sp.converged = true;
  if (failed_out)
    for (std::size_t i = 0; i < m; ++i) (*failed_out)[i] = failed[i];
  for (std::size_t i = 0; i < m; ++i) {
    if (failed[i]) {  // keeps its QR value, and the refinement is reported as failed
      sp.eigenvalues[first + i] = start[i].value;
      sp.error[first + i] = double(std::abs(refined[i] - as_ld(start[i].value)));
      // Its band is the error it actually has, not the failed refinement's: at least the
      // distance the refinement moved and 64 times the QR's a-priori bound (eps ||J|| from
      // the direct matrix, eps ||(J - sigma)^-1|| |lambda - sigma|^2 from the inverse), so
      // a QR value that cannot be told from the axis is marginal, never unstable.
      const auto& e = start[i];
      const ld apriori = e.source ? ld(apriori_error(e)) : 0;
      band[first + i] = std::max({band[first + i], std::abs(refined[i] - as_ld(e.value)), 64 * apriori});
      sp.error[first + i] = std::max(sp.error[first + i], double(64 * apriori));
      sp.converged = false;
      sp.status.merge(Outcome::not_converged, "an eigenvalue refinement did not converge; its QR value is kept");
    } else if (!converged_at[i] && !skipped[i]) {
      sp.converged = false;
      sp.status.merge(Outcome::not_converged, "an eigenvalue refinement stopped above its tolerance");
    }
  }
}

template <int N>
void finish_spectrum(SpectrumT<N>& sp, const std::array<ld, SpectrumT<N>::capacity>& band, int structural_zeros) {
  sort_and_classify(sp, band, structural_zeros);
}

template void assemble_spectrum<2>(const Linearization<ld, 2>&, const Starts<2>&, SpectrumMethod,
                                   const VectorSource<2>&, SpectrumT<2>&, std::array<ld, SpectrumT<2>::capacity>&,
                                   std::array<bool, SpectrumT<2>::capacity>*,
                                   const std::array<bool, SpectrumT<2>::capacity>*);
template void assemble_spectrum<any_balls>(const Linearization<ld, any_balls>&, const Starts<any_balls>&,
                                           SpectrumMethod, const VectorSource<any_balls>&, SpectrumT<any_balls>&,
                                           std::array<ld, SpectrumT<any_balls>::capacity>&,
                                           std::array<bool, SpectrumT<any_balls>::capacity>*,
                                           const std::array<bool, SpectrumT<any_balls>::capacity>*);
template void finish_spectrum<2>(SpectrumT<2>&, const std::array<ld, SpectrumT<2>::capacity>&, int);
template void finish_spectrum<any_balls>(SpectrumT<any_balls>&, const std::array<ld, SpectrumT<any_balls>::capacity>&,
                                         int);

}  // namespace spectrum_detail

template <int N>
SpectrumT<N> compute_spectrum(const Linearization<ld, N>& lin, SpectrumMethod method, int structural_zeros) {
  using namespace spectrum_detail;
  Starts<N> starts;
  starting_values(lin, method, starts);
  SpectrumT<N> sp;
  sp.count = starts.count;
  sp.status = starts.status;
  std::array<ld, SpectrumT<N>::capacity> band{};
  const VectorSource<N> vector_of = [](const Estimate<N>& e, bool complex) {
    return complex ? position_vector<std::complex<double>, N>(e) : position_vector<double, N>(e);
  };
  std::array<bool, SpectrumT<N>::capacity> failed{};
  assemble_spectrum(lin, starts, method, vector_of, sp, band, &failed);
  // Failed refinements (at kappa = 1e12 the spectrum spans 30 decades, and a
  // pair at -8 +- 100i came out of both QRs as two real values near +-0.8 that Newton could
  // not leave): retry them from a shifted inverse near their scale, where the QR resolves
  // them, and take the retry only if every eigenvalue then converges. Exact cases never
  // come here, so their bytes are unchanged.
  const std::size_t m = eigen_count<N>(starts.count);
  const auto n_failed = [m](const std::array<bool, SpectrumT<N>::capacity>& f) {
    return std::count(f.begin(), f.begin() + std::ptrdiff_t(m), true);
  };
  if (method == SpectrumMethod::refined && n_failed(failed) > 0) {
    // Every round keeps what converged (at its refined value) and reshifts for the rest,
    // at the scale of their starts; a round is taken only if fewer fail. The Starts stay
    // alive: the estimates point into the QR each came from.
    // (Fixed storage: the map's cells allocate nothing, tests/perf no_allocation.)
    constexpr int kRounds = 4;
    std::array<Starts<N>, kRounds> rounds;
    const Starts<N>* current = &starts;
    for (int round = 0; round < kRounds && n_failed(failed) > 0; ++round) {
      std::array<std::complex<double>, SpectrumT<N>::capacity> kept{};
      double scale = 0;
      for (std::size_t i = 0; i < m; ++i) {
        kept[i] = sp.eigenvalues[i];
        // A start inside its own QR error (a creep mode at 0 +- 1e-13) sets the scale by
        // that error: a shift there resolves what the QR could not.
        if (failed[i]) {
          const auto& e = current->estimates[i];
          scale = std::max({scale, std::abs(e.value), e.source ? apriori_error(e) : 0.0});
        }
      }
      if (!(scale > 0) || !std::isfinite(scale)) scale = 1;
      bool progress = false;
      for (const double factor : {1.0, 1e2, 1e4}) {
        Starts<N>* const retry = &rounds[std::size_t(round)];
        *retry = *current;
        if (!middle_starts<N>(lin, -factor * scale, failed, kept, *retry)) continue;
        SpectrumT<N> again;
        again.count = retry->count;
        again.status = retry->status;
        std::array<ld, SpectrumT<N>::capacity> band_again{};
        std::array<bool, SpectrumT<N>::capacity> failed_again{};
        assemble_spectrum(lin, *retry, method, vector_of, again, band_again, &failed_again);
        if (!(n_failed(failed_again) < n_failed(failed))) continue;
        sp = again;
        band = band_again;
        failed = failed_again;
        current = retry;
        progress = true;
        break;
      }
      if (!progress) break;
    }
  }
  sort_and_classify(sp, band, structural_zeros);
  return sp;
}

template SpectrumT<2> compute_spectrum<2>(const Linearization<ld, 2>&, SpectrumMethod, int);
template SpectrumT<any_balls> compute_spectrum<any_balls>(const Linearization<ld, any_balls>&, SpectrumMethod, int);

std::optional<TrackedSpectrum> track_spectrum(const Linearization<ld, 2>& lin,
                                              const std::array<std::complex<double>, 8>& values,
                                              const std::array<QepVector<2>, 8>& vectors) {
  using Vec4c = QepVector<2>;
  TrackedSpectrum out;
  Spectrum& sp = out.spectrum;
  std::array<ld, 8> band{};
  std::array<bool, 8> done{};
  for (std::size_t k = 0; k < 8; ++k) {
    if (done[k]) continue;
    const auto z = values[k];
    // Each mode may move by less than half the predicted distance to its nearest
    // neighbour (its conjugate excepted), or tracking would be ambiguous.
    double radius_squared = std::numeric_limits<double>::infinity();  // (std::norm: no hypot)
    for (std::size_t j = 0; j < 8; ++j)
      if (j != k && values[j] != std::conj(z)) radius_squared = std::min(radius_squared, std::norm(values[j] - z) / 4);
    const bool real = z.imag() == 0;
    const auto r = real ? refine_eigenpair<double, 2>(lin, z, vectors[k])
                        : refine_eigenpair<std::complex<double>, 2>(lin, z, vectors[k]);
    const std::complex<double> value(double(r.value.real()), double(r.value.imag()));
    // Newton started from this mode's own eigenvector stays on that mode even when the
    // extrapolated eigenvalue misses by more than the gap to a neighbour (two balls'
    // nearly equal fast modes): the eigenvector's alignment identifies it then.
    const bool aligned = std::abs(r.vector.dot(vectors[k].normalized())) >= 0.95;
    if (!r.converged || !(std::norm(value - z) < radius_squared || aligned)) return std::nullopt;
    const auto store = [&](std::size_t m, std::complex<double> v, const Vec4c& x) {
      out.modes[m] = v;
      out.mode_vectors[m] = x;
      sp.eigenvalues[m] = v;
      sp.vectors[m] = x;
      sp.error[m] = double(r.abs_condition * r.backward_error);
      sp.condition[m] = std::abs(v) > 0 ? double(r.abs_condition) / std::abs(v) : std::numeric_limits<double>::infinity();
      band[m] = 8 * r.abs_condition * (r.backward_error + ld(kEps));
      sp.ill_conditioned = sp.ill_conditioned || !(sp.condition[m] * kEps <= 1e-8);
      done[m] = true;
    };
    store(k, value, r.vector);
    if (real) continue;
    std::size_t partner = 8;
    for (std::size_t j = 0; j < 8; ++j)
      if (!done[j] && values[j] == std::conj(z)) partner = j;
    if (partner == 8) return std::nullopt;  // a complex mode without its conjugate
    store(partner, std::conj(value), Vec4c(r.vector.conjugate()));
  }
  // Two modes on one eigenvalue: one of them lost its identity.
  for (std::size_t i = 0; i < 8; ++i)
    for (std::size_t j = i + 1; j < 8; ++j)
      if (std::abs(out.modes[i] - out.modes[j]) <= 1e-9 * std::abs(out.modes[i])) return std::nullopt;
  sort_and_classify(sp, band, 0);
  return out;
}

}  // namespace abu
