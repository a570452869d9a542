// model.md §11: path radius, equations of motion and linearization on an unround race.
#include "abu/model/unround_race.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "abu/model/friction.hpp"

namespace abu {

bool RaceShape::round() const {
  for (const auto& list : balls)
    for (const auto& h : list)
      if (h.amplitude != 0.0) return false;
  return true;
}

int RaceShape::max_order() const {
  int k = 0;
  for (const auto& list : balls)
    for (const auto& h : list)
      if (h.amplitude != 0.0) k = std::max(k, h.order);
  return k;
}

double unround_lambda(const ParamsN& p, const RaceShape& race) {
  double lambda = 0;
  const double w2 = p.omega * p.omega;
  const double dyn = std::hypot(p.rotor.stiffness - w2 * p.total_mass(), p.rotor.damping * p.omega);
  for (std::size_t i = 0; i < race.balls.size() && i < p.balls.size(); ++i)
    for (const auto& h : race.balls[i])
      lambda = std::max(lambda, h.order * h.order * h.amplitude * dyn / (p.balls[i].mass * w2));
  return lambda;
}

RaceShape scaled_race(const RaceShape& race, double factor) {
  RaceShape out = race;
  for (auto& list : out.balls)
    for (auto& h : list) h.amplitude *= factor;
  return out;
}

template <class T>
PathPoint<T> path_point(const RaceHarmonics& h, T l, T beta) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  // The offset circle E (order 1, exact): x = beta - phi, S = sqrt(l^2 - d^2 sin^2 x),
  // E = d cos x + S, E' = -d sin x - d^2 sin x cos x / S,
  // E'' = -d cos x - d^2 cos 2x / S - d^4 sin^2 x cos^2 x / S^3 (model.md §11.1).
  T e0 = l, e1 = 0, e2 = 0;
  // The product factor H = 1 + sum_{k >= 2} eps_k cos(k beta - phi_k) and its derivatives.
  T h0 = 1, h1 = 0, h2 = 0;
  for (const auto& harmonic : h) {
    if (harmonic.amplitude == 0.0) continue;
    const T eps = T(harmonic.amplitude);
    if (harmonic.order == 1) {
      const T d = l * eps;
      const T x = beta - T(harmonic.phase);
      const T sx = sin(x), cx = cos(x);
      const T S = sqrt(l * l - d * d * sx * sx);
      e0 = d * cx + S;
      e1 = -d * sx - d * d * sx * cx / S;
      e2 = -d * cx - d * d * (cx * cx - sx * sx) / S - d * d * d * d * sx * sx * cx * cx / (S * S * S);
    } else {
      const T k = T(harmonic.order);
      const T arg = k * beta - T(harmonic.phase);
      const T c = cos(arg), s = sin(arg);
      h0 += eps * c;
      h1 -= eps * k * s;
      h2 -= eps * k * k * c;
    }
  }
  PathPoint<T> pt;
  pt.ell = e0 * h0;
  pt.d1 = e1 * h0 + e0 * h1;
  pt.d2 = e2 * h0 + T(2) * e1 * h1 + e0 * h2;
  const T sb = sin(beta), cb = cos(beta);
  pt.u = pt.d1 * cb - pt.ell * sb;
  pt.v = pt.d1 * sb + pt.ell * cb;
  pt.du = (pt.d2 - pt.ell) * cb - T(2) * pt.d1 * sb;
  pt.dv = (pt.d2 - pt.ell) * sb + T(2) * pt.d1 * cb;
  pt.speed = sqrt(pt.ell * pt.ell + pt.d1 * pt.d1);
  pt.dspeed = pt.d1 * (pt.ell + pt.d2) / pt.speed;
  return pt;
}
template PathPoint<double> path_point<double>(const RaceHarmonics&, double, double);
template PathPoint<long double> path_point<long double>(const RaceHarmonics&, long double, long double);

