// Two balls: the column scan of the stick set (the arcs of E in beta_2 on each beta_1
// column, ends by bisection to rounding) and its components (model.md §14.3).
#include "stick_set_model.hpp"

#include <algorithm>
#include <limits>

#include "abu/core/cancel.hpp"

namespace abu::stick_detail {

bool arcs_overlap(const Arc& x, const Arc& y) {
  if (x.length() >= two_pi || y.length() >= two_pi) return true;
  for (double shift : {-two_pi, 0.0, two_pi})
    if (x.lo <= y.hi + shift && y.lo + shift <= x.hi) return true;
  return false;
}

bool arc_contains(const Arc& x, double b) {
  if (x.length() >= two_pi) return true;
  for (double shift : {-two_pi, 0.0, two_pi})
    if (x.lo <= b + shift && b + shift <= x.hi) return true;
  return false;
}

// Distance from angle b to the arc (0 inside).
double arc_distance(const Arc& x, double b) {
  if (arc_contains(x, b)) return 0.0;
  auto d = [](double u, double v) {
    const double t = std::fabs(wrap(u - v));
    return std::min(t, two_pi - t);
  };
  return std::min(d(b, x.lo), d(b, x.hi));
}

std::array<std::array<double, 2>, 2> s_jacobian(const StickModel& m, const double* beta) {
  std::array<std::array<double, 2>, 2> J{};
  const double h = 1e-6;
  for (int j = 0; j < 2; ++j) {
    double bp[2] = {beta[0], beta[1]}, bm[2] = {beta[0], beta[1]};
    bp[j] += h;
    bm[j] -= h;
    const cplx qp = m.q(bp), qm = m.q(bm);
    for (int i = 0; i < 2; ++i) J[std::size_t(i)][std::size_t(j)] = (m.s(qp, i, bp[i]) - m.s(qm, i, bm[i])) / (2 * h);
  }
  return J;
}


std::vector<double> sample_positions(int uniform, const std::vector<std::pair<double, double>>& windows) {
  std::vector<double> x;
  for (int k = 0; k < uniform; ++k) x.push_back(two_pi * k / uniform);
  const double coarse = two_pi / uniform;
  for (const auto& [centre, width] : windows) {
    x.push_back(wrap(centre));
    const double h = width / 24.0;
    if (!(h < coarse / 2)) continue;
    const double half = std::min(6.0 * width, 2.0 * coarse + 6.0 * width);
    const int count = std::min(4000, int(half / h));
    for (int k = 1; k <= count; ++k) {
      x.push_back(wrap(centre + k * h));
      x.push_back(wrap(centre - k * h));
    }
  }
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end(), [](double u, double v) { return v - u < 1e-13; }), x.end());
  return x;
}

double covering_length(std::vector<Arc> arcs) {
  if (arcs.empty()) return 0.0;
  for (const auto& a : arcs)
    if (a.length() >= two_pi) return two_pi;
  // Merge on the circle: sort by lo, find the largest gap.
  std::vector<std::pair<double, double>> iv;
  for (const auto& a : arcs) {
    if (a.hi <= two_pi) {
      iv.push_back({a.lo, a.hi});
    } else {
      iv.push_back({a.lo, two_pi});
      iv.push_back({0.0, a.hi - two_pi});
    }
  }
  std::sort(iv.begin(), iv.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& v : iv) {
    if (!merged.empty() && v.first <= merged.back().second)
      merged.back().second = std::max(merged.back().second, v.second);
    else
      merged.push_back(v);
  }
  if (merged.empty()) return 0.0;
  double largest_gap = merged.front().first + two_pi - merged.back().second;
  for (std::size_t k = 1; k < merged.size(); ++k)
    largest_gap = std::max(largest_gap, merged[k].first - merged[k - 1].second);
  return std::max(0.0, two_pi - largest_gap);
}

