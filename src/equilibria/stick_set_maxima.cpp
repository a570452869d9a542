// Two balls: the maximum of |q| on one component of the stick set, refined from the best
// column value (model.md §14.3): golden section over beta_1 on the arcs that overlap the
// best one, Newton on the corner equations s_1 = +-1, s_2 = +-1, and a local zoom.
#include "stick_set_model.hpp"

#include <algorithm>
#include <cmath>

namespace abu::stick_detail {

ComponentMaximum refine_component_maximum(const StickModel& m, const TwoBallScan& scan1, const AxisAnalysis& A,
                                          int column, int arc_index, ComponentMaximum start, double zoom) {
  const std::size_t N = A.columns.size();
  const auto& col = A.columns[std::size_t(column)];
  const Arc ref = col.arcs[std::size_t(arc_index)];
  const std::size_t j = std::size_t(column);
  const double lo = j == 0 ? A.columns[N - 1].column - two_pi : A.columns[j - 1].column;
  const double hi = j + 1 == N ? two_pi + A.columns[0].column : A.columns[j + 1].column;
  double best_w2 = start.w2, best_c = start.column, best_along = start.along;
  auto F = [&](double x) {
    double v = -1.0;
    for (const auto& arc : scan1.arcs(wrap(x))) {
      if (!arcs_overlap(arc, ref)) continue;
      const auto [w2, along] = scan1.max_w2(wrap(x), arc);
      if (w2 > v) v = w2;
      if (w2 > best_w2) best_w2 = w2, best_c = wrap(x), best_along = along;
    }
    return v;
  };
  const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, bb = hi;
  double x1 = bb - gr * (bb - a), x2 = a + gr * (bb - a);
  double f1 = F(x1), f2 = F(x2);
  for (int it = 0; it < 90 && bb - a > 1e-14; ++it) {
    if (f1 >= f2) {
      bb = x2, x2 = x1, f2 = f1;
      x1 = bb - gr * (bb - a), f1 = F(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + gr * (bb - a), f2 = F(x2);
    }
  }
  // The maximum of a small island sits at a sharp corner (model.md §14.3) whose tip can be
  // thinner than the sampling: Newton on the corner equations s_1 = +-1, s_2 = +-1 from
  // the best point; a corner counts if the segment to it lies in E (same component).
  for (int sa : {-1, 1})
    for (int sb : {-1, 1}) {
      double b[2] = {best_c, best_along};
      bool converged = false;
      for (int it = 0; it < 40 && !converged; ++it) {
        const cplx qq = m.q(b);
        const double r0 = m.s(qq, 0, b[0]) - sa, r1 = m.s(qq, 1, b[1]) - sb;
        if (std::fabs(r0) < 1e-13 && std::fabs(r1) < 1e-13) converged = true;
        const auto J = s_jacobian(m, b);
        const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (!(std::fabs(det) > 0)) break;
        b[0] -= (J[1][1] * r0 - J[0][1] * r1) / det;
        b[1] -= (-J[1][0] * r0 + J[0][0] * r1) / det;
      }
      if (!converged) continue;
      const double d0 = std::remainder(b[0] - best_c, two_pi), d1 = std::remainder(b[1] - best_along, two_pi);
      if (std::hypot(d0, d1) > 0.5) continue;
      bool segment_inside = true;
      for (int k = 1; k < 64 && segment_inside; ++k) {
        const double t = k / 64.0;
        const double x[2] = {best_c + t * d0, best_along + t * d1};
        segment_inside = m.excess(x) <= 1e-9;
      }
      const double w2 = std::norm(m.W(b));
      if (segment_inside && w2 > best_w2) best_w2 = w2, best_c = wrap(b[0]), best_along = wrap(b[1]);
    }
  // Last, a local brute-force zoom (41 x 41 points, the window shrinking threefold per
  // round from a few sample steps): the maximum on a curved edge next to a thin tip that
  // neither the columns nor the corner Newton reached.
  {
    double w = zoom;
    for (int round = 0; round < 30; ++round) {
      const double c0 = best_c, a0 = best_along;
      for (int i = -20; i <= 20; ++i)
        for (int k = -20; k <= 20; ++k) {
          const double x[2] = {c0 + w * i / 20.0, a0 + w * k / 20.0};
          if (m.excess(x) > 0.0) continue;
          const double w2 = std::norm(m.W(x));
          if (w2 > best_w2) best_w2 = w2, best_c = wrap(x[0]), best_along = wrap(x[1]);
        }
      w /= 3.0;
    }
  }
  return {best_w2, best_c, best_along};
}

}  // namespace abu::stick_detail
