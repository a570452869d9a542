// The stick set of set-valued Coulomb friction and its worst residual vibration
// (model.md §14). See the header for the method.
#include "abu/equilibria/stick_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <deque>
#include <limits>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"

namespace abu {

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;
using cplx = std::complex<double>;

double wrap(double b) {
  double w = std::fmod(b, two_pi);
  if (w < 0) w += two_pi;
  if (w >= two_pi) w = 0.0;
  return w;
}

// The model of (14.1) in the form the column scans need: q = G W(beta), G = omega^2/(K+iC).
struct StickModel {
  cplx G;
  double U = 0.0;
  std::vector<double> a;      // a_i = m_i l_i
  std::vector<double> bound;  // mu_i l_i [m]
  int n = 0;

  explicit StickModel(const ParamsN& p) {
    n = p.n_balls();
    const double M = p.total_mass();
    const double K = p.rotor.stiffness - p.omega * p.omega * M;
    const double C = p.rotor.damping * p.omega;
    if (K == 0.0 && C == 0.0)
      throw NotSupportedError("stick set: K = C = 0 (c = 0 at omega = omega_n): q(beta) is not defined (model.md §14.2)");
    G = p.omega * p.omega / cplx(K, C);
    U = p.rotor.unbalance;
    for (int i = 0; i < n; ++i) {
      const auto& b = p.balls[std::size_t(i)];
      if (!(b.mu > 0.0))
        throw NotSupportedError(fmt::format(
            "stick set: mu{} = {} : coulomb-set needs mu > 0 for every ball (with mu = 0 the ball sticks only on "
            "the line of q, a set without area, model.md §14.2)",
            i + 1, b.mu));
      a.push_back(b.mass * b.race_radius);
      bound.push_back(b.mu * b.race_radius);
    }
  }
  cplx W(const double* beta) const {
    cplx w(U, 0.0);
    for (int i = 0; i < n; ++i) w += a[std::size_t(i)] * std::polar(1.0, beta[i]);
    return w;
  }
  cplx q(const double* beta) const { return G * W(beta); }
  // s_i = (q1 sin b_i - q2 cos b_i) / (mu_i l_i)
  double s(const cplx& q, int i, double beta_i) const {
    return (q.real() * std::sin(beta_i) - q.imag() * std::cos(beta_i)) / bound[std::size_t(i)];
  }
  // max_i |s_i| - 1: <= 0 inside E.
  double excess(const double* beta) const {
    const cplx qq = q(beta);
    double m = 0.0;
    for (int i = 0; i < n; ++i) m = std::max(m, std::abs(s(qq, i, beta[i])));
    return m - 1.0;
  }
};

// ---------------------------------------------------------------- two balls -------------

struct Arc {
  double lo = 0.0, hi = 0.0;  // hi in (lo, lo + 2 pi]; full circle: hi - lo = 2 pi
  double length() const { return hi - lo; }
};

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

// The two-ball scan with the roles of the angles given by `axis`: axis 0 scans columns of
// constant beta_1 and intervals in beta_2, axis 1 the transpose.
class TwoBallScan {
 public:
  TwoBallScan(const StickModel& m, int axis, std::vector<double> samples)
      : m_(m), axis_(axis), samples_(std::move(samples)) {}

  double excess(double column, double along) const {
    double b[2];
    b[axis_] = column;
    b[1 - axis_] = along;
    return m_.excess(b);
  }

  // The arcs of E on one column, ends by bisection to rounding.
  std::vector<Arc> arcs(double column) const {
    const std::size_t K = samples_.size();
    std::vector<char> inside(K);
    bool any_in = false, any_out = false;
    for (std::size_t k = 0; k < K; ++k) {
      inside[k] = excess(column, samples_[k]) <= 0.0;
      (inside[k] ? any_in : any_out) = true;
    }
    std::vector<Arc> out;
    if (!any_in) return out;
    if (!any_out) return {Arc{0.0, two_pi}};
    // Walk from the first outside sample around the circle.
    std::size_t start = 0;
    while (inside[start]) ++start;
    double lo = 0.0;
    for (std::size_t step = 1; step <= K; ++step) {
      const std::size_t k0 = (start + step - 1) % K, k1 = (start + step) % K;
      if (inside[k0] == inside[k1]) continue;
      double x0 = samples_[k0], x1 = samples_[k1];
      if (x1 < x0) x1 += two_pi;
      const double root = bisect(column, x0, x1, bool(inside[k0]));
      if (inside[k1]) {
        lo = root;
      } else {
        double hi = root;
        while (hi < lo) hi += two_pi;
        const double l0 = wrap(lo);
        out.push_back(Arc{l0, l0 + (hi - lo)});
      }
    }
    return out;
  }