bool linked(const TwoBallScan& scan, double c0, const Arc& x, double c1, const Arc& y, int depth) {
  if (arcs_overlap(x, y)) return true;
  if (depth == 0 || arc_distance(x, y.lo) > 20.0 * (c1 - c0) + 1e-3 * (x.length() + y.length() + 1.0)) return false;
  const double mid = 0.5 * (c0 + c1);
  std::vector<Arc> middle = scan.arcs(wrap(mid));
  double a = x.lo, b = x.hi;
  for (double shift : {-two_pi, 0.0, two_pi}) {  // the window between x and y, the short way round
    if (std::fabs(y.lo + shift - x.lo) < std::numbers::pi) a = std::min(a, y.lo + shift), b = std::max(b, y.hi + shift);
  }
  if (b - a < std::numbers::pi)
    for (const auto& z : scan.arcs_in(wrap(mid), a, b, 256)) middle.push_back(z);
  for (const auto& z : middle)
    if (linked(scan, c0, x, mid, z, depth - 1) && linked(scan, mid, z, c1, y, depth - 1)) return true;
  return false;
}

AxisAnalysis analyze_axis(const TwoBallScan& scan, const std::vector<double>& column_positions) {
  AxisAnalysis A;
  A.columns.reserve(column_positions.size());
  for (double c : column_positions) {
    throw_if_stopped("stick set");
    ColumnData col;
    col.column = c;
    col.arcs = scan.arcs(c);
    for (std::size_t k = 0; k < col.arcs.size(); ++k) col.node.push_back(A.uf.add());
    A.columns.push_back(std::move(col));
  }
  const std::size_t N = A.columns.size();
  for (std::size_t j = 0; j < N; ++j) {
    const auto& c0 = A.columns[j];
    const auto& c1 = A.columns[(j + 1) % N];
    double x1 = c1.column;
    if (x1 <= c0.column) x1 += two_pi;
    for (std::size_t x = 0; x < c0.arcs.size(); ++x)
      for (std::size_t y = 0; y < c1.arcs.size(); ++y)
        if (arcs_overlap(c0.arcs[x], c1.arcs[y]) || linked(scan, c0.column, c0.arcs[x], x1, c1.arcs[y], 6))
          A.uf.join(c0.node[x], c1.node[y]);
  }
  return A;
}


std::pair<int, int> locate(const AxisAnalysis& A, double column, double along) {
  // nearest column
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < A.columns.size(); ++j) {
    double d = std::fabs(wrap(A.columns[j].column - column));
    d = std::min(d, two_pi - d);
    if (d < best_d) best_d = d, best = int(j);
  }
  if (best < 0) return {-1, -1};
  const auto& col = A.columns[std::size_t(best)];
  int arc = -1;
  double arc_d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < col.arcs.size(); ++k) {
    const double d = arc_distance(col.arcs[k], along);
    if (d < arc_d) arc_d = d, arc = int(k);
  }
  if (arc < 0 || arc_d > 1e-3) return {-1, -1};
  return {best, arc};
}


double column_extent(const TwoBallScan& scan, AxisAnalysis& A, int root) {
  const std::size_t N = A.columns.size();
  std::vector<char> in(N, 0);
  for (std::size_t j = 0; j < N; ++j)
    for (int node : A.columns[j].node)
      if (A.uf.find(node) == root) in[j] = 1;
  if (std::all_of(in.begin(), in.end(), [](char c) { return c != 0; })) return two_pi;
  std::vector<Arc> pieces;
  for (std::size_t j = 0; j < N; ++j) {
    if (!in[j]) continue;
    // a run of columns: extend both ends
    const std::size_t prev = (j + N - 1) % N, next = (j + 1) % N;
    double lo = A.columns[j].column, hi = A.columns[j].column;
    auto refine = [&](std::size_t inside, std::size_t outside) {
      std::vector<Arc> mine;
      for (std::size_t k = 0; k < A.columns[inside].arcs.size(); ++k)
        if (A.uf.find(A.columns[inside].node[k]) == root) mine.push_back(A.columns[inside].arcs[k]);
      double a = A.columns[inside].column, b = A.columns[outside].column;
      if (outside == (inside + 1) % N && b < a) b += two_pi;
      if (outside == (inside + N - 1) % N && b > a) b -= two_pi;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (a + b);
        bool hit = false;
        for (const auto& arc : scan.arcs(wrap(mid)))
          for (const auto& m : mine)
            if (arcs_overlap(arc, m)) hit = true;
        (hit ? a : b) = mid;
      }
      return a;
    };
    if (!in[prev]) lo = refine(j, prev);
    if (!in[next]) hi = refine(j, next);
    if (hi < lo) hi += two_pi;
    pieces.push_back(Arc{wrap(lo), wrap(lo) + (hi - lo)});
  }
  return covering_length(pieces);
}

}  // namespace abu::stick_detail
