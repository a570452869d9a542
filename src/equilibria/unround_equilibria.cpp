// model.md §11.4: every equilibrium on an unround race (see the header for the method).
#include "abu/equilibria/unround_equilibria.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/equilibria/equilibria_n.hpp"

namespace abu {

namespace {
using L = long double;
using Angles = UnroundAngles;
using AngleMatrix = UnroundAngleMatrix;
constexpr L kTwoPi = 2 * std::numbers::pi_v<L>;

const RaceHarmonics& harmonics_of(const RaceShape& race, int i) {
  static const RaceHarmonics round;
  return std::size_t(i) < race.balls.size() ? race.balls[std::size_t(i)] : round;
}

// g(beta), q(beta) and dg/dbeta (§11.4; g_i scaled by 1/l_i^2).
}  // namespace

UnroundReduced unround_reduced(const LongParamsN& p, const RaceShape& race, const Angles& beta) {
  const int n = p.n_balls();
  const L w2 = p.omega * p.omega;
  const std::complex<L> dyn(p.rotor.stiffness - w2 * p.total_mass(), p.rotor.damping * p.omega);
  std::array<PathPoint<L>, max_balls> pts{};
  std::complex<L> W(p.rotor.unbalance, 0);
  for (int i = 0; i < n; ++i) {
    const auto k = std::size_t(i);
    pts[k] = path_point<L>(harmonics_of(race, i), p.balls[k].race_radius, beta(i));
    W += p.balls[k].mass * pts[k].ell * std::polar(L(1), beta(i));
  }
  UnroundReduced r;
  r.q = w2 * W / dyn;
  r.g.resize(n);
  r.dg.resize(n, n);
  for (int i = 0; i < n; ++i) {
    const auto& pt = pts[std::size_t(i)];
    const L l2 = p.balls[std::size_t(i)].race_radius * p.balls[std::size_t(i)].race_radius;
    const L c = std::cos(beta(i)), s = std::sin(beta(i));
    const L x = r.q.real() + pt.ell * c, y = r.q.imag() + pt.ell * s;  // q + p_i
    r.g(i) = (pt.u * x + pt.v * y) / l2;
    for (int j = 0; j < n; ++j) {
      const auto& pj = pts[std::size_t(j)];
      const std::complex<L> dq = w2 * p.balls[std::size_t(j)].mass * std::complex<L>(pj.u, pj.v) / dyn;
      r.dg(i, j) = (pt.u * dq.real() + pt.v * dq.imag()) / l2;
    }
    r.dg(i, i) += (pt.du * x + pt.dv * y + pt.u * pt.u + pt.v * pt.v) / l2;
  }
  return r;
}

namespace {
UnroundReduced reduced(const LongParamsN& p, const RaceShape& race, const Angles& beta) {
  return unround_reduced(p, race, beta);
}

L wrap(L a) {
  a = std::fmod(a, kTwoPi);
  return a < 0 ? a + kTwoPi : a;
}
L torus_distance(const Angles& a, const Angles& b) {
  L d = 0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    L x = std::abs(wrap(a(i) - b(i)));
    d = std::max(d, std::min(x, kTwoPi - x));
  }
  return d;
}

// Newton with step halving on |g|; nullopt if it does not converge in 200 iterations.
std::optional<Angles> newton(const LongParamsN& p, const RaceShape& race, Angles beta) {
  UnroundReduced r = reduced(p, race, beta);
  for (int it = 0; it < 200; ++it) {
    const Eigen::FullPivLU<AngleMatrix> lu(r.dg);
    if (lu.rank() < r.dg.rows()) return std::nullopt;
    const Angles step = lu.solve(r.g);
    if (!step.allFinite()) return std::nullopt;
    L t = 1;
    const L norm0 = r.g.norm();
    for (int h = 0; h < 30; ++h, t /= 2) {
      Angles trial = beta - t * step;
      UnroundReduced rt = reduced(p, race, trial);
      if (rt.g.norm() < norm0 || h == 29 || norm0 < 1e-17L) {
        beta = trial;
        r = std::move(rt);
        break;
      }
    }
    if (step.cwiseAbs().maxCoeff() * t < 1e-15L || r.g.norm() < 1e-19L) {
      for (Eigen::Index i = 0; i < beta.size(); ++i) beta(i) = wrap(beta(i));
      return beta;
    }
  }
  return std::nullopt;
}

// Bounds of |p|, |p'|, |p''| over all angles, from the amplitudes and orders (§11.4's
// exclusion test): E = offset circle, H = 1 + sum_{k >= 2} eps_k cos(...).
struct PathBounds {
  L p0 = 0, p1 = 0, p2 = 0;  // |p| = l, |p'|, |p''|
  L d1 = 0, d2 = 0;          // |l'|, |l''|
};
PathBounds path_bounds(const RaceHarmonics& h, L l) {
  L e0 = l, e1 = 0, e2 = 0, h0 = 1, h1 = 0, h2 = 0;
  for (const auto& x : h) {
    const L eps = std::abs(L(x.amplitude));
    if (x.order == 1) {
      const L d = l * eps, smin = std::sqrt(l * l - d * d);
      e0 = l + d;
      e1 = d + d * d / smin;
      e2 = d + d * d / smin + d * d * d * d / (smin * smin * smin);
    } else {
      const L k = L(x.order);
      h0 += eps, h1 += k * eps, h2 += k * k * eps;
    }
  }
  const L ell = e0 * h0, d1 = e1 * h0 + e0 * h1, d2 = e2 * h0 + 2 * e1 * h1 + e0 * h2;
  return {ell, std::sqrt(ell * ell + d1 * d1), d2 + ell + 2 * d1, d1, d2};
}

struct Box {
  Angles centre;
  L half;
};

}  // namespace

