// Internal to the equilibria module: the pieces of the stick-set computation of
// set-valued Coulomb friction (model.md §14) that its files share:
//   stick_set.cpp            the entry point: the smooth equilibria as seeds, one method per ball count
//   stick_set_columns.cpp    two balls: the column scan (the arcs in beta_2 of each beta_1 column) and
//                            the components, by linking the arcs of neighbouring columns
//   stick_set_two_balls.cpp  two balls: area and |q| integral (adaptive Simpson), the components'
//                            figures, spreads and totals
//   stick_set_maxima.cpp     two balls: refinement of a component's max |q| (golden section, corner
//                            Newton, local zoom; model.md §14.3)
//   stick_set_boundary.cpp   two balls: tracing the boundary curves s_i = +-1
//   stick_set_grid.cpp       n >= 3: a grid and a flood fill on the torus
#pragma once

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <utility>
#include <vector>

#include "abu/core/errors.hpp"
#include "abu/core/params.hpp"
#include "abu/equilibria/stick_set.hpp"
#include "abu/model/unround_race.hpp"

namespace abu::stick_detail {

inline constexpr double two_pi = 2.0 * std::numbers::pi;
using cplx = std::complex<double>;

inline double wrap(double b) {
  double w = std::fmod(b, two_pi);
  if (w < 0) w += two_pi;
  if (w >= two_pi) w = 0.0;
  return w;
}

// The model of (14.1) in the form the column scans need: q = G W(beta), G = omega^2/(K+iC);
// on an unround race (model.md (20.5)) W = U + sum m_i p_i(beta_i), p_i = l_i(beta) e^{i beta}.
struct StickModel {
  cplx G;
  double U = 0.0;
  std::vector<double> a;      // a_i = m_i l_i
  std::vector<double> bound;  // mu_i l_i [m]
  std::vector<double> mass, radius;  // m_i, l_i (the unround race's paths)
  const RaceShape* race = nullptr;   // unround centre paths; null: the round race of (14.1)
  int n = 0;

  explicit StickModel(const ParamsN& p, const RaceShape* unround = nullptr) {
    race = unround && !unround->round() ? unround : nullptr;
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
      mass.push_back(b.mass);
      radius.push_back(b.race_radius);
    }
  }
  const RaceHarmonics& path_of(int i) const {
    static const RaceHarmonics circle;
    return std::size_t(i) < race->balls.size() ? race->balls[std::size_t(i)] : circle;
  }
  cplx W(const double* beta) const {
    cplx w(U, 0.0);
    if (race) {
      for (int i = 0; i < n; ++i)
        w += mass[std::size_t(i)] * path_point<double>(path_of(i), radius[std::size_t(i)], beta[i]).ell *
             std::polar(1.0, beta[i]);
      return w;
    }
    for (int i = 0; i < n; ++i) w += a[std::size_t(i)] * std::polar(1.0, beta[i]);
    return w;
  }
  cplx q(const double* beta) const { return G * W(beta); }
  // s_i = (q1 sin b_i - q2 cos b_i) / (mu_i l_i); on an unround race (20.5)
  // s_i = -Re(conj(p_i') (p_i + q)) / (s_i' mu_i l_i), which is that on a circle.
  double s(const cplx& q, int i, double beta_i) const {
    if (race) {
      const PathPoint<double> pt = path_point<double>(path_of(i), radius[std::size_t(i)], beta_i);
      const cplx e = std::polar(1.0, beta_i), p = pt.ell * e, dp = cplx(pt.d1, pt.ell) * e;
      return -(std::conj(dp) * (p + q)).real() / (pt.speed * bound[std::size_t(i)]);
    }
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

bool arcs_overlap(const Arc& x, const Arc& y);

bool arc_contains(const Arc& x, double b);

// Distance from angle b to the arc (0 inside).
double arc_distance(const Arc& x, double b);

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
std::array<std::array<double, 2>, 2> s_jacobian(const StickModel& m, const double* beta);

// Sample positions along one angle: a uniform grid plus dense windows around the given
// centres (the seeds), where E may be a small island (model.md §14.3).
std::vector<double> sample_positions(int uniform, const std::vector<std::pair<double, double>>& windows);

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
double covering_length(std::vector<Arc> arcs);

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
bool linked(const TwoBallScan& scan, double c0, const Arc& x, double c1, const Arc& y, int depth);

// One axis's column analysis: the arcs of every column, linked into components.
AxisAnalysis analyze_axis(const TwoBallScan& scan, const std::vector<double>& column_positions);

// The (column index, arc index) holding the point (column, along), or {-1, -1}.
std::pair<int, int> locate(const AxisAnalysis& A, double column, double along);

// Spread of one component along the column axis, the column ends refined by bisection on
// "a column there has an arc overlapping the component's arcs at the neighbouring column".
double column_extent(const TwoBallScan& scan, AxisAnalysis& A, int root);

// The boundary of a two-ball set: the level curves s_i = +-1 through the column ends, kept
// where the other constraint holds (stick_set_boundary.cpp).
std::vector<StickBoundaryArc> trace_boundary(const StickModel& m, const AxisAnalysis& A, double step);

// A component's largest |W|^2 and where (column angle, along angle).
struct ComponentMaximum {
  double w2 = -1.0;
  double column = 0.0, along = 0.0;
};
// Refines the maximum of |W|^2 over the component holding arc `arc_index` of column `column` of
// A, from the best column value `start` (stick_set_maxima.cpp, model.md §14.3); `zoom` is
// the first window of the local zoom [rad].
ComponentMaximum refine_component_maximum(const StickModel& m, const TwoBallScan& scan, const AxisAnalysis& A,
                                          int column, int arc_index, ComponentMaximum start, double zoom);

// The set of two balls (stick_set_two_balls.cpp) and of n >= 3 (stick_set_grid.cpp).
StickSet two_ball_set(const StickModel& m, const StickSetOptions& o, std::vector<StickSeed> seeds);
StickSet sampled_set(const StickModel& m, const StickSetOptions& o, std::vector<StickSeed> seeds);

}  // namespace abu::stick_detail
