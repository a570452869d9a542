// Points and order statistics of a study (docs/model.md §21.2, §21.3).
#include "abu/core/sampling.hpp"

#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_qrng.h>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "abu/core/errors.hpp"

namespace abu {

std::string_view to_string(SampleDesign d) { return d == SampleDesign::sobol ? "sobol" : "random"; }

std::optional<SampleDesign> sample_design_from_string(std::string_view name) {
  if (name == "sobol") return SampleDesign::sobol;
  if (name == "random") return SampleDesign::random;
  return std::nullopt;
}

std::vector<double> sobol_points(int count, int dims) {
  const std::unique_ptr<gsl_qrng, decltype(&gsl_qrng_free)> q(gsl_qrng_alloc(gsl_qrng_sobol, unsigned(dims)),
                                                               &gsl_qrng_free);
  if (!q) throw NumericalError(fmt::format("no Sobol sequence in {} dimensions (GSL)", dims));
  std::vector<double> u(static_cast<std::size_t>(count) * static_cast<std::size_t>(dims));
  for (int k = 0; k < count; ++k) gsl_qrng_get(q.get(), u.data() + std::size_t(k) * std::size_t(dims));
  return u;
}

std::vector<double> sample_points(int count, int dims, SampleDesign design, unsigned long seed) {
  if (count < 1) throw InputError("--samples", 0, "", fmt::format("a study needs at least one sample, got {}", count));
  if (dims < 1) throw InputError("sample_points", 0, "", "a point needs at least one dimension");
  if (design == SampleDesign::sobol && dims > kMaxSobolDimensions)
    throw InputError("--design", 0, "sobol",
                     fmt::format("the Sobol design has at most {} dimensions (the balls' angles and the uncertain "
                                 "inputs), this study has {}: use --design random or fewer uncertain inputs",
                                 kMaxSobolDimensions, dims));
  const std::unique_ptr<gsl_rng, decltype(&gsl_rng_free)> rng(gsl_rng_alloc(gsl_rng_mt19937), &gsl_rng_free);
  gsl_rng_set(rng.get(), seed);
  if (design == SampleDesign::random) {
    std::vector<double> u(static_cast<std::size_t>(count) * static_cast<std::size_t>(dims));
    for (double& x : u) x = gsl_rng_uniform(rng.get());
    return u;
  }
  // A random shift modulo 1 (Cranley-Patterson): each point is uniform on the cube, the set keeps
  // the sequence's low discrepancy, and the seed makes a study reproducible.
  std::vector<double> shift(static_cast<std::size_t>(dims));
  for (double& s : shift) s = gsl_rng_uniform(rng.get());
  std::vector<double> u = sobol_points(count, dims);
  for (int k = 0; k < count; ++k) {
    double* x = u.data() + std::size_t(k) * std::size_t(dims);
    for (int d = 0; d < dims; ++d) {
      x[d] += shift[std::size_t(d)];
      if (x[d] >= 1.0) x[d] -= 1.0;
    }
  }
  return u;
}

OrderRanks quantile_ranks(int n, double p, double confidence) {
  const double tail = 0.5 * (1.0 - confidence);
  OrderRanks r{0, n + 1};
  // P(x_(l) > xi_p) = P(B <= l - 1): the largest l with that at most the tail.
  for (int l = n; l >= 1; --l)
    if (gsl_cdf_binomial_P(unsigned(l - 1), p, unsigned(n)) <= tail) {
      r.low = l;
      break;
    }
  // P(x_(u) < xi_p) = P(B >= u) = Q(u - 1): the smallest u with that at most the tail.
  for (int u = 1; u <= n; ++u)
    if (gsl_cdf_binomial_Q(unsigned(u - 1), p, unsigned(n)) <= tail) {
      r.high = u;
      break;
    }
  return r;
}

QuantileEstimate quantile_estimate(std::vector<double> values, double p, double confidence) {
  if (values.empty()) throw std::invalid_argument("quantile_estimate: no values");
  if (!(p > 0 && p <= 1)) throw std::invalid_argument("quantile_estimate: p outside (0, 1]");
  std::sort(values.begin(), values.end());
  const int n = int(values.size());
  QuantileEstimate e;
  e.probability = p;
  e.confidence = confidence;
  e.count = n;
  const int rank = std::clamp(int(std::ceil(p * n - 1e-12)), 1, n);
  e.value = values[std::size_t(rank - 1)];
  if (p < 1) {
    const OrderRanks r = quantile_ranks(n, p, confidence);
    if (r.low >= 1) e.low = values[std::size_t(r.low - 1)];
    if (r.high <= n) e.high = values[std::size_t(r.high - 1)];
  }
  return e;
}

ProportionEstimate proportion_estimate(int events, int count, double confidence) {
  ProportionEstimate e;
  e.events = events;
  e.count = count;
  e.confidence = confidence;
  if (count <= 0) return e;
  const double n = count, k = events, z = gsl_cdf_ugaussian_Pinv(0.5 + 0.5 * confidence), z2 = z * z;
  e.value = k / n;
  const double centre = (k + 0.5 * z2) / (n + z2);
  const double half = z / (n + z2) * std::sqrt(k * (n - k) / n + 0.25 * z2);
  // At k = 0 (k = n) the interval's end is 0 (1) exactly; the formula leaves rounding there.
  e.low = events == 0 ? 0.0 : std::max(0.0, centre - half);
  e.high = events == count ? 1.0 : std::min(1.0, centre + half);
  return e;
}

}  // namespace abu
