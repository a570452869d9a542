#include "abu/model/friction.hpp"

#include "abu/core/errors.hpp"
#include "abu/core/taylor.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <type_traits>

namespace abu {

namespace {

// The commands refuse `coulomb-set` before any vector field is evaluated (model.md §4).
constexpr const char* kNotVectorField = "friction law 'coulomb-set' is not a vector field (model.md §4)";

template <class T>
struct RealOf {
  using type = T;
};
template <class T>
struct RealOf<std::complex<T>> {
  using type = T;
};
template <class T, int K>
struct RealOf<Taylor<T, K>> {
  using type = T;
};

// (2/pi) atan(kappa v) and its derivatives: the smoothed sign of model.md §4.
template <class T>
T smooth_sign(const T& kappa, const T& v) {
  using R = typename RealOf<T>::type;
  using std::atan;
  return R(2) / std::numbers::pi_v<R> * atan(kappa * v);
}
template <class T>
T smooth_sign_dv(const T& kappa, const T& v) {
  using R = typename RealOf<T>::type;
  return R(2) / std::numbers::pi_v<R> * kappa / (R(1) + kappa * kappa * v * v);
}
template <class T>
T smooth_sign_dkappa(const T& kappa, const T& v) {
  using R = typename RealOf<T>::type;
  return R(2) / std::numbers::pi_v<R> * v / (R(1) + kappa * kappa * v * v);
}

// Stribeck level g(v) = mu_c + (mu_s - mu_c) exp(-(v/v_s)^2).
template <class T>
T stribeck_level(const BallT<T>& b, const T& v) {
  using std::exp;
  const T x = v / b.v_s;
  return b.mu_c + (b.mu_s - b.mu_c) * exp(-x * x);
}

// LuGre's force depends on the bristle state z_i too (model.md §12): it has its own
// (3n + 4) field in model/lugre.hpp. The CLI commands that use the (2n + 4) model refuse
// a LuGre scene up front; any other caller (the Python API) gets NotSupportedError here.
constexpr const char* kLugreHere =
    "friction law 'lugre' (model.md §12) is analysed by 'equilibria' only; this analysis uses the (2n + 4) "
    "model of the smooth laws";

}  // namespace

template <class T, int N>
T friction_force(const ParamsT<T, N>& p, int ball, const T& beta_dot) {
  const auto& b = p.balls[std::size_t(ball)];
  switch (p.law) {
    case FrictionLaw::none: return T(0);
    case FrictionLaw::viscous: return -b.d * b.race_radius * beta_dot;
    case FrictionLaw::coulomb: {
      const T normal = b.mass * b.race_radius * p.omega * p.omega;
      return -b.mu * normal * smooth_sign(p.kappa, beta_dot);
    }
    case FrictionLaw::stribeck: {
      const T normal = b.mass * b.race_radius * p.omega * p.omega;
      return -normal * stribeck_level(b, beta_dot) * smooth_sign(p.kappa, beta_dot);
    }
    case FrictionLaw::lugre: throw NotSupportedError(kLugreHere);
    case FrictionLaw::coulomb_set: throw NotSupportedError(kNotVectorField);
  }
  return T(0);
}

template <class T, int N>
T friction_slope(const ParamsT<T, N>& p, int ball, const T& beta_dot) {
  const auto& b = p.balls[std::size_t(ball)];
  switch (p.law) {
    case FrictionLaw::none: return T(0);
    case FrictionLaw::viscous: return -b.d * b.race_radius;
    case FrictionLaw::coulomb: {
      const T normal = b.mass * b.race_radius * p.omega * p.omega;
      return -b.mu * normal * smooth_sign_dv(p.kappa, beta_dot);
    }
    case FrictionLaw::stribeck: {
      using std::exp;
      const T normal = b.mass * b.race_radius * p.omega * p.omega;
      const T x = beta_dot / b.v_s;
      const T level_dv = (b.mu_s - b.mu_c) * exp(-x * x) * (T(-2) * x / b.v_s);
      return -normal * (level_dv * smooth_sign(p.kappa, beta_dot) +
                        stribeck_level(b, beta_dot) * smooth_sign_dv(p.kappa, beta_dot));
    }
    case FrictionLaw::lugre: throw NotSupportedError(kLugreHere);
    case FrictionLaw::coulomb_set: throw NotSupportedError(kNotVectorField);
  }
  return T(0);
}

template <class T, int N>
T friction_partial(const ParamsT<T, N>& p, int ball, const T& beta_dot, Quantity q) {
  const auto& b = p.balls[std::size_t(ball)];
  const T zero(0);
  switch (p.law) {
    case FrictionLaw::coulomb_set: throw NotSupportedError(kNotVectorField);
    case FrictionLaw::none: return zero;
    case FrictionLaw::viscous:
      if (q == Quantity::d) return -b.race_radius * beta_dot;
      if (q == Quantity::race_radius) return -b.d * beta_dot;
      return zero;
    case FrictionLaw::coulomb:
    case FrictionLaw::stribeck: {
      // F = -N level sign; N = m l omega^2 carries the m, l, omega dependence.
      const T w2 = p.omega * p.omega;
      const T normal = b.mass * b.race_radius * w2;
      const T sign = smooth_sign(p.kappa, beta_dot);
      const bool coulomb = p.law == FrictionLaw::coulomb;
      const T level = coulomb ? b.mu : stribeck_level(b, beta_dot);
      switch (q) {
        case Quantity::omega: return -T(2) * b.mass * b.race_radius * p.omega * level * sign;
        case Quantity::ball_mass: return -b.race_radius * w2 * level * sign;
        case Quantity::race_radius: return -b.mass * w2 * level * sign;
        case Quantity::kappa: return -normal * level * smooth_sign_dkappa(p.kappa, beta_dot);
        default: break;
      }
      if (coulomb) return q == Quantity::mu ? -normal * sign : zero;
      using std::exp;
      const T x = beta_dot / b.v_s;
      const T e = exp(-x * x);
      switch (q) {
        case Quantity::mu_c: {
          // 1 - exp(-x^2) cancels for |beta_dot| << v_s; expm1 keeps it exact (real scalars).
          T one_minus_e;
          if constexpr (std::is_floating_point_v<T>) {
            one_minus_e = -std::expm1(-x * x);
          } else {
            one_minus_e = T(1) - e;
          }
          return -normal * one_minus_e * sign;
        }
        case Quantity::mu_s: return -normal * e * sign;
        // d/dv_s exp(-(v/v_s)^2) = exp(..) 2 v^2 / v_s^3
        case Quantity::v_s: return -normal * (b.mu_s - b.mu_c) * e * (T(2) * x * x / b.v_s) * sign;
        default: return zero;
      }
    }
    case FrictionLaw::lugre: throw NotSupportedError(kLugreHere);
  }
  return zero;
}

#define ABU_INSTANTIATE_FRICTION(T, N)                                                  \
  template T friction_force<T, N>(const ParamsT<T, N>&, int, const T&);                 \
  template T friction_slope<T, N>(const ParamsT<T, N>&, int, const T&);                 \
  template T friction_partial<T, N>(const ParamsT<T, N>&, int, const T&, Quantity);
ABU_INSTANTIATE_FRICTION(double, 2)
ABU_INSTANTIATE_FRICTION(long double, 2)
ABU_INSTANTIATE_FRICTION(std::complex<double>, 2)
ABU_INSTANTIATE_FRICTION(double, 3)
ABU_INSTANTIATE_FRICTION(std::complex<double>, 3)
ABU_INSTANTIATE_FRICTION(double, any_balls)
ABU_INSTANTIATE_FRICTION(long double, any_balls)
ABU_INSTANTIATE_FRICTION(std::complex<double>, any_balls)
#undef ABU_INSTANTIATE_FRICTION
template Taylor<long double, 3> friction_force<Taylor<long double, 3>, 2>(const ParamsT<Taylor<long double, 3>, 2>&, int,
                                                                         const Taylor<long double, 3>&);

}  // namespace abu
