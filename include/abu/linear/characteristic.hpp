// Stability from the characteristic polynomial P(lambda) = det(lambda^2 A + lambda C + K)
// of the second-order linearization (degree 8 for two balls): the fast path of the maps.
//
//  - the coefficients are computed in long double by expanding the 4x4 determinant of
//    quadratic polynomials (Leibniz), each with the sum of the magnitudes of its terms,
//    which bounds its rounding error;
//  - the Routh array (equivalent to the Routh-Hurwitz / Lienard-Chipart conditions: the
//    number of sign changes in its first column is the number of roots with Re > 0) is
//    computed with a running bound on the error of every entry; a first-column entry
//    within its bound of zero leaves the decision open, and the caller falls back to the
//    full eigenvalues (spectrum.hpp): that is "close to the stability boundary";
//  - the spectral abscissa: the rightmost root of a neighbouring cell is followed by
//    Newton and certified as rightmost by the Routh count of the shifted polynomial
//    P(mu + alpha'), alpha' just right of it, being zero (no root further right).
//
// Friction enters the linearization at an equilibrium only through the two ball entries
// C(2+i, 2+i) = s_i of the damping matrix (model.md §4: F_i(0) = 0, so equilibria do not
// move). The determinant is affine in each of those entries, so
//     P = P00 + s1 lambda P10 + s2 lambda P01 + s1 s2 lambda^2 P11
// with P10, P01 the principal minors without ball 1 resp. ball 2 and P11 the rotor
// block's determinant, all of the friction-free pencil: a map over a friction coefficient
// computes them once per column and each cell's polynomial in a few dozen flops.
//
//   auto split = abu::friction_split(linearization_without_ball_damping);
//   abu::Polynomial p = abu::combine(split, s1, s2);
//   abu::RouthCount rc = abu::routh_count(p);
#pragma once

#include <array>
#include <complex>

#include "abu/model/model.hpp"

namespace abu {

/// Coefficients c[k] of lambda^k (degree <= 8) with absolute error bounds.
struct Polynomial {
  std::array<double, 9> c{};
  std::array<double, 9> error{};
};

/// The same in long double, with magnitude[k] = sum of |terms| of c[k] (its rounding
/// error is below a few eps_ld * magnitude[k]).
struct PolynomialLD {
  std::array<long double, 9> c{};
  std::array<long double, 9> magnitude{};
};

/// det(lambda^2 A + lambda C + K).
PolynomialLD characteristic_polynomial(const Linearization<long double, 2>& lin);

/// The four polynomials of the friction split; `lin` is the linearization with the ball
/// friction entries C(2,2), C(3,3) zeroed (friction_free).
struct FrictionSplit {
  PolynomialLD p00, p10, p01, p11;
  Polynomial d00, d10, d01, d11;  ///< the same rounded to double, for the per-cell sums
};
FrictionSplit friction_split(const Linearization<long double, 2>& friction_free);
/// `lin` with the balls' friction damping removed.
Linearization<long double, 2> friction_free(Linearization<long double, 2> lin);

/// P for ball friction damping s1, s2 [N s m] (the C(2+i, 2+i) entries), in double with
/// error bounds.
Polynomial to_double(const PolynomialLD& p);
Polynomial combine(const FrictionSplit& split, double s1, double s2);
/// The same in long double, the magnitudes carried (the products' terms and their sums).
PolynomialLD combine_long(const FrictionSplit& split, long double s1, long double s2);


/// Result of the Routh test: `decided` false when a first-column entry is within its
/// error bound of zero (or the leading coefficient is); then n_unstable is meaningless.
struct RouthCount {
  bool decided = false;
  int n_unstable = 0;  ///< roots with Re > 0
};
RouthCount routh_count(const Polynomial& p);

/// Polishes one root by Newton on P (in real arithmetic if it is real); false if it does
/// not converge (z is then unchanged).
bool polish_root(const Polynomial& p, std::complex<double>& z);

/// Coefficients of P(mu + alpha) (Taylor shift) with error bounds.
Polynomial shifted(const Polynomial& p, double alpha);

/// The spectral abscissa from a root near the rightmost: polished, then certified (no
/// root right of it, by the Routh count of the shifted polynomial). On success returns
/// true and updates `rightmost`.
bool certified_abscissa(const Polynomial& p, std::complex<double>& rightmost);

}  // namespace abu
