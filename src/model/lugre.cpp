// LuGre friction per ball: the (3n + 4) field, its Jacobian and the spring-dashpot
// linearization at rest (model.md §12). The mechanical part reuses model.hpp with the law
// `none` (F = 0) and adds l_i F_i to each ball row of b, so that §3 is written once.
#include "abu/model/lugre.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

namespace abu {

std::string_view to_string(RestSide side) { return side == RestSide::forward ? "forward" : "backward"; }

namespace {

template <class T>
ParamsT<T, any_balls> frictionless(const ParamsT<T, any_balls>& p) {
  ParamsT<T, any_balls> q = p;
  q.law = FrictionLaw::none;
  return q;
}

template <class T>
T normal_force(const ParamsT<T, any_balls>& p, int i) {
  const auto& b = p.balls[std::size_t(i)];
  return b.mass * b.race_radius * p.omega * p.omega;  // N_i = m_i l_i omega^2, (1.6)
}

// (dA/ds) y of model.md (6.6): only the beta_j columns are nonzero.
template <class T>
DofMatrix<T, any_balls> mass_derivative_times(const ParamsT<T, any_balls>& p, const Coordinates<T, any_balls>& s,
                                              const Coordinates<T, any_balls>& y) {
  using std::cos;
  using std::sin;
  const int n = p.n_balls();
  DofMatrix<T, any_balls> out = DofMatrix<T, any_balls>::Zero(n + 2, n + 2);
  for (int j = 0; j < n; ++j) {
    const auto& b = p.balls[std::size_t(j)];
    const T a = b.mass * b.race_radius, c = cos(s(2 + j)), sn = sin(s(2 + j));
    out(0, 2 + j) = -a * c * y(2 + j);
    out(1, 2 + j) = -a * sn * y(2 + j);
    out(2 + j, 2 + j) = -a * (c * y(0) + sn * y(1));
  }
  return out;
}

}  // namespace

template <class T>
T lugre_level(const BallT<T>& b, const T& v) {
  using std::exp;
  const T x = v / b.v_s;
  return b.mu_c + (b.mu_s - b.mu_c) * exp(-x * x);
}

template <class T>
T bristle_rate(const BallT<T>& b, const T& v, const T& z) {
  using std::abs;
  return v - b.sigma0 * abs(v) * z / lugre_level(b, v);
}

template <class T>
T lugre_force(const ParamsT<T, any_balls>& p, int ball, const T& v, const T& z) {
  const auto& b = p.balls[std::size_t(ball)];
  return -normal_force(p, ball) * (b.sigma0 * z + b.sigma1 * bristle_rate(b, v, z) + b.sigma2 * v);
}

template <class T>
T bristle_rate_dv(const BallT<T>& b, const T& v, const T& z, RestSide side) {
  using std::abs;
  using std::exp;
  if (v == T(0)) {  // one-sided limit (12.9): g(0) = mu_s, d|v|/dv = +-1
    const T sign = side == RestSide::forward ? T(1) : T(-1);
    return T(1) - b.sigma0 * z * sign / b.mu_s;
  }
  const T g = lugre_level(b, v);
  const T x = v / b.v_s;
  const T dg = (b.mu_s - b.mu_c) * exp(-x * x) * (T(-2) * x / b.v_s);
  const T sign = v > T(0) ? T(1) : T(-1);
  return T(1) - b.sigma0 * z * (sign * g - abs(v) * dg) / (g * g);  // (12.7)
}

template <class T>
LugreState<T> lugre_vector_field(const ParamsT<T, any_balls>& p, const LugreState<T>& x) {
  const int n = p.n_balls(), d = n + 2;
  if (x.size() != 3 * n + 4) throw std::invalid_argument("lugre_vector_field: state is not of size 3n + 4");
  const State<T, any_balls> xm = x.head(2 * d);
  const auto pn = frictionless(p);
  Coordinates<T, any_balls> b = generalized_forces(pn, xm);
  for (int i = 0; i < n; ++i)
    b(2 + i) += p.balls[std::size_t(i)].race_radius * lugre_force(p, i, x(d + 2 + i), x(2 * d + i));
  const DofMatrix<T, any_balls> A = mass_matrix(pn, Coordinates<T, any_balls>(x.head(d)));
  LugreState<T> f(3 * n + 4);
  f.head(d) = x.segment(d, d);
  f.segment(d, d) = A.partialPivLu().solve(b);
  for (int i = 0; i < n; ++i) f(2 * d + i) = bristle_rate(p.balls[std::size_t(i)], x(d + 2 + i), x(2 * d + i));
  return f;
}

template <class T>
LugreMatrix<T> lugre_jacobian(const ParamsT<T, any_balls>& p, const LugreState<T>& x, RestSide side) {
  using std::abs;
  const int n = p.n_balls(), d = n + 2, m = 3 * n + 4;
  if (x.size() != m) throw std::invalid_argument("lugre_jacobian: state is not of size 3n + 4");
  const State<T, any_balls> xm = x.head(2 * d);
  const Coordinates<T, any_balls> s = x.head(d);
  const auto pn = frictionless(p);
  Linearization<T, any_balls> lin = linearize(pn, xm);  // F = 0: K holds (dA/ds) s''(F = 0)
  const auto lu = lin.mass.partialPivLu();
  // The friction's share of s'' and of K = -db/ds + (dA/ds) s'' (model.md (6.5)).
  Coordinates<T, any_balls> friction_rows = Coordinates<T, any_balls>::Zero(d);
  for (int i = 0; i < n; ++i)
    friction_rows(2 + i) = p.balls[std::size_t(i)].race_radius * lugre_force(p, i, x(d + 2 + i), x(2 * d + i));
  const Coordinates<T, any_balls> friction_accel = lu.solve(friction_rows);
  lin.stiffness += mass_derivative_times(p, s, friction_accel);
  DofMatrix<T, any_balls> bz = DofMatrix<T, any_balls>::Zero(d, d);  // db/dz in columns 2 + i
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const T v = x(d + 2 + i), z = x(2 * d + i), nf = normal_force(p, i);
    const T dzdv = bristle_rate_dv(b, v, z, side);
    const T dzdz = -b.sigma0 * abs(v) / lugre_level(b, v);  // (12.8)
    lin.damping(2 + i, 2 + i) += b.race_radius * nf * (b.sigma1 * dzdv + b.sigma2);  // C = -db/ds'
    bz(2 + i, 2 + i) = -b.race_radius * nf * (b.sigma0 + b.sigma1 * dzdz);
  }
  LugreMatrix<T> J = LugreMatrix<T>::Zero(m, m);
  J.block(0, d, d, d).setIdentity();
  J.block(d, 0, d, d) = -lu.solve(lin.stiffness);
  J.block(d, d, d, d) = -lu.solve(lin.damping);
  const DofMatrix<T, any_balls> az = lu.solve(bz);
  J.block(d, 2 * d, d, n) = az.rightCols(n);
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const T v = x(d + 2 + i), z = x(2 * d + i);
    J(2 * d + i, d + 2 + i) = bristle_rate_dv(b, v, z, side);
    J(2 * d + i, 2 * d + i) = -b.sigma0 * abs(v) / lugre_level(b, v);
  }
  return J;
}

