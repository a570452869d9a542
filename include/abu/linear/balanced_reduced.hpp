// The balanced set of n >= 3 equal balls: its normal spectrum from a problem of two
// degrees of freedom per axis in one variable (model.md §13.9).
//
// For equal balls (a = m l, J0 = j m l^2, friction damping gamma = -l F'(0)) the ball
// coordinates couple to the rotor only through w = sum_i delta_i e^{i beta_i}; the tangent
// directions (w = 0) carry the structural zeros and, with friction, n - 2 copies of
// -gamma / J0; what is left depends on the arrangement only through
//     g = |sum_i e^{2 i beta_i}|   (0 <= g <= n, g = n exactly at the collinear points),
// and is the two-ball problem of a rotor of mass M with two balls of capacities
// a sqrt((n + g)/2) and a sqrt((n - g)/2) at right angles, both of inertia J0 and friction
// gamma (13.9.6). Its 8 eigenvalues and the copies are the n + 6 normal eigenvalues.
//
//   const abu::BalancedReduction r = abu::balanced_reduction(p);
//   if (abu::reducible(r, e)) sp = abu::reduced_normal_spectrum(r, p, e);
#pragma once

#include <array>
#include <complex>

#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/characteristic.hpp"
#include "abu/linear/spectrum.hpp"

namespace abu {

/// The constants of the reduced problem for one parameter set.
struct BalancedReduction {
  bool applies = false;  ///< n >= 3, every ball equal, a smooth law (none, viscous, coulomb, stribeck)
  int n = 0;
  /// 2 where no ball has a friction slope (as compute_normal_spectrum decides it: the
  /// zeros pair into Jordan chains and -gamma / J0 is deflated with them), else 1.
  int level = 1;
  long double total_mass = 0, stiffness = 0, damping = 0, omega = 0;
  long double capacity = 0;  ///< a = m l of one ball [kg m]
  long double inertia = 0;   ///< J0 = j m l^2 [kg m^2]
  long double friction = 0;  ///< gamma = -l F'(0) [N s m]
};
BalancedReduction balanced_reduction(const ParamsN& p);

/// n >= 3 balls, every one equal, under a smooth law (none, viscous, coulomb, stribeck): the
/// premise shared by the reductions of §13.9 and §13.10.
bool equal_smooth_balls(const ParamsN& p);

/// g = |sum_i e^{2 i beta_i}| (13.9.4) and the frame angle alpha = arg(sum) / 2.
struct Arrangement {
  long double g = 0;
  long double alpha = 0;
};
Arrangement arrangement_of(const Coordinates<long double, any_balls>& position);

/// The reduced problem can stand for e's normal spectrum: a polished sample of the set,
/// regular (not collinear: g well below n, where the tangent space has n - 2 directions).
bool reducible(const BalancedReduction& r, const EquilibriumN& e);
/// The same with e's g already known (arrangement_of(e.position).g).
bool reducible(const BalancedReduction& r, const EquilibriumN& e, long double g);

/// The reduced linearization at g (13.9.6), coordinates (q1, q2, u1, u2) in the frame
/// turned by alpha.
Linearization<long double, 2> reduced_linearization(const BalancedReduction& r, long double g);

/// The spectrum compute_normal_spectrum gives at sample e, from the reduced problem: the
/// structural zeros, the copies of -gamma / J0 (level 1), the 8 reduced eigenvalues
/// refined as compute_spectrum's; eigenvectors mapped back to the n + 2 coordinates when
/// `vectors` (13.9.7).
SpectrumN reduced_normal_spectrum(const BalancedReduction& r, const ParamsN& p, const EquilibriumN& e,
                                  bool vectors = true);

/// What a map cell needs of a sample: the verdict of its normal spectrum.
struct NormalVerdict {
  Stability stability = Stability::marginal;
  int n_unstable = 0;
  int n_structural = 0;
  double abscissa = 0;  ///< normal spectral abscissa [1/s]
  bool converged = true;  ///< certified, or every refinement of the reduced spectrum converged
};
/// The characteristic polynomial of (13.9.6) is bilinear in x = s1^2 and y = s2^2: its
/// values at the corners (x, y) in {0, X}^2, X = n / 2, give it at any g in ~40 flops.
struct ReducedPolynomials {
  std::array<PolynomialLD, 4> corner;  ///< (0,0), (X,0), (0,X), (X,X)
};
ReducedPolynomials reduced_polynomials(const BalancedReduction& r);
/// The corners without the balls' friction damping, split (characteristic.hpp): fixed while
/// only friction changes (a map's friction axis); the corners at r.friction from them.
struct ReducedSplits {
  std::array<FrictionSplit, 4> corner;
};
ReducedSplits reduced_splits(const BalancedReduction& r);
ReducedPolynomials reduced_polynomials(const ReducedSplits& splits, const BalancedReduction& r);
/// P(lambda; g) with error bounds (characteristic.hpp's Polynomial).
Polynomial reduced_polynomial(const BalancedReduction& r, const ReducedPolynomials& corners, long double g);

/// The verdict at g from the reduced problem's characteristic polynomial of degree 8
/// (characteristic.hpp: the rightmost root followed from `rightmost` by Newton,
/// certified by a Routh count) where that is decided clear of the axis, else from its
/// refined spectrum. `rightmost` (valid if `tracked`) is updated for the next call.
/// Shared by the reductions (§13.9, §13.10): a spectrum of n balls filled from a two-ball one —
/// count 2n + 4 and the reduced spectrum's status, convergence and conditioning — and the
/// reduced eigenvalue k put into `slot` (value, error, condition; its band: infinite where the
/// reduced classification put it on the axis, compute_spectrum not returning its bands).
SpectrumN spectrum_of_reduction(const Spectrum& reduced, int n_balls);
void put_reduced_eigenvalue(const Spectrum& reduced, std::size_t k, std::size_t slot, SpectrumN& sp,
                            std::array<long double, SpectrumN::capacity>& band);

/// The verdict of a 4-dof pencil `lin` (two balls' shape) from its characteristic
/// polynomial `poly` (read only when `tracked`): the rightmost root followed from
/// `rightmost` by Newton, certified by a Routh count and accepted clear of the axis; else
/// the refined spectrum of `lin`. Updates `rightmost` and sets `tracked`.
NormalVerdict pencil_verdict(const Polynomial& poly, const Linearization<long double, 2>& lin,
                             std::complex<double>& rightmost, bool& tracked);

NormalVerdict reduced_normal_verdict(const BalancedReduction& r, const ReducedPolynomials& corners, long double g,
                                     std::complex<double>& rightmost, bool& tracked);

}  // namespace abu
