// The balanced set's normal spectrum for equal balls from the reduced problem in g
// (balanced_reduced.hpp; model.md §13.9).
#include "abu/linear/balanced_reduced.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "abu/equilibria/ball_permutations.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/characteristic.hpp"
#include "abu/model/friction.hpp"
#include "spectrum_starts.hpp"

namespace abu {

namespace {

using ld = long double;
using cld = std::complex<ld>;
constexpr ld kEpsLong = std::numeric_limits<ld>::epsilon() / 2;
constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;
// balanced_tangent_basis's rank threshold, sqrt(8 eps_double): its QR calls the balls
// collinear below it.
constexpr ld kRankThreshold = 4.3e-8L;

}  // namespace

bool equal_smooth_balls(const ParamsN& p) {
  const bool smooth = p.law == FrictionLaw::none || p.law == FrictionLaw::viscous || p.law == FrictionLaw::coulomb ||
                      p.law == FrictionLaw::stribeck;
  return p.n_balls() >= 3 && smooth && ball_kinds(p).all_equal;
}

BalancedReduction balanced_reduction(const ParamsN& p) {
  BalancedReduction r;
  r.n = p.n_balls();
  if (!equal_smooth_balls(p)) return r;
  const auto pl = p.cast<ld>();
  const auto& b = pl.balls[0];
  r.total_mass = pl.total_mass();
  r.stiffness = pl.rotor.stiffness;
  r.damping = pl.rotor.damping;
  r.omega = pl.omega;
  r.capacity = b.mass * b.race_radius;
  // As the linearization forms them (model.cpp): A(2+i, 2+i), C(2+i, 2+i).
  r.inertia = b.inertia_factor * r.capacity * b.race_radius;
  r.friction = -b.race_radius * friction_slope(pl, 0, ld(0));
  // compute_normal_spectrum's level: ||C V_T||_F <= 64 eps_ld ||C||_F, with
  // ||C V_T||_F = gamma sqrt(n - 2) on the set and ||C||_F independent of the angles:
  // 2 c^2 + 2 (2 M omega)^2 + 2 n (2 omega a)^2 + n gamma^2 (model.md (6.4)).
  const ld w = r.omega, a = r.capacity;
  const ld c_norm = std::sqrt(2 * r.damping * r.damping + 8 * r.total_mass * r.total_mass * w * w +
                              8 * ld(r.n) * w * w * a * a + ld(r.n) * r.friction * r.friction);
  const ld cv = std::abs(r.friction) * std::sqrt(ld(r.n - 2));
  const ld threshold = 64 * kEpsLong * c_norm;
  // Near the threshold rounding of the full products decides: leave it to the full path.
  if (cv > threshold / 4 && cv < 4 * threshold) return r;
  r.level = cv <= threshold ? 2 : 1;
  r.applies = true;
  return r;
}

Arrangement arrangement_of(const Coordinates<ld, any_balls>& position) {
  cld z = 0;
  for (Eigen::Index i = 2; i < position.size(); ++i) z += std::polar(ld(1), 2 * position(i));
  return {std::abs(z), std::abs(z) > 0 ? std::arg(z) / 2 : ld(0)};
}

bool reducible(const BalancedReduction& r, const EquilibriumN& e) {
  return r.applies && e.on_balanced_set && reducible(r, e, arrangement_of(e.position).g);
}

bool reducible(const BalancedReduction& r, const EquilibriumN& e, ld g) {
  if (!r.applies || !e.on_balanced_set || !e.converged || e.n_balls() != r.n) return false;
  if (e.structural_zeros != r.n - 2 && e.structural_zeros != 2 * (r.n - 2)) return false;
  // The tangent basis has n - 2 directions: the smaller singular value of [a cos; a sin],
  // a sqrt((n - g)/2), well above the rank threshold relative to the larger.
  const ld n = ld(r.n);
  return std::sqrt(std::max(n - g, ld(0)) / (n + g)) > 16 * kRankThreshold;
}

Linearization<ld, 2> reduced_linearization(const BalancedReduction& r, ld g) {
  // (13.9.6): balls of capacities a s1 at angle 0 and a s2 at pi/2 on a rotor of mass M.
  const ld n = ld(r.n), w = r.omega, M = r.total_mass, a = r.capacity;
  const ld s1 = std::sqrt((n + g) / 2), s2 = std::sqrt(std::max(n - g, ld(0)) / 2);
  const ld a1 = a * s1, a2 = a * s2, K = r.stiffness - M * w * w, C = r.damping * w;
  Linearization<ld, 2> lin;
  lin.mass << M, 0, 0, -a2,  //
      0, M, a1, 0,           //
      0, a1, r.inertia, 0,   //
      -a2, 0, 0, r.inertia;
  lin.damping << r.damping, -2 * w * M, -2 * w * a1, 0,  //
      2 * w * M, r.damping, 0, -2 * w * a2,                //
      2 * w * a1, 0, r.friction, 0,                        //
      0, 2 * w * a2, 0, r.friction;
  lin.stiffness << K, -C, 0, w * w * a2,  //
      C, K, -w * w * a1, 0,               //
      0, -w * w * a1, 0, 0,               //
      w * w * a2, 0, 0, 0;
  return lin;
}

SpectrumN reduced_normal_spectrum(const BalancedReduction& r, const ParamsN& p, const EquilibriumN& e, bool vectors) {
  const Arrangement arr = arrangement_of(e.position);
  const Spectrum reduced = compute_spectrum(reduced_linearization(r, arr.g), SpectrumMethod::refined, 0);
  const int n = r.n, t = n - 2, d = n + 2;
  SpectrumN sp = spectrum_of_reduction(reduced, n);
  std::array<ld, SpectrumN::capacity> band{};
  TangentBasis V;
  if (vectors) V = balanced_tangent_basis(p, e.position);
  std::size_t slot = 0;
  for (int k = 0; k < r.level * t; ++k, ++slot) {  // the structural zeros, exactly 0
    sp.eigenvalues[slot] = 0;
    sp.structural[slot] = true;
    if (vectors) sp.vectors[slot] = V.col(k % t).cast<std::complex<double>>();
  }
  if (r.level == 1) {
    // -gamma / J0 on every tangent direction (13.9.3): relative condition 2 (T'(lambda) v =
    // -gamma v, y = x = v), error that of one long-double division.
    const ld lambda = -r.friction / r.inertia;
    for (int k = 0; k < t; ++k, ++slot) {
      sp.eigenvalues[slot] = double(lambda);
      sp.condition[slot] = 2;
      sp.error[slot] = double(2 * std::abs(lambda) * kEpsLong);
      band[slot] = 8 * 2 * std::abs(lambda) * (kEpsLong + ld(kEps));
      if (vectors) sp.vectors[slot] = V.col(k).cast<std::complex<double>>();
    }
  }
  // The 8 reduced eigenvalues; their vectors (q, u) in the turned frame back to (q, delta):
  // q and w = (s1 u1, s2 u2) turned by alpha, delta = [c s] G^-1 w (13.9.7).
  const ld nn = ld(n), s1 = std::sqrt((nn + arr.g) / 2), s2 = std::sqrt((nn - arr.g) / 2);
  const ld ca = std::cos(arr.alpha), sa = std::sin(arr.alpha);
  ld g11 = 0, g12 = 0, g22 = 0;
  if (vectors)
    for (int i = 0; i < n; ++i) {
      const ld c = std::cos(e.position(2 + i)), s = std::sin(e.position(2 + i));
      g11 += c * c, g12 += c * s, g22 += s * s;
    }
  const ld det = g11 * g22 - g12 * g12;
  for (std::size_t k = 0; k < 8; ++k, ++slot) {
    put_reduced_eigenvalue(reduced, k, slot, sp, band);
    if (!vectors) continue;
    const auto& x = reduced.vectors[k];
    using C = std::complex<ld>;
    const C q1(x(0).real(), x(0).imag()), q2(x(1).real(), x(1).imag());
    const C w1r = s1 * C(x(2).real(), x(2).imag()), w2r = s2 * C(x(3).real(), x(3).imag());
    const C w1 = ca * w1r - sa * w2r, w2 = sa * w1r + ca * w2r;
    const C t1 = (g22 * w1 - g12 * w2) / det, t2 = (g11 * w2 - g12 * w1) / det;
    QepVector<any_balls> s(d);
    s(0) = std::complex<double>(ca * q1 - sa * q2);
    s(1) = std::complex<double>(sa * q1 + ca * q2);
    for (int i = 0; i < n; ++i)
      s(2 + i) = std::complex<double>(t1 * std::cos(e.position(2 + i)) + t2 * std::sin(e.position(2 + i)));
    sp.vectors[slot] = s.normalized();
  }
  spectrum_detail::finish_spectrum(sp, band, 0);
  return sp;
}

SpectrumN spectrum_of_reduction(const Spectrum& reduced, int n_balls) {
  SpectrumN sp;
  sp.count = 2 * (n_balls + 2);
  sp.status = reduced.status;
  sp.converged = reduced.converged;
  sp.ill_conditioned = reduced.ill_conditioned;
  return sp;
}

void put_reduced_eigenvalue(const Spectrum& reduced, std::size_t k, std::size_t slot, SpectrumN& sp,
                            std::array<ld, SpectrumN::capacity>& band) {
  sp.eigenvalues[slot] = reduced.eigenvalues[k];
  sp.error[slot] = reduced.error[k];
  sp.condition[slot] = reduced.condition[k];
  band[slot] = reduced.on_axis[k] ? std::numeric_limits<ld>::infinity() : ld(0);
}

ReducedSplits reduced_splits(const BalancedReduction& r) {
  // The corners need s1^2 + s2^2 = n only for the physical g; the determinant is a
  // polynomial in s1^2, s2^2 whatever their sum: evaluate it on the pencil directly.
  ReducedSplits out;
  const ld X = ld(r.n) / 2;
  const std::array<std::array<ld, 2>, 4> at{{{0, 0}, {X, 0}, {0, X}, {X, X}}};
  for (std::size_t c = 0; c < 4; ++c) {
    Linearization<ld, 2> lin = reduced_linearization(r, 0);
    const ld s1 = std::sqrt(at[c][0]), s2 = std::sqrt(at[c][1]);
    const ld w = r.omega, a = r.capacity;
    lin.mass(0, 3) = lin.mass(3, 0) = -a * s2;
    lin.mass(1, 2) = lin.mass(2, 1) = a * s1;
    lin.damping(0, 2) = -2 * w * a * s1;
    lin.damping(2, 0) = 2 * w * a * s1;
    lin.damping(1, 3) = -2 * w * a * s2;
    lin.damping(3, 1) = 2 * w * a * s2;
    lin.stiffness(0, 3) = lin.stiffness(3, 0) = w * w * a * s2;
    lin.stiffness(1, 2) = lin.stiffness(2, 1) = -w * w * a * s1;
    out.corner[c] = friction_split(friction_free(lin));
  }
  return out;
}

ReducedPolynomials reduced_polynomials(const ReducedSplits& splits, const BalancedReduction& r) {
  ReducedPolynomials out;
  for (std::size_t c = 0; c < 4; ++c) out.corner[c] = combine_long(splits.corner[c], r.friction, r.friction);
  return out;
}

ReducedPolynomials reduced_polynomials(const BalancedReduction& r) { return reduced_polynomials(reduced_splits(r), r); }

Polynomial reduced_polynomial(const BalancedReduction& r, const ReducedPolynomials& corners, ld g) {
  // Bilinear interpolation in (x, y) = ((n + g)/2, (n - g)/2) between the corners, exact
  // for a bilinear function; |weights| <= 2, so the corners' bounds grow by at most 4.
  const ld n = ld(r.n), X = n / 2;
  const ld xi = (n + g) / 2 / X, eta = std::max(n - g, ld(0)) / 2 / X;
  const std::array<ld, 4> w{(1 - xi) * (1 - eta), xi * (1 - eta), (1 - xi) * eta, xi * eta};
  PolynomialLD p;
  for (std::size_t k = 0; k <= 8; ++k)
    for (std::size_t c = 0; c < 4; ++c) {
      const ld term = w[c] * corners.corner[c].c[k];
      p.c[k] += term;
      p.magnitude[k] += std::abs(w[c]) * corners.corner[c].magnitude[k] + std::abs(term);
    }
  return to_double(p);
}

NormalVerdict pencil_verdict(const Polynomial& poly, const Linearization<ld, 2>& lin, std::complex<double>& rightmost,
                             bool& tracked) {
  NormalVerdict v;
  if (tracked) {
    std::complex<double> z = rightmost;
    // Clear of the axis by 1e-6 of its modulus: a band that wide needs a condition number
    // 60 times the one flagged ill-conditioned (developers.md, Stability threshold).
    if (certified_abscissa(poly, z) && std::abs(z.real()) > 1e-6 * std::abs(z)) {
      RouthCount rc{true, 0};
      if (z.real() > 0) rc = routh_count(poly);
      if (rc.decided && (z.real() > 0) == (rc.n_unstable > 0)) {
        rightmost = z;
        v.n_unstable = rc.n_unstable;
        v.stability = rc.n_unstable > 0 ? Stability::unstable : Stability::stable;
        v.abscissa = z.real();
        return v;
      }
    }
  }
  const Spectrum sp = compute_spectrum(lin, SpectrumMethod::refined, 0);
  rightmost = sp.eigenvalues[0];
  tracked = true;
  v.n_unstable = sp.n_unstable;
  v.stability = sp.stability;
  v.abscissa = sp.abscissa;
  v.converged = sp.converged;
  return v;
}

NormalVerdict reduced_normal_verdict(const BalancedReduction& r, const ReducedPolynomials& corners, ld g,
                                     std::complex<double>& rightmost, bool& tracked) {
  const Polynomial poly = tracked ? reduced_polynomial(r, corners, g) : Polynomial{};
  NormalVerdict v = pencil_verdict(poly, reduced_linearization(r, g), rightmost, tracked);
  v.n_structural = r.level * (r.n - 2);
  if (r.level == 1) v.abscissa = std::max(v.abscissa, double(-r.friction / r.inertia));
  return v;
}

}  // namespace abu
