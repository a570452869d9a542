// Rotordynamics views of a spectrum (docs/model.md §16): each rotating-frame eigenpair as
// the whirl a rotor engineer reads in the fixed frame — its fixed-frame eigenvalue and
// whirl frequency (forward or backward), damping ratio, logarithmic decrement — and a
// label by eigenvector participation (rotor forward/backward whirl, ball mode, ball
// relative mode). Also the scalar answers of one parameter point: omega_n, the ball
// capacity, and the rotor's response without a balancing effect (§16.5).
//
//   abu::Spectrum sp = abu::equilibrium_spectrum(p, e);
//   for (const abu::ModeView& m : abu::mode_views(p, e.position, sp))
//     if (m.kind == abu::ModeKind::rotor_forward) ... m.whirl_frequency, m.damping_ratio ...
#pragma once

#include <complex>
#include <string_view>
#include <vector>

#include "abu/core/params.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"

namespace abu {

/// What a mode is, by the share of its kinetic-energy-like measure (§16.3).
enum class ModeKind {
  rotor_forward,   ///< rotor translation dominates, fixed-frame whirl in the sense of rotation
  rotor_backward,  ///< rotor translation dominates, whirl against the sense of rotation
  ball,            ///< the balls dominate and move together (the resultant ball unbalance turns)
  ball_relative,   ///< the balls dominate and move against each other
  set_direction,   ///< a structural zero: a direction along the balanced set (§13.4)
};
std::string_view to_string(ModeKind kind);

/// One physical mode: a conjugate pair of rotating-frame eigenvalues (or one real one).
struct ModeView {
  int index = 0;      ///< the eigenvalue's index in the sorted spectrum (the one with Im >= 0)
  int conjugate = -1; ///< index of its conjugate partner, -1 for a real eigenvalue
  std::complex<double> rotating;  ///< lambda, rotating frame, Im lambda >= 0 [1/s]
  /// The fixed-frame eigenvalue carrying most of the mode's motion (16.1.2), (16.2.1): lambda + i omega
  /// (forward circular component dominant) or conj(lambda) + i omega; its imaginary part is
  /// the signed whirl frequency [rad/s], > 0 forward, < 0 backward.
  std::complex<double> fixed;
  /// The other fixed-frame component's eigenvalue (same real part, frequency 2 omega - |.|).
  std::complex<double> fixed_minor;
  double whirl_frequency = 0;  ///< Im fixed [rad/s], signed: > 0 forward, < 0 backward
  double plus_share = 0;       ///< f+ = |w+|^2 / (|w+|^2 + |w-|^2), mass-weighted over the bodies (16.2.1)
  double forward_share = 0;    ///< the share of that motion at a positive fixed-frame frequency (§16.2)
  double rotor_share = 0;      ///< rotor translation's share of the mode's inertia measure (16.3.1)
  double common_share = 0;     ///< of the balls' part: the share of all balls turning together (16.3.1)
  double damping_ratio = 0;    ///< zeta = -Re fixed / |fixed| (16.4.1), fixed frame
  /// delta = 2 pi zeta / sqrt(1 - zeta^2) = -2 pi Re / |Im| (16.4.1); not finite when the
  /// fixed-frame frequency is 0 (`has_log_decrement` false).
  double log_decrement = 0;
  bool has_log_decrement = false;
  ModeKind kind = ModeKind::ball;
};

/// The modes of `sp` (one per conjugate pair or real eigenvalue, in the order of the
/// sorted spectrum), at the equilibrium configuration `position` of `p`. Needs the
/// eigenvectors of the refined method; structural zeros come out as `set_direction`.
template <int N>
std::vector<ModeView> mode_views(const ParamsT<double, N>& p, const Coordinates<long double, N>& position,
                                 const SpectrumT<N>& sp);

/// For every eigenvalue index k of `sp` the mode (index into `modes`) it belongs to.
std::vector<int> mode_of_eigenvalue(const std::vector<ModeView>& modes, int count);

/// omega_n = sqrt(k / M), M = M_r + sum m_i (model.md (1.3)) [rad/s].
template <int N>
double natural_frequency(const ParamsT<double, N>& p);
/// sum m_i l_i [kg m]: the largest unbalance the balls can cancel (model.md (1.5)).
template <int N>
double ball_capacity_of(const ParamsT<double, N>& p);
/// Steady whirl radius of the rotor of mass `mass` carrying U and nothing that balances it
/// (§16.5): U omega^2 / |k - mass omega^2 + i c omega| [m].
template <int N>
double unbalanced_amplitude(const ParamsT<double, N>& p, double mass);

}  // namespace abu
