// The equations of motion of model.md §3 for N balls, their linearization (§6) and
// their derivatives with respect to the parameters.
//
// Mass-matrix form A(beta) s'' = b(s, s') with s = (q1, q2, beta_1..beta_N); the state
// is x = (s, s') in that order everywhere (model.md §2). The linearization is kept in
// second-order form
//
//     A ds'' + C ds' + K ds = 0,   C = -db/ds',   K = -db/ds + (dA/ds) s''
//
// so that the spectrum can be computed from the quadratic eigenproblem
// det(lambda^2 A + lambda C + K) = 0 (see spectrum.hpp); `jacobian` assembles the
// first-order J = [[0, I], [-A^-1 K, -A^-1 C]] from it. Everything is templated on the
// scalar: double, long double (refinement) and std::complex<double> (complex-step
// checks), and on the ball count: N = 2 (fixed-size types, the hot path), N = 3 (tests)
// and N = any_balls (bounded-dynamic types: the size is 2 n + 4 at run time, the
// storage that of max_balls, so no evaluation allocates).
//
//   abu::State<double, 2> x = ...;
//   auto f = abu::vector_field(p, x);
//   auto J = abu::jacobian(p, x);                       // analytic, any state
//   auto dfdw = abu::parameter_derivative(p, x, *abu::parse_param("omega", 2));
#pragma once

#include <Eigen/Core>

#include "abu/core/params.hpp"

