// Two balls: the boundary of the stick set traced as level curves s_i = +-1 of (14.1)
// (predictor-corrector, model.md §14.3), kept where the other constraint holds.
#include "stick_set_model.hpp"

#include <algorithm>
#include <unordered_map>

#include "abu/core/cancel.hpp"

namespace abu::stick_detail {

struct Tracer {
  const StickModel& m;
  double step;

  double value(int i, const double* b) const { return m.s(m.q(b), i, b[i]); }
  std::array<double, 2> gradient(int i, const double* b) const {
    const double h = 1e-7;
    std::array<double, 2> g{};
    for (int j = 0; j < 2; ++j) {
      double bp[2] = {b[0], b[1]}, bm[2] = {b[0], b[1]};
      bp[j] += h;
      bm[j] -= h;
      g[std::size_t(j)] = (value(i, bp) - value(i, bm)) / (2 * h);
    }
    return g;
  }
  bool project(int i, double sign, double* b) const {
    for (int it = 0; it < 20; ++it) {
      const double r = value(i, b) - sign;
      const auto g = gradient(i, b);
      const double g2 = g[0] * g[0] + g[1] * g[1];
      if (!(g2 > 0)) return false;
      b[0] -= r * g[0] / g2;
      b[1] -= r * g[1] / g2;
      if (std::fabs(r) < 1e-13) return true;
    }
    return std::fabs(value(i, b) - sign) < 1e-9;
  }
  // The level curve through `start` (unwrapped coordinates) in direction `orientation`
  // (+1, -1), closed if it returned, until `outside` has held for a few steps: the stick set's
  // part of the curve and the step out of it (a curve runs around the torus, ~2 pi / step
  // points, while an island at small mu is ~mu across with the step scaled to it: tracing the
  // whole curve cost 37 s and 340 MB at mu = 1e-7, 500 s and 2 GB at 1e-8).
  template <class Outside>
  std::vector<std::array<double, 2>> trace(int i, double sign, std::array<double, 2> start, int orientation,
                                           const Outside& outside, bool& closed) const {
    std::vector<std::array<double, 2>> pts{start};
    double b[2] = {start[0], start[1]};
    closed = false;
    // (in double first: at mu = 1e-20 the step is ~1e-16 rad and 40 turns overflow an int)
    const long max_steps = long(std::min(40.0 * two_pi / step, 1e8)) + 1000;
    int out_steps = 0;
    std::array<double, 2> dir{};
    for (long k = 0; k < max_steps; ++k) {
      const auto g = gradient(i, b);
      const double gn = std::hypot(g[0], g[1]);
      if (!(gn > 0)) break;
      std::array<double, 2> t{-orientation * g[1] / gn, orientation * g[0] / gn};
      if (k > 0 && t[0] * dir[0] + t[1] * dir[1] < 0) t = {-t[0], -t[1]};
      dir = t;
      double nb[2] = {b[0] + step * t[0], b[1] + step * t[1]};
      if (!project(i, sign, nb)) break;
      b[0] = nb[0];
      b[1] = nb[1];
      pts.push_back({b[0], b[1]});
      out_steps = outside(pts.back()) ? out_steps + 1 : 0;
      if (out_steps > 4) break;
      if (k > 3) {
        double d0 = std::fabs(wrap(b[0] - start[0] + std::numbers::pi) - std::numbers::pi);
        double d1 = std::fabs(wrap(b[1] - start[1] + std::numbers::pi) - std::numbers::pi);
        if (std::hypot(d0, d1) < 0.6 * step) {
          pts.push_back(start);  // close exactly (mod 2 pi)
          pts.back()[0] = b[0] + (wrap(start[0] - b[0] + std::numbers::pi) - std::numbers::pi);
          pts.back()[1] = b[1] + (wrap(start[1] - b[1] + std::numbers::pi) - std::numbers::pi);
          closed = true;
          break;
        }
      }
    }
    return pts;
  }
};

std::vector<StickBoundaryArc> trace_boundary(const StickModel& m, const AxisAnalysis& A, double step) {
  Tracer tr{m, step};
  struct Start {
    int ball;
    int sign;
    std::array<double, 2> b;
  };
  std::vector<Start> starts;
  for (const auto& col : A.columns) {
    for (const auto& arc : col.arcs) {
      if (arc.length() >= two_pi) continue;
      for (double end : {arc.lo, arc.hi}) {
        double b[2] = {col.column, wrap(end)};
        const cplx q = m.q(b);
        const double s0 = m.s(q, 0, b[0]), s1 = m.s(q, 1, b[1]);
        const int ball = std::fabs(s0) >= std::fabs(s1) ? 0 : 1;
        const double s = ball == 0 ? s0 : s1;
        starts.push_back({ball, s >= 0 ? 1 : -1, {b[0], b[1]}});
      }
    }
  }
  // spatial hash of traced points per curve
  const double cell = 2.0 * step;
  // At most 2^30 cells a side (the keys, cx * cells + cy, fit a long): a step of 1e-16 rad
  // (mu = 1e-20) made two_pi / cell overflow an int.
  const long cells = std::max(1L, long(std::min(two_pi / cell, double(1L << 30))));
  std::vector<std::unordered_map<long, char>> seen(4);
  auto key = [&](double x, double y) {
    const long cx = long(wrap(x) / two_pi * cells) % cells, cy = long(wrap(y) / two_pi * cells) % cells;
    return cx * cells + cy;
  };
  auto near_seen = [&](int curve, double x, double y) {
    const long cx = long(wrap(x) / two_pi * cells) % cells, cy = long(wrap(y) / two_pi * cells) % cells;
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        const long k = ((cx + dx + cells) % cells) * cells + (cy + dy + cells) % cells;
        if (seen[std::size_t(curve)].count(k)) return true;
      }
    return false;
  };
  std::vector<StickBoundaryArc> out;
  for (const auto& st : starts) {
    throw_if_stopped("stick set");
    const int curve = st.ball * 2 + (st.sign > 0 ? 0 : 1);
    if (near_seen(curve, st.b[0], st.b[1])) continue;
    double b[2] = {st.b[0], st.b[1]};
    if (!tr.project(st.ball, st.sign, b)) continue;
    // keep the runs where the other constraint holds
    const int other = 1 - st.ball;
    auto inside = [&](const std::array<double, 2>& p) {
      double bb[2] = {p[0], p[1]};
      return std::fabs(tr.value(other, bb)) <= 1.0 + 1e-12;
    };
    const auto outside = [&](const std::array<double, 2>& p) { return !inside(p); };
    // Both ways from the start until each leaves the set (one way if the curve closes).
    bool closed = false;
    std::vector<std::array<double, 2>> pts = tr.trace(st.ball, st.sign, {b[0], b[1]}, +1, outside, closed);
    if (!closed) {
      bool back_closed = false;
      auto back = tr.trace(st.ball, st.sign, {b[0], b[1]}, -1, outside, back_closed);
      std::reverse(back.begin(), back.end());
      back.pop_back();  // the start, which `pts` begins with
      pts.insert(pts.begin(), back.begin(), back.end());
    }
    for (const auto& p : pts) seen[std::size_t(curve)][key(p[0], p[1])] = 1;
    std::vector<char> in(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) in[k] = inside(pts[k]);
    const bool all_in = std::all_of(in.begin(), in.end(), [](char c) { return c != 0; });
    StickBoundaryArc cur{st.ball, st.sign, all_in && closed, {}};
    auto crossing = [&](std::array<double, 2> p0, std::array<double, 2> p1) {
      // bisection along the chord, projected back on the curve
      for (int it = 0; it < 50; ++it) {
        std::array<double, 2> mid{0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1])};
        double bb[2] = {mid[0], mid[1]};
        tr.project(st.ball, st.sign, bb);
        mid = {bb[0], bb[1]};
        (inside(mid) == inside(p0) ? p0 : p1) = mid;
      }
      return inside(p0) ? p0 : p1;
    };
    for (std::size_t k = 0; k < pts.size(); ++k) {
      if (k > 0 && in[k] != in[k - 1]) {
        const auto c = crossing(pts[k - 1], pts[k]);
        cur.points.push_back({wrap(c[0]), wrap(c[1])});
        if (!in[k]) {
          out.push_back(cur);
          cur.points.clear();
        }
      }
      if (in[k]) cur.points.push_back({wrap(pts[k][0]), wrap(pts[k][1])});
    }
    if (cur.points.size() >= 2) out.push_back(cur);
  }
  // an open run that continues past the start of a closed traced curve: join the last
  // piece to the first one of the same curve when they meet
  return out;
}

}  // namespace abu::stick_detail
