#include "abu/model/model.hpp"
#include "abu/model/mass_derivative.hpp"

#include <cmath>
#include <complex>

#include <Eigen/LU>

#include "abu/core/taylor.hpp"
#include "abu/model/friction.hpp"

namespace abu {

namespace {

// sin and cos of an angle. For long double the argument is first reduced by pi/2 with a
// three-part (Cody-Waite) constant: glibc's sinl/cosl send every |x| > pi/4 through the
// multi-precision __kernel_rem_pio2, which made trigonometry a third of all the work.
// P1 and P2 carry 32 bits each, so k * P1 and k * P2 are exact for |k| < 2^31.
template <class T>
void sin_cos(const T& angle, T& s, T& c) {
  using std::cos;
  using std::sin;
  s = sin(angle);
  c = cos(angle);
}
template <>
void sin_cos<long double>(const long double& angle, long double& s, long double& c) {
  constexpr long double kP1 = 0xc.90fdaa200000000p-3L;  // pi/2 to 32 bits
  constexpr long double kP2 = 0x8.5a308d300000000p-37L;  // the next 32 bits
  constexpr long double kP3 = 0x9.8cc51701b839a25p-72L;  // the next 64 bits (error 2e-41)
  const long double quadrants = angle / (kP1 + kP2);
  if (!(std::abs(quadrants) < 0x1p31L)) {  // far outside any angle the model produces
    s = std::sin(angle);
    c = std::cos(angle);
    return;
  }
  // Round to the nearest quadrant with an inline conversion (nearbyintl is a slow call).
  const long double k = static_cast<long double>(static_cast<long long>(quadrants + (quadrants < 0 ? -0.5L : 0.5L)));
  const long double r = ((angle - k * kP1) - k * kP2) - k * kP3;
  const long double sr = std::sin(r), cr = std::cos(r);
  switch (static_cast<long long>(k) & 3) {
    case 0: s = sr, c = cr; break;
    case 1: s = cr, c = -sr; break;
    case 2: s = -sr, c = -cr; break;
    default: s = -cr, c = sr; break;
  }
}

// Kinematic pieces shared by b, its derivatives and the mass matrix.
template <class T, int N>
struct Kinematics {
  std::array<T, ball_capacity<N>> sin_b, cos_b, ml;  // sin beta_i, cos beta_i, m_i l_i
  // Per-ball constants of the mass solve, m_i / j_i, 1 / (j_i l_i) and j_i m_i l_i^2: once per
  // evaluation, not once per right-hand side (the Jacobian solves 2 n + 4 of them; the
  // same expressions, so the same values).
  std::array<T, ball_capacity<N>> m_over_j, inv_jl, ball_inertia;
  int n;                                              // number of balls
  T w, w2;                                            // omega, omega^2
  T wd;                                               // angular acceleration omega' (model.md §9)
  bool accelerating;                                  // wd != 0: the Euler terms of §9 are present
  // P1, P2: q1'' - P1 and q2'' - P2 are the rotating-frame accelerations a1, a2 (§3; with
  // omega' != 0 they include the Euler terms -omega' q2, +omega' q1 of (9.1)).
  T p1, p2;