  // The arcs of E on one column inside the window [a, b] (b - a < 2 pi), from `count`
  // samples there: the dense look at a thin tip that the global samples step over. Arcs
  // cut by the window ends end there.
  std::vector<Arc> arcs_in(double column, double a, double b, int count) const {
    std::vector<Arc> out;
    bool in_prev = false;
    double lo = a;
    for (int k = 0; k <= count; ++k) {
      const double x = a + (b - a) * k / count;
      const bool in = excess(column, wrap(x)) <= 0.0;
      if (in && !in_prev) lo = x;
      if (!in && in_prev) out.push_back(Arc{wrap(lo), wrap(lo) + (x - lo)});
      in_prev = in;
    }
    if (in_prev) out.push_back(Arc{wrap(lo), wrap(lo) + (b - lo)});
    return out;
  }

  // Largest |W|^2 on the segment {column} x arc: |W|^2 = |A|^2 + a^2 + 2 a |A| cos(b - arg A).
  std::pair<double, double> max_w2(double column, const Arc& arc) const {
    const double a_col = m_.a[std::size_t(axis_)], a_along = m_.a[std::size_t(1 - axis_)];
    const cplx A = m_.U + a_col * std::polar(1.0, column);
    const double phase = std::arg(A);
    auto value = [&](double b) { return std::norm(A + a_along * std::polar(1.0, b)); };
    if (arc_contains(arc, wrap(phase))) return {value(phase), wrap(phase)};
    const double vl = value(arc.lo), vh = value(arc.hi);
    return vl >= vh ? std::pair{vl, wrap(arc.lo)} : std::pair{vh, wrap(arc.hi)};
  }

  // Integral of |q| over {column} x arc: composite Gauss-Legendre.
  double q_abs_integral(double column, const Arc& arc) const {
    static constexpr double x[5] = {0.0, 0.5384693101056831, -0.5384693101056831, 0.9061798459386640,
                                    -0.9061798459386640};
    static constexpr double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                    0.2369268850561891, 0.2369268850561891};
    const int pieces = std::max(1, int(std::ceil(arc.length() / 0.02)));
    const double h = arc.length() / pieces;
    double sum = 0.0;
    for (int k = 0; k < pieces; ++k) {
      const double mid = arc.lo + (k + 0.5) * h;
      for (int g = 0; g < 5; ++g) {
        double b[2];
        b[axis_] = column;
        b[1 - axis_] = mid + 0.5 * h * x[g];
        sum += w[g] * 0.5 * h * std::abs(m_.q(b));
      }
    }
    return sum;
  }

 private:
  double bisect(double column, double x_in_or_out, double x1, bool first_inside) const {
    double a = x_in_or_out, b = x1;
    for (int it = 0; it < 200 && b - a > 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(b));
         ++it) {
      const double mid = 0.5 * (a + b);
      const bool in = excess(column, mid) <= 0.0;
      (in == first_inside ? a : b) = mid;
    }
    return first_inside ? a : b;  // the inside end: the arc is closed
  }

  const StickModel& m_;
  int axis_;
  std::vector<double> samples_;
};

// Jacobian of s = (s_1, s_2) with respect to beta at a point, by central differences.
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

// Sample positions along one angle: a uniform grid plus dense windows around the given
// centres (the seeds), where E may be a small island (model.md §14.3).
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

struct UnionFind {
  std::vector<int> parent;
  int add() {
    parent.push_back(int(parent.size()));
    return parent.back();
  }
  int find(int x) {
    while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
    return x;
  }
  void join(int x, int y) { parent[std::size_t(find(x))] = find(y); }
};

// Length of the shortest arc of the circle that holds every given arc.
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

struct ColumnData {
  double column = 0.0;
  std::vector<Arc> arcs;
  std::vector<int> node;  // union-find node per arc
};