RaceHarmonics surface_to_path(const RaceHarmonics& surface, double l, double r) {
  RaceHarmonics out = surface;
  for (auto& h : out) h.amplitude *= (l + r) / l;
  return out;
}

std::optional<std::string> path_violation(const RaceHarmonics& h, double l, double r) {
  int kmax = 1;
  for (const auto& harmonic : h) {
    if (harmonic.order == 1 && !(harmonic.amplitude < 1.0))
      return fmt::format("the race centre's offset l eps_1 = {} m must be below the path radius l = {} m "
                         "(eps_1 < 1, got {})",
                         l * harmonic.amplitude, l, harmonic.amplitude);
    kmax = std::max(kmax, harmonic.order);
  }
  const int samples = 4096 * kmax;
  double min_ell = HUGE_VAL, min_bend = HUGE_VAL, at_ell = 0, at_bend = 0;
  for (int j = 0; j < samples; ++j) {
    const long double beta = 2 * std::numbers::pi_v<long double> * j / samples;
    const auto pt = path_point<long double>(h, l, beta);
    if (double(pt.ell) < min_ell) min_ell = double(pt.ell), at_ell = double(beta);
    // Signed curvature of the centre path (positive: turning about the axis); the wall,
    // its parallel at distance r outwards, is smooth iff 1 + r kappa > 0 (model.md §11.1).
    const long double kappa = (pt.ell * pt.ell + 2 * pt.d1 * pt.d1 - pt.ell * pt.d2) / (pt.speed * pt.speed * pt.speed);
    const double bend = double(1 + r * kappa);
    if (bend < min_bend) min_bend = bend, at_bend = double(beta);
  }
  if (!(min_ell > 0))
    return fmt::format("the path radius l(beta) crosses zero (l({:.4g} rad) = {:.4g} m): the harmonics are too large "
                       "for l = {} m",
                       at_ell, min_ell, l);
  if (!(min_bend > 0))
    return fmt::format("the race is curved more tightly than a ball of radius r = {} m can follow (at beta = {:.4g} "
                       "rad the race wall's radius of curvature is below r: 1 + r kappa = {:.4g} <= 0, model.md "
                       "§11.1)",
                       r, at_bend, min_bend);
  return std::nullopt;
}

namespace {
using L = long double;
using CoordL = Coordinates<L, any_balls>;

std::array<PathPoint<L>, max_balls> path_points(const LongParamsN& p, const RaceShape& race, const CoordL& s) {
  std::array<PathPoint<L>, max_balls> pts{};
  static const RaceHarmonics round;
  for (int i = 0; i < p.n_balls(); ++i) {
    const auto k = std::size_t(i);
    pts[k] = path_point<L>(k < race.balls.size() ? race.balls[k] : round, p.balls[k].race_radius, s(2 + i));
  }
  return pts;
}
}  // namespace

DofMatrix<L, any_balls> unround_mass_matrix(const LongParamsN& p, const RaceShape& race, const CoordL& s) {
  const int n = p.n_balls();
  const auto pts = path_points(p, race, s);
  DofMatrix<L, any_balls> A = DofMatrix<L, any_balls>::Zero(n + 2, n + 2);
  const L M = p.total_mass();
  A(0, 0) = M;
  A(1, 1) = M;
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const auto& pt = pts[std::size_t(i)];
    A(0, 2 + i) = A(2 + i, 0) = b.mass * pt.u;
    A(1, 2 + i) = A(2 + i, 1) = b.mass * pt.v;
    A(2 + i, 2 + i) = b.inertia_factor * b.mass * pt.speed * pt.speed;
  }
  return A;
}

