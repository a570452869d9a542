#include "abu/scan/map.hpp"
#include "abu/linear/spectrum_counts.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "abu/linear/lugre_spectrum.hpp"
#include "abu/core/errors.hpp"
#include "abu/linear/balanced_floquet.hpp"
#include "abu/linear/balanced_reduced.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/linear/spectrum_verdict.hpp"
#include "abu/model/friction.hpp"

namespace abu {

double Axis::value(int i) const {
  if (ball_count) return from + i;
  if (i <= 0) return from;
  if (i >= count - 1) return to;
  const double t = double(i) / double(count - 1);
  return logarithmic ? std::exp(std::log(from) + t * (std::log(to) - std::log(from))) : from + t * (to - from);
}

std::string Axis::name() const { return ball_count ? std::string("n") : to_string(param); }

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

namespace {

// Eigenvalues inside their error bands (at kappa = 4e13 near resonance neither QR resolves
// the rotor pair at -8 +- 13i nor, then, its creep pair at 3e-15 +- 6e-16i, and their
// refinements fail): the certified Routh count of the same polynomial (with its error
// bounds) and an abscissa certified as rightmost decide instead; else the verdict stays
// undecided, and says so.
void second_opinion(const Spectrum& sp, const Polynomial& p, MapEquilibrium& m) {
  Spectrum decided = sp;
  if (!certify_counts(decided, p)) {
    m.n_undecided = std::int8_t(sp.n_marginal);
    return;
  }
  m.n_unstable = std::int8_t(decided.n_unstable);
  m.stable = decided.stability == Stability::stable;
  m.abscissa = decided.abscissa;
}

}  // namespace

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
  if (sp.n_marginal > 0 && !t.equilibrium.singular()) second_opinion(sp, p, m);
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

// ---------------------------------------------------------------------------------------
// n balls (model.md §13.8): every cell by the full analysis, no per-column shortcut (the
// degree-(2n+4) polynomial is not used beyond two balls).

int MapCellN::best_stable() const {
  int best = -1;
  for (int i = 0; i < int(equilibria.size()); ++i) {
    const auto& e = equilibria[std::size_t(i)];
    if (e.stable && (best < 0 || e.q_abs < equilibria[std::size_t(best)].q_abs)) best = i;
  }
  return best;
}

CellAnalyzerN::CellAnalyzerN(const ParamsN& base, std::vector<ParamsN> by_count, const Axis& x, const Axis& y,
                             const BalancedSampling& sampling, std::optional<AnisotropicSupport> support)
    : base_(base), by_count_(std::move(by_count)), x_(x), y_(y), sampling_(sampling), support_(support) {}

namespace {
// Whether find_equilibria and the permutation classes give the same for both: every
// parameter but the friction coefficients (which do not move equilibria, model.md §4), the
// balls' kinds (which do depend on them) and whether any ball has a friction slope at rest
// (the structural zeros of the balanced samples, model.md §13.4).
bool same_equilibria(const ParamsN& a, const ParamsN& b) {
  if (a.n_balls() != b.n_balls() || a.omega != b.omega || a.law != b.law || a.rotor.mass != b.rotor.mass ||
      a.rotor.stiffness != b.rotor.stiffness || a.rotor.damping != b.rotor.damping ||
      a.rotor.unbalance != b.rotor.unbalance)
    return false;
  bool slope_a = false, slope_b = false;
  for (int i = 0; i < a.n_balls(); ++i) {
    const auto &x = a.balls[std::size_t(i)], &y = b.balls[std::size_t(i)];
    if (x.mass != y.mass || x.race_radius != y.race_radius || x.radius != y.radius ||
        x.inertia_factor != y.inertia_factor)
      return false;
    slope_a = slope_a || friction_slope(a, i, 0.0) != 0.0;
    slope_b = slope_b || friction_slope(b, i, 0.0) != 0.0;
  }
  return slope_a == slope_b && ball_kinds(a).kind == ball_kinds(b).kind;
}
}  // namespace

ParamsN CellAnalyzerN::cell_params(int ix, int iy) const {
  ParamsN p = x_.ball_count ? by_count_[std::size_t(ix)] : y_.ball_count ? by_count_[std::size_t(iy)] : base_;
  if (!x_.ball_count) set(p, x_.param, x_.value(ix));
  if (!y_.ball_count) set(p, y_.param, y_.value(iy));
  return p;
}

void CellAnalyzerN::analyze(int ix, int iy, MapCellN& out) {
  const ParamsN p = cell_params(ix, iy);
  const auto pl = p.cast<long double>();
  // LuGre (model.md §12.8): the z = 0 equilibria are the frictionless model's; their
  // stability is (12.10) with c = 1, where both one-sided spectra coincide.
  const bool lugre = p.law == FrictionLaw::lugre;
  ParamsN frictionless = p;
  if (lugre) frictionless.law = FrictionLaw::none;
  const bool same_statics = have_set_ && same_equilibria(set_params_, frictionless);
  if (!same_statics) {
    find_equilibria(frictionless, sampling_, set_);
    // Equal balls (model.md §13.9): a permutation image takes its representative's verdict.
    find_permutation_classes(lugre ? BallKinds{} : ball_kinds(p), set_.points(), classes_);
    set_params_ = frictionless;
    have_set_ = true;
    // What the reductions of §13.9 and §13.10 need of each equilibrium: the geometry only.
    const auto found = set_.points();
    const bool equal = !lugre && equal_smooth_balls(p);
    sample_g_.assign(found.size(), 0);
    sides_.assign(found.size(), AlignedReduction{});
    for (std::size_t k = 0; k < found.size(); ++k) {
      if (found[k].on_balanced_set) sample_g_[k] = arrangement_of(found[k].position).g;
      if (equal) sides_[k] = aligned_sides(found[k]);
    }
    aligned_roots_.assign(found.size(), {});
    pencil_of_.assign(found.size(), -1);
    pencils_.clear();
    reduced_splits_.reset();
  }
  out.n_balls = p.n_balls();
  out.capacity = 0;
  for (const auto& b : p.balls) out.capacity += b.mass * b.race_radius;
  out.unbalance = p.rotor.unbalance;
  out.balanced_exists = balanced_set_exists(p);
  out.degeneracy = set_.degeneracy;
  out.balanced_samples = out.balanced_stable = out.aligned = out.aligned_stable = 0;
  out.normal_abscissa_max = 0;
  const auto points = set_.points();
  if (support_) {
    analyze_floquet_cell(p, points, out);
    return;
  }
  out.equilibria.resize(points.size());
  // An aligned root is followed per equilibrium along a column while its statics stay (a
  // friction axis; a new set starts untracked above, since it may list other equilibria at an index).
  if (ix != column_) {
    column_ = ix;
    reduced_tracked_ = false;
    for (auto& r : aligned_roots_) r.tracked = false;
  }
  // The balanced samples of equal balls are judged by the reduced problem in g.
  const BalancedReduction reduction = lugre ? BalancedReduction{} : balanced_reduction(p);
  std::optional<ReducedPolynomials> corners;  // (once per cell, at the first sample that needs them)
  // A class copies the verdict of a member whose refinements converged (as analyze does).
  source_.assign(points.size(), -1);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const EquilibriumN& e = points[k];
    MapEquilibriumN& m = out.equilibria[k];
    const auto rep = std::size_t(classes_.images[k].representative);
    bool converged = true;
    if (const int from = source_[rep]; from >= 0) {
      const MapEquilibriumN& r = out.equilibria[std::size_t(from)];
      m.n_unstable = r.n_unstable;
      m.n_structural = r.n_structural;
      m.stable = r.stable;
      m.abscissa = r.abscissa;
    } else if (reducible(reduction, e, sample_g_[k])) {
      if (!reduced_splits_) reduced_splits_ = reduced_splits(reduction);
      if (!corners) corners = reduced_polynomials(*reduced_splits_, reduction);
      const NormalVerdict v = reduced_normal_verdict(reduction, *corners, sample_g_[k], reduced_root_, reduced_tracked_);
      m.n_unstable = v.n_unstable;
      m.n_structural = v.n_structural;
      m.stable = v.stability == Stability::stable;
      m.abscissa = v.abscissa;
      converged = v.converged;
    } else if (const AlignedVerdict a = aligned_cell_verdict(pl, k); a.decided) {
      m.n_unstable = a.verdict.n_unstable;
      m.n_structural = 0;
      m.stable = a.verdict.stability == Stability::stable;
      m.abscissa = a.verdict.abscissa;
      converged = a.verdict.converged;
    } else {
      // As equilibrium_spectrum (scan.hpp): on the balanced set the normal spectrum, the
      // tangent directions deflated (model.md §13.5); elsewhere the verdict of the refined
      // spectrum, refining only what it needs (spectrum_verdict.hpp).
      if (lugre || e.on_balanced_set) {
        const SpectrumN sp = lugre ? lugre_zero_bristle_spectrum(p, e.position)
                                   : compute_normal_spectrum(linearize(pl, e.state()),
                                                             balanced_tangent_basis(p, e.position));
        m.n_unstable = sp.n_unstable;
        m.n_structural = sp.n_structural;
        m.stable = sp.stability == Stability::stable;
        m.abscissa = sp.abscissa;
        converged = sp.converged;
      } else {
        const SpectrumVerdict v = spectrum_verdict(linearize(pl, e.state()), e.structural_zeros);
        m.n_unstable = v.n_unstable;
        m.n_structural = v.n_structural;
        m.stable = v.stability == Stability::stable;
        m.abscissa = v.abscissa;
        converged = v.converged;
      }
    }
    if (source_[rep] < 0 && converged) source_[rep] = int(k);
    m.family = e.family;
    m.pattern = e.pattern;
    m.member = e.member;
    m.q_abs = std::hypot(double(e.position(0)), double(e.position(1)));
    m.beta.fill(0);
    for (int i = 0; i < out.n_balls; ++i) m.beta[std::size_t(i)] = double(e.position(2 + i));
    if (e.family == Family::balanced) {
      out.normal_abscissa_max =
          out.balanced_samples == 0 ? m.abscissa : std::max(out.normal_abscissa_max, m.abscissa);
      ++out.balanced_samples;
      out.balanced_stable += m.stable;
    } else {
      ++out.aligned;
      out.aligned_stable += m.stable;
    }
  }
}