// One axis's column analysis: columns, arcs, component labels.
struct AxisAnalysis {
  std::vector<ColumnData> columns;
  UnionFind uf;
};

// Two arcs of neighbouring columns that do not overlap can still be one piece of E: a thin
// slanted band (the tips of the small islands, model.md §14.3) moves further between the
// columns than it is long. They are linked if some arc of the middle column is linked to
// both, down to `depth` halvings of the column step.
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

// The (column index, arc index) holding the point (column, along), or {-1, -1}.
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

// Spread of one component along the column axis, the column ends refined by bisection on
// "a column there has an arc overlapping the component's arcs at the neighbouring column".
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

// ---- boundary tracing: level curves s_i = sign, kept where the other constraint holds.
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
  // The whole level curve through `start` (unwrapped coordinates), closed if it returned.
  std::vector<std::array<double, 2>> trace(int i, double sign, std::array<double, 2> start, bool& closed) const {
    std::vector<std::array<double, 2>> pts{start};
    double b[2] = {start[0], start[1]};
    closed = false;
    const int max_steps = int(40.0 * two_pi / step) + 1000;
    std::array<double, 2> dir{};
    for (int k = 0; k < max_steps; ++k) {
      const auto g = gradient(i, b);
      const double gn = std::hypot(g[0], g[1]);
      if (!(gn > 0)) break;
      std::array<double, 2> t{-g[1] / gn, g[0] / gn};
      if (k > 0 && t[0] * dir[0] + t[1] * dir[1] < 0) t = {-t[0], -t[1]};
      dir = t;
      double nb[2] = {b[0] + step * t[0], b[1] + step * t[1]};
      if (!project(i, sign, nb)) break;
      b[0] = nb[0];
      b[1] = nb[1];
      pts.push_back({b[0], b[1]});
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
  const int cells = std::max(1, int(two_pi / cell));
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
    bool closed = false;
    const auto pts = tr.trace(st.ball, st.sign, {b[0], b[1]}, closed);
    for (const auto& p : pts) seen[std::size_t(curve)][key(p[0], p[1])] = 1;
    // keep the runs where the other constraint holds
    const int other = 1 - st.ball;
    auto inside = [&](const std::array<double, 2>& p) {
      double bb[2] = {p[0], p[1]};
      return std::fabs(tr.value(other, bb)) <= 1.0 + 1e-12;
    };
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

StickSet two_ball_set(const StickModel& m, const StickSetOptions& o,
                      std::vector<StickSeed> seeds) {
  StickSet S;
  S.n_balls = 2;
  S.seeds = std::move(seeds);
  // island widths at the seeds, from the Jacobian of s (model.md §14.3)
  std::vector<std::pair<double, double>> win1, win2;
  double smallest_width = two_pi / o.columns;
  for (const auto& sd : S.seeds) {
    const double b[2] = {sd.beta[0], sd.beta[1]};
    const auto J = s_jacobian(m, b);
    const double row = std::max(std::fabs(J[0][0]) + std::fabs(J[0][1]), std::fabs(J[1][0]) + std::fabs(J[1][1]));
    const double width = row > 0 ? std::min(1.0, 1.0 / row) : 1.0;
    smallest_width = std::min(smallest_width, width / 24.0);
    win1.push_back({sd.beta[0], width});
    win2.push_back({sd.beta[1], width});
  }
  const std::vector<double> cols1 = sample_positions(o.columns, win1);
  const std::vector<double> samp2 = sample_positions(o.samples, win2);
  const TwoBallScan scan1(m, 0, samp2);
  AxisAnalysis A = analyze_axis(scan1, cols1);
  S.resolution = smallest_width;

  // --- area and integral of |q|: adaptive Simpson over beta_1 on each panel.
  auto column_values = [&](double c) {
    std::array<double, 2> v{0.0, 0.0};
    for (const auto& arc : scan1.arcs(wrap(c))) {
      v[0] += arc.length();
      v[1] += scan1.q_abs_integral(wrap(c), arc);
    }
    return v;
  };
  struct Panel {
    double a, b;
    std::array<double, 2> fa, fm, fb;
    int depth;
  };
  double area = 0.0, qint = 0.0;
  std::vector<std::array<double, 2>> at_column(A.columns.size());
  for (std::size_t j = 0; j < A.columns.size(); ++j) {
    double L = 0.0;
    for (const auto& arc : A.columns[j].arcs) L += arc.length();
    at_column[j] = {L, 0.0};
    for (const auto& arc : A.columns[j].arcs) at_column[j][1] += scan1.q_abs_integral(A.columns[j].column, arc);
  }
  for (std::size_t j = 0; j < A.columns.size(); ++j) {
    throw_if_stopped("stick set");
    const std::size_t jn = (j + 1) % A.columns.size();
    const double a = A.columns[j].column;
    const double b = jn == 0 ? two_pi : A.columns[jn].column;
    std::vector<Panel> stack{{a, b, at_column[j], column_values(0.5 * (a + b)), at_column[jn], 0}};
    while (!stack.empty()) {
      const Panel P = stack.back();
      stack.pop_back();
      const double h = P.b - P.a;
      const double l = P.a + 0.25 * h, r = P.a + 0.75 * h;
      const auto fl = column_values(l), fr = column_values(r);
      std::array<double, 2> coarse{}, fine{};
      for (int k = 0; k < 2; ++k) {
        coarse[std::size_t(k)] = h / 6 * (P.fa[std::size_t(k)] + 4 * P.fm[std::size_t(k)] + P.fb[std::size_t(k)]);
        fine[std::size_t(k)] = h / 12 *
                               (P.fa[std::size_t(k)] + 4 * fl[std::size_t(k)] + 2 * P.fm[std::size_t(k)] +
                                4 * fr[std::size_t(k)] + P.fb[std::size_t(k)]);
      }
      const double err = std::fabs(fine[0] - coarse[0]);
      if (err <= 15.0 * o.area_tolerance * h || P.depth >= 24) {
        area += fine[0] + (fine[0] - coarse[0]) / 15.0;
        qint += fine[1] + (fine[1] - coarse[1]) / 15.0;
      } else {
        stack.push_back({P.a, P.a + 0.5 * h, P.fa, fl, P.fm, P.depth + 1});
        stack.push_back({P.a + 0.5 * h, P.b, P.fm, fr, P.fb, P.depth + 1});
      }
    }
  }
  S.area = std::clamp(area, 0.0, two_pi * two_pi);
  S.area_fraction = S.area / (two_pi * two_pi);

  // --- components
  std::unordered_map<int, int> comp_of_root;
  for (auto& col : A.columns)
    for (int node : col.node) {
      const int r = A.uf.find(node);
      if (!comp_of_root.count(r)) {
        comp_of_root[r] = int(S.components.size());
        S.components.emplace_back();
      }
    }
  std::vector<int> root_of_comp(S.components.size());
  for (const auto& [r, c] : comp_of_root) root_of_comp[std::size_t(c)] = r;
  S.whole_torus = std::all_of(A.columns.begin(), A.columns.end(), [](const ColumnData& c) {
    return c.arcs.size() == 1 && c.arcs[0].length() >= two_pi;
  });

  // per-component area and |q| integral (trapezoid on the columns; the totals above are
  // the accurate ones, these split them), best column for the maximum
  struct Best {
    double w2 = -1.0;
    int column = -1, arc = -1;
    double along = 0.0;
  };
  std::vector<Best> best(S.components.size());
  std::vector<double> comp_area(S.components.size(), 0.0), comp_q(S.components.size(), 0.0);
  const std::size_t N = A.columns.size();
  for (std::size_t j = 0; j < N; ++j) {
    const std::size_t jn = (j + 1) % N, jp = (j + N - 1) % N;
    double dnext = (jn == 0 ? two_pi : A.columns[jn].column) - A.columns[j].column;
    double dprev = A.columns[j].column - (j == 0 ? A.columns[jp].column - two_pi : A.columns[jp].column);
    const double weight = 0.5 * (dnext + dprev);
    const auto& col = A.columns[j];
    for (std::size_t k = 0; k < col.arcs.size(); ++k) {
      const int c = comp_of_root[A.uf.find(col.node[k])];
      comp_area[std::size_t(c)] += weight * col.arcs[k].length();
      comp_q[std::size_t(c)] += weight * scan1.q_abs_integral(col.column, col.arcs[k]);
      const auto [w2, along] = scan1.max_w2(col.column, col.arcs[k]);
      if (w2 > best[std::size_t(c)].w2) best[std::size_t(c)] = {w2, int(j), int(k), along};
    }
  }
  const double trapezoid_area = std::accumulate(comp_area.begin(), comp_area.end(), 0.0);
  const double trapezoid_q = std::accumulate(comp_q.begin(), comp_q.end(), 0.0);

  // refine each component's maximum over beta_1 by golden section
  const double gabs = std::abs(m.G);
  for (std::size_t c = 0; c < S.components.size(); ++c) {
    throw_if_stopped("stick set");
    auto& comp = S.components[c];
    const Best b0 = best[c];
    const auto& col = A.columns[std::size_t(b0.column)];
    const Arc ref = col.arcs[std::size_t(b0.arc)];
    const std::size_t j = std::size_t(b0.column);
    const double lo = j == 0 ? A.columns[N - 1].column - two_pi : A.columns[j - 1].column;
    const double hi = j + 1 == N ? two_pi + A.columns[0].column : A.columns[j + 1].column;
    double best_w2 = b0.w2, best_c = col.column, best_along = b0.along;
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
      double w = 4.0 * std::max(two_pi / o.samples, S.resolution);
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
    comp.q_abs_max = gabs * std::sqrt(std::max(0.0, best_w2));
    comp.beta_at_max = {best_c, best_along};
    const double scale_a = trapezoid_area > 0 ? S.area / trapezoid_area : 0.0;
    const double scale_q = trapezoid_q > 0 ? qint / trapezoid_q : 0.0;
    comp.area = comp_area[c] * scale_a;
    comp.q_abs_integral = comp_q[c] * scale_q;
  }

  // seeds in components
  for (std::size_t k = 0; k < S.seeds.size(); ++k) {
    auto& sd = S.seeds[k];
    const auto [j, arc] = locate(A, sd.beta[0], sd.beta[1]);
    if (j < 0) continue;
    sd.component = comp_of_root[A.uf.find(A.columns[std::size_t(j)].node[std::size_t(arc)])];
    auto& comp = S.components[std::size_t(sd.component)];
    comp.seeds.push_back(int(k));
    if (sd.family == "balanced") comp.balanced_points.push_back(int(k));
  }

  // spreads of the balanced components: beta_1 from these columns, beta_2 from the transposed scan
  const TwoBallScan scan2(m, 1, sample_positions(o.samples, win1));
  AxisAnalysis B = analyze_axis(scan2, sample_positions(o.columns, win2));
  for (std::size_t c = 0; c < S.components.size(); ++c) {
    auto& comp = S.components[c];
    if (comp.balanced_points.empty()) continue;
    throw_if_stopped("stick set");
    const double s1 = column_extent(scan1, A, root_of_comp[c]);
    const auto& sd = S.seeds[std::size_t(comp.balanced_points.front())];
    const auto [j, arc] = locate(B, sd.beta[1], sd.beta[0]);
    double s2 = 0.0;
    if (j >= 0) s2 = column_extent(scan2, B, B.uf.find(B.columns[std::size_t(j)].node[std::size_t(arc)]));
    comp.spread = {s1, s2};
  }

  // totals
  S.mean_q_abs = S.area > 0 ? qint / S.area : 0.0;
  S.spread = {0.0, 0.0};
  for (const auto& comp : S.components) {
    if (comp.q_abs_max > S.worst_q_abs_any) S.worst_q_abs_any = comp.q_abs_max, S.worst_beta_any = comp.beta_at_max;
    if (comp.balanced_points.empty()) continue;
    S.balanced_exists = true;
    if (comp.q_abs_max > S.worst_q_abs) S.worst_q_abs = comp.q_abs_max, S.worst_beta = comp.beta_at_max;
    for (int i = 0; i < 2; ++i)
      S.spread[std::size_t(i)] = std::max(S.spread[std::size_t(i)], comp.spread[std::size_t(i)]);
  }
  for (auto& comp : S.components) {
    // a component wraps if its columns cover the whole circle in beta_1 with one arc each
    // reaching around in beta_2, or it covers every column
    comp.wraps = comp.area >= two_pi * two_pi * (1 - 1e-12);
  }
  if (o.trace) S.boundary = trace_boundary(m, A, std::min(0.01, 0.25 * S.resolution * 24.0 / 4.0));
  double mx = 0.0;
  for (const auto& col : A.columns)
    for (double x : samp2) {
      const double b[2] = {col.column, x};
      mx = std::max(mx, m.excess(b) + 1.0);
    }
  S.max_abs_s = mx;
  if (!S.balanced_exists) S.status = Status{Outcome::not_converged, "no balanced state in the stick set"};
  return S;
}

// ---------------------------------------------------------------- n >= 3: a grid ---------

StickSet sampled_set(const ParamsN& p, const StickModel& m, const StickSetOptions& o, std::vector<StickSeed> seeds) {
  StickSet S;
  const int n = m.n;
  S.n_balls = n;
  S.sampled = true;
  S.seeds = std::move(seeds);
  int G = int(std::floor(std::pow(double(o.grid_budget), 1.0 / n) + 1e-9));
  G = std::max(G, 4);
  S.grid_points_per_angle = G;
  S.resolution = two_pi / G;
  long total = 1;
  for (int i = 0; i < n; ++i) total *= G;
  std::vector<int> label(std::size_t(total), -2);  // -2 outside, -1 inside unlabelled
  std::vector<double> qabs(std::size_t(total), 0.0);
  
  std::vector<double> beta(static_cast<std::size_t>(n), 0.0);
  long inside_count = 0;
  double qsum = 0.0, mx = 0.0;
  for (long cell = 0; cell < total; ++cell) {
    if ((cell & 0xffff) == 0) throw_if_stopped("stick set");
    long r = cell;
    for (int i = 0; i < n; ++i) {
      beta[std::size_t(i)] = two_pi * double(r % G) / G;
      r /= G;
    }
    const double e = m.excess(beta.data());
    mx = std::max(mx, e + 1.0);
    if (e <= 0.0) {
      label[std::size_t(cell)] = -1;
      ++inside_count;
      qabs[std::size_t(cell)] = std::abs(m.q(beta.data()));
      qsum += qabs[std::size_t(cell)];
    }
  }
  (void)p;
  S.max_abs_s = mx;
  const double cell_volume = std::pow(S.resolution, n);
  S.area = double(inside_count) * cell_volume;
  S.area_fraction = double(inside_count) / double(total);
  S.whole_torus = inside_count == total;
  S.mean_q_abs = inside_count ? qsum / double(inside_count) : 0.0;
  // flood fill with the torus wrap in every angle
  std::vector<long> stride;
  for (long st = 1; int(stride.size()) < n; st *= G) stride.push_back(st);
  std::vector<std::vector<std::vector<char>>> proj;  // per component, per ball: occupied grid values
  for (long cell = 0; cell < total; ++cell) {
    if (label[std::size_t(cell)] != -1) continue;
    const int c = int(S.components.size());
    S.components.emplace_back();
    auto& comp = S.components.back();
    std::vector<std::vector<char>> occ(std::size_t(n), std::vector<char>(std::size_t(G), 0));
    std::deque<long> queue{cell};
    label[std::size_t(cell)] = c;
    long count = 0;
    double best = -1.0;
    long best_cell = cell;
    while (!queue.empty()) {
      const long x = queue.front();
      queue.pop_front();
      ++count;
      comp.q_abs_integral += qabs[std::size_t(x)] * cell_volume;
      if (qabs[std::size_t(x)] > best) best = qabs[std::size_t(x)], best_cell = x;
      for (int i = 0; i < n; ++i) {
        const long coord = (x / stride[std::size_t(i)]) % G;
        occ[std::size_t(i)][std::size_t(coord)] = 1;
        for (int d : {-1, 1}) {
          const long nc = (coord + d + G) % G;
          const long y = x + (nc - coord) * stride[std::size_t(i)];
          if (label[std::size_t(y)] == -1) {
            label[std::size_t(y)] = c;
            queue.push_back(y);
          }
        }
      }
    }
    comp.area = double(count) * cell_volume;
    comp.q_abs_max = best;
    comp.beta_at_max.resize(std::size_t(n));
    for (int i = 0; i < n; ++i)
      comp.beta_at_max[std::size_t(i)] = two_pi * double((best_cell / stride[std::size_t(i)]) % G) / G;
    comp.spread.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) {
      // shortest covering arc of the occupied grid values (each value stands for its cell)
      const auto& v = occ[std::size_t(i)];
      int gap = 0, run = 0, first_run = -1;
      for (int k = 0; k < 2 * G; ++k) {
        if (!v[std::size_t(k % G)]) {
          ++run;
        } else {
          if (first_run < 0) first_run = run;
          gap = std::max(gap, run);
          run = 0;
        }
      }
      gap = std::max(gap, std::min(run, G));
      comp.spread[std::size_t(i)] = two_pi * double(G - gap) / G;
    }
  }
  // seeds: nearest grid point
  for (std::size_t k = 0; k < S.seeds.size(); ++k) {
    auto& sd = S.seeds[k];
    long cell = 0;
    for (int i = 0; i < n; ++i) {
      const long g = std::lround(wrap(sd.beta[std::size_t(i)]) / S.resolution) % G;
      cell += g * stride[std::size_t(i)];
    }
    const int c = label[std::size_t(cell)];
    if (c < 0) continue;
    sd.component = c;
    S.components[std::size_t(c)].seeds.push_back(int(k));
    if (sd.family == "balanced") S.components[std::size_t(c)].balanced_points.push_back(int(k));
  }
  S.spread.assign(std::size_t(n), 0.0);
  for (const auto& comp : S.components) {
    if (comp.q_abs_max > S.worst_q_abs_any) S.worst_q_abs_any = comp.q_abs_max, S.worst_beta_any = comp.beta_at_max;
    if (comp.balanced_points.empty()) continue;
    S.balanced_exists = true;
    if (comp.q_abs_max > S.worst_q_abs) S.worst_q_abs = comp.q_abs_max, S.worst_beta = comp.beta_at_max;
    for (int i = 0; i < n; ++i)
      S.spread[std::size_t(i)] = std::max(S.spread[std::size_t(i)], comp.spread[std::size_t(i)]);
  }
  const bool any_balanced_seed =
      std::any_of(S.seeds.begin(), S.seeds.end(), [](const StickSeed& s) { return s.family == "balanced"; });
  if (!S.balanced_exists)
    S.status = Status{Outcome::not_converged, any_balanced_seed
                                                  ? "the grid does not resolve the stick set around the balanced set"
                                                  : "no balanced state in the stick set"};
  return S;
}

}  // namespace

