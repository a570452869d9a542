// Physical parameters of the rotor + automatic ball balancer (model.md §1, §4) and
// the symbols by which the CLI, the scenes' overrides and the CSV headers address them.
//
// The parameter structs are templated on the scalar so that the model can be evaluated
// in double (fast path), long double (refinement), and std::complex<double>
// (complex-step derivative checks) from one set of equations.
//
//   abu::Params p = abu::params_of<2>(scene);
//   abu::set(p, *abu::parse_param("omega", 2), 1200.0);
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace abu {

/// Friction law acting on each ball along +beta_i (model.md §4). Only the smooth laws
/// are modelled; `coulomb-set` (the kappa -> infinity limit) is not a vector field.
enum class FrictionLaw { none, viscous, coulomb, stribeck };
std::string_view to_string(FrictionLaw law);
std::optional<FrictionLaw> friction_law_from_string(std::string_view name);

/// One ball of the balancing unit. Friction coefficients are per ball; which of them
/// enter the model depends on the law (see `law_uses`).
template <class T>
struct BallT {
  T mass{};            ///< m_i [kg]
  T race_radius{};     ///< l_i [m], rotor axis to ball centre
  T radius{};          ///< r_i [m]; enters model.md §3 only through j_i, which is fixed below
  T inertia_factor{};  ///< j_i = 1 + I_i/(m_i r_i^2): 7/5 rolling solid sphere, 1 sliding
  T mu{};              ///< coulomb: mu_i = f_i / r_i [-]
  T d{};               ///< viscous: d_i [N s/m]
  T mu_c{};            ///< stribeck: Coulomb level [-]
  T mu_s{};            ///< stribeck: static (breakaway) level [-]
  T v_s{};             ///< stribeck: Stribeck velocity [rad/s]

  template <class U>
  BallT<U> cast() const {
    return {U(mass), U(race_radius), U(radius), U(inertia_factor), U(mu), U(d), U(mu_c), U(mu_s), U(v_s)};
  }
};

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

/// Everything the vector field of model.md §3 depends on, for N balls.
template <class T, int N>
struct ParamsT {
  static constexpr int balls_count = N;
  RotorT<T> rotor{};
  T omega{};  ///< spin speed [rad/s]
  FrictionLaw law = FrictionLaw::none;
  T kappa{};  ///< arctan sharpness of coulomb/stribeck [s/rad]
  std::array<BallT<T>, N> balls{};

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
    for (int i = 0; i < N; ++i) p.balls[std::size_t(i)] = balls[std::size_t(i)].template cast<U>();
    return p;
  }
};

/// The two-ball model: the analyzer's fixed-size hot path.
using Params = ParamsT<double, 2>;

/// What a parameter symbol refers to.
enum class Quantity {
  omega, unbalance, stiffness, damping, rotor_mass,          // global
  ball_mass, race_radius, ball_radius, mu, d, mu_c, mu_s, v_s,  // per ball
  kappa                                                        // global friction
};

/// A parameter as model.md names it: `omega U k c M_r kappa` (global) and
/// `m l r mu d mu_c mu_s v_s` (every ball) or `m1 l2 mu1 ...` (one ball, 1-based).
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
