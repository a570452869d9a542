// LuGre friction per ball (model.md §12): one bristle state z_i per ball, so that the
// state is x = (q1, q2, beta_1..beta_n, q1', q2', beta_1'..beta_n', z_1..z_n), of
// dimension 3n + 4, z last (the first 2n + 4 components keep model.md §2's order). The
// mechanical part is model.md §3 with the friction force
//
//     g_i(v)  = mu_c + (mu_s - mu_c) exp(-(v/v_s)^2)                 (12.1)
//     z_i'    = v_i - sigma0 |v_i| z_i / g_i(v_i),     v_i = beta_i'  (12.2)
//     F_i     = -N_i (sigma0 z_i + sigma1 z_i' + sigma2 v_i),   N_i = m_i l_i omega^2  (12.3)
//
// The field is not differentiable in v_i at v_i = 0 unless z_i = 0 (|v_i|): the Jacobian
// there takes the one-sided limit of `side` (model.md §12.4, (12.9)).
//
//   abu::LugreState<double> x = abu::lugre_state(p, s);      // at rest, z = 0
//   auto f = abu::lugre_vector_field(p, x);
//   auto Jp = abu::lugre_jacobian(p, x, abu::RestSide::forward);
//   auto lin = abu::lugre_rest_linearization(p, s, abu::RestSide::forward);  // §12.5 spring-dashpot
#pragma once

#include <Eigen/Core>

#include "abu/core/params.hpp"
#include "abu/model/model.hpp"

namespace abu {

inline constexpr int lugre_state_capacity = 3 * max_balls + 4;
/// x = (s, s', z): 3n + 4 components in bounded storage (no heap).
template <class T>
using LugreState = Eigen::Matrix<T, Eigen::Dynamic, 1, Eigen::ColMajor, lugre_state_capacity, 1>;
template <class T>
using LugreMatrix =
    Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, lugre_state_capacity, lugre_state_capacity>;

/// Which one-sided limit the Jacobian takes for a ball at rest (v_i = 0 exactly):
/// forward (v_i -> 0+, c_i+ of model.md (12.9)) or backward (v_i -> 0-).
enum class RestSide { forward, backward };
std::string_view to_string(RestSide side);

/// g_i(v) of (12.1), the Stribeck level, > 0 for a valid scene (mu_c > 0).
template <class T>
T lugre_level(const BallT<T>& b, const T& v);
/// z_i' of (12.2).
template <class T>
T bristle_rate(const BallT<T>& b, const T& v, const T& z);
/// F_i of (12.3) [N].
template <class T>
T lugre_force(const ParamsT<T, any_balls>& p, int ball, const T& v, const T& z);
/// dz_i'/dv_i: (12.7), and at v = 0 the one-sided limit c_i = 1 -+ sigma0 z / mu_s of `side`.
template <class T>
T bristle_rate_dv(const BallT<T>& b, const T& v, const T& z, RestSide side);

/// x' = f(x) of model.md §12.2 (3n + 4 components).
template <class T>
LugreState<T> lugre_vector_field(const ParamsT<T, any_balls>& p, const LugreState<T>& x);

/// Analytic df/dx (model.md (12.6)); `side` chooses the one-sided limit for every ball at
/// rest (v_i = 0 exactly); elsewhere the field is smooth and `side` is not used.
template <class T>
LugreMatrix<T> lugre_jacobian(const ParamsT<T, any_balls>& p, const LugreState<T>& x, RestSide side);

/// During a run-up (model.md §9, §12.7): the field of a prescribed omega(t) with
/// omega' = omega_dot. The friction does not contain omega', so the Euler terms are those
/// of the frictionless model: f + omega' df/domega' (angular_acceleration_derivative).
template <class T>
LugreState<T> lugre_vector_field(const ParamsT<T, any_balls>& p, const LugreState<T>& x, const T& omega_dot);
template <class T>
LugreMatrix<T> lugre_jacobian(const ParamsT<T, any_balls>& p, const LugreState<T>& x, RestSide side,
                              const T& omega_dot);
/// df/domega at fixed x (what df/dt = omega' df/domega of a run-up needs, model.md (12.12)):
/// the frictionless model's parameter derivative plus 2/omega times the friction's share of
/// s'' (N_i = m_i l_i omega^2).
template <class T>
LugreState<T> lugre_omega_derivative(const ParamsT<T, any_balls>& p, const LugreState<T>& x);

/// The equilibrium of configuration s (model.md §12.3): s' = 0 and the bristle states that
/// hold every ball, sigma0 z_i = -tau_i with tau_i = (q1 sin beta_i - q2 cos beta_i) / l_i.
/// Requires b(s, 0) = 0 in the rotor rows (q = q(beta)); the ball rows are what z holds.
template <class T>
LugreState<T> lugre_equilibrium(const ParamsT<T, any_balls>& p, const Coordinates<T, any_balls>& s);

/// tau_i / mu_s,i at a configuration: the load of ball i over its breakaway level
/// (model.md §12.3); |.| <= 1 is reachable from z(0) = 0.
template <class T>
T lugre_load_ratio(const ParamsT<T, any_balls>& p, const Coordinates<T, any_balls>& s, int ball);

/// The one-sided slope c_i of (12.9) at an equilibrium: 1 -+ sigma0 z_i / mu_s = 1 +- tau_i / mu_s.
template <class T>
T lugre_rest_slope(const ParamsT<T, any_balls>& p, const Coordinates<T, any_balls>& s, int ball, RestSide side);

/// The (2n + 4) spring-dashpot linearization of model.md §12.5 at an equilibrium s: the
/// smooth model's A, C, K with each ball held by F_i = -N_i sigma0 c_i (beta_i - beta_i*)
/// - N_i (sigma1 c_i + sigma2) beta_i'. Its 2n + 4 eigenvalues are the normal spectrum of
/// the one-sided Jacobian (the other n eigenvalues are 0, along the family).
/// zero_bristle: s is an equilibrium of the smooth laws (tau = 0 in exact arithmetic), so
/// c = 1 is taken exactly instead of 1 +- tau/mu_s with tau at rounding level.
template <class T>
Linearization<T, any_balls> lugre_rest_linearization(const ParamsT<T, any_balls>& p,
                                                     const Coordinates<T, any_balls>& s, RestSide side,
                                                     bool zero_bristle = false);

}  // namespace abu