  Kinematics(const ParamsT<T, N>& p, const State<T, N>& x, const T& omega_dot = T(0))
      : n(ball_count(p)), w(p.omega), w2(p.omega * p.omega), wd(omega_dot), accelerating(omega_dot != T(0)) {
    for (int i = 0; i < n; ++i) {
      const auto k = std::size_t(i);
      sin_cos(x(2 + i), sin_b[k], cos_b[k]);
      const auto& b = p.balls[k];
      ml[k] = b.mass * b.race_radius;
      m_over_j[k] = b.mass / b.inertia_factor;
      inv_jl[k] = T(1) / (b.inertia_factor * b.race_radius);
      ball_inertia[k] = b.inertia_factor * ml[k] * b.race_radius;
    }
    p1 = T(2) * w * x(n + 3) + w2 * x(0);
    p2 = T(-2) * w * x(n + 2) + w2 * x(1);
    if (accelerating) {  // (9.1): a1 = q1'' - 2 w q2' - w' q2 - w^2 q1, a2 = q2'' + 2 w q1' + w' q1 - w^2 q2
      p1 += wd * x(1);
      p2 -= wd * x(0);
    }
  }
  int dofs() const { return n + 2; }
};

// Solves A(beta) z = r for one or more right-hand sides by block elimination: the ball
// block of A is diagonal (j_i m_i l_i^2), so z_q comes from the 2x2 Schur complement
// S = M I - sum_i (m_i / j_i) [[s^2, -s c], [-s c, c^2]] and the balls follow.
// Exact for complex (symmetric, not Hermitian) A too, which LLT would not be.
template <class T, int N, class Rhs>
Rhs solve_mass(const ParamsT<T, N>& p, const Kinematics<T, N>& kin, const Rhs& r) {
  const T M = p.total_mass();
  T s11 = M, s22 = M, s12 = T(0);
  const int n = kin.n;
  for (int i = 0; i < n; ++i) {
    const auto k = std::size_t(i);
    const T mj = kin.m_over_j[k];
    s11 -= mj * kin.sin_b[k] * kin.sin_b[k];
    s22 -= mj * kin.cos_b[k] * kin.cos_b[k];
    s12 += mj * kin.sin_b[k] * kin.cos_b[k];
  }
  const T det = s11 * s22 - s12 * s12;
  Rhs z(r.rows(), r.cols());
  for (Eigen::Index col = 0; col < r.cols(); ++col) {
    T y1 = r(0, col), y2 = r(1, col);
    for (int i = 0; i < n; ++i) {
      const auto k = std::size_t(i);
      const T inv_jl = kin.inv_jl[k];
      y1 += kin.sin_b[k] * r(2 + i, col) * inv_jl;
      y2 -= kin.cos_b[k] * r(2 + i, col) * inv_jl;
    }
    const T z1 = (s22 * y1 - s12 * y2) / det;
    const T z2 = (s11 * y2 - s12 * y1) / det;
    z(0, col) = z1;
    z(1, col) = z2;
    for (int i = 0; i < n; ++i) {
      const auto k = std::size_t(i);
      z(2 + i, col) = (r(2 + i, col) + kin.ml[k] * (kin.sin_b[k] * z1 - kin.cos_b[k] * z2)) / kin.ball_inertia[k];
    }
  }
  return z;
}

template <class T, int N>
Coordinates<T, N> forces(const ParamsT<T, N>& p, const State<T, N>& x, const Kinematics<T, N>& kin) {
  const T M = p.total_mass();
  const T c = p.rotor.damping;
  const T k = p.rotor.stiffness;
  const int n = kin.n;
  Coordinates<T, N> b(kin.dofs());
  // Rotor (model.md §3, first two equations, everything but A s'' moved right).
  b(0) = M * kin.p1 - c * (x(n + 2) - kin.w * x(1)) - k * x(0) + kin.w2 * p.rotor.unbalance;
  b(1) = M * kin.p2 - c * (x(n + 3) + kin.w * x(0)) - k * x(1);
  for (int i = 0; i < n; ++i) {
    const auto j = std::size_t(i);
    const T spin = x(n + 4 + i) + kin.w;  // absolute angular speed of ball i
    const T centrifugal = kin.ml[j] * spin * spin;
    b(0) += centrifugal * kin.cos_b[j];
    b(1) += centrifugal * kin.sin_b[j];
    // Ball i times l_i: j m l^2 beta'' - m l (q1'' sin - q2'' cos) = l F + m l (-P1 sin + P2 cos).
    b(2 + i) = p.balls[j].race_radius * friction_force(p, i, x(n + 4 + i)) +
               kin.ml[j] * (-kin.p1 * kin.sin_b[j] + kin.p2 * kin.cos_b[j]);
  }
  if (kin.accelerating) {
    // Run-up (model.md §9): the Euler terms of (9.2)-(9.4) beyond those inside P1, P2. The
    // balls' tangential inertia (beta'' + omega') gives omega' sum a_i (sin, -cos); the
    // unbalance -i omega' U; ball i lags by m_i omega' (l_i - (j_i - 1) r_i), times l_i.
    b(1) -= kin.wd * p.rotor.unbalance;
    for (int i = 0; i < n; ++i) {
      const auto j = std::size_t(i);
      const auto& ball = p.balls[j];
      b(0) += kin.wd * kin.ml[j] * kin.sin_b[j];
      b(1) -= kin.wd * kin.ml[j] * kin.cos_b[j];
      b(2 + i) -= kin.wd * kin.ml[j] * (ball.race_radius - (ball.inertia_factor - T(1)) * ball.radius);
    }
  }
  return b;
}

// (dA/dbeta_i) z for i = 0..n-1 stacked as columns 2+i of an (n+2)x(n+2) matrix
// (columns 0, 1 zero): A depends on beta_i through -m l sin beta_i (row/col 0) and
// m l cos beta_i (row/col 1).
template <class T, int N>
DofMatrix<T, N> mass_derivative_times(const Kinematics<T, N>& kin, const Coordinates<T, N>& z) {
  DofMatrix<T, N> D = DofMatrix<T, N>::Zero(kin.dofs(), kin.dofs());
  for (int i = 0; i < kin.n; ++i) {
    const auto j = std::size_t(i);
    D(0, 2 + i) = -kin.ml[j] * kin.cos_b[j] * z(2 + i);
    D(1, 2 + i) = -kin.ml[j] * kin.sin_b[j] * z(2 + i);
    D(2 + i, 2 + i) = -kin.ml[j] * (kin.cos_b[j] * z(0) + kin.sin_b[j] * z(1));
  }
  return D;
}

}  // namespace

template <class T, int N>
DofMatrix<T, N> mass_matrix(const ParamsT<T, N>& p, const Coordinates<T, N>& s) {
  const Kinematics<T, N> kin(p, at_rest<T, N>(s));
  DofMatrix<T, N> A = DofMatrix<T, N>::Zero(kin.dofs(), kin.dofs());
  A(0, 0) = A(1, 1) = p.total_mass();
  for (int i = 0; i < kin.n; ++i) {
    const auto j = std::size_t(i);
    A(0, 2 + i) = A(2 + i, 0) = -kin.ml[j] * kin.sin_b[j];
    A(1, 2 + i) = A(2 + i, 1) = kin.ml[j] * kin.cos_b[j];
    A(2 + i, 2 + i) = p.balls[j].inertia_factor * kin.ml[j] * p.balls[j].race_radius;
  }
  return A;
}

template <class T, int N>
DofMatrix<T, N> mass_derivative_times(const ParamsT<T, N>& p, const Coordinates<T, N>& s, const Coordinates<T, N>& z) {
  return mass_derivative_times(Kinematics<T, N>(p, at_rest<T, N>(s)), z);
}

template <class T, int N>
Coordinates<T, N> generalized_forces(const ParamsT<T, N>& p, const State<T, N>& x) {
  return forces(p, x, Kinematics<T, N>(p, x));
}

template <class T, int N>
State<T, N> vector_field(const ParamsT<T, N>& p, const State<T, N>& x) {
  return vector_field(p, x, T(0));
}

namespace {
// x' = (s', s'') from the accelerations s'' = A^-1 b.
template <class T, int N>
State<T, N> field_from(const State<T, N>& x, int d, const Coordinates<T, N>& accel) {
  State<T, N> f(2 * d);
  f.template head<dof_size<N>>(d) = x.template segment<dof_size<N>>(d, d);
  f.template segment<dof_size<N>>(d, d) = accel;
  return f;
}
}  // namespace

template <class T, int N>
State<T, N> vector_field(const ParamsT<T, N>& p, const State<T, N>& x, const T& omega_dot) {
  const Kinematics<T, N> kin(p, x, omega_dot);
  return field_from<T, N>(x, kin.dofs(), Coordinates<T, N>(solve_mass(p, kin, forces(p, x, kin))));
}

template <class T, int N>
Linearization<T, N> linearize(const ParamsT<T, N>& p, const State<T, N>& x) {
  return linearize(p, x, T(0));
}

namespace {
// C and K of the linearization (model.md §6) at x, from the kinematics and the
// accelerations s'' = A^-1 b already evaluated (shared by linearize, jacobian and
// field_derivatives, which each used to recompute them).
template <class T, int N>
void damping_and_stiffness(const ParamsT<T, N>& p, const State<T, N>& x, const Kinematics<T, N>& kin,
                           const Coordinates<T, N>& accel, DofMatrix<T, N>& C, DofMatrix<T, N>& K) {
  const T M = p.total_mass();
  const T c = p.rotor.damping;
  const T k = p.rotor.stiffness;
  const T w = kin.w;
  const int n = kin.n, d = kin.dofs();
  C.setZero(d, d);
  K.setZero(d, d);
  // Rotor: support damping, Coriolis (skew), support stiffness against centrifugal
  // softening, and the circulatory part of the rotating damper.
  C(0, 0) = C(1, 1) = c;
  C(0, 1) = -T(2) * w * M;
  C(1, 0) = T(2) * w * M;
  K(0, 0) = K(1, 1) = k - M * kin.w2;
  K(0, 1) = -c * w;
  K(1, 0) = c * w;
  for (int i = 0; i < n; ++i) {
    const auto j = std::size_t(i);
    const T ml = kin.ml[j];
    const T spin = x(n + 4 + i) + w;
    const T s = kin.sin_b[j], co = kin.cos_b[j];
    // Centrifugal force of ball i on the rotor and its dependence on beta_i, beta_i'.
    C(0, 2 + i) = -T(2) * ml * spin * co;
    C(1, 2 + i) = -T(2) * ml * spin * s;
    K(0, 2 + i) = ml * spin * spin * s;
    K(1, 2 + i) = -ml * spin * spin * co;
    // Rotating-frame inertial forces on ball i (Coriolis and centrifugal of the rotor).
    C(2 + i, 0) = T(2) * w * ml * co;
    C(2 + i, 1) = T(2) * w * ml * s;
    K(2 + i, 0) = ml * kin.w2 * s;
    K(2 + i, 1) = -ml * kin.w2 * co;
    K(2 + i, 2 + i) = ml * (kin.p1 * co + kin.p2 * s);
    // Friction: the only dissipation on the balls (model.md §4).
    C(2 + i, 2 + i) = -p.balls[j].race_radius * friction_slope(p, i, x(n + 4 + i));
    if (kin.accelerating) {
      // Run-up (model.md §9): -d/ds of the Euler terms: omega' a_i (sin, -cos) in the rotor
      // rows, and the omega' q parts of P1, P2 in the ball rows.
      K(0, 2 + i) -= kin.wd * ml * co;
      K(1, 2 + i) -= kin.wd * ml * s;
      K(2 + i, 0) += kin.wd * ml * co;
      K(2 + i, 1) += kin.wd * ml * s;
      // (the ball diagonal ml (P1 cos + P2 sin) above already carries omega' through P1, P2)
    }
  }
  if (kin.accelerating) {  // M omega' q2 in b_1, -M omega' q1 in b_2
    K(0, 1) -= kin.wd * M;
    K(1, 0) += kin.wd * M;
  }
  // Off equilibrium A depends on beta while s'' != 0: K += (dA/ds) s'' (model.md §6).
  if (!accel.isZero(0)) K += mass_derivative_times(kin, accel);
}
}  // namespace

template <class T, int N>
Linearization<T, N> linearize(const ParamsT<T, N>& p, const State<T, N>& x, const T& omega_dot) {
  const Kinematics<T, N> kin(p, x, omega_dot);
  Linearization<T, N> lin;
  lin.mass = mass_matrix<T, N>(p, Coordinates<T, N>(x.template head<dof_size<N>>(kin.dofs())));
  damping_and_stiffness(p, x, kin, Coordinates<T, N>(solve_mass(p, kin, forces(p, x, kin))), lin.damping,
                        lin.stiffness);
  return lin;
}

// [-K, -C]: the lower block row of J before the solve with A.
template <class T, int N>
using LowerRows = Eigen::Matrix<T, dof_size<N>, N == any_balls ? Eigen::Dynamic : 2 * (N + 2), Eigen::ColMajor,
                                dof_capacity<N>, 2 * dof_capacity<N>>;

template <class T, int N>
StateMatrix<T, N> jacobian(const Linearization<T, N>& lin) {
  constexpr int n_ = dof_size<N>;
  const int d = int(lin.mass.rows());
  StateMatrix<T, N> J = StateMatrix<T, N>::Zero(2 * d, 2 * d);
  J.template block<n_, n_>(0, d, d, d).setIdentity();
  LowerRows<T, N> rhs(d, 2 * d);
  rhs << -lin.stiffness, -lin.damping;
  // A is SPD for real T; PartialPivLU keeps complex (symmetric) A correct as well.
  J.template block<n_, LowerRows<T, N>::ColsAtCompileTime>(d, 0, d, 2 * d) = lin.mass.partialPivLu().solve(rhs);
  return J;
}

template <class T, int N>
StateMatrix<T, N> jacobian(const ParamsT<T, N>& p, const State<T, N>& x) {
  return jacobian(p, x, T(0));
}

namespace {
// [[0, I], [-A^-1 K, -A^-1 C]] with A^-1 applied by solve_mass (model.md §6).
template <class T, int N>
StateMatrix<T, N> jacobian_from(const ParamsT<T, N>& p, const Kinematics<T, N>& kin, const DofMatrix<T, N>& C,
                                const DofMatrix<T, N>& K) {
  constexpr int n_ = dof_size<N>;
  const int d = kin.dofs();
  StateMatrix<T, N> J = StateMatrix<T, N>::Zero(2 * d, 2 * d);
  J.template block<n_, n_>(0, d, d, d).setIdentity();
  LowerRows<T, N> rhs(d, 2 * d);
  rhs << -K, -C;
  J.template block<n_, LowerRows<T, N>::ColsAtCompileTime>(d, 0, d, 2 * d) = solve_mass(p, kin, rhs);
  return J;
}
}  // namespace

template <class T, int N>
StateMatrix<T, N> jacobian(const ParamsT<T, N>& p, const State<T, N>& x, const T& omega_dot) {
  const Kinematics<T, N> kin(p, x, omega_dot);
  DofMatrix<T, N> C, K;
  damping_and_stiffness(p, x, kin, Coordinates<T, N>(solve_mass(p, kin, forces(p, x, kin))), C, K);
  return jacobian_from(p, kin, C, K);
}

namespace {
// db/dp and (dA/dp) s'' for one parameter: the two pieces of df/dp.
template <class T, int N>
struct ParameterPartials {
  explicit ParameterPartials(int dofs) : db(Coordinates<T, N>::Zero(dofs)), dA_accel(Coordinates<T, N>::Zero(dofs)) {}
  Coordinates<T, N> db;
  Coordinates<T, N> dA_accel;
};

template <class T, int N>
ParameterPartials<T, N> parameter_partials(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref,
                                           const Kinematics<T, N>& kin, const Coordinates<T, N>& accel) {
  ParameterPartials<T, N> out(kin.dofs());
  if (acts_through_specification(ref.quantity)) {
    // r, rho, f, R_s enter §3 only through m, mu, l (model.md (1.1.1)-(1.1.3)): the chain
    // rule over the balls they move (r alone enters nothing, §1).
    const int first = ref.ball < 0 ? 0 : ref.ball;
    const int last = ref.ball < 0 ? kin.n : ref.ball + 1;
    for (int i = first; i < last; ++i) {
      const auto s = specified_sensitivity(p.balls[std::size_t(i)], ref.quantity);
      for (const auto& [q, factor] : {std::pair{Quantity::ball_mass, s.dmass}, std::pair{Quantity::mu, s.dmu},
                                      std::pair{Quantity::race_radius, s.drace_radius}}) {
        if (factor == T(0)) continue;
        const ParameterPartials<T, N> d = parameter_partials(p, x, ParamRef{q, i}, kin, accel);
        out.db += factor * d.db;
        out.dA_accel += factor * d.dA_accel;
      }
    }
    return out;
  }
  auto& db = out.db;
  auto& dA_accel = out.dA_accel;
  const T w = kin.w;
  const int n = kin.n;
  const T qd1 = x(n + 2), qd2 = x(n + 3);
  // A change of M (rotor or ball mass) acts on the rotor rows of A and b alike.
  const auto add_translating_mass = [&] {
    db(0) += kin.p1;
    db(1) += kin.p2;
    dA_accel(0) += accel(0);
    dA_accel(1) += accel(1);
  };
  const auto per_ball = [&](int i) {
    const auto j = std::size_t(i);
    const auto& b = p.balls[j];
    const T s = kin.sin_b[j], co = kin.cos_b[j];
    const T spin = x(n + 4 + i) + w;
    const T beta_dot = x(n + 4 + i);
    const T dF = friction_partial(p, i, beta_dot, ref.quantity);
    switch (ref.quantity) {
      case Quantity::ball_mass:
        add_translating_mass();
        db(0) += b.race_radius * spin * spin * co;
        db(1) += b.race_radius * spin * spin * s;
        db(2 + i) += b.race_radius * dF + b.race_radius * (-kin.p1 * s + kin.p2 * co);
        dA_accel(0) += -b.race_radius * s * accel(2 + i);
        dA_accel(1) += b.race_radius * co * accel(2 + i);
        dA_accel(2 + i) += b.race_radius * (-s * accel(0) + co * accel(1)) +
                           b.inertia_factor * b.race_radius * b.race_radius * accel(2 + i);
        break;
      case Quantity::race_radius:
        db(0) += b.mass * spin * spin * co;
        db(1) += b.mass * spin * spin * s;
        db(2 + i) += friction_force(p, i, beta_dot) + b.race_radius * dF +
                     b.mass * (-kin.p1 * s + kin.p2 * co);
        dA_accel(0) += -b.mass * s * accel(2 + i);
        dA_accel(1) += b.mass * co * accel(2 + i);
        dA_accel(2 + i) += b.mass * (-s * accel(0) + co * accel(1)) +
                           T(2) * b.inertia_factor * b.mass * b.race_radius * accel(2 + i);
        break;
      default:  // friction coefficients; the ball radius does not enter §3
        db(2 + i) += b.race_radius * dF;
        break;
    }
  };
  switch (ref.quantity) {
    case Quantity::omega: {
      const T M = p.total_mass();
      const T dp1 = T(2) * qd2 + T(2) * w * x(0);
      const T dp2 = T(-2) * qd1 + T(2) * w * x(1);
      db(0) = M * dp1 + p.rotor.damping * x(1) + T(2) * w * p.rotor.unbalance;
      db(1) = M * dp2 - p.rotor.damping * x(0);
      for (int i = 0; i < n; ++i) {
        const auto j = std::size_t(i);
        const T spin = x(n + 4 + i) + w;
        db(0) += T(2) * kin.ml[j] * spin * kin.cos_b[j];
        db(1) += T(2) * kin.ml[j] * spin * kin.sin_b[j];
        db(2 + i) = p.balls[j].race_radius * friction_partial(p, i, x(n + 4 + i), Quantity::omega) +
                    kin.ml[j] * (-dp1 * kin.sin_b[j] + dp2 * kin.cos_b[j]);
      }
      break;
    }
    case Quantity::unbalance: db(0) = kin.w2; break;
    case Quantity::stiffness:
      db(0) = -x(0);
      db(1) = -x(1);
      break;
    case Quantity::damping:
      db(0) = -(qd1 - w * x(1));
      db(1) = -(qd2 + w * x(0));
      break;
    case Quantity::rotor_mass: add_translating_mass(); break;
    case Quantity::kappa:
      for (int i = 0; i < n; ++i) per_ball(i);
      break;
    default:
      if (ref.ball >= 0) {
        per_ball(ref.ball);
      } else {
        for (int i = 0; i < n; ++i) per_ball(i);
      }
  }
  return out;
}
}  // namespace

namespace {
// df/dp = (0, A^-1 (db/dp - (dA/dp) s'')) from the kinematics and s''.
template <class T, int N>
State<T, N> parameter_derivative_from(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref,
                                      const Kinematics<T, N>& kin, const Coordinates<T, N>& accel) {
  const ParameterPartials<T, N> d = parameter_partials(p, x, ref, kin, accel);
  State<T, N> df = State<T, N>::Zero(2 * kin.dofs());
  df.template segment<dof_size<N>>(kin.dofs(), kin.dofs()) = solve_mass(p, kin, Coordinates<T, N>(d.db - d.dA_accel));
  return df;
}
}  // namespace

template <class T, int N>
State<T, N> parameter_derivative(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref) {
  const Kinematics<T, N> kin(p, x);
  return parameter_derivative_from<T, N>(p, x, ref, kin, Coordinates<T, N>(solve_mass(p, kin, forces(p, x, kin))));
}

template <class T, int N>
FieldDerivatives<T, N> field_derivatives(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref) {
  // One kinematics (the balls' sin/cos), one b and one s'' = A^-1 b for all three: f,
  // df/dx and df/dp each recomputed them (a third of the cycle shooting's time went to
  // sin/cos and the mass solves, model.md §17.9).
  const Kinematics<T, N> kin(p, x);
  const Coordinates<T, N> accel = solve_mass(p, kin, forces(p, x, kin));
  DofMatrix<T, N> C, K;
  damping_and_stiffness(p, x, kin, accel, C, K);
  return {field_from<T, N>(x, kin.dofs(), accel), jacobian_from(p, kin, C, K),
          parameter_derivative_from<T, N>(p, x, ref, kin, accel)};
}

template <class T, int N>
Coordinates<T, N> generalized_force_derivative(const ParamsT<T, N>& p, const State<T, N>& x, ParamRef ref) {
  const Kinematics<T, N> kin(p, x);
  // db/dp does not involve s''; the accelerations only feed the (dA/dp) s'' part.
  return parameter_partials(p, x, ref, kin, Coordinates<T, N>(Coordinates<T, N>::Zero(kin.dofs()))).db;
}

template <class T, int N>
State<T, N> angular_acceleration_derivative(const ParamsT<T, N>& p, const State<T, N>& x) {
  // b is affine in omega' (model.md §9) and A does not depend on it: df/domega' = (0, A^-1 db/domega').
  const Kinematics<T, N> kin(p, x);
  const int n = kin.n, d = kin.dofs();
  Coordinates<T, N> db(d);
  db(0) = p.total_mass() * x(1);
  db(1) = -p.total_mass() * x(0) - p.rotor.unbalance;
  for (int i = 0; i < n; ++i) {
    const auto j = std::size_t(i);
    const auto& ball = p.balls[j];
    db(0) += kin.ml[j] * kin.sin_b[j];
    db(1) -= kin.ml[j] * kin.cos_b[j];
    db(2 + i) = kin.ml[j] * (-x(1) * kin.sin_b[j] - x(0) * kin.cos_b[j]) -
                kin.ml[j] * (ball.race_radius - (ball.inertia_factor - T(1)) * ball.radius);
  }
  State<T, N> df = State<T, N>::Zero(2 * d);
  df.template segment<dof_size<N>>(d, d) = solve_mass(p, kin, db);
  return df;
}

template <class T, int N>
T displacement_scale(const ParamsT<T, N>& p) {
  T capacity = p.rotor.unbalance;
  for (const auto& b : p.balls) capacity += b.mass * b.race_radius;
  return capacity / p.total_mass();
}

template <class T, int N>
Coordinates<T, N> static_force_scale(const ParamsT<T, N>& p, const Coordinates<T, N>& s) {
  using std::abs;
  using std::hypot;
  const T w2 = p.omega * p.omega;
  const T M = p.total_mass();
  T capacity = p.rotor.unbalance;
  for (const auto& b : p.balls) capacity += b.mass * b.race_radius;
  const T q = hypot(s(0), s(1));
  // Rotor: (K + iC) q = omega^2 (U + sum m l e^{i beta}); each side's largest terms.
  const T rotor = w2 * capacity + (p.rotor.stiffness + M * w2 + p.rotor.damping * p.omega) * q;
  const int n = ball_count(p);
  Coordinates<T, N> scale(n + 2);
  scale(0) = scale(1) = rotor;
  // Ball i: m l omega^2 (q1 sin - q2 cos); measured against the natural displacement.
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    scale(2 + i) = b.mass * b.race_radius * w2 * (q + displacement_scale(p));
  }
  return scale;
}

