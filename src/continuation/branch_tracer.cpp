#include "branch_tracer.hpp"

#include <fmt/format.h>

#include "abu/continuation/bifurcation.hpp"
#include "abu/core/cancel.hpp"

namespace abu {

namespace {
using ld = long double;
}  // namespace

arclength::Crossing BranchTracer::crossing(const Vec5& /*from*/, const Vec5& to) const {
  // The end of the interval first: a step that overshoots a tiny end value (m = 1e-8)
  // into the unphysical range ends on the end value, not on the range rule.
  arclength::Crossing x = arclength::box_crossing(to, {4});
  if (x.kind != arclength::Crossing::inside) return x;
  // Inside the interval the parameter can still leave its physical range only if the
  // interval itself crosses it (the library's callers check the end value).
  if (const auto rule = range_violation(eq.param().quantity, double(eq.parameter(to))))
    return arclength::Crossing::leaving(
        fmt::format("{} would become {:.17g}: {}", to_string(eq.param()), double(eq.parameter(to)), *rule));
  return x;
}

// Each mode's eigenvalue extrapolated linearly in arclength from the last two points to
// z; its eigenvector as at the last point.
ModePrediction BranchTracer::predict(const Vec5& z) const {
  const std::size_t n = points.size();
  ModePrediction out;
  out.values = points[n - 1].modes;
  out.si_vectors = points[n - 1].mode_vectors;
  for (std::size_t k = 0; k < 8; ++k) out.vectors[k] = scaled_vector(points[n - 1].mode_vectors[k]);
  if (n < 2) return out;
  const ld last = (zs_[n - 1] - zs_[n - 2]).norm();
  const double ratio = last > 0 ? double((z - zs_[n - 1]).norm() / last) : 0.0;
  for (std::size_t k = 0; k < 8; ++k) out.values[k] += ratio * (points[n - 1].modes[k] - points[n - 2].modes[k]);
  return out;
}

BranchPoint BranchTracer::make_point(const Vec5& z, const Vec5& t, const Mat45& DF, const ModePrediction* predicted,
                                     double* ambiguity) {
  BranchPoint pt;
  pt.parameter = eq.parameter(z);
  pt.position = eq.position(z);
  pt.family = classify(eq.base(), pt.position);
  // Signs relative to the direction of increasing parameter, whichever way we travel.
  pt.tangent_parameter = double(t(4));
  pt.branch_test = double(arclength::bordered_determinant(DF, t));
  const Linearization<ld, 2> lin = eq.linearization(z);
  // Eigenvalue continuation from the predicted modes first (cheap, keeps every mode's
  // identity); a fresh spectrum matched to the prediction where that fails.
  if (predicted) {
    if (auto tracked = track_spectrum(lin, predicted->values, predicted->si_vectors)) {
      ++stats.tracked_spectra;
      pt.spectrum = tracked->spectrum;
      pt.modes = tracked->modes;
      pt.mode_vectors = tracked->mode_vectors;
      if (ambiguity) *ambiguity = 0;
      return pt;
    }
  }
  pt.spectrum = compute_spectrum(lin);
  ++stats.full_spectra;
  if (predicted) {
    std::array<Vec4c, 8> scaled{};
    for (std::size_t k = 0; k < 8; ++k) scaled[k] = scaled_vector(pt.spectrum.vectors[k]);
    std::array<int, 8> source{};
    track(*predicted, pt.spectrum, scaled, pt.modes, source);
    for (std::size_t k = 0; k < 8; ++k) pt.mode_vectors[k] = pt.spectrum.vectors[std::size_t(source[k])];
    if (ambiguity) *ambiguity = tracking_ambiguity(*predicted, pt.spectrum, scaled, source);
  } else {
    pt.modes = pt.spectrum.eigenvalues;
    pt.mode_vectors = pt.spectrum.vectors;
  }
  return pt;
}

arclength::Evaluation<ld, BranchTracer::test_count> BranchTracer::evaluate(const Vec5& z, const Vec5& t,
                                                                           const Mat45& DF, arclength::Stage stage) {
  throw_if_stopped("continuation");  // a stop request (SIGINT/SIGTERM) is seen at every point
  arclength::Evaluation<ld, test_count> e;
  if (stage == arclength::Stage::start) {
    pending_ = make_point(z, t, DF, nullptr, nullptr);
  } else {
    // Eigenvalue tracking needs the modes to move little per step: else a shorter step.
    // (Not at the end of the interval: that point is where it is.)
    const ModePrediction predicted = predict(z);
    double ambiguity = 0;
    pending_ = make_point(z, t, DF, &predicted, stage == arclength::Stage::step ? &ambiguity : nullptr);
    e.retry = ambiguity > 1;
    e.reason = "the eigenvalues moved too far for tracking";
  }
  e.tests = {ld(pending_.tangent_parameter), ld(pending_.branch_test), ld(hopf_test_sign(pending_.spectrum))};
  return e;
}

void BranchTracer::commit(Vec5& z, Vec5& /*t*/, arclength::Stage stage) {
  points.push_back(std::move(pending_));
  if (stage == arclength::Stage::edge) points.back().label = Label::EP;
  zs_.push_back(z);
}

}  // namespace abu
