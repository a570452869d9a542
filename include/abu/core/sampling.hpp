// Samples of a machine's uncertain start and inputs, and what a sample of runs says
// (docs/model.md §21.2, §21.3): points in the unit cube, low-discrepancy or independent,
// reproducible from a seed; a quantile with the distribution-free interval of its order
// statistics; a proportion with Wilson's score interval.
//
//   auto u = abu::sample_points(256, 3, abu::SampleDesign::sobol, 7);   // 256 x 3, row-major
//   abu::QuantileEstimate p90 = abu::quantile_estimate(residuals, 0.9);
//   abu::ProportionEstimate stall = abu::proportion_estimate(12, 256);  // 4.7 % [2.7, 8.0] %
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace abu {

/// How the points of a study are drawn (docs/model.md §21.2).
enum class SampleDesign {
  sobol,   ///< GSL's Sobol sequence (up to 40 dimensions), shifted modulo 1 by one uniform vector from the seed
  random,  ///< independent uniform points (GSL's mt19937 from the seed)
};
std::string_view to_string(SampleDesign d);
std::optional<SampleDesign> sample_design_from_string(std::string_view name);

/// The most dimensions the Sobol design takes (GSL's gsl_qrng_sobol).
inline constexpr int kMaxSobolDimensions = 40;

/// The first `count` points of GSL's Sobol sequence in `dims` <= kMaxSobolDimensions dimensions
/// (gsl_qrng_sobol, in order; its first point is (1/2, ..., 1/2)), row-major, unshifted.
std::vector<double> sobol_points(int count, int dims);

/// `count` points in [0, 1)^dims, row-major (point k at k * dims). The same arguments give the
/// same points on every machine and thread count. Throws InputError for count < 1, dims < 1, or
/// dims > kMaxSobolDimensions with the Sobol design.
std::vector<double> sample_points(int count, int dims, SampleDesign design, unsigned long seed);

/// A quantile of a sample with its confidence interval (docs/model.md §21.3).
struct QuantileEstimate {
  double probability = 0.5;  ///< p
  double value = 0;          ///< the order statistic x_(ceil(p n)) (1-based; the largest for p = 1)
  /// x_(l) and x_(u): P(x_(l) <= xi_p <= x_(u)) >= confidence for any continuous distribution;
  /// empty where the sample is too small to bound that side (x_(0) = -inf, x_(n+1) = +inf).
  std::optional<double> low, high;
  double confidence = 0.95;
  int count = 0;  ///< n
};

/// The 1-based ranks (l, u) of the order statistics that bound the p-quantile of n samples
/// with at least `confidence`, equal tails: l the largest with P(B <= l - 1) <= alpha / 2, u the
/// smallest with P(B >= u) <= alpha / 2, B ~ Binomial(n, p) the count below the quantile;
/// l = 0 or u = n + 1 where no rank does.
struct OrderRanks {
  int low = 0, high = 0;
};
OrderRanks quantile_ranks(int n, double p, double confidence);

/// The p-quantile of `values` (any order; finite) and its interval. Throws
/// std::invalid_argument for an empty sample or p outside (0, 1].
QuantileEstimate quantile_estimate(std::vector<double> values, double p, double confidence = 0.95);

/// A proportion k / n with Wilson's score interval at `confidence` (docs/model.md §21.3).
struct ProportionEstimate {
  int events = 0, count = 0;
  double value = 0, low = 0, high = 0;  ///< in [0, 1]
  double confidence = 0.95;
};
ProportionEstimate proportion_estimate(int events, int count, double confidence = 0.95);

}  // namespace abu
