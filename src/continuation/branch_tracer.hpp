// One direction of one equilibrium branch as a Problem of the pseudo-arclength engine
// (arclength.hpp): the points with their tracked spectra, the test functions, and the
// location of the special points they flag (branch_specials.cpp).
//
// Test functions between consecutive points (sign changes):
//   LP  the parameter component of the tangent, t_p;
//   BP  det [F_u; t^T] (it keeps its sign through a fold, changes it at a branch point);
//   HB  the sign of prod_{i<j} (lambda_i + lambda_j) (bifurcation.hpp hopf_test_sign).
#pragma once

#include <string>
#include <vector>

#include "abu/continuation/arclength.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/continuation/corrector.hpp"
#include "abu/continuation/tracking.hpp"

namespace abu {

class BranchTracer : public EquilibriumSystem {
 public:
  using Vec5 = StaticEquations::Vec5;
  using Mat45 = StaticEquations::Mat45;
  static constexpr std::size_t test_count = 3;
  enum Test : unsigned { lp_test = 1u << 0, bp_test = 1u << 1, hb_test = 1u << 2 };  // bits of `changed`

  explicit BranchTracer(const StaticEquations& equations) : EquilibriumSystem{equations} {}

  // The engine's hooks.
  arclength::Crossing crossing(const Vec5& from, const Vec5& to) const;
  arclength::Evaluation<long double, test_count> evaluate(const Vec5& z, const Vec5& t, const Mat45& DF,
                                                          arclength::Stage stage);
  void locate(unsigned changed, const arclength::Segment<Vec5>& between);
  void commit(Vec5& z, Vec5& t, arclength::Stage stage);
  long double distance(const Vec5& a, const Vec5& b) const { return abu::distance(a, b); }

  std::vector<BranchPoint> points;
  std::vector<SpecialPoint> specials;
  ContinuationStats stats;  ///< the spectra (the engine counts the steps)

 private:
  // Two consecutive points of the branch, a special point between them.
  struct Bracket {
    const BranchPoint &a, &b;
    const Vec5 &za, &zb, &ta;
  };

  // The point at z with its modes matched to `predicted` (none: the first point, sorted
  // order); `ambiguity` receives tracking_ambiguity.
  BranchPoint make_point(const Vec5& z, const Vec5& t, const Mat45& DF, const ModePrediction* predicted,
                         double* ambiguity);
  ModePrediction predict(const Vec5& z) const;
  // An eigenvector with q in displacement-scale units, unit norm (for overlaps).
  Vec4c scaled_vector(const Vec4c& v) const {
    const double length = double(eq.length());
    return Vec4c(v(0) / length, v(1) / length, v(2), v(3)).normalized();
  }

  void locate_singular_between(const Bracket& br, bool fold_test);
  std::optional<Vec5> root_on_branch(const Bracket& br, bool fold_test) const;
  void locate_hopf_between(const Bracket& br);
  SpecialPoint special_at(Label label, const Vec5& z, const Bracket& br) const;

  BranchPoint pending_;     // evaluated, not yet committed
  std::vector<Vec5> zs_;    // of the points
};

}  // namespace abu
