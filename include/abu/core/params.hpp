// Physical parameters of the rotor + automatic ball balancer (model.md §1, §4) and
// the symbols by which the CLI, the scenes' overrides and the CSV headers address them.
//
// The parameter structs are templated on the scalar so that the model can be evaluated
// in double (fast path), long double (refinement), and std::complex<double>
// (complex-step derivative checks) from one set of equations, and on the ball count N:
// a compile-time count (N = 2, the analyzer's fixed-size hot path) or `any_balls`, a
// count known at run time, at most `max_balls`, kept in bounded storage (no heap).
//
//   abu::Params p = abu::params_of<2>(scene);
//   abu::set(p, *abu::parse_param("omega", 2), 1200.0);
//   abu::ParamsN pn = abu::params_of<abu::any_balls>(scene);   // any 2 <= n <= 12
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <stdexcept>
#include <string_view>
#include <numbers>
#include <type_traits>

namespace abu {

/// Friction law acting on each ball along +beta_i (model.md §4). `lugre` (model.md §12)
/// adds one bristle state z_i per ball: its field is model/lugre.hpp's, of dimension
/// 3n + 4; the (2n + 4) field of model.hpp is not defined for it. `coulomb_set` (scene
/// name `coulomb-set`, the kappa -> infinity limit (4.6)) is not a vector field: only the
/// stick-set analysis of model.md §14 (equilibria/stick_set.hpp) takes it.
enum class FrictionLaw { none, viscous, coulomb, stribeck, lugre, coulomb_set };
std::string_view to_string(FrictionLaw law);
std::optional<FrictionLaw> friction_law_from_string(std::string_view name);

/// Which of a ball's model values follow from an engineer's specification (model.md
/// §1.1): bits of BallT::specified. A set bit makes the derived value follow the ball
/// radius r (set_ball).
namespace specified {
inline constexpr std::uint8_t density = 1;         ///< m = rho (4/3) pi r^3 = rho pi d^3 / 6   (1.1.1)
inline constexpr std::uint8_t rolling_length = 2;  ///< mu = f / r                               (1.1.2)
inline constexpr std::uint8_t surface_radius = 4;  ///< l = R_s - r                              (1.1.3)
}  // namespace specified

/// The density a ball given by its diameter has unless the scene says otherwise:
/// bearing steel [kg/m^3].
inline constexpr double kSteelDensity = 7850.0;

/// One ball of the balancing unit. Friction coefficients are per ball; which of them
/// enter the model depends on the law (see `law_uses`). mass, mu and race_radius are
/// what the equations use; density, rolling_length and surface_radius are the
/// engineer's specification they were derived from, where `specified` says so.
template <class T>
struct BallT {
  T mass{};            ///< m_i [kg]
  T race_radius{};     ///< l_i [m], rotor axis to ball centre
  T radius{};          ///< r_i [m]; enters model.md §3 only through j_i, which is fixed below
  T inertia_factor{};  ///< j_i = 1 + I_i/(m_i r_i^2): 7/5 rolling solid sphere, 1 sliding
  T mu{};              ///< coulomb: mu_i = f_i / r_i [-]
  T d{};               ///< viscous: d_i [N s/m]
  T mu_c{};            ///< stribeck, lugre: Coulomb level [-]
  T mu_s{};            ///< stribeck, lugre: static (breakaway) level [-]
  T v_s{};             ///< stribeck, lugre: Stribeck velocity [rad/s]
  T sigma0{};          ///< lugre: bristle stiffness per unit normal force [1/rad]
  T sigma1{};          ///< lugre: bristle damping per unit normal force [s/rad]
  T sigma2{};          ///< lugre: viscous coefficient per unit normal force [s/rad]
  T density{};         ///< rho_i [kg/m^3], if specified & specified::density
  T rolling_length{};  ///< f_i [m], if specified & specified::rolling_length
  T surface_radius{};  ///< R_s,i [m], race surface radius, if specified & specified::surface_radius
  std::uint8_t specified = 0;  ///< bits of abu::specified: which of m, mu, l are derived

  template <class U>
  BallT<U> cast() const {
    return {U(mass),   U(race_radius), U(radius),         U(inertia_factor), U(mu),
            U(d),      U(mu_c),        U(mu_s),           U(v_s),            U(sigma0),
            U(sigma1), U(sigma2),      U(density),        U(rolling_length), U(surface_radius),
            specified};
  }
};

/// The analyzer's bound on the number of balls (real balancers carry 3 to 12).
inline constexpr int max_balls = 12;
/// N for a ball count known only at run time. Equal to Eigen::Dynamic, so that the
/// model's matrix types become bounded-dynamic: fixed storage for max_balls, no heap.
inline constexpr int any_balls = -1;
/// Storage for N balls: N itself, or max_balls for a run-time count.
template <int N>
inline constexpr int ball_capacity = N == any_balls ? max_balls : N;

/// Up to max_balls balls in fixed storage: the ball list of a run-time ball count.
/// Invariant: 0 <= size() <= max_balls.
template <class B>
class BoundedBalls {
 public:
  std::size_t size() const { return count_; }
  /// Sets the count; the new balls are value-initialized. Throws std::length_error
  /// beyond max_balls (scenes are checked before, so this is a programming error).
  void resize(std::size_t n);
  B& operator[](std::size_t i) { return items_[i]; }
  const B& operator[](std::size_t i) const { return items_[i]; }
  B* begin() { return items_.data(); }
  B* end() { return items_.data() + count_; }
  const B* begin() const { return items_.data(); }
  const B* end() const { return items_.data() + count_; }

