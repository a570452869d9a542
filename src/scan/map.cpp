#include "abu/scan/map.hpp"

#include <fmt/format.h>

#include <charconv>
#include <limits>
#include <cmath>
#include <string>
#include <vector>

#include "abu/core/errors.hpp"
#include "abu/model/friction.hpp"
#include "abu/linear/spectrum.hpp"

namespace abu {

double Axis::value(int i) const {
  if (i <= 0) return from;
  if (i >= count - 1) return to;
  const double t = double(i) / double(count - 1);
  return logarithmic ? std::exp(std::log(from) + t * (std::log(to) - std::log(from))) : from + t * (to - from);
}

Axis parse_axis(std::string_view spec, const Scene& scene, const std::string& origin) {
  const std::string text(spec);
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= spec.size(); ++i)
    if (i == spec.size() || spec[i] == ':') {
      parts.emplace_back(spec.substr(start, i - start));
      start = i + 1;
    }
  const auto fail = [&](const std::string& rule) -> Axis { throw InputError(origin, 0, text, rule); };
  if (parts.size() != 4 && parts.size() != 5) return fail("expected NAME:FROM:TO:N or NAME:FROM:TO:N:log");
  Axis axis;
  const auto ref = parse_param(parts[0], int(scene.balls.size()));
  if (!ref) return fail(fmt::format("unknown parameter '{}'; known: {}", parts[0], param_symbols_help()));
  if (ref->quantity == Quantity::ball_radius)
    return fail("the ball radius does not enter the equations of motion (model.md §3)");
  axis.param = *ref;
  const auto number = [&](const std::string& s, const char* what) {
    double v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v))
      fail(fmt::format("{} '{}' is not a finite number", what, s));
    return v;
  };
  axis.from = number(parts[1], "FROM");
  axis.to = number(parts[2], "TO");
  {
    long n = 0;
    const auto& s = parts[3];
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), n);
    if (ec != std::errc() || ptr != s.data() + s.size()) return fail(fmt::format("N '{}' is not an integer", s));
    if (n < 1 || n > kMaxAxisCount) return fail(fmt::format("N must be in [1, {}] (got {})", kMaxAxisCount, n));
    axis.count = int(n);
  }
  if (parts.size() == 5) {
    if (parts[4] != "log") return fail(fmt::format("the fifth field must be 'log' (got '{}')", parts[4]));
    if (!(axis.from > 0 && axis.to > 0))
      return fail(fmt::format("a log axis needs both ends > 0 (got {} .. {})", axis.from, axis.to));
    axis.logarithmic = true;
  }
  if (axis.count > 1 && axis.from == axis.to) return fail("FROM and TO are equal but N > 1");
  // The axis is an interval; the physical range and the scene's rules hold at both ends.
  Scene probe = scene;
  set_checked(probe, axis.param, axis.from, origin);
  set_checked(probe, axis.param, axis.to, origin);
  return axis;
}

int MapCell::best_stable() const {
  int best = -1;
  for (int i = 0; i < count; ++i) {
    const auto& e = equilibria[std::size_t(i)];
    if (e.stable && (best < 0 || e.q_abs < equilibria[std::size_t(best)].q_abs)) best = i;
  }
  return best;
}

CellAnalyzer::CellAnalyzer(const Params& base, const Axis& x, const Axis& y, CellMethod method)
    : base_(base), x_(x), y_(y), method_(method) {
  // Friction coefficients do not move equilibria (model.md §4): with one on the y axis a
  // column shares its equilibria and its friction-free linearization.
  const Quantity q = y.param.quantity;
  friction_y_ = q == Quantity::mu || q == Quantity::d || q == Quantity::mu_c || q == Quantity::mu_s ||
                q == Quantity::v_s || q == Quantity::kappa;
}

void CellAnalyzer::fill(MapEquilibrium& m, const Equilibrium& e) const {
  m.family = e.family;
  m.member = std::int8_t(e.member);
  m.q_abs = std::hypot(double(e.position(0)), double(e.position(1)));
  m.beta1 = double(e.position(2));
  m.beta2 = double(e.position(3));
}