#define ABU_INSTANTIATE_MODEL(T, N)                                                                  \
  template DofMatrix<T, N> mass_matrix<T, N>(const ParamsT<T, N>&, const Coordinates<T, N>&);         \
  template DofMatrix<T, N> mass_derivative_times<T, N>(const ParamsT<T, N>&, const Coordinates<T, N>&,  \
                                                       const Coordinates<T, N>&);                    \
  template Coordinates<T, N> generalized_forces<T, N>(const ParamsT<T, N>&, const State<T, N>&);      \
  template State<T, N> vector_field<T, N>(const ParamsT<T, N>&, const State<T, N>&);                  \
  template State<T, N> vector_field<T, N>(const ParamsT<T, N>&, const State<T, N>&, const T&);        \
  template Linearization<T, N> linearize<T, N>(const ParamsT<T, N>&, const State<T, N>&);             \
  template Linearization<T, N> linearize<T, N>(const ParamsT<T, N>&, const State<T, N>&, const T&);   \
  template StateMatrix<T, N> jacobian<T, N>(const ParamsT<T, N>&, const State<T, N>&, const T&);      \
  template State<T, N> angular_acceleration_derivative<T, N>(const ParamsT<T, N>&, const State<T, N>&); \
  template StateMatrix<T, N> jacobian<T, N>(const Linearization<T, N>&);                              \
  template StateMatrix<T, N> jacobian<T, N>(const ParamsT<T, N>&, const State<T, N>&);                \
  template State<T, N> parameter_derivative<T, N>(const ParamsT<T, N>&, const State<T, N>&, ParamRef); \
  template Coordinates<T, N> generalized_force_derivative<T, N>(const ParamsT<T, N>&, const State<T, N>&, ParamRef); \
  template T displacement_scale<T, N>(const ParamsT<T, N>&);