template <class T>
LugreState<T> lugre_vector_field(const ParamsT<T, any_balls>& p, const LugreState<T>& x, const T& omega_dot) {
  LugreState<T> f = lugre_vector_field(p, x);
  if (omega_dot == T(0)) return f;
  const int d = p.n_balls() + 2;
  const State<T, any_balls> euler = angular_acceleration_derivative(frictionless(p), State<T, any_balls>(x.head(2 * d)));
  f.head(2 * d) += omega_dot * euler;  // (12.11)
  return f;
}

template <class T>
LugreMatrix<T> lugre_jacobian(const ParamsT<T, any_balls>& p, const LugreState<T>& x, RestSide side,
                              const T& omega_dot) {
  LugreMatrix<T> J = lugre_jacobian(p, x, side);
  if (omega_dot == T(0)) return J;
  const int d = p.n_balls() + 2;
  const auto pn = frictionless(p);
  const State<T, any_balls> xm = x.head(2 * d);
  // The Euler terms' Jacobian: the frictionless model's with and without omega'.
  J.topLeftCorner(2 * d, 2 * d) += jacobian(pn, xm, omega_dot) - jacobian(pn, xm);
  return J;
}

template <class T>
LugreState<T> lugre_omega_derivative(const ParamsT<T, any_balls>& p, const LugreState<T>& x) {
  const int n = p.n_balls(), d = n + 2;
  const auto pn = frictionless(p);
  const State<T, any_balls> xm = x.head(2 * d);
  LugreState<T> df = LugreState<T>::Zero(3 * n + 4);
  df.head(2 * d) = parameter_derivative(pn, xm, ParamRef{Quantity::omega, -1});
  // The friction's share of s'' is proportional to omega^2 (N_i, (12.3)); at omega = 0
  // its derivative 2 m l omega (...) vanishes.
  if (p.omega == T(0)) return df;
  const LugreState<T> with = lugre_vector_field(p, x);
  const State<T, any_balls> without = vector_field(pn, xm);
  df.segment(d, d) += (T(2) / p.omega) * (with.segment(d, d) - without.segment(d, d));
  return df;
}

