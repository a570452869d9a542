// An aligned equilibrium of equal balls from a two-ball pencil and the relative modes of
// each side (aligned_reduced.hpp; model.md §13.10).
#include "abu/linear/aligned_reduced.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "abu/linear/characteristic.hpp"
#include "abu/model/friction.hpp"
#include "spectrum_starts.hpp"

namespace abu {

namespace {

using ld = long double;
constexpr ld kEpsLong = std::numeric_limits<ld>::epsilon() / 2;
constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;

// The premise of (13.10.1), checked on the linearization itself: the ball blocks of A, D, E
// diagonal, and every ball of a side with its side's first ball's rows (to 1e-12 of the
// largest entry of the row: the polished angles of one side agree to ~1e-18).
bool sides_alike(const AlignedReduction& r, const Linearization<ld, any_balls>& lin, const EquilibriumN& e) {
  const int n = int(lin.mass.rows()) - 2;
  for (const auto* m : {&lin.mass, &lin.damping, &lin.stiffness}) {
    for (int i = 0; i < n; ++i) {
      // (every ball on one side: all compared with ball 1)
      const int b = ((e.pattern >> i) & 1u) ? r.first[1] : 0;
      const ld scale = std::max({std::abs((*m)(2 + b, 0)), std::abs((*m)(2 + b, 1)), std::abs((*m)(2 + b, 2 + b))});
      for (int c = 0; c < 2; ++c)
        if (std::abs((*m)(2 + i, c) - (*m)(2 + b, c)) > 1e-12L * scale ||
            std::abs((*m)(c, 2 + i) - (*m)(c, 2 + b)) > 1e-12L * scale)
          return false;
      if (std::abs((*m)(2 + i, 2 + i) - (*m)(2 + b, 2 + b)) > 1e-12L * scale) return false;
      for (int j = 0; j < n; ++j)
        if (j != i && (*m)(2 + i, 2 + j) != 0) return false;
    }
  }
  return true;
}

// The two-ball pencil of the sides' common modes (13.10.1), the side's first ball standing for it.
Linearization<ld, 2> sides_pencil(const AlignedReduction& r, const Linearization<ld, any_balls>& lin) {
  Linearization<ld, 2> out;
  const std::array<ld, 2> t{std::sqrt(ld(r.size[0])), std::sqrt(ld(r.size[1]))};
  const auto reduce = [&](const DofMatrix<ld, any_balls>& m, DofMatrix<ld, 2>& o) {
    o.setZero();
    o.topLeftCorner(2, 2) = m.topLeftCorner(2, 2);
    for (std::size_t s = 0; s < 2; ++s) {
      const int b = 2 + r.first[s], k = 2 + int(s);
      for (int i = 0; i < 2; ++i) {
        o(i, k) = t[s] * m(i, b);
        o(k, i) = t[s] * m(b, i);
      }
      o(k, k) = m(b, b);
    }
  };
  reduce(lin.mass, out.mass);
  reduce(lin.damping, out.damping);
  reduce(lin.stiffness, out.stiffness);
  return out;
}

}  // namespace

AlignedReduction aligned_reduction(const ParamsN& p, const EquilibriumN& e) {
  return e.n_balls() == p.n_balls() && equal_smooth_balls(p) ? aligned_sides(e) : AlignedReduction{};
}

AlignedReduction aligned_sides(const EquilibriumN& e) {
  AlignedReduction r;
  const int n = e.n_balls();
  if (e.family == Family::balanced || e.on_balanced_set || !e.converged || e.structural_zeros != 0 || e.is_set)
    return r;
  const unsigned all = (1u << n) - 1;
  const unsigned minus = e.pattern & all;
  if (minus == 0) {
    // Every ball on one side: one ball and the other n - 1 as the pencil's two "sides".
    r.size = {1, n - 1};
    r.first = {0, 1};
  } else {
    const int k2 = std::popcount(minus);
    r.size = {n - k2, k2};
    r.first = {0, std::countr_zero(minus)};
  }
  r.applies = true;
  return r;
}

RelativeModes relative_modes(ld inertia, ld friction, ld stiffness) {
  RelativeModes m;
  const ld disc = friction * friction - 4 * inertia * stiffness;
  if (disc < 0) {
    const ld re = -friction / (2 * inertia), im = std::sqrt(-disc) / (2 * inertia);
    m.roots = {std::complex<double>(double(re), double(im)), std::complex<double>(double(re), -double(im))};
    m.n_unstable = re > 0 ? 2 : 0;
    m.clear = std::abs(re) > 1e-6L * std::hypot(re, im);
    return m;
  }
  // Real roots, the smaller in modulus from the product (no cancellation).
  const ld big = (-friction - std::copysign(std::sqrt(disc), friction)) / (2 * inertia);
  const ld small = big != 0 ? stiffness / (inertia * big) : ld(0);
  m.roots = {std::complex<double>(double(big)), std::complex<double>(double(small))};
  m.n_unstable = (big > 0) + (small > 0);
  m.clear = big != 0 && small != 0;
  return m;
}

AlignedPencil aligned_pencil(const AlignedReduction& r, const Linearization<ld, any_balls>& lin, const EquilibriumN& e) {
  AlignedPencil a;
  if (!r.applies || !sides_alike(r, lin, e)) return a;
  a.free = friction_free(sides_pencil(r, lin));
  a.split = friction_split(a.free);
  for (std::size_t s = 0; s < 2; ++s) {
    const int b = 2 + r.first[s];
    a.copies[s] = r.size[s] - 1;
    a.inertia[s] = lin.mass(b, b);
    a.stiffness[s] = lin.stiffness(b, b);
  }
  a.applies = true;
  return a;
}

std::array<ld, 2> side_friction(const ParamsT<ld, any_balls>& pl, const AlignedReduction& r) {
  std::array<ld, 2> friction{};
  for (std::size_t s = 0; s < 2; ++s) {
    const int b = r.first[s];
    friction[s] = -pl.balls[std::size_t(b)].race_radius * friction_slope(pl, b, ld(0));
  }
  return friction;
}

AlignedVerdict aligned_verdict(const AlignedPencil& a, const std::array<ld, 2>& friction, std::complex<double>& rightmost,
                               bool& tracked) {
  AlignedVerdict out;
  if (!a.applies) return out;
  double abscissa = -HUGE_VAL;
  int unstable = 0;
  for (std::size_t s = 0; s < 2; ++s) {
    if (a.copies[s] == 0) continue;
    const RelativeModes m = relative_modes(a.inertia[s], friction[s], a.stiffness[s]);
    if (!m.clear) return out;
    unstable += a.copies[s] * m.n_unstable;
    abscissa = std::max({abscissa, m.roots[0].real(), m.roots[1].real()});
  }
  Linearization<ld, 2> pencil = a.free;
  pencil.damping(2, 2) = friction[0];
  pencil.damping(3, 3) = friction[1];
  const Polynomial poly = tracked ? to_double(combine_long(a.split, friction[0], friction[1])) : Polynomial{};
  NormalVerdict v = pencil_verdict(poly, pencil, rightmost, tracked);
  v.n_unstable += unstable;
  v.abscissa = std::max(v.abscissa, abscissa);
  if (v.n_unstable > 0) v.stability = Stability::unstable;
  out.verdict = v;
  out.decided = true;
  return out;
}

SpectrumN aligned_spectrum(const AlignedPencil& a, const AlignedReduction& r, const std::array<ld, 2>& friction,
                           const EquilibriumN& e) {
  const int n = e.n_balls(), d = n + 2;
  Linearization<ld, 2> pencil = a.free;
  pencil.damping(2, 2) = friction[0];
  pencil.damping(3, 3) = friction[1];
  const Spectrum reduced = compute_spectrum(pencil, SpectrumMethod::refined, 0);
  SpectrumN sp = spectrum_of_reduction(reduced, n);
  std::array<ld, SpectrumN::capacity> band{};
  // The balls of each side (every ball on one side: ball 1, then the others).
  std::array<std::array<int, max_balls>, 2> side{};
  std::array<int, 2> count{};
  for (int i = 0; i < n; ++i) {
    const std::size_t s = r.size[0] == 1 && e.pattern == 0 ? (i == 0 ? 0 : 1) : ((e.pattern >> i) & 1u);
    side[s][std::size_t(count[s]++)] = i;
  }
  std::size_t slot = 0;
  for (std::size_t k = 0; k < 8; ++k, ++slot) {
    put_reduced_eigenvalue(reduced, k, slot, sp, band);
    const auto& x = reduced.vectors[k];
    QepVector<any_balls> v(d);
    v(0) = x(0);
    v(1) = x(1);
    for (std::size_t s = 0; s < 2; ++s)
      for (int j = 0; j < count[s]; ++j) v(2 + side[s][std::size_t(j)]) = x(2 + int(s)) / std::sqrt(double(count[s]));
    sp.vectors[slot] = v.normalized();
  }
  for (std::size_t s = 0; s < 2; ++s) {
    if (a.copies[s] == 0) continue;
    const RelativeModes m = relative_modes(a.inertia[s], friction[s], a.stiffness[s]);
    for (const auto root : m.roots) {
      const std::complex<ld> l(root.real(), root.imag());
      const ld size = a.inertia[s] * std::norm(l) + std::abs(friction[s]) * std::abs(l) + std::abs(a.stiffness[s]);
      const ld slope = std::abs(std::complex<ld>(2 * a.inertia[s]) * l + std::complex<ld>(friction[s]));
      const ld condition = std::abs(l) > 0 && slope > 0 ? size / (std::abs(l) * slope) : std::numeric_limits<ld>::infinity();
      for (int c = 1; c < count[s]; ++c, ++slot) {
        sp.eigenvalues[slot] = root;
        sp.condition[slot] = double(condition);
        sp.error[slot] = double(4 * condition * std::abs(l) * kEpsLong);
        band[slot] = 8 * condition * std::abs(l) * (kEpsLong + ld(kEps));
        QepVector<any_balls> v = QepVector<any_balls>::Zero(d);
        v(2 + side[s][0]) = 1;
        v(2 + side[s][std::size_t(c)]) = -1;
        sp.vectors[slot] = v.normalized();
      }
    }
  }
  spectrum_detail::finish_spectrum(sp, band, 0);
  return sp;
}

}  // namespace abu