ABU_INSTANTIATE_MODEL(double, 2)
template FieldDerivatives<double, 2> field_derivatives<double, 2>(const ParamsT<double, 2>&, const State<double, 2>&,
                                                                  ParamRef);
ABU_INSTANTIATE_MODEL(long double, 2)
ABU_INSTANTIATE_MODEL(std::complex<double>, 2)
ABU_INSTANTIATE_MODEL(double, 3)
ABU_INSTANTIATE_MODEL(std::complex<double>, 3)
ABU_INSTANTIATE_MODEL(double, any_balls)
ABU_INSTANTIATE_MODEL(long double, any_balls)
ABU_INSTANTIATE_MODEL(std::complex<double>, any_balls)
#undef ABU_INSTANTIATE_MODEL
// Exact second and third derivatives along a direction (the first Lyapunov coefficient,
// model.md §6.3): the vector field alone, in truncated Taylor series.
template State<Taylor<long double, 3>, 2> vector_field<Taylor<long double, 3>, 2>(
    const ParamsT<Taylor<long double, 3>, 2>&, const State<Taylor<long double, 3>, 2>&);
template State<Taylor<long double, 3>, 2> vector_field<Taylor<long double, 3>, 2>(
    const ParamsT<Taylor<long double, 3>, 2>&, const State<Taylor<long double, 3>, 2>&, const Taylor<long double, 3>&);
template Coordinates<double, 2> static_force_scale<double, 2>(const ParamsT<double, 2>&, const Coordinates<double, 2>&);
template Coordinates<long double, 2> static_force_scale<long double, 2>(const ParamsT<long double, 2>&,
                                                                        const Coordinates<long double, 2>&);
template Coordinates<double, any_balls> static_force_scale<double, any_balls>(const ParamsT<double, any_balls>&,
                                                                              const Coordinates<double, any_balls>&);
template Coordinates<long double, any_balls> static_force_scale<long double, any_balls>(
    const ParamsT<long double, any_balls>&, const Coordinates<long double, any_balls>&);

}  // namespace abu
