#include "abu/equilibria/equilibria_n.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "line_roots.hpp"

#include "abu/equilibria/ball_permutations.hpp"
#include "abu/model/friction.hpp"

namespace abu {

namespace {

using ld = long double;
using cld = std::complex<ld>;
constexpr ld kPi = std::numbers::pi_v<ld>;
using equilibria_detail::kInputRounding;  // (line_roots.hpp)
constexpr ld kLongEps = std::numeric_limits<ld>::epsilon();

// The quantities of model.md §13.1 in long double from the exact doubles.
struct Problem {
  int n = 0;
  ld K = 0, C = 0, U = 0, w2 = 0;
  std::array<ld, max_balls> a{};  // m_i l_i
  ld capacity = 0;                // sum m_i l_i
  bool no_rotor_equilibrium = false;
};

Problem problem_of(const ParamsN& p) {
  Problem f;
  f.n = p.n_balls();
  f.w2 = ld(p.omega) * ld(p.omega);
  ld M = p.rotor.mass;
  for (const auto& b : p.balls) M += ld(b.mass);
  const ld Mw2 = M * f.w2;
  f.K = ld(p.rotor.stiffness) - Mw2;
  f.C = ld(p.rotor.damping) * ld(p.omega);
  f.U = p.rotor.unbalance;
  for (int i = 0; i < f.n; ++i) {
    f.a[std::size_t(i)] = ld(p.balls[std::size_t(i)].mass) * ld(p.balls[std::size_t(i)].race_radius);
    f.capacity += f.a[std::size_t(i)];
  }
  f.no_rotor_equilibrium = f.C == 0 && std::abs(f.K) <= kInputRounding * (ld(p.rotor.stiffness) + Mw2);
  return f;
}

EquilibriumN make_equilibrium(const Problem& f, Family family, unsigned pattern, int member, const cld& q,
                              const std::array<ld, max_balls>& beta) {
  EquilibriumN e;
  e.family = family;
  e.pattern = pattern;
  e.member = member;
  e.position = Coordinates<ld, any_balls>::Zero(f.n + 2);
  e.position(0) = q.real();
  e.position(1) = q.imag();
  for (int i = 0; i < f.n; ++i) e.position(2 + i) = wrap_angle(beta[std::size_t(i)]);
  return e;
}


// `e` (unpolished, same k and root as `done`, equal balls) made the image of `done`: the
// polished angles of done's + balls go to e's + balls in order, likewise the - balls, and
// everything else is copied. False (e untouched) if the two differ in a flag that the
// polish does not decide (structural zeros) or in the number of balls per side.
bool image_of(const EquilibriumN& done, EquilibriumN& e) {
  const int n = e.n_balls();
  if (done.structural_zeros != e.structural_zeros || std::popcount(done.pattern) != std::popcount(e.pattern))
    return false;
  EquilibriumN out = done;
  out.pattern = e.pattern;
  out.member = e.member;
  std::array<int, 2> next{0, 0};
  for (int i = 0; i < n; ++i) {
    const unsigned side = e.pattern >> i & 1u;
    int& j = next[side];
    while ((done.pattern >> j & 1u) != side) ++j;  // the next ball of done on that side
    out.position(2 + i) = done.position(2 + j);
    ++j;
  }
  e = out;
  return true;
}

// The isolated equilibria, every ball on the line of q (model.md §13.2).
void add_aligned(const ParamsN& p, const Problem& f, EquilibriumSetN& set) {
  if (f.no_rotor_equilibrium) {
    set.degeneracy |= no_rotor_equilibrium;
    return;
  }
  const ld tol = kInputRounding * (f.capacity + f.U);
  const unsigned patterns = 1u << (f.n - 1);
  // Equal balls (model.md §13.9): a pattern with k balls opposite is a permutation image of
  // every other with k, root by root; the first one of each (k, root) is polished, the others
  // are its image (its polished angles handed to their balls side by side), exact by (13.9.1).
  const bool images = ball_kinds(p).all_equal;
  std::array<int, 2 * (max_balls + 1)> polished;  // by k * 2 + root: its index in set.list, -1 none yet
  polished.fill(-1);
  // (twice that where no ball's friction has a slope: Jordan pairs, model.md §13.4)
  bool any_slope = false;
  for (int i = 0; i < f.n; ++i) any_slope = any_slope || friction_slope(p, i, 0.0) != 0.0;
  for (unsigned mask = 0; mask < patterns; ++mask) {
    const unsigned pattern = mask << 1;  // ball 1 is always +
    ld S = 0;
    for (int i = 0; i < f.n; ++i) S += (pattern >> i & 1u) ? -f.a[std::size_t(i)] : f.a[std::size_t(i)];
    const bool zero_resultant = std::abs(S) <= tol;
    if (zero_resultant) {
      set.degeneracy |= aligned_zero_resultant;
      S = 0;
    }
    const Family family = f.n == 2 ? (pattern == 0 ? Family::together : Family::opposite) : Family::aligned;
    const auto angles = [&](ld phi) {
      std::array<ld, max_balls> beta{};
      for (int i = 0; i < f.n; ++i) beta[std::size_t(i)] = (pattern >> i & 1u) ? phi + kPi : phi;
      return beta;
    };
    const auto rotor_response = [&](ld phi) { return f.w2 * (f.U + S * std::polar(ld(1), phi)) / cld(f.K, f.C); };
    if (f.U == 0) {
      set.degeneracy |= unbalance_zero;
      // Rotationally symmetric: a whole circle (C S = 0) or nothing; S = 0 gives q = 0, a
      // point of the balanced set, listed there.
      if (f.C == 0 && !zero_resultant) {
        EquilibriumN e = make_equilibrium(f, family, pattern, 1, rotor_response(0), angles(0));
        e.is_set = true;
        e.structural_zeros = 1;
        set.list.push_back(e);
      }
      continue;
    }
    std::array<ld, 2> roots{};
    bool double_root = false;
    const int count = equilibria_detail::line_roots(f.K, f.C, f.U, S, roots, double_root);
    if (double_root) set.degeneracy |= aligned_double_root;
    for (int r = 0; r < count; ++r) {
      const ld phi = roots[std::size_t(r)];
      EquilibriumN e = make_equilibrium(f, family, pattern, r + 1, rotor_response(phi), angles(phi));
      // |U + S e^{i phi}| = 0: q = 0, a collinear point of the balanced set where this
      // branch meets it (two balls: the merge U = m1 l1 + m2 l2); the set's n - 2 tangent
      // directions and the merging one are all zero modes there.
      const bool on_set = std::abs(f.U + S * std::polar(ld(1), phi)) <= tol;
      if (on_set) {
        set.degeneracy |= balanced_collinear;
        e.position(0) = e.position(1) = 0;
      }
      e.structural_zeros = on_set ? (any_slope ? 1 : 2) * (f.n - 1) : double_root ? 1 : 0;
      int& done = polished[std::size_t(std::popcount(pattern) * 2 + r)];
      if (images && done >= 0 && image_of(set.list[std::size_t(done)], e)) {
        set.list.push_back(e);
        continue;
      }
      set.list.push_back(polish_equilibrium(p, e));
      if (images && done < 0) done = int(set.list.size()) - 1;
    }
  }
}

// Angles of the triangle with sides a1, a2, rho next to side rho: gamma1 opposite a2,
// gamma2 opposite a1, from the half-angle formula tan(g/2) = sqrt((s-x)(s-rho)/(s(s-y)))
// (accurate where arccos would lose half the digits, at the ends of existence).
void triangle_angles(ld a1, ld a2, ld rho, ld tol, ld& gamma1, ld& gamma2) {
  const ld s = (a1 + a2 + rho) / 2;
  const auto gap = [tol](ld v) { return v < tol ? ld(0) : v; };
  const ld s1 = gap(s - a1), s2 = gap(s - a2), sr = gap(s - rho);
  gamma1 = 2 * std::atan2(std::sqrt(s1 * sr), std::sqrt(s * s2));
  gamma2 = 2 * std::atan2(std::sqrt(s2 * sr), std::sqrt(s * s1));
}

// Newton on W(beta) = U + sum a_j e^{i beta_j} = 0 in (beta_1, beta_2), the others held:
// the closed form is accurate to a few roundings already; this removes them.
int polish_on_set(const Problem& f, std::array<ld, max_balls>& beta, ld& residual) {
  int it = 0;
  for (; it < 8; ++it) {
    cld W = f.U;
    for (int i = 0; i < f.n; ++i) W += f.a[std::size_t(i)] * std::polar(ld(1), beta[std::size_t(i)]);
    residual = std::abs(W) / (f.U + f.capacity);
    if (residual <= 4 * kLongEps) break;
    // dW/dbeta_j = i a_j e^{i beta_j}; solve the 2x2 real system by Cramer's rule.
    const ld j11 = -f.a[0] * std::sin(beta[0]), j12 = -f.a[1] * std::sin(beta[1]);
    const ld j21 = f.a[0] * std::cos(beta[0]), j22 = f.a[1] * std::cos(beta[1]);
    const ld det = j11 * j22 - j12 * j21;
    if (!(std::abs(det) > 0)) break;
    beta[0] -= (W.real() * j22 - j12 * W.imag()) / det;
    beta[1] -= (j11 * W.imag() - j21 * W.real()) / det;
  }
  return it;
}

// Samples of the balanced set (header comment).
void add_balanced_samples(const ParamsN& p, const Problem& f, const BalancedSampling& sampling, EquilibriumSetN& set) {
  auto& info = set.balanced_set;
  info.dimension = f.n - 2;
  info.exists = balanced_set_exists(p);
  if (!info.exists) {
    set.degeneracy |= balanced_absent;
    return;
  }
  const int free = f.n - 2;
  const int G = balanced_grid_size(f.n, sampling);
  long per_sheet = 1;
  for (int j = 0; j < free; ++j) per_sheet *= G;
  info.grid = G;
  info.grid_points = int(2 * per_sheet);
  const ld tol = kInputRounding * (f.capacity + f.U);
  const ld a1 = f.a[0], a2 = f.a[1];
  int member = 0;
  for (int sheet : {1, -1}) {
    for (long index = 0; index < per_sheet; ++index) {
      std::array<ld, max_balls> beta{};
      cld R = f.U;
      long digits = index;
      for (int j = 2; j < f.n; ++j) {
        beta[std::size_t(j)] = 2 * kPi * ld(digits % G) / ld(G);
        digits /= G;
        R += f.a[std::size_t(j)] * std::polar(ld(1), beta[std::size_t(j)]);
      }
      const ld rho = std::abs(R);
      if (rho < std::abs(a1 - a2) - tol || rho > a1 + a2 + tol) continue;  // balls 1, 2 cannot close it
      ld gamma1 = 0, gamma2 = 0;
      triangle_angles(a1, a2, rho, tol, gamma1, gamma2);
      const bool collinear = std::abs(std::sin(gamma1)) <= std::sqrt(kInputRounding) &&
                             std::abs(std::sin(gamma2)) <= std::sqrt(kInputRounding);
      if (sheet < 0 && collinear) continue;  // the two sheets meet: listed once
      const ld theta = rho > 0 ? std::arg(-R) : 0;
      beta[0] = theta - sheet * gamma1;
      beta[1] = theta + sheet * gamma2;
      ld residual = 0;
      const int iterations = polish_on_set(f, beta, residual);
      EquilibriumN e = make_equilibrium(f, Family::balanced, 0, ++member, cld(0, 0), beta);
      e.on_balanced_set = f.n >= 3;
      e.newton_iterations = iterations;
      e.converged = residual <= ld(1e-17);
      e.status = e.converged ? Status{}
                             : Status{Outcome::not_converged, "the polish onto the balanced set stopped above 1e-17"};
      if (collinear) set.degeneracy |= balanced_collinear;
      e.residual = static_residual(p, Coordinates<ld, any_balls>(e.position.cast<double>().cast<ld>()));
      // Structural zeros: the tangent directions, twice over where no ball's friction has
      // a slope (the balls drift along the set: Jordan pairs, model.md §13.4).
      bool any_slope = false;
      for (int i = 0; i < f.n; ++i) any_slope = any_slope || friction_slope(p, i, 0.0) != 0.0;
      const int tangent = collinear ? f.n - 1 : f.n - 2;
      e.structural_zeros = any_slope ? tangent : 2 * tangent;
      set.list.push_back(e);
    }
  }
  info.samples = member;
}

}  // namespace

std::optional<std::string> options_violation(const BalancedSampling& s) {
  if (s.samples_per_sheet < 1 || s.samples_per_sheet > 100000)
    return fmt::format("samples per sheet must be in 1 .. 100000 (got {})", s.samples_per_sheet);
  return std::nullopt;
}

int balanced_grid_size(int n, const BalancedSampling& sampling) {
  const int free = n - 2;
  return free <= 0 ? 1 : std::max(2, int(std::lround(std::pow(double(sampling.samples_per_sheet), 1.0 / free))));
}

double balanced_grid_points(int n, const BalancedSampling& sampling) {
  return n <= 2 ? 2.0 : 2 * std::pow(double(balanced_grid_size(n, sampling)), n - 2);
}

bool balanced_set_exists(const ParamsN& p) {
  const Problem f = problem_of(p);
  const ld tol = kInputRounding * (f.capacity + f.U);
  ld largest = f.U;
  for (int i = 0; i < f.n; ++i) largest = std::max(largest, f.a[std::size_t(i)]);
  return largest <= (f.U + f.capacity) / 2 + tol;
}

TangentBasis balanced_tangent_basis(const ParamsN& p, const Coordinates<ld, any_balls>& s) {
  const int n = p.n_balls();
  // G^T (n x 2): columns (a_j cos beta_j) and (a_j sin beta_j); the trailing columns of
  // its full Q span null(G), the directions that keep W = 0 to first order.
  using Tall = Eigen::Matrix<ld, Eigen::Dynamic, 2, Eigen::ColMajor, max_balls, 2>;
  using Square = Eigen::Matrix<ld, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, max_balls, max_balls>;
  Tall g(n, 2);
  ld scale = 0;
  for (int j = 0; j < n; ++j) {
    const auto& b = p.balls[std::size_t(j)];
    const ld a = ld(b.mass) * ld(b.race_radius);
    g(j, 0) = a * std::cos(s(2 + j));
    g(j, 1) = a * std::sin(s(2 + j));
    scale = std::max(scale, a);
  }
  Eigen::ColPivHouseholderQR<Tall> qr(g / scale);
  qr.setThreshold(std::sqrt(kInputRounding));  // collinear balls: rank 1, one more direction
  const int rank = int(qr.rank());
  const Square Q = qr.householderQ() * Square::Identity(n, n);
  TangentBasis V = TangentBasis::Zero(n + 2, n - rank);
  V.bottomRows(n) = Q.rightCols(n - rank);
  return V;
}

std::string pattern_string(unsigned pattern, int n_balls) {
  std::string s(std::size_t(n_balls), '+');
  for (int i = 0; i < n_balls; ++i)
    if (pattern >> i & 1u) s[std::size_t(i)] = '-';
  return s;
}

void find_equilibria(const ParamsN& p, const BalancedSampling& sampling, EquilibriumSetN& set) {
  const Problem f = problem_of(p);
  set.list.clear();  // (keeps its capacity: a reused set does not allocate again)
  set.degeneracy = degeneracy_none;
  set.balanced_set = BalancedSetSummary{};
  add_balanced_samples(p, f, sampling, set);
  add_aligned(p, f, set);
}

EquilibriumSetN find_equilibria(const ParamsN& p, const BalancedSampling& sampling) {
  EquilibriumSetN set;
  find_equilibria(p, sampling, set);
  return set;
}

}  // namespace abu