namespace abu {

static_assert(any_balls == Eigen::Dynamic, "a run-time ball count maps to Eigen's Dynamic sizes");
/// Compile-time sizes (Eigen::Dynamic for a run-time count) and storage bounds.
template <int N>
inline constexpr int dof_size = N == any_balls ? Eigen::Dynamic : N + 2;
template <int N>
inline constexpr int dof_capacity = ball_capacity<N> + 2;
template <int N>
inline constexpr int state_size = N == any_balls ? Eigen::Dynamic : 2 * N + 4;
template <int N>
inline constexpr int state_capacity = 2 * ball_capacity<N> + 4;

/// The number of configuration coordinates n + 2 of a matrix or vector of the model:
/// the constant for a fixed ball count (so that loops over it unroll), else its size.
template <int N>
constexpr Eigen::Index dofs_of(Eigen::Index runtime) {
  if constexpr (N == any_balls) {
    return runtime;
  } else {
    return N + 2;
  }
}

template <class T, int N>
using Coordinates = Eigen::Matrix<T, dof_size<N>, 1, Eigen::ColMajor, dof_capacity<N>, 1>;  ///< s = (q1, q2, beta_1..beta_n)
template <class T, int N>
using State = Eigen::Matrix<T, state_size<N>, 1, Eigen::ColMajor, state_capacity<N>, 1>;  ///< x = (s, s')
template <class T, int N>
using DofMatrix = Eigen::Matrix<T, dof_size<N>, dof_size<N>, Eigen::ColMajor, dof_capacity<N>, dof_capacity<N>>;
template <class T, int N>
using StateMatrix =
    Eigen::Matrix<T, state_size<N>, state_size<N>, Eigen::ColMajor, state_capacity<N>, state_capacity<N>>;

/// An orthonormal basis of directions along a set of equilibria (the balanced set of
/// n >= 3 balls), in configuration space: n + 2 rows, one column per direction.
using TangentBasis =
    Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, max_balls + 2, max_balls>;

/// Second-order linearization A ds'' + C ds' + K ds = 0 about a state (model.md §6).
/// C holds the support damping, the friction slopes and the gyroscopic (skew) coupling;
/// K the support stiffness, the centrifugal softening and the circulatory terms.
template <class T, int N>
struct Linearization {
  DofMatrix<T, N> mass;       ///< A(beta), symmetric positive definite
  DofMatrix<T, N> damping;    ///< C = -db/ds'
  DofMatrix<T, N> stiffness;  ///< K = -db/ds + (dA/ds) s''
};

/// A(beta) of model.md §3 (each ball equation multiplied by l_i).
template <class T, int N>
DofMatrix<T, N> mass_matrix(const ParamsT<T, N>& p, const Coordinates<T, N>& s);

/// b(s, s'): the right-hand side of A s'' = b (model.md §3).
template <class T, int N>
Coordinates<T, N> generalized_forces(const ParamsT<T, N>& p, const State<T, N>& x);

/// x' = f(x) = (s', A^-1 b).
template <class T, int N>
State<T, N> vector_field(const ParamsT<T, N>& p, const State<T, N>& x);

/// Run-up (model.md §9): x' = f(x; omega, omega') with the spin speed p.omega and the
/// angular acceleration omega_dot [rad/s^2] of the rotating frame, (9.1)-(9.4). With
/// omega_dot = 0 this is vector_field(p, x) exactly.
template <class T, int N>
State<T, N> vector_field(const ParamsT<T, N>& p, const State<T, N>& x, const T& omega_dot);

/// Second-order linearization at any state (the off-equilibrium term included in K).
template <class T, int N>
Linearization<T, N> linearize(const ParamsT<T, N>& p, const State<T, N>& x);
/// The same during a run-up (model.md §9): the Euler terms' derivatives in K.
template <class T, int N>
Linearization<T, N> linearize(const ParamsT<T, N>& p, const State<T, N>& x, const T& omega_dot);

/// First-order Jacobian df/dx from a linearization: [[0, I], [-A^-1 K, -A^-1 C]].
template <class T, int N>
StateMatrix<T, N> jacobian(const Linearization<T, N>& lin);

/// Analytic df/dx at any state (model.md §6 including -A^-1 (dA/ds) s'').
template <class T, int N>
StateMatrix<T, N> jacobian(const ParamsT<T, N>& p, const State<T, N>& x);
/// Analytic df/dx during a run-up with angular acceleration omega_dot (model.md §9).
template <class T, int N>
StateMatrix<T, N> jacobian(const ParamsT<T, N>& p, const State<T, N>& x, const T& omega_dot);

/// df/d(omega') (model.md §9): f is affine in the angular acceleration, so along a
/// prescribed speed omega(t) df/dt = omega' df/domega + omega'' df/domega'. The
/// df/domega of parameter_derivative holds during a run-up too (the Euler terms do not
/// contain omega).
template <class T, int N>
State<T, N> angular_acceleration_derivative(const ParamsT<T, N>& p, const State<T, N>& x);

/// Analytic df/dp for any parameter of params.hpp (every-ball references sum over the
/// balls): (0, A^-1 (db/dp - (dA/dp) s'')).
template <class T, int N>
State<T, N> parameter_derivative(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref);

/// f, df/dx and df/dp at one state (omega' = 0), sharing the kinematics and s'' between
/// them: equal to vector_field, jacobian and parameter_derivative up to rounding, at about
/// half their summed cost (the variational equations of cycle shooting, model.md §17.9).
template <class T, int N>
struct FieldDerivatives {
  State<T, N> field;                 ///< f(x)
  StateMatrix<T, N> jacobian;        ///< df/dx
  State<T, N> parameter_derivative;  ///< df/dp
};
/// Instantiated for double and two balls (the cycle shooting's type).
template <class T, int N>
FieldDerivatives<T, N> field_derivatives(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref);

/// Analytic db/dp: the parameter derivative of the generalized forces, which is what
/// the static equations b(s, 0; p) = 0 of continuation need.
template <class T, int N>
Coordinates<T, N> generalized_force_derivative(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref);

/// Natural displacement scale (U + sum m_i l_i) / M [m]: the rotor excursion the
/// unbalance and the ball set can cause. Internal computations measure q in this unit
/// so that micrometres and radians are equally well conditioned.
template <class T, int N>
T displacement_scale(const ParamsT<T, N>& p);

/// Natural magnitude of each static equation b_i(s, 0) (model.md §5): the size of its
/// largest terms. |b_i| / scale_i is the dimensionless residual reported for
/// equilibria; rounding level is about 1e-16.
template <class T, int N>
Coordinates<T, N> static_force_scale(const ParamsT<T, N>& p, const Coordinates<T, N>& s);

/// The state (s, 0) of a configuration at rest.
template <class T, int N>
State<T, N> at_rest(const Coordinates<T, N>& s) {
  State<T, N> x = State<T, N>::Zero(2 * s.size());
  x.template head<dof_size<N>>(s.size()) = s;
  return x;
}

}  // namespace abu
