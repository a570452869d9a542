// Locating special points of equilibrium branches by solving augmented systems, and the
// normal-form coefficient that tells a supercritical Hopf point from a subcritical one.
//
// Minimally augmented systems (Govaerts, "Numerical methods for bifurcations of
// dynamical equilibria", 2000), on the scaled static equations of static_equations.hpp:
//
//   fold   [F_s  b] [v]   [0]        unknowns (s, p):         F(s, p) = 0, g(s, p) = 0
//          [c^T  0] [g] = [1]
//
//   Hopf   [T(i w)  b] [v]   [0]     unknowns (s, p, w):      F(s, p) = 0, g(s, p, w) = 0
//          [c^H     0] [g] = [1]     (g complex: two real equations)
//
// with T(lambda) = lambda^2 A + lambda C + K the quadratic pencil of the linearization
// (the 4x4 form of J - i w I, see spectrum.hpp) and b, c fixed approximate null vectors.
// g vanishes exactly where F_s (resp. T(i w)) is singular. Newton runs in long double;
// the residuals are analytic, the Jacobian rows of g central differences.
//
//   auto fold = abu::locate_fold(eq, z_guess);
//   auto hopf = abu::locate_hopf(eq, z_guess, omega_guess);
//   double l1 = abu::first_lyapunov_coefficient(p, s, hopf.frequency);
#pragma once

#include <complex>

#include <optional>
#include <utility>

#include "abu/linear/spectrum.hpp"
#include "abu/model/static_equations.hpp"

namespace abu {

/// The fold test function g(z) of the minimally augmented system, for borders fixed at
/// construction (the singular vectors of F_s there; rebuild it as the fold moves).
/// N = 2 and any_balls (F_s of the n + 2 static equations).
template <int N>
class FoldConditionT {
 public:
  FoldConditionT(const StaticEquationsT<N>& eq, const typename StaticEquationsT<N>::Unknowns& z);
  long double operator()(const StaticEquationsT<N>& eq, const typename StaticEquationsT<N>::Unknowns& z) const;

 private:
  Coordinates<long double, N> left_, right_;
};
using FoldCondition = FoldConditionT<2>;

/// The Hopf test function g(z, w) (complex) for T(i w) equilibrated and bordered at
/// construction. N = 2 and any_balls.
template <int N>
class HopfConditionT {
 public:
  HopfConditionT(const StaticEquationsT<N>& eq, const typename StaticEquationsT<N>::Unknowns& z, long double omega);
  std::complex<long double> operator()(const StaticEquationsT<N>& eq, const typename StaticEquationsT<N>::Unknowns& z,
                                       long double omega) const;

 private:
  Coordinates<long double, N> rows_, cols_;
  Coordinates<std::complex<long double>, N> left_, right_;
};
using HopfCondition = HopfConditionT<2>;

/// Normal-form coefficients along fold curves, whose sign changes flag codimension-two
/// points: the cusp coefficient w^T F_ss[v, v] (CP where it vanishes) and w^T C v, the
/// derivative of the pencil at lambda = 0 along the null vectors (BT where it vanishes:
/// the zero eigenvalue becomes double). v, w: right and left null vectors of F_s.
/// The null vectors are oriented against `previous`' (their SVD signs are arbitrary, and
/// both coefficients change sign with them): pass the last point's result along a curve.
struct FoldCoefficients {
  long double cusp = 0;
  long double bogdanov_takens = 0;
  Eigen::Matrix<long double, 4, 1> right = Eigen::Matrix<long double, 4, 1>::Zero();  ///< v
  Eigen::Matrix<long double, 4, 1> left = Eigen::Matrix<long double, 4, 1>::Zero();   ///< w
};
FoldCoefficients fold_coefficients(const StaticEquations& eq, const StaticEquations::Vec5& z,
                                   const FoldCoefficients* previous = nullptr);

/// Sign of the Hopf test function prod_{i<j} (lambda_i + lambda_j): +1 or -1. It changes
/// where a complex pair crosses the imaginary axis, and at neutral saddles (a real pair
/// lambda, -lambda), which the location tells apart. Factors within their error bands are
/// left out (their sign is noise: the conservative case's centres).
/// Structural zeros (SpectrumT::structural) are left out. N = 2 and any_balls.
template <int N>
int hopf_test_sign(const SpectrumT<N>& sp);

/// The complex pair that crosses the imaginary axis between two spectra: an upper-half-
/// plane eigenvalue of `a` clear of the real axis whose nearest counterpart in `b` is too
/// and lies on the other side. N = 2 and any_balls.
template <int N>
std::optional<std::pair<std::complex<double>, std::complex<double>>> crossing_pair(const SpectrumT<N>& a,
                                                                                    const SpectrumT<N>& b);

struct Located {
  StaticEquations::Vec5 z = StaticEquations::Vec5::Zero();
  long double frequency = 0;  ///< Hopf: omega_H [rad/s]
  bool converged = false;
  int iterations = 0;
};

/// Fold (limit point) of the branch through z_guess: F = 0 and F_s singular.
Located locate_fold(const StaticEquations& eq, const StaticEquations::Vec5& z_guess);

/// Hopf point near (z_guess, omega_guess): F = 0 and T(i omega) singular, omega > 0.
Located locate_hopf(const StaticEquations& eq, const StaticEquations::Vec5& z_guess, long double omega_guess);

/// First Lyapunov coefficient l1 at a Hopf point (Kuznetsov, "Elements of applied
/// bifurcation theory", eq. 3.20): l1 < 0 supercritical (a stable cycle is born),
/// l1 > 0 subcritical. Computed on the first-order field f of model.md §3 in SI state
/// coordinates with the critical eigenvector q normalized to <q, q> = 1; its sign is
/// coordinate-free. The second and third derivatives of f are exact: Taylor coefficients
/// of f along each direction in long double (model.md (6.8)-(6.10)), no step size.
double first_lyapunov_coefficient(const Params& p, const Coordinates<long double, 2>& s, long double omega);

}  // namespace abu