AlignedVerdict CellAnalyzerN::aligned_cell_verdict(const ParamsT<long double, any_balls>& pl, std::size_t k) {
  const AlignedReduction& sides = sides_[k];
  if (!sides.applies) return {};
  if (pencil_of_[k] < 0) {
    pencils_.push_back(aligned_pencil(sides, linearize(pl, set_.points()[k].state()), set_.points()[k]));
    pencil_of_[k] = int(pencils_.size()) - 1;
  }
  return aligned_verdict(pencils_[std::size_t(pencil_of_[k])], side_friction(pl, sides), aligned_roots_[k].root,
                         aligned_roots_[k].tracked);
}

void CellAnalyzerN::analyze_floquet_cell(const ParamsN& p, std::span<const EquilibriumN> points, MapCellN& out) {
  // Anisotropic support (model.md §10.12): the balanced states stay equilibria, judged by
  // the Floquet multipliers over pi/omega on the magnus route (§10.10, ~1 ms a state); the
  // mean system's other equilibria are periodic orbits and have no row here.
  FloquetOptions options;
  options.route = FloquetRoute::magnus;
  std::size_t count = 0;
  for (const EquilibriumN& e : points) count += e.family == Family::balanced;
  out.equilibria.resize(count);
  std::size_t k = 0;
  for (const EquilibriumN& e : points) {
    if (e.family != Family::balanced) continue;
    const BalancedFloquet f = balanced_floquet(p, *support_, e, options);
    if (!f.status.ok())
      throw NumericalError(fmt::format("omega={}: Floquet multipliers of balanced state {}: {}", p.omega, e.member,
                                       f.status.reason));
    MapEquilibriumN& m = out.equilibria[k++];
    m.family = e.family;
    m.pattern = e.pattern;
    m.member = e.member;
    m.n_unstable = 0;
    for (const auto& rho : f.multipliers) m.n_unstable += std::abs(rho) > 1.0;
    m.n_structural = f.deflated;
    m.stable = f.verdict == Stability::stable;
    m.abscissa = f.abscissa;
    m.rho_abs_max = f.max_modulus;
    m.q_abs = std::hypot(double(e.position(0)), double(e.position(1)));
    m.beta.fill(0);
    for (int i = 0; i < out.n_balls; ++i) m.beta[std::size_t(i)] = double(e.position(2 + i));
    out.normal_abscissa_max = out.balanced_samples == 0 ? m.abscissa : std::max(out.normal_abscissa_max, m.abscissa);
    ++out.balanced_samples;
    out.balanced_stable += m.stable;
  }
}

}  // namespace abu
