// An aligned equilibrium of n >= 3 equal balls: its spectrum from a two-ball pencil and
// one scalar quadratic per side (model.md §13.10).
//
// At an aligned equilibrium (every ball on the line of q, §13.2) the balls on one side sit
// at one angle. Equal balls there have identical rows and columns in (6.3)-(6.4), and the
// ball blocks of A, D, E are diagonal, so the modes in which the balls of one side move
// alike form an invariant subspace — the two-ball pencil of one ball per side, its
// coupling scaled by sqrt(k) for k balls on that side (13.10.1) — and the k - 1 relative
// modes of a side, which leave the rotor at rest, each solve the ball's own diagonal
// quadratic
//     J0 lambda^2 + gamma lambda + e = 0,     e = omega^2 a Re(q e^{-i beta})            (13.10.2)
// A side with every ball (pattern ++..+) is split as one ball and n - 1: the pencil then
// holds one relative mode itself. det T = det T_r * d_1^(k1 - 1) * d_2^(k2 - 1) (13.10.3).
//
//   const abu::AlignedReduction r = abu::aligned_reduction(p, e);
//   const abu::AlignedPencil a = abu::aligned_pencil(r, abu::linearize(pl, e.state()), e);
//   if (a.applies) v = abu::aligned_verdict(a, {gamma, gamma}, root, tracked);
#pragma once

#include <array>
#include <complex>

#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/balanced_reduced.hpp"
#include "abu/linear/characteristic.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"

namespace abu {

/// The two sides of an aligned equilibrium of equal balls.
struct AlignedReduction {
  bool applies = false;  ///< n >= 3 equal balls, a smooth law, a polished aligned equilibrium, no structural zero
  std::array<int, 2> size{};   ///< balls per side (k1 + k2 = n, each >= 1)
  std::array<int, 2> first{};  ///< the first ball of each side (its rows stand for the side's)
};
AlignedReduction aligned_reduction(const ParamsN& p, const EquilibriumN& e);
/// The same where equal_smooth_balls(p) is already known to hold (a map's set: once per set).
AlignedReduction aligned_sides(const EquilibriumN& e);

/// The two roots of J0 lambda^2 + gamma lambda + e = 0 (13.10.2) in long double, with
/// whether both are clear of the axis (|Re| > 1e-6 |lambda|; a root exactly 0 is not).
struct RelativeModes {
  std::array<std::complex<double>, 2> roots{};
  int n_unstable = 0;  ///< of the two roots
  bool clear = false;
};
RelativeModes relative_modes(long double inertia, long double friction, long double stiffness);

/// What the verdicts along a friction axis need of one aligned equilibrium, fixed while
/// only friction changes (friction enters only the balls' damping entries, (6.4)).
struct AlignedPencil {
  bool applies = false;  ///< the premise of (13.10.1) held on the linearization
  /// (13.10.1) without the balls' friction damping: rotor, then one coordinate per side, its
  /// couplings to the rotor times sqrt(k) (a similarity of the side-sum pencil)
  Linearization<long double, 2> free;
  FrictionSplit split;                 ///< of `free` (characteristic.hpp)
  std::array<int, 2> copies{};         ///< relative modes per side (k - 1; 0 for the lone ball of ++..+)
  std::array<long double, 2> inertia{}, stiffness{};  ///< J0 and e of each side's ball (13.10.2)
};
/// `lin`: the full linearization at e.
AlignedPencil aligned_pencil(const AlignedReduction& r, const Linearization<long double, any_balls>& lin,
                             const EquilibriumN& e);

/// gamma = -l F'(0) of each side's first ball, as the linearization forms D(2+i, 2+i) (6.4).
std::array<long double, 2> side_friction(const ParamsT<long double, any_balls>& pl, const AlignedReduction& r);

/// The verdict compute_spectrum would give (stability, unstable count, abscissa) for the
/// sides' friction damping gamma = -l F'(0) (the entries D(2+i, 2+i) of (6.4)): the pencil
/// by pencil_verdict (its polynomial followed from `rightmost` when `tracked`, else its
/// refined spectrum), the relative modes in closed form. `decided` false where a relative
/// mode is not clear of the axis: the caller takes the full spectrum then.
struct AlignedVerdict {
  NormalVerdict verdict;
  bool decided = false;
};
AlignedVerdict aligned_verdict(const AlignedPencil& a, const std::array<long double, 2>& friction,
                               std::complex<double>& rightmost, bool& tracked);

/// The spectrum compute_spectrum(lin, refined) gives at e, from the reduction: the pencil's 8
/// eigenvalues refined by compute_spectrum with their vectors mapped back (each ball of side ±
/// moves by u_± / sqrt(k_±)), and each side's relative modes k_± - 1 times in closed form with
/// the vectors e_b - e_j (b the side's first ball), relative condition
/// (J0|λ|² + |γ||λ| + |e|) / (|λ| |2 J0 λ + γ|) of a root of (13.10.2).
SpectrumN aligned_spectrum(const AlignedPencil& a, const AlignedReduction& r, const std::array<long double, 2>& friction,
                           const EquilibriumN& e);

}  // namespace abu
