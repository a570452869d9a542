// The fold and Hopf curves of a map's plane (map_driver.hpp: map_boundaries, map_boundaries_n):
// the branches along the map's bottom and top edges, their special points continued across.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/scan/map_driver.hpp"

namespace abu {

namespace {
// The fold and Hopf curves of the map's plane from the continuations in x along its bottom
// and top edges (`trace(p, to2)`: the branches at p, their points continued in y to to2).
// Two points of boundary curves are one point of the plane: both parameters within 1e-8
// of the map's extent (a curve's end on an edge and the special point located there each
// solve an augmented system, to ~1e-12). The configuration is not compared: a curve and
// its mirror image (equal balls swapped) are one boundary in the plane, and the curves of
// distinct equilibria (n balls: the samples of the balanced set) lie ~1e-5 apart or more.
template <class Point>
bool same_point(const Point& a, const Point& b, const MapJob& job) {
  using std::abs;
  const double sx = abs(job.x.to - job.x.from), sy = abs(job.y.to - job.y.from);
  return abs(double(a.parameter - b.parameter)) <= 1e-8 * sx && abs(double(a.parameter2 - b.parameter2)) <= 1e-8 * sy;
}

// A curve traced from the top edge that a curve from the bottom edge already crossed the
// map with (it starts where that one ends, or ends where it starts) is the same curve:
// written once.
template <class Curve>
bool already_traced(const Curve& c, const std::vector<Curve>& bottom, const MapJob& job) {
  if (c.points.empty()) return false;
  for (const auto& k : bottom) {
    if (k.kind != c.kind || k.points.empty()) continue;
    for (const auto* end : {&k.points.front(), &k.points.back()})
      if (same_point(c.points.front(), *end, job) || same_point(c.points.back(), *end, job)) return true;
  }
  return false;
}

template <class BoundaryRunT, class P, class Trace>
BoundaryRunT along_edges(const MapJob& job, const P& base, Trace trace) {
  BoundaryRunT all;
  all.param = job.x.param;
  all.param2 = job.y.param;
  all.from = job.x.from, all.to = job.x.to, all.from2 = job.y.from, all.to2 = job.y.to;
  std::size_t duplicates = 0;
  decltype(all.curves) bottom;  // the curves from the bottom edge
  for (const auto& [at, to] : {std::pair{job.y.from, job.y.to}, std::pair{job.y.to, job.y.from}}) {
    P p = base;
    set(p, job.x.param, job.x.from);
    set(p, job.y.param, at);
    BoundaryRunT part = trace(p, to);
    const bool top = at != job.y.from;
    for (auto& c : part.curves) {
      if (top && already_traced(c, bottom, job)) {
        ++duplicates;
        continue;
      }
      if (!top) bottom.push_back(c);
      all.curves.push_back(std::move(c));
    }
    for (auto& n : part.notes) all.notes.push_back(std::move(n));
  }
  if (duplicates > 0)
    all.notes.push_back(fmt::format("{} curves traced from the top edge crossed the map along a curve from the "
                                    "bottom edge: each curve is written once",
                                    duplicates));
  static const std::string edges_note =
      "curves found from the fold and Hopf points on the bottom and top edges of the map; a closed curve "
      "inside the map touching neither edge is not drawn";
  all.notes.push_back(edges_note);
  return all;
}
}  // namespace

std::optional<BoundaryRun> map_boundaries(const MapJob& job) {
  if (job.any_balls || job.stick_set) return std::nullopt;
  const ContinuationOptions options;
  return along_edges<BoundaryRun>(job, job.params, [&](const Params& p, double to2) {
    const ContinuationRun run = continue_branches(p, job.x.param, job.x.to, options, StartSelection{});
    return continue_boundaries(p, run, job.y.param, to2, options);
  });
}

std::optional<BoundaryRunN> map_boundaries_n(const MapJob& job) {
  if (!job.any_balls || job.stick_set || job.support || job.x.ball_count || job.y.ball_count ||
      job.params_n.n_balls() < 3)
    return std::nullopt;
  const ContinuationOptions options;
  BoundaryRunN all = along_edges<BoundaryRunN>(job, job.params_n, [&](const ParamsN& p, double to2) {
    const ContinuationRunN run = continue_branches(p, job.x.param, job.x.to, options, job.sampling);
    return continue_boundaries(p, run, job.y.param, to2, options);
  });
  all.n_balls = job.params_n.n_balls();
  return all;
}

}  // namespace abu