Coordinates<long double, any_balls> unround_rotor_and_residual(const LongParamsN& p, const RaceShape& race,
                                                               const Angles& beta, Angles& g) {
  const UnroundReduced r = reduced(p, race, beta);
  g = r.g;
  Coordinates<L, any_balls> s(beta.size() + 2);
  s(0) = r.q.real();
  s(1) = r.q.imag();
  s.tail(beta.size()) = beta;
  return s;
}

UnroundRoot unround_root_at(const LongParamsN& p, const RaceShape& race, const Angles& beta) {
  const int n = p.n_balls();
  const L w2 = p.omega * p.omega;
  const L dyn = std::hypot(p.rotor.stiffness - w2 * p.total_mass(), p.rotor.damping * p.omega);
  // The rotor row's natural size: the largest centrifugal load the balls and U can make.
  L load = p.rotor.unbalance;
  for (int i = 0; i < n; ++i)
    load += p.balls[std::size_t(i)].mass * path_bounds(harmonics_of(race, i), p.balls[std::size_t(i)].race_radius).p0;
  UnroundRoot e;
  const UnroundReduced r = reduced(p, race, beta);
  Angles g;
  e.position = unround_rotor_and_residual(p, race, beta, g);
  e.converged = true;
  e.amplitude = double(std::abs(r.q));
  const Eigen::FullPivLU<AngleMatrix> lu(r.dg);
  const L det = lu.determinant();
  const L scale = std::pow(r.dg.cwiseAbs().maxCoeff(), L(n));
  e.index = std::abs(det) <= 1e-13L * scale ? 0 : (det > 0 ? 1 : -1);
  // Residual of the full static equations b(s, 0) = 0 (§11.3), each row over its size.
  const Coordinates<L, any_balls> b = unround_generalized_forces(p, race, at_rest<L, any_balls>(e.position));
  L res = std::abs(b(0)) + std::abs(b(1));
  res /= w2 * (p.rotor.unbalance + load) + dyn * std::abs(r.q) + 1e-300L;
  for (int i = 0; i < n; ++i) {
    const auto& ball = p.balls[std::size_t(i)];
    res = std::max(res, std::abs(b(2 + i)) / (ball.mass * w2 * ball.race_radius * ball.race_radius));
  }
  e.residual = double(res);
  return e;
}