StickPoint stick_point(const ParamsN& p, const std::vector<double>& beta) {
  const StickModel m(p);
  const cplx q = m.q(beta.data());
  StickPoint out{q.real(), q.imag(), {}};
  for (int i = 0; i < m.n; ++i) out.s.push_back(m.s(q, i, beta[std::size_t(i)]));
  return out;
}

StickSet stick_set(const ParamsN& p, const StickSetOptions& options) {
  const StickModel m(p);
  // the smooth equilibria: tau = 0, always in E (model.md §14.2)
  std::vector<StickSeed> seeds;
  if (m.n == 2) {
    Params p2;
    p2.rotor = p.rotor;
    p2.omega = p.omega;
    p2.law = FrictionLaw::none;
    p2.balls = {p.balls[0], p.balls[1]};
    const EquilibriumSet set = closed_form_equilibria(p2);
    for (const auto& e : set.points()) {
      StickSeed sd;
      sd.family = std::string(to_string(e.family));
      sd.beta = {double(wrap_angle(e.position[2])), double(wrap_angle(e.position[3]))};
      sd.q_abs = std::abs(m.q(sd.beta.data()));
      seeds.push_back(sd);
    }
  } else {
    ParamsN pn = p;
    pn.law = FrictionLaw::none;
    const EquilibriumSetN set = find_equilibria(pn, BalancedSampling{});
    for (const auto& e : set.points()) {
      StickSeed sd;
      sd.family = std::string(to_string(e.family));
      for (int i = 0; i < m.n; ++i) sd.beta.push_back(double(wrap_angle(e.position[2 + i])));
      sd.q_abs = std::abs(m.q(sd.beta.data()));
      seeds.push_back(sd);
    }
  }
  StickSet S = m.n == 2 ? two_ball_set(m, options, std::move(seeds)) : sampled_set(p, m, options, std::move(seeds));
  const double bare = std::abs(m.G) * m.U;
  S.bare_rotor_q_abs = bare;
  return S;
}

}  // namespace abu