Coordinates<L, any_balls> unround_generalized_forces(const LongParamsN& p, const RaceShape& race,
                                                     const State<L, any_balls>& x) {
  const int n = p.n_balls();
  const CoordL s = x.head(n + 2);
  const auto pts = path_points(p, race, s);
  const L w = p.omega, w2 = w * w, M = p.total_mass();
  const L q1 = x(0), q2 = x(1), dq1 = x(n + 2), dq2 = x(n + 3);
  const auto& r = p.rotor;
  CoordL b = CoordL::Zero(n + 2);
  b(0) = w2 * r.unbalance + M * (2 * w * dq2 + w2 * q1) - r.damping * (dq1 - w * q2) - r.stiffness * q1;
  b(1) = M * (-2 * w * dq1 + w2 * q2) - r.damping * (dq2 + w * q1) - r.stiffness * q2;
  for (int i = 0; i < n; ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const auto& pt = pts[std::size_t(i)];
    const L m = ball.mass, db = x(n + 4 + i);
    b(0) += m * (w2 * pt.ell * std::cos(s(2 + i)) - pt.du * db * db + 2 * w * pt.v * db);
    b(1) += m * (w2 * pt.ell * std::sin(s(2 + i)) - pt.dv * db * db - 2 * w * pt.u * db);
    // Friction at the equivalent rate nu = s' beta' / l (§11.2), generalized force s' F.
    const L F = friction_force(p, i, pt.speed * db / ball.race_radius);
    b(2 + i) = pt.speed * F + m * w2 * pt.ell * pt.d1 -
               m * (pt.u * (-2 * w * dq2 - w2 * q1) + pt.v * (2 * w * dq1 - w2 * q2)) -
               ball.inertia_factor * m * pt.speed * pt.dspeed * db * db;
  }
  return b;
}

Linearization<L, any_balls> unround_linearization(const LongParamsN& p, const RaceShape& race, const CoordL& s) {
  const int n = p.n_balls();
  const auto pts = path_points(p, race, s);
  const L w = p.omega, w2 = w * w, M = p.total_mass();
  const auto& r = p.rotor;
  const L K = r.stiffness - w2 * M, C = r.damping * w;
  Linearization<L, any_balls> lin;
  lin.mass = unround_mass_matrix(p, race, s);
  auto& D = lin.damping;
  auto& E = lin.stiffness;
  D = DofMatrix<L, any_balls>::Zero(n + 2, n + 2);
  E = DofMatrix<L, any_balls>::Zero(n + 2, n + 2);
  // §11.5 with the signs of D = -db/ds', E = -db/ds.
  E(0, 0) = K, E(0, 1) = -C, E(1, 0) = C, E(1, 1) = K;
  D(0, 0) = r.damping, D(0, 1) = -2 * M * w, D(1, 0) = 2 * M * w, D(1, 1) = r.damping;
  for (int i = 0; i < n; ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    const auto& pt = pts[std::size_t(i)];
    const L m = ball.mass;
    E(0, 2 + i) = E(2 + i, 0) = -w2 * m * pt.u;
    E(1, 2 + i) = E(2 + i, 1) = -w2 * m * pt.v;
    E(2 + i, 2 + i) = -w2 * m * (pt.du * s(0) + pt.dv * s(1) + pt.d1 * pt.d1 + pt.ell * pt.d2);
    D(0, 2 + i) = -2 * w * m * pt.v;
    D(1, 2 + i) = 2 * w * m * pt.u;
    D(2 + i, 0) = 2 * w * m * pt.v;
    D(2 + i, 1) = -2 * w * m * pt.u;
    D(2 + i, 2 + i) = -pt.speed * pt.speed / ball.race_radius * friction_slope(p, i, L(0));
  }
  return lin;
}

std::string describe_race(const RaceShape& race, std::string_view prefix) {
  std::string out;
  for (std::size_t i = 0; i < race.balls.size(); ++i) {
    out += fmt::format("{}race, ball {} (path radius l_i (1 + ...), model.md §11.1):", prefix, i + 1);
    if (race.balls[i].empty()) out += " round";
    for (const auto& h : race.balls[i]) out += fmt::format(" order {} amplitude {} phase {} rad;", h.order, h.amplitude, h.phase);
    out += "\n";
  }
  return out;
}

}  // namespace abu