void CellAnalyzer::start_column(int ix) {
  column_ = ix;
  column_params_ = base_;
  set(column_params_, x_.param, x_.value(ix));
  tracked_count_ = 0;
  if (!friction_y_) return;
  set(column_params_, y_.param, y_.value(0));
  const EquilibriumSet set = find_equilibria(column_params_);
  column_degeneracy_ = set.degeneracy;
  const auto pl = column_params_.cast<long double>();
  for (const auto& e : set.points()) {
    Tracked& t = tracked_[std::size_t(tracked_count_++)];
    t.equilibrium = e;
    t.linearization = linearize(pl, e.state());
    t.split = friction_split(friction_free(t.linearization));
    t.have_roots = false;
  }
}

void CellAnalyzer::decide(Tracked& t, const Polynomial& p, const Linearization<long double, 2>& lin,
                          MapEquilibrium& m, MapCell& cell) {
  if (method_ == CellMethod::fast && !t.equilibrium.singular() && t.have_roots) {
    std::complex<double> rightmost = t.rightmost;
    if (certified_abscissa(p, rightmost)) {
      // A certified abscissa below zero is stability itself; above, the Routh count gives
      // the number of unstable eigenvalues (and must agree that there are some).
      RouthCount rc{true, 0};
      if (rightmost.real() > 0) rc = routh_count(p);
      if (rc.decided && (rightmost.real() > 0) == (rc.n_unstable > 0)) {
        t.rightmost = rightmost;
        m.n_unstable = std::int8_t(rc.n_unstable);
        m.stable = rc.n_unstable == 0;
        m.abscissa = rightmost.real();
        return;
      }
    }
  }
  // The full eigenvalues: at the first cell of a column, for singular equilibria, and
  // wherever the fast decision is not certain (close to the stability boundary).
  const Spectrum sp = compute_spectrum(lin, SpectrumMethod::refined, t.equilibrium.structural_zeros);
  ++cell.fallbacks;
  t.rightmost = sp.eigenvalues[0];  // sorted: the largest real part first
  t.have_roots = true;
  m.n_unstable = std::int8_t(sp.n_unstable);
  m.stable = sp.stability == Stability::stable;
  m.abscissa = sp.abscissa;
}

void CellAnalyzer::analyze(int ix, int iy, MapCell& out) {
  if (ix != column_) start_column(ix);
  out = MapCell{};
  if (friction_y_) {
    Params p = column_params_;
    set(p, y_.param, y_.value(iy));
    out.degeneracy = column_degeneracy_;
    for (int k = 0; k < tracked_count_; ++k) {
      Tracked& t = tracked_[std::size_t(k)];
      // The balls' friction damping C(2+i, 2+i) = -l_i dF_i/d(beta_i') at rest.
      const double s1 = -p.balls[0].race_radius * friction_slope(p, 0, 0.0);
      const double s2 = -p.balls[1].race_radius * friction_slope(p, 1, 0.0);
      t.linearization.damping(2, 2) = s1;
      t.linearization.damping(3, 3) = s2;
      auto& m = out.equilibria[out.count++];
      fill(m, t.equilibrium);
      decide(t, combine(t.split, s1, s2), t.linearization, m, out);
    }
    return;
  }
  // General axes: the equilibria of this cell, each matched to the same family member of
  // the column's previous cell for the root tracking.
  Params p = column_params_;
  set(p, y_.param, y_.value(iy));
  const EquilibriumSet set = find_equilibria(p);
  out.degeneracy = set.degeneracy;
  const auto pl = p.cast<long double>();
  std::array<Tracked, 6> next{};
  int next_count = 0;
  for (const auto& e : set.points()) {
    Tracked& t = next[std::size_t(next_count++)];
    t.equilibrium = e;
    for (int k = 0; k < tracked_count_; ++k) {
      const Tracked& old = tracked_[std::size_t(k)];
      if (old.equilibrium.family == e.family && old.equilibrium.member == e.member && old.have_roots) {
        t.rightmost = old.rightmost;
        t.have_roots = true;
      }
    }
    t.linearization = linearize(pl, e.state());
    auto& m = out.equilibria[out.count++];
    fill(m, e);
    decide(t, to_double(characteristic_polynomial(t.linearization)), t.linearization, m, out);
  }
  tracked_ = next;
  tracked_count_ = next_count;
}

}  // namespace abu
