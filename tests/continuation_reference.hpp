// The references of the continuation tests (test_continuation.cpp,
// test_continuation_tracking.cpp), derived by hand (model.md §3, §5): the default scene and its
// viscous twin, the together family's folds in omega (a quadratic in omega^2), the balanced
// state's characteristic polynomial and its Hopf point (Newton on it in long double), and the
// checks a located Hopf point must pass.
#pragma once

#include <catch2/catch.hpp>

#include <gsl/gsl_errno.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/core/params.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"

// The observed margins (error against tolerance) go with each check's failure message;
// build with -DABU_SHOW_MARGINS to print them on every run.
#ifdef ABU_SHOW_MARGINS
#define MARGIN(msg) WARN(msg)
#else
#define MARGIN(msg) INFO(msg)
#endif

namespace continuation_reference {

using ld = long double;
using cld = std::complex<ld>;
using cd = std::complex<double>;
using abu::Family;
using abu::Label;
inline constexpr ld kPi = std::numbers::pi_v<ld>;

// The library's root finders are GSL's: report errors, never abort the test binary.
inline void quiet_gsl() {
  static const bool once = [] {
    gsl_set_error_handler_off();
    return true;
  }();
  (void)once;
}

// The default scene of model.md (coulomb friction); `viscous` gives its viscous twin.
inline abu::Params base_params(bool viscous = false) {
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = viscous ? abu::FrictionLaw::viscous : abu::FrictionLaw::coulomb;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, viscous ? 1e-4 : 0.0, 0.0, 0.0, 0.0};
  return p;
}

// M = M_r + m1 + m2, from the exact doubles, in long double.
inline ld total_mass(const abu::Params& p) { return ld(p.rotor.mass) + ld(p.balls[0].mass) + ld(p.balls[1].mass); }
// a = m1 l1 + m2 l2, the ball set's capacity, in long double.
inline ld capacity(const abu::Params& p) {
  return ld(p.balls[0].mass) * ld(p.balls[0].race_radius) + ld(p.balls[1].mass) * ld(p.balls[1].race_radius);
}
// omega_n = sqrt(k / M), in double as a scene would give it.
inline double omega_n(const abu::Params& p) { return std::sqrt(p.rotor.stiffness / p.total_mass()); }

inline abu::ParamRef param(const char* symbol) {
  const auto ref = abu::parse_param(symbol, 2);
  REQUIRE(ref.has_value());
  return *ref;
}

inline ld relative(ld x, ld expected) { return std::abs(x - expected) / std::abs(expected); }

// ---------------------------------------------------------------------------------------
// Folds of the together family in omega (model.md §5). Its angle solves
// K U sin b + C U cos b + C a = 0, i.e. U R sin(b + theta) = -C a with R = sqrt(K^2 + C^2):
// two roots while |C a| < U R, a double root (a fold) where C^2 a^2 = U^2 (K^2 + C^2).
// With x = omega^2, K = k - x M, C^2 = c^2 x this is the quadratic
//     M^2 x^2 + (c^2 (1 - a^2 / U^2) - 2 k M) x + k^2 = 0,
// whose roots multiply to (k / M)^2 = omega_n^4. The larger root from the formula without
// cancellation (B < 0 here), the smaller from the product.
inline std::vector<ld> together_fold_omegas(const abu::Params& p) {
  const ld M = total_mass(p), k = p.rotor.stiffness, c = p.rotor.damping, U = p.rotor.unbalance, a = capacity(p);
  const ld A = M * M, B = c * c * (1 - (a / U) * (a / U)) - 2 * k * M, C0 = k * k;
  const ld disc = B * B - 4 * A * C0;
  if (disc < 0 || B >= 0) return {};  // no real root, or both negative
  const ld x_big = (-B + std::sqrt(disc)) / (2 * A);
  const ld x_small = C0 / (A * x_big);
  return {std::sqrt(x_small), std::sqrt(x_big)};
}