namespace {
// §11.4's exclusion box search on T^n (n = 2, 3): the zeros of g, every one (see the header).
std::vector<Angles> box_search(const LongParamsN& p, const RaceShape& race, const UnroundSearch& search,
                               UnroundRoots& result) {
  const int n = p.n_balls();
  const L w2 = p.omega * p.omega;
  const L dyn = std::hypot(p.rotor.stiffness - w2 * p.total_mass(), p.rotor.damping * p.omega);
  // Lipschitz bounds G_ij of g_i in beta_j (scaled by 1/l_i^2), valid on the whole torus.
  std::vector<PathBounds> pb(static_cast<std::size_t>(n));
  L qmax = p.rotor.unbalance;
  for (int i = 0; i < n; ++i) {
    pb[std::size_t(i)] = path_bounds(harmonics_of(race, i), p.balls[std::size_t(i)].race_radius);
    qmax += p.balls[std::size_t(i)].mass * pb[std::size_t(i)].p0;
  }
  qmax *= w2 / dyn;
  // g_i = l_i l_i' + u_i q1 + v_i q2 (the identity Re(conj(p') p) = l l' removes the
  // O(l^2) terms that cancel), so dg_i/dbeta_i = l'^2 + l l'' + u' q1 + v' q2 + p_i'.dq/dbeta_i
  // and dg_i/dbeta_j = p_i'.dq/dbeta_j, with |dq/dbeta_j| <= omega^2 m_j |p_j'| / |K + iC|.
  AngleMatrix G(n, n);
  for (int i = 0; i < n; ++i) {
    const auto& b = pb[std::size_t(i)];
    const L l2 = p.balls[std::size_t(i)].race_radius * p.balls[std::size_t(i)].race_radius;
    for (int j = 0; j < n; ++j) {
      const L dq = w2 * p.balls[std::size_t(j)].mass * pb[std::size_t(j)].p1 / dyn;
      G(i, j) = b.p1 * dq / l2;
    }
    G(i, i) += (b.d1 * b.d1 + b.p0 * b.d2 + b.p2 * qmax) / l2;
  }
  const Angles row_sum = G.rowwise().sum() * (1 + 1e-9L);

  const int kmax = std::max(1, race.max_order());
  const int start = search.start_boxes > 0 ? search.start_boxes : 8 * (kmax + 1);
  const int leaf = search.leaf_boxes > 0 ? search.leaf_boxes : (n == 2 ? 512 : 128);
  const L leaf_half = kTwoPi / L(std::max(leaf, start)) / 2;

  std::vector<Box> level;
  {
    long long total = 1;
    for (int i = 0; i < n; ++i) total *= start;
    level.reserve(std::size_t(total));
    for (long long c = 0; c < total; ++c) {
      Box b{Angles(n), kTwoPi / L(start) / 2};
      long long rest = c;
      for (int i = 0; i < n; ++i, rest /= start) b.centre(i) = (L(rest % start) + 0.5L) * kTwoPi / L(start);
      level.push_back(b);
    }
  }
  std::vector<Box> leaves;
  while (!level.empty()) {
    throw_if_stopped("unround equilibria: box search");
    std::vector<Box> next;
    for (const Box& b : level) {
      ++result.search.boxes_tested;
      const Angles g = reduced(p, race, b.centre).g;
      bool excluded = false;
      for (int i = 0; i < n && !excluded; ++i) excluded = std::abs(g(i)) > b.half * row_sum(i);
      if (excluded) continue;
      if (b.half <= leaf_half * (1 + 1e-9L)) {
        leaves.push_back(b);
        continue;
      }
      for (int c = 0; c < (1 << n); ++c) {
        Box child{b.centre, b.half / 2};
        for (int i = 0; i < n; ++i) child.centre(i) += ((c >> i) & 1 ? 1 : -1) * child.half;
        next.push_back(child);
      }
      if (std::ssize(next) + std::ssize(leaves) > search.max_leaves) break;
    }
    if (std::ssize(next) + std::ssize(leaves) > search.max_leaves) {
      result.search.budget_exhausted = true;
      leaves.insert(leaves.end(), next.begin(), next.end());
      break;
    }
    level = std::move(next);
  }

  // Newton from every leaf; a leaf whose Newton fails is unresolved.
  // A leaf whose Newton fails (it stalls at a minimum of |g| that is not a zero) is
  // halved again, up to 1/64 of the leaf width, and its children tested and started
  // afresh; only what remains then is unresolved.
  std::vector<Angles> zeros;
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    if (k % 4096 == 0) throw_if_stopped("unround equilibria: Newton starts");
    const auto z = newton(p, race, leaves[k].centre);
    if (!z) {
      const Box b = leaves[k];
      if (b.half > leaf_half / 64 && std::ssize(leaves) < search.max_leaves) {
        for (int c = 0; c < (1 << n); ++c) {
          Box child{b.centre, b.half / 2};
          for (int i = 0; i < n; ++i) child.centre(i) += ((c >> i) & 1 ? 1 : -1) * child.half;
          ++result.search.boxes_tested;
          const Angles g = reduced(p, race, child.centre).g;
          bool excluded = false;
          for (int i = 0; i < n && !excluded; ++i) excluded = std::abs(g(i)) > child.half * row_sum(i);
          if (!excluded) leaves.push_back(child);
        }
      } else {
        ++result.search.unresolved;
      }
      continue;
    }
    // A Newton that leaves its box is no doubt: the bound (11.4.5) is global and keeps
    // boxes some way from any zero; every zero's own leaf lies within h sqrt(n) of it.
    const bool known = std::any_of(zeros.begin(), zeros.end(), [&](const Angles& a) {
      return torus_distance(a, *z) < 1e-9L;
    });
    if (!known) zeros.push_back(*z);
  }