 private:
  std::array<B, max_balls> items_{};
  std::size_t count_ = 0;
};

template <class B>
void BoundedBalls<B>::resize(std::size_t n) {
  if (n > std::size_t(max_balls)) throw std::length_error("BoundedBalls: more than max_balls balls");
  for (std::size_t i = count_; i < n; ++i) items_[i] = B{};
  count_ = n;
}

/// Jeffcott rotor on an isotropic elastic support (model.md §1).
template <class T>
struct RotorT {
  T mass{};       ///< M_r [kg], without the balls, including the unbalance mass
  T stiffness{};  ///< k [N/m]
  T damping{};    ///< c [N s/m]
  T unbalance{};  ///< U = m_u e [kg m]

  template <class U>
  RotorT<U> cast() const {
    return {U(mass), U(stiffness), U(damping), U(unbalance)};
  }
};

/// Everything the vector field of model.md §3 depends on, for N balls (N = any_balls:
/// as many as `balls` holds).
template <class T, int N>
struct ParamsT {
  RotorT<T> rotor{};
  T omega{};  ///< spin speed [rad/s]
  FrictionLaw law = FrictionLaw::none;
  T kappa{};  ///< arctan sharpness of coulomb/stribeck [s/rad]
  std::conditional_t<N == any_balls, BoundedBalls<BallT<T>>, std::array<BallT<T>, std::size_t(N < 0 ? 0 : N)>> balls{};

  int n_balls() const { return int(balls.size()); }

  /// M = M_r + sum m_i, the translating mass.
  T total_mass() const {
    T m = rotor.mass;
    for (const auto& b : balls) m += b.mass;
    return m;
  }