// ---------------------------------------------------------------------------------------
// Characteristic polynomial of the balanced equilibrium (q = 0, equal balls at
// b_{1,2} = pi -+ phi, cos phi = U / 2ml), derived by hand from model.md §3:
//
// Linearize with q1 = Q1 e^{lt}, q2 = Q2 e^{lt}, db_i = b_i e^{lt} and z+- = q1 +- i q2.
// The rotor's complex equation gives, with P(l) = M (l + i w)^2 + c (l + i w) + k and
// Pt(l) = M (l - i w)^2 + c (l - i w) + k,
//     P  z+ =  i (w - i l)^2 sum_j m l e^{ i b_j} b_j = -i (l + i w)^2 sum_j m l e^{ i b_j} b_j,
//     Pt z- = -i (w + i l)^2 sum_j m l e^{-i b_j} b_j =  i (l - i w)^2 sum_j m l e^{-i b_j} b_j,
// the ball equation, with a = (l + i w)^2 z+ (and (l - i w)^2 z-) and the friction slope
// dF/db' = -rho m l (coulomb: rho = (2/pi) mu w^2 kappa; viscous: rho = d / m),
//     j m l l^2 b_i = -rho m l l b_i + (i m / 2) (a+ e^{-i b_i} - a- e^{i b_i}).
// Eliminating z+-, with G+- = (l +- i w)^4 / P (resp. Pt) and D = b_2 - b_1:
//     l (j l + rho) b_i = (m / 2) sum_j (G+ e^{i(b_j - b_i)} + G- e^{-i(b_j - b_i)}) b_j.
// The 2x2 determinant, times P Pt, is the degree-8 polynomial (s = l (j l + rho))
//     Phi(l) = s^2 P Pt - m s ((l + i w)^4 Pt + (l - i w)^4 P) + m^2 (l^2 + w^2)^4 sin^2 D,
// with sin^2 D = sin^2 (2 phi) = 4 cos^2 phi sin^2 phi. Its roots are the 8 eigenvalues.
struct BalancedScene {
  ld M, k, c, m, l, j, U, rho_over_w2 = 0, rho_viscous = 0;  // rho = rho_over_w2 w^2 + rho_viscous
};

inline BalancedScene balanced_scene(const abu::Params& p) {
  BalancedScene s{total_mass(p), p.rotor.stiffness, p.rotor.damping, p.balls[0].mass, p.balls[0].race_radius,
                  p.balls[0].inertia_factor, p.rotor.unbalance};
  if (p.law == abu::FrictionLaw::coulomb) s.rho_over_w2 = 2 / kPi * ld(p.balls[0].mu) * ld(p.kappa);
  if (p.law == abu::FrictionLaw::viscous) s.rho_viscous = ld(p.balls[0].d) / ld(p.balls[0].mass);
  return s;
}

inline cld balanced_characteristic(const BalancedScene& s, ld w, cld lambda) {
  const cld i(0, 1);
  const ld rho = s.rho_over_w2 * w * w + s.rho_viscous;
  const ld cos_phi = s.U / (2 * s.m * s.l), sin2_phi = (1 - cos_phi) * (1 + cos_phi);
  const ld sin2_D = 4 * cos_phi * cos_phi * sin2_phi;
  const cld up = lambda + i * w, dn = lambda - i * w;
  const cld P = s.M * up * up + s.c * up + s.k, Pt = s.M * dn * dn + s.c * dn + s.k;
  const cld sigma = lambda * (s.j * lambda + rho);
  const cld up2 = up * up, dn2 = dn * dn, l2w2 = lambda * lambda + w * w, l2w2_2 = l2w2 * l2w2;
  return sigma * sigma * P * Pt - s.m * sigma * (up2 * up2 * Pt + dn2 * dn2 * P) + s.m * s.m * l2w2_2 * l2w2_2 * sin2_D;
}

// The Hopf point (w, nu) of the balanced state: Phi(i nu; w) = 0, two real equations in
// two unknowns, by Newton in long double with central differences. Converged when the
// step is at the rounding level (relative 1e-15 of both unknowns).
struct HopfPoint {
  ld omega = 0, frequency = 0;
  bool converged = false;
};

inline HopfPoint balanced_hopf(const BalancedScene& s, ld omega_guess, ld frequency_guess) {
  HopfPoint h{omega_guess, frequency_guess};
  for (int it = 0; it < 60; ++it) {
    const cld F = balanced_characteristic(s, h.omega, cld(0, h.frequency));
    const ld hw = h.omega * 1e-9L, hn = h.frequency * 1e-7L;
    const cld Fw = (balanced_characteristic(s, h.omega + hw, cld(0, h.frequency)) -
                    balanced_characteristic(s, h.omega - hw, cld(0, h.frequency))) /
                   (2 * hw);
    const cld Fn = (balanced_characteristic(s, h.omega, cld(0, h.frequency + hn)) -
                    balanced_characteristic(s, h.omega, cld(0, h.frequency - hn))) /
                   (2 * hn);
    const ld det = Fw.real() * Fn.imag() - Fn.real() * Fw.imag();
    const ld dw = -(Fn.imag() * F.real() - Fn.real() * F.imag()) / det;
    const ld dn = -(Fw.real() * F.imag() - Fw.imag() * F.real()) / det;
    h.omega += dw;
    h.frequency += dn;
    if (std::abs(dw) <= 1e-15L * h.omega && std::abs(dn) <= 1e-15L * std::abs(h.frequency)) {
      h.converged = h.frequency > 0;
      return h;
    }
  }
  return h;
}