template <class T>
T lugre_load_ratio(const ParamsT<T, any_balls>& p, const Coordinates<T, any_balls>& s, int ball) {
  using std::cos;
  using std::sin;
  const auto& b = p.balls[std::size_t(ball)];
  const T beta = s(2 + ball);
  const T tau = (s(0) * sin(beta) - s(1) * cos(beta)) / b.race_radius;  // (12.5)
  return tau / b.mu_s;
}

template <class T>
LugreState<T> lugre_equilibrium(const ParamsT<T, any_balls>& p, const Coordinates<T, any_balls>& s) {
  const int n = p.n_balls(), d = n + 2;
  LugreState<T> x = LugreState<T>::Zero(3 * n + 4);
  x.head(d) = s;
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    x(2 * d + i) = -lugre_load_ratio(p, s, i) * b.mu_s / b.sigma0;  // sigma0 z_i = -tau_i (12.5)
  }
  return x;
}

template <class T>
T lugre_rest_slope(const ParamsT<T, any_balls>& p, const Coordinates<T, any_balls>& s, int ball, RestSide side) {
  const T ratio = lugre_load_ratio(p, s, ball);
  return side == RestSide::forward ? T(1) + ratio : T(1) - ratio;  // (12.9)
}

template <class T>
Linearization<T, any_balls> lugre_rest_linearization(const ParamsT<T, any_balls>& p,
                                                     const Coordinates<T, any_balls>& s, RestSide side,
                                                     bool zero_bristle) {
  const int n = p.n_balls();
  const auto pn = frictionless(p);
  Linearization<T, any_balls> lin = linearize(pn, at_rest<T, any_balls>(s));
  // At the LuGre equilibrium s'' = 0; linearize(pn) used s''(F = 0) = A^-1 b(s, 0; F = 0),
  // whose (dA/ds) s'' term is taken out again (model.md (6.3) holds at s'' = 0).
  const Coordinates<T, any_balls> accel_free = lin.mass.partialPivLu().solve(generalized_forces(pn, at_rest<T, any_balls>(s)));
  lin.stiffness -= mass_derivative_times(p, s, accel_free);
  for (int i = 0; i < n; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const T c = zero_bristle ? T(1) : lugre_rest_slope(p, s, i, side), nf = normal_force(p, i);
    lin.stiffness(2 + i, 2 + i) += b.race_radius * nf * b.sigma0 * c;            // bristle spring
    lin.damping(2 + i, 2 + i) += b.race_radius * nf * (b.sigma1 * c + b.sigma2);  // bristle damper + viscous
  }
  return lin;
}

#define ABU_INSTANTIATE_LUGRE(T)                                                                               \
  template T lugre_level<T>(const BallT<T>&, const T&);                                                        \
  template T bristle_rate<T>(const BallT<T>&, const T&, const T&);                                             \
  template T lugre_force<T>(const ParamsT<T, any_balls>&, int, const T&, const T&);                            \
  template T bristle_rate_dv<T>(const BallT<T>&, const T&, const T&, RestSide);                                \
  template LugreState<T> lugre_vector_field<T>(const ParamsT<T, any_balls>&, const LugreState<T>&);            \
  template LugreMatrix<T> lugre_jacobian<T>(const ParamsT<T, any_balls>&, const LugreState<T>&, RestSide);     \
  template LugreState<T> lugre_vector_field<T>(const ParamsT<T, any_balls>&, const LugreState<T>&, const T&);      \
  template LugreMatrix<T> lugre_jacobian<T>(const ParamsT<T, any_balls>&, const LugreState<T>&, RestSide, const T&); \
  template LugreState<T> lugre_omega_derivative<T>(const ParamsT<T, any_balls>&, const LugreState<T>&);          \
  template LugreState<T> lugre_equilibrium<T>(const ParamsT<T, any_balls>&, const Coordinates<T, any_balls>&); \
  template T lugre_load_ratio<T>(const ParamsT<T, any_balls>&, const Coordinates<T, any_balls>&, int);         \
  template T lugre_rest_slope<T>(const ParamsT<T, any_balls>&, const Coordinates<T, any_balls>&, int, RestSide); \
  template Linearization<T, any_balls> lugre_rest_linearization<T>(                                            \
      const ParamsT<T, any_balls>&, const Coordinates<T, any_balls>&, RestSide, bool);
ABU_INSTANTIATE_LUGRE(double)
ABU_INSTANTIATE_LUGRE(long double)
#undef ABU_INSTANTIATE_LUGRE

}  // namespace abu
