#include "abu/equilibria/equilibria.hpp"

#include <Eigen/QR>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "line_roots.hpp"

namespace abu {

namespace {

using ld = long double;
constexpr ld kPi = std::numbers::pi_v<ld>;
constexpr ld kTwoPi = 2 * kPi;
using equilibria_detail::kInputRounding;  // (line_roots.hpp)
constexpr ld kLongEps = std::numeric_limits<ld>::epsilon();

// The quantities of the closed forms (model.md §5), in long double from exact doubles.
struct ClosedForm {
  ld K, C, U, w2;
  ld a1, a2;  // m_i l_i
  bool no_rotor_equilibrium;
};

ClosedForm closed_form(const ParamsT<ld, 2>& p) {
  ClosedForm f{};
  f.w2 = p.omega * p.omega;
  const ld Mw2 = p.total_mass() * f.w2;
  f.K = p.rotor.stiffness - Mw2;
  f.C = p.rotor.damping * p.omega;
  f.U = p.rotor.unbalance;
  f.a1 = p.balls[0].mass * p.balls[0].race_radius;
  f.a2 = p.balls[1].mass * p.balls[1].race_radius;
  f.no_rotor_equilibrium = f.C == 0 && std::abs(f.K) <= kInputRounding * (p.rotor.stiffness + Mw2);
  return f;
}

// q from the two rotor equations: (K + iC) q = omega^2 (U + sum m_i l_i e^{i beta_i}).
Coordinates<ld, 2> with_rotor_response(const ClosedForm& f, ld beta1, ld beta2) {
  const std::complex<ld> load =
      f.w2 * (f.U + f.a1 * std::polar(ld(1), beta1) + f.a2 * std::polar(ld(1), beta2));
  const std::complex<ld> q = load / std::complex<ld>(f.K, f.C);
  Coordinates<ld, 2> s;
  s << q.real(), q.imag(), beta1, beta2;
  return s;
}

Equilibrium make(Family family, int member, const Coordinates<ld, 2>& s, bool is_set = false) {
  Equilibrium e;
  // The balanced family has q = 0 exactly; the load sum only rounds to zero.
  e.family = family;
  e.member = member;
  e.position = s;
  if (family == Family::balanced) e.position.head<2>().setZero();
  e.is_set = is_set;
  e.structural_zeros = is_set ? 1 : 0;
  if (family == Family::opposite) e.pattern = 0b10;  // ball 2 on the far side (model.md §13.2)
  return e;
}

// Balanced: the ball vectors a1 e^{i b1}, a2 e^{i b2} and U close a triangle. With
// b1 = pi - t1, b2 = pi + t2, t1 and t2 are its angles next to side U; the half-angle
// formula tan(t/2) = sqrt((s-x)(s-U) / (s(s-y))) keeps them accurate near merging,
// where arccos(U / 2ml) would lose half the digits to cancellation.
void add_balanced(const ClosedForm& f, EquilibriumSet& set) {
  const ld tol = kInputRounding * (f.a1 + f.a2 + f.U);
  if (f.U == 0) {
    set.degeneracy |= unbalance_zero;
    if (std::abs(f.a1 - f.a2) <= tol)  // the circle b2 = b1 + pi
      set.add(make(Family::balanced, 1, with_rotor_response(f, 0, kPi), true));
    return;
  }
  const ld twice_s_minus_u = f.a1 + f.a2 - f.U;  // 2 (s - U): the merging gap
  const ld twice_s_minus_a1 = f.a2 + f.U - f.a1;
  const ld twice_s_minus_a2 = f.a1 + f.U - f.a2;
  if (twice_s_minus_u < -tol || twice_s_minus_a1 < -tol || twice_s_minus_a2 < -tol) return;
  const bool merges_together = std::abs(twice_s_minus_u) <= tol;
  const bool merges_opposite = std::abs(twice_s_minus_a1) <= tol || std::abs(twice_s_minus_a2) <= tol;
  if (merges_together) set.degeneracy |= balanced_merges_together;
  if (merges_opposite) set.degeneracy |= balanced_merges_opposite;
  const ld su = merges_together ? 0 : twice_s_minus_u / 2;
  const ld s1 = std::abs(twice_s_minus_a1) <= tol ? 0 : twice_s_minus_a1 / 2;
  const ld s2 = std::abs(twice_s_minus_a2) <= tol ? 0 : twice_s_minus_a2 / 2;
  const ld s = (f.a1 + f.a2 + f.U) / 2;
  const ld t1 = 2 * std::atan2(std::sqrt(s1 * su), std::sqrt(s * s2));
  const ld t2 = 2 * std::atan2(std::sqrt(s2 * su), std::sqrt(s * s1));
  Equilibrium first = make(Family::balanced, 1, with_rotor_response(f, kPi - t1, kPi + t2));
  first.structural_zeros = merges_together || merges_opposite ? 1 : 0;  // a pitchfork: the mirror points have met
  set.add(first);
  if (!first.singular()) set.add(make(Family::balanced, 2, with_rotor_response(f, kPi + t1, kPi - t2)));
}


// Together (b1 = b2 = b) and opposite (b2 = b1 + pi) points: the balls on the line of q.
void add_collinear(const ClosedForm& f, Family family, EquilibriumSet& set) {
  const bool together = family == Family::together;
  const ld a = together ? f.a1 + f.a2 : f.a1 - f.a2;  // the ball set's resultant along b1
  const ld offset = together ? 0 : kPi;
  if (f.no_rotor_equilibrium) {
    set.degeneracy |= no_rotor_equilibrium;
    return;
  }
  if (f.U == 0) {
    set.degeneracy |= unbalance_zero;
    // Rotationally symmetric: either a whole circle (C a = 0) or nothing. Equal balls
    // opposite each other are the balanced circle, listed once there.
    const bool on_balanced_circle = !together && std::abs(a) <= kInputRounding * (f.a1 + f.a2);
    if (f.C == 0 && !on_balanced_circle)
      set.add(make(family, 1, with_rotor_response(f, 0, offset), true));
    return;
  }
  std::array<ld, 2> roots{};
  bool double_root = false;
  const int n = equilibria_detail::line_roots(f.K, f.C, f.U, a, roots, double_root);
  if (double_root) set.degeneracy |= together ? together_double_root : opposite_double_root;
  // Where the balanced points merged into this family, its root at the merging point is
  // the same configuration and shares the zero eigenvalue.
  const Equilibrium* merged = nullptr;
  for (const auto& p : set.points())
    if (p.family == Family::balanced && p.singular() && !p.is_set) merged = &p;
  const auto same_angle = [](ld u, ld v) { return std::abs(std::remainder(u - v, kTwoPi)) < 1e-6L; };
  for (int i = 0; i < n; ++i) {
    const ld b = roots[std::size_t(i)];
    Equilibrium e = make(family, i + 1, with_rotor_response(f, b, b + offset));
    const bool at_merge =
        merged && same_angle(b, merged->position(2)) && same_angle(b + offset, merged->position(3));
    e.structural_zeros = double_root || at_merge ? 1 : 0;
    set.add(e);
  }
}

}  // namespace

std::string_view to_string(Family family) {
  switch (family) {
    case Family::balanced: return "balanced";
    case Family::together: return "together";
    case Family::opposite: return "opposite";
    case Family::aligned: return "aligned";
  }
  return "?";
}

void EquilibriumSet::add(const Equilibrium& e) {
  if (count_ < points_.size()) points_[count_++] = e;
}

long double wrap_angle(long double beta) {
  ld w = std::fmod(beta, kTwoPi);
  if (w < 0) w += kTwoPi;
  // 2 pi - 1e-20 is below 2 pi in long double but rounds to double(2 pi): call it 0.
  if (double(w) >= 2 * std::numbers::pi) w = 0;
  return w;
}

template <int N>
double static_residual(const ParamsT<double, N>& p, const Coordinates<long double, N>& s) {
  const auto pl = p.template cast<ld>();
  const Coordinates<ld, N> b = generalized_forces(pl, at_rest<ld, N>(s));
  const Coordinates<ld, N> scale = static_force_scale(pl, s);
  return double((b.array().abs() / scale.array()).maxCoeff());
}

template <int N>
EquilibriumT<N> polish_equilibrium(const ParamsT<double, N>& p, const EquilibriumT<N>& guess) {
  const auto pl = p.template cast<ld>();
  const ld length = displacement_scale(pl);
  EquilibriumT<N> e = guess;
  Coordinates<ld, N> s = guess.position;
  const Eigen::Index d = s.size();
  // Newton on b(s, 0) = 0 with q in units of `length` and every equation divided by its
  // natural size, so the 4x4 system is O(1) in all entries. db/ds = -K at rest (the
  // (dA/ds) s'' part of K vanishes quadratically as s'' -> 0). A rank-revealing solve
  // gives the minimum-norm step where the equilibrium is not isolated (U = 0 circles,
  // merging points).
  Coordinates<ld, N> column_scale = Coordinates<ld, N>::Ones(d);
  column_scale(0) = column_scale(1) = length;
  constexpr int kMaxIterations = 30;
  ld residual = std::numeric_limits<ld>::infinity();
  int it = 0;
  for (;; ++it) {
    const State<ld, N> x = at_rest<ld, N>(s);
    const Coordinates<ld, N> b = generalized_forces(pl, x);
    const Coordinates<ld, N> scale = static_force_scale(pl, s);
    const ld previous = residual;
    residual = (b.array().abs() / scale.array()).maxCoeff();
    // Done at the rounding level of long double, or where the residual stops falling
    // (it has reached the rounding level of evaluating b, which varies with the terms).
    if (residual <= 4 * kLongEps || residual > previous / 2 || it == kMaxIterations) break;
    const DofMatrix<ld, N> db_ds = -linearize(pl, x).stiffness;
    const DofMatrix<ld, N> scaled = scale.cwiseInverse().asDiagonal() * db_ds * column_scale.asDiagonal();
    const Coordinates<ld, N> step =
        scaled.completeOrthogonalDecomposition().solve(Coordinates<ld, N>(-(b.array() / scale.array())));
    s += column_scale.asDiagonal() * step;
  }
  for (Eigen::Index i = 2; i < d; ++i) s(i) = wrap_angle(s(i));
  e.position = s;
  e.newton_iterations = it;
  // Converged: as exact as long double allows, far below the double rounding of the
  // reported state (whose own residual is ~1e-16).
  e.converged = residual <= ld(1e-17);
  if (e.converged)
    e.status = {};
  else if (!std::isfinite(residual) || !s.allFinite())
    e.status = {Outcome::numerical_issue, "the static residual or a Newton step was not finite"};
  else if (it == kMaxIterations)
    e.status = {Outcome::not_converged, "Newton ran out of iterations above the tolerance 1e-17"};
  else
    e.status = {Outcome::not_converged, "Newton stalled (the residual stopped halving) above the tolerance 1e-17"};
  e.residual = static_residual(p, Coordinates<ld, N>(s.template cast<double>().template cast<ld>()));
  return e;
}

template double static_residual<2>(const Params&, const Coordinates<ld, 2>&);
template double static_residual<any_balls>(const ParamsN&, const Coordinates<ld, any_balls>&);
template Equilibrium polish_equilibrium<2>(const Params&, const Equilibrium&);
template EquilibriumN polish_equilibrium<any_balls>(const ParamsN&, const EquilibriumN&);

EquilibriumSet closed_form_equilibria(const Params& p) {
  const ClosedForm f = closed_form(p.cast<ld>());
  EquilibriumSet set;
  add_balanced(f, set);
  add_collinear(f, Family::together, set);
  add_collinear(f, Family::opposite, set);
  for (auto& e : set.points()) {
    e.position(2) = wrap_angle(e.position(2));
    e.position(3) = wrap_angle(e.position(3));
  }
  return set;
}

EquilibriumSet find_equilibria(const Params& p) {
  EquilibriumSet set = closed_form_equilibria(p);
  for (auto& e : set.points()) {
    if (e.is_set) {  // exact by symmetry; Newton has no isolated root to converge to
      e.converged = true;
      e.status = {};
      e.residual = static_residual(p, Coordinates<ld, 2>(e.position.cast<double>().cast<ld>()));
    } else {
      e = polish_equilibrium(p, e);
    }
  }
  return set;
}

std::vector<std::string> describe_degeneracy(unsigned degeneracy) {
  std::vector<std::string> lines;
  if (degeneracy & unbalance_zero)
    lines.emplace_back(
        "U = 0: the model is rotationally symmetric and its equilibria form circles; one "
        "representative per circle is listed (beta1 = 0) and its spectrum has a zero "
        "eigenvalue along the circle");
  if (degeneracy & balanced_merges_together)
    lines.emplace_back(
        "U = m1 l1 + m2 l2 within input rounding: the two balanced points have merged with a "
        "together point (beta1 = beta2 = pi, q = 0)");
  if (degeneracy & balanced_merges_opposite)
    lines.emplace_back(
        "U = |m1 l1 - m2 l2| within input rounding: the two balanced points have merged with "
        "an opposite point");
  if (degeneracy & no_rotor_equilibrium)
    lines.emplace_back(
        "K = k - omega^2 M = 0 and C = c omega = 0: no bounded rotor equilibrium exists but "
        "the balanced one (undamped resonance)");
  if (degeneracy & together_double_root)
    lines.emplace_back("the two together points coincide (double root: a fold of that family)");
  if (degeneracy & opposite_double_root)
    lines.emplace_back("the two opposite points coincide (double root: a fold of that family)");
  if (degeneracy & aligned_double_root)
    lines.emplace_back(
        "C^2 S^2 = U^2 (K^2 + C^2) for a ball pattern within input rounding: its two aligned points coincide "
        "(double root: a fold)");
  if (degeneracy & aligned_zero_resultant)
    lines.emplace_back(
        "S = sum sigma_i m_i l_i = 0 for a ball pattern: its balls cancel, and its two aligned points carry the "
        "rotor's response without a balancer");
  if (degeneracy & balanced_collinear)
    lines.emplace_back(
        "U = |sum sigma_i m_i l_i| for a ball pattern within input rounding: the balanced set has a collinear "
        "point where an aligned branch meets it; the set is not smooth there");
  if (degeneracy & balanced_absent)
    lines.emplace_back(
        "no balanced state: the unbalance and the balls' m_i l_i cannot close a polygon "
        "(max(U, m_i l_i) > (U + sum m_j l_j) / 2; for equal balls, capacity sum m_i l_i < U)");
  return lines;
}

}  // namespace abu