  template <class U>
  ParamsT<U, N> cast() const {
    ParamsT<U, N> p;
    p.rotor = rotor.template cast<U>();
    p.omega = U(omega);
    p.law = law;
    p.kappa = U(kappa);
    if constexpr (N == any_balls) p.balls.resize(balls.size());
    for (std::size_t i = 0; i < balls.size(); ++i) p.balls[i] = balls[i].template cast<U>();
    return p;
  }
};

/// The number of balls: the constant N, or the run-time count for N = any_balls (so
/// that loops over the balls of a fixed-size model keep a compile-time bound).
template <class T, int N>
constexpr int ball_count(const ParamsT<T, N>& p) {
  if constexpr (N == any_balls) {
    return p.n_balls();
  } else {
    return N;
  }
}

/// The two-ball model: the analyzer's fixed-size hot path.
using Params = ParamsT<double, 2>;
/// Any number of balls, 2 <= n <= max_balls, in bounded storage.
using ParamsN = ParamsT<double, any_balls>;

/// What a parameter symbol refers to.
enum class Quantity {
  omega, unbalance, stiffness, damping, rotor_mass,          // global
  ball_mass, race_radius, ball_radius, mu, d, mu_c, mu_s, v_s,  // per ball
  sigma0, sigma1, sigma2,                                      // per ball (lugre)
  kappa,                                                       // global friction
  density, rolling_length, surface_radius                      // per ball: specification (model.md §1.1)
};

/// A parameter as model.md names it: `omega U k c M_r kappa` (global) and
/// `m l r mu d mu_c mu_s v_s sigma0 sigma1 sigma2 rho f R_s` (every ball) or `m1 l2 mu1 ...`
/// (one ball, 1-based).
struct ParamRef {
  Quantity quantity = Quantity::omega;
  int ball = -1;  ///< -1: every ball; otherwise 0-based ball index
  friend bool operator==(const ParamRef&, const ParamRef&) = default;
};

bool is_per_ball(Quantity q);
/// Parses a model.md symbol for a scene with `n_balls` balls; nullopt if unknown or
/// the ball index is out of range.
std::optional<ParamRef> parse_param(std::string_view symbol, int n_balls);
/// The model.md symbol: "omega", "M_r", "m", "m2", "mu_c", ...
std::string to_string(ParamRef ref);
/// SI unit of the quantity, as written in CSV headers ("rad/s", "kg", "-").
std::string_view unit(Quantity q);
/// The symbols accepted on the command line, for help texts.
std::string_view param_symbols_help();

/// Does the friction law read this coefficient? (`mu` is coulomb's, `d` viscous', ...)
bool law_uses(FrictionLaw law, Quantity q);

/// The member of a ball that a per-ball quantity names (ball_mass -> mass, mu -> mu, ...;
/// v_s for any other quantity).
template <class T>
T& ball_field(BallT<T>& b, Quantity q) {
  switch (q) {
    case Quantity::ball_mass: return b.mass;
    case Quantity::race_radius: return b.race_radius;
    case Quantity::ball_radius: return b.radius;
    case Quantity::mu: return b.mu;
    case Quantity::d: return b.d;
    case Quantity::mu_c: return b.mu_c;
    case Quantity::mu_s: return b.mu_s;
    case Quantity::sigma0: return b.sigma0;
    case Quantity::sigma1: return b.sigma1;
    case Quantity::sigma2: return b.sigma2;
    case Quantity::density: return b.density;
    case Quantity::rolling_length: return b.rolling_length;
    case Quantity::surface_radius: return b.surface_radius;
    default: return b.v_s;
  }
}
template <class T>
const T& ball_field(const BallT<T>& b, Quantity q) {
  return ball_field(const_cast<BallT<T>&>(b), q);
}

/// pi in the scalar's own precision (double's for scalars that are not floating point).
template <class T>
T pi_in() {
  if constexpr (std::is_floating_point_v<T>) {
    return std::numbers::pi_v<T>;
  } else {
    return T(std::numbers::pi_v<double>);
  }
}

/// Recomputes the values of a ball that its specification gives (model.md (1.1.1)-(1.1.3)):
/// m = rho (4/3) pi r^3, mu = f / r, l = R_s - r, each where `specified` has its bit.
template <class T>
void derive_specified(BallT<T>& b) {
  if (b.specified & specified::density) b.mass = b.density * T(4) / T(3) * pi_in<T>() * b.radius * b.radius * b.radius;
  if (b.specified & specified::rolling_length) b.mu = b.rolling_length / b.radius;
  if (b.specified & specified::surface_radius) b.race_radius = b.surface_radius - b.radius;
}

/// Sets one per-ball quantity of a ball, keeping its specification consistent: a
/// specification value (rho, f, R_s) sets its bit, the value it gives directly (m, mu,
/// l) clears it (the last one set wins), and every derived value follows (r included:
/// with f given, a new r is a new mu).
template <class T>
void set_ball(BallT<T>& b, Quantity q, T value) {
  ball_field(b, q) = value;
  switch (q) {
    case Quantity::density: b.specified |= specified::density; break;
    case Quantity::rolling_length: b.specified |= specified::rolling_length; break;
    case Quantity::surface_radius: b.specified |= specified::surface_radius; break;
    case Quantity::ball_mass: b.specified &= std::uint8_t(~specified::density); break;
    case Quantity::mu: b.specified &= std::uint8_t(~specified::rolling_length); break;
    case Quantity::race_radius: b.specified &= std::uint8_t(~specified::surface_radius); break;
    default: break;
  }
  derive_specified(b);
}

/// How the values the model uses (m, mu, l) of a ball change with a quantity that its
/// specification ties to them: the chain rule's factors dm/dq, dmu/dq, dl/dq (all zero
/// for a quantity that is not r, rho, f or R_s). rho, f and R_s count as specified (setting
/// them makes them so); r moves only the values specified through it.
template <class T>
struct SpecifiedSensitivity {
  T dmass{}, dmu{}, drace_radius{};
};
template <class T>
SpecifiedSensitivity<T> specified_sensitivity(const BallT<T>& b, Quantity q) {
  SpecifiedSensitivity<T> s;
  const T r = b.radius;
  switch (q) {
    case Quantity::ball_radius:
      if (b.specified & specified::density) s.dmass = T(4) * pi_in<T>() * b.density * r * r;  // d/dr (1.1.1)
      if (b.specified & specified::rolling_length) s.dmu = -b.rolling_length / (r * r);            // d/dr (1.1.2)
      if (b.specified & specified::surface_radius) s.drace_radius = T(-1);                         // d/dr (1.1.3)
      break;
    case Quantity::density: s.dmass = T(4) / T(3) * pi_in<T>() * r * r * r; break;
    case Quantity::rolling_length: s.dmu = T(1) / r; break;
    case Quantity::surface_radius: s.drace_radius = T(1); break;
    default: break;
  }
  return s;
}
/// Is q a quantity that moves m, mu or l through a specification (r, rho, f, R_s)?
bool acts_through_specification(Quantity q);

/// Value of a parameter. For an every-ball reference it is ball 1's value (the balls
/// of a scene addressed as a set are usually equal; `set` makes them so).
template <class T, int N>
T get(const ParamsT<T, N>& p, ParamRef ref);
/// Sets a parameter (every ball, or one). Instantiated for double and long double.
template <class T, int N>
void set(ParamsT<T, N>& p, ParamRef ref, T value);

/// The physical range of a quantity, as a rule that names it (nullopt: value allowed).
/// Used by the scene parser, `--set`, sweeps and continuation alike.
std::optional<std::string> range_violation(Quantity q, double value);

}  // namespace abu