  result.search.leaves = std::ssize(leaves);
  return zeros;
}

// n >= 4 (model.md §11.11): Newton from the round race's equilibria (its aligned patterns
// and the samples of its balanced set, whose isolated survivors lie near them for small
// unroundness) and from search.multistart quasi-random points of T^n (Halton). Not
// proven complete: the result says so.
std::vector<Angles> multistart(const LongParamsN& p, const RaceShape& race, const UnroundSearch& search,
                               UnroundRoots& result) {
  const int n = p.n_balls();
  std::vector<Angles> starts;
  for (const auto& e : find_equilibria(p.cast<double>()).list) starts.push_back(e.position.tail(n).cast<L>());
  static constexpr std::array<int, max_balls> primes{2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  for (int k = 1; k <= search.multistart; ++k) {
    Angles a(n);
    for (int i = 0; i < n; ++i) {
      // The radical inverse of k in base primes[i], in [0, 1).
      L f = 1, x = 0;
      for (int m = k; m > 0; m /= primes[std::size_t(i)]) {
        f /= primes[std::size_t(i)];
        x += f * (m % primes[std::size_t(i)]);
      }
      a(i) = x * kTwoPi;
    }
    starts.push_back(a);
  }
  std::vector<Angles> zeros;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    if (k % 1024 == 0) throw_if_stopped("unround equilibria: multistart");
    const auto z = newton(p, race, starts[k]);
    if (!z) {
      ++result.search.unresolved;
      continue;
    }
    if (std::none_of(zeros.begin(), zeros.end(), [&](const Angles& a) { return torus_distance(a, *z) < 1e-9L; }))
      zeros.push_back(*z);
  }
  result.search.leaves = std::ssize(starts);
  return zeros;
}
}  // namespace

UnroundRoots find_unround_roots(const ParamsN& pd, const RaceShape& race, const UnroundSearch& search) {
  const int n = pd.n_balls();
  const LongParamsN p = pd.cast<L>();
  const L w2 = p.omega * p.omega;
  const L dyn = std::hypot(p.rotor.stiffness - w2 * p.total_mass(), p.rotor.damping * p.omega);
  if (!(dyn > 0))
    throw NumericalError(fmt::format("omega={}: K = C = 0 (c = 0 at omega = omega_n): q is not determined by the "
                                     "balls (model.md §11.4)",
                                     pd.omega));

  UnroundRoots result;
  const std::vector<Angles> zeros = n <= 3 ? box_search(p, race, search, result) : multistart(p, race, search, result);
  for (const Angles& beta : zeros) {
    UnroundRoot e = unround_root_at(p, race, beta);
    result.search.index_sum += e.index;
    result.list.push_back(std::move(e));
  }
  std::sort(result.list.begin(), result.list.end(), [](const UnroundRoot& a, const UnroundRoot& b) {
    if (a.amplitude != b.amplitude) return a.amplitude < b.amplitude;
    for (Eigen::Index i = 2; i < a.position.size(); ++i)
      if (a.position(i) != b.position(i)) return a.position(i) < b.position(i);
    return false;
  });
  if (n > 3)
    result.doubt = fmt::format("not proven complete: with {} balls the equilibria come from Newton at the round race's "
                               "equilibria and {} quasi-random starts, not from the box search of model.md §11.4 "
                               "(n = 2, 3); {} starts did not converge, index sum {}",
                               n, search.multistart, result.search.unresolved, result.search.index_sum);
  else if (result.search.budget_exhausted)
    result.doubt = (fmt::format("the box search stopped at {} leaves: equilibria may be missing",
                                               search.max_leaves));
  else if (result.search.unresolved > 0 || result.search.index_sum != 0)
    result.doubt = (fmt::format("{} of {} leaves did not lead to a nearby equilibrium; index sum {} "
                                               "(0 when complete): equilibria may be missing or degenerate",
                                               result.search.unresolved, result.search.leaves,
                                               result.search.index_sum));
  return result;
}

}  // namespace abu