// The quasi-static limit of Phi (rho -> infinity, |lambda| << omega): the balls creep as
// db_i' = (m w^2 / rho) sum_j Re(H e^{i(b_j - b_i)}) b_j with H = w^2 / (K + i C), whose
// trace 2 (m w^2 / rho) Re H vanishes at K = 0 (omega = omega_n) with the frequency
// (m w^2 / rho) |H| |sin D| = pi m omega_n |sin D| / (2 mu kappa c) (coulomb).
inline ld quasi_static_hopf_frequency(const abu::Params& p) {
  const BalancedScene s = balanced_scene(p);
  const ld wn = std::sqrt(s.k / s.M);
  const ld cos_phi = s.U / (2 * s.m * s.l);
  const ld sin_D = 2 * cos_phi * std::sqrt((1 - cos_phi) * (1 + cos_phi));
  return kPi * s.m * wn * sin_D / (2 * ld(p.balls[0].mu) * ld(p.kappa) * s.c);
}

// The spectrum at a configuration and parameter values given in long double, linearized
// independently of the continuation (model.hpp's linearize, then spectrum.hpp).
inline abu::Spectrum spectrum_at(abu::ParamsT<ld, 2> p, const abu::Coordinates<ld, 2>& s) {
  return abu::compute_spectrum(abu::linearize(p, abu::at_rest<ld, 2>(s)));
}

inline cd nearest(const abu::Spectrum& sp, cd target) {
  cd best = sp.eigenvalues[0];
  for (const cd l : sp.eigenvalues)
    if (std::abs(l - target) < std::abs(best - target)) best = l;
  return best;
}

// A located Hopf point of the balanced state against the exact one (Newton on Phi) and
// against the spectrum recomputed at it.
inline void check_hopf_point(const abu::Params& p, const abu::SpecialPoint& sp, const HopfPoint& exact,
                             const char* tag) {
  // omega_HB to 1e-12: both sides solve their equations to long-double rounding (Phi's
  // terms cancel by ~1, K's by k / |K| ~ 1e8 at kappa = 1e6: 1e-19 * 1e8 = 1e-11 relative
  // in K, i.e. ~1e-19 in omega). omega_H to 1e-10: the program reports it in double;
  // Phi's root is good to ~1e-15.
  MARGIN(tag << ": omega_HB rel err vs Phi root " << double(relative(sp.parameter, exact.omega))
             << " (tol 1e-12), omega_H rel err " << double(relative(sp.frequency, exact.frequency))
             << " (tol 1e-10)");
  CHECK(relative(sp.parameter, exact.omega) <= 1e-12L);
  CHECK(relative(sp.frequency, exact.frequency) <= 1e-10L);
  // At the located point a pair sits on the imaginary axis: the augmented system makes
  // T(i omega_H) singular to long-double rounding; the recomputed eigenvalue carries the
  // refined spectrum's error (cond * backward error ~ 1e-16 relative to |lambda|). 1e-10.
  abu::ParamsT<ld, 2> pl = p.cast<ld>();
  pl.omega = sp.parameter;
  const abu::Spectrum s = spectrum_at(pl, sp.position);
  const cd up = nearest(s, cd(0, sp.frequency)), down = nearest(s, cd(0, -sp.frequency));
  MARGIN(tag << ": |Re lambda| / |lambda| = " << std::abs(up.real()) / std::abs(up) << " (tol 1e-10), Im rel err "
             << std::abs(up.imag() - sp.frequency) / sp.frequency);
  CHECK(std::abs(up.real()) <= 1e-10 * std::abs(up));
  CHECK(std::abs(up.imag() - sp.frequency) <= 1e-10 * sp.frequency);
  CHECK(std::abs(down - std::conj(up)) <= 1e-10 * std::abs(up));
  // The eigenvalue the special point reports is that pair's.
  CHECK(std::abs(sp.eigenvalue - up) <= 1e-10 * std::abs(up));
}

// Every number a branch reports is finite.
inline bool finite(const abu::BranchPoint& pt) {
  bool ok = std::isfinite(pt.parameter) && pt.position.allFinite() && std::isfinite(pt.tangent_parameter) &&
            std::isfinite(pt.branch_test);
  for (std::size_t k = 0; k < 8; ++k) {
    ok = ok && std::isfinite(pt.modes[k].real()) && std::isfinite(pt.modes[k].imag());
    ok = ok && std::isfinite(pt.spectrum.eigenvalues[k].real()) && std::isfinite(pt.spectrum.eigenvalues[k].imag());
  }
  return ok;
}

// Wrapped angle difference.
inline ld angle_difference(ld a, ld b) { return std::abs(std::remainder(a - b, 2 * kPi)); }

}  // namespace continuation_reference
