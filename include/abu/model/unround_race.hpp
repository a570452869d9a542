// An unround race (model.md §11): the centre path of each ball is a curve
// p_i(beta) = l_i(beta) e^{i beta} instead of the circle l_i e^{i beta}, with
//
//     l_i(beta) = E_i(beta) (1 + sum_{k >= 2} eps_k cos(k beta - phi_k))          (11.1.1)
//
// where E_i is the exactly offset circle of radius l_i, centre d = l_i eps_1 e^{i phi_1}
// (order 1, E_i = l_i when there is none). The equations of motion (§11.3), their
// linearization at rest (§11.5) and the scene rules on the shape (§11.1) live here.
//
//   abu::RaceShape race{{ {{2, 1e-3, 0.3}}, {{2, 1e-3, 0.3}} }};   // both balls, one oval
//   auto pt = abu::path_point(race.balls[0], 0.018L, 0.5L);          // l, l', l'', p', p'', s', s''
//   auto lin = abu::unround_linearization(p, race, s);                // p: ParamsT<long double, any_balls>
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abu/model/model.hpp"

namespace abu {

/// One harmonic of a path radius (model.md §11.1): order k >= 1, relative amplitude
/// eps_k >= 0, phase phi_k [rad]. Order 1 is the exact offset circle (d = l eps_1).
struct RaceHarmonic {
  int order = 2;
  double amplitude = 0.0;
  double phase = 0.0;
  friend bool operator==(const RaceHarmonic&, const RaceHarmonic&) = default;
};
using RaceHarmonics = std::vector<RaceHarmonic>;

/// The centre paths of all balls: one list of harmonics per ball (an empty list: round).
struct RaceShape {
  std::vector<RaceHarmonics> balls;
  /// Every amplitude is zero: the round race of model.md §3, handled by the round model.
  bool round() const;
  /// The largest order present (0 for a round race).
  int max_order() const;
};

/// The race's harmonics, one line per ball, each starting with `prefix` ("# " in CSV
/// headers): "race, ball 1 (path radius l_i (1 + ...), model.md §11.1): order 2 amplitude ...".
std::string describe_race(const RaceShape& race, std::string_view prefix);

/// The race with every amplitude (order 1's offset included) times `factor` >= 0: the
/// unroundness parameter of model.md §11.10 (factor 1 is the scene's race, 0 the round one).
RaceShape scaled_race(const RaceShape& race, double factor);

/// The path radius and what §11.1 derives from it at one angle (' = d/d beta).
template <class T>
struct PathPoint {
  T ell{}, d1{}, d2{};  ///< l(beta), l', l''
  T u{}, v{};           ///< p' = u + i v
  T du{}, dv{};         ///< p'' = u' + i v'
  T speed{};            ///< s' = |p'|
  T dspeed{};           ///< s'' = l' (l + l'') / s'
};

/// The path point of a ball with race radius l at angle beta (11.1.1), exact.
/// Instantiated for double and long double.
template <class T>
PathPoint<T> path_point(const RaceHarmonics& h, T l, T beta);

/// Harmonics of a race *surface* rho(theta) = R_s (1 + sum e_k cos(k theta - phi_k)),
/// R_s = l + r, converted to the path radius of a ball of radius r (§11.1): eps_k =
/// e_k (l + r) / l, the same phases; exact for order 1 (parallel circles), O(e^2) otherwise.
RaceHarmonics surface_to_path(const RaceHarmonics& surface, double l, double r);

/// The rule a ball's centre path breaks, if any (§11.1): the path radius must stay > 0,
/// and the race wall (the path's outer parallel at distance r) must be smooth, i.e. its
/// radius of curvature must exceed r wherever it is concave towards the ball. Checked
/// on 4096 k_max angles (and an offset below l for order 1).
std::optional<std::string> path_violation(const RaceHarmonics& h, double l, double r);

/// Lambda = max over balls and harmonics of k^2 eps_k |K + iC| / (m_i omega^2) (§11.6):
/// the race-lock stiffness over the balancing stiffness; first order holds for Lambda << 1.
double unround_lambda(const ParamsN& p, const RaceShape& race);
/// Lambda <= this is reported as the first-order regime (marked in tables, sweeps and maps).
inline constexpr double kFirstOrderLambda = 0.1;

using LongParamsN = ParamsT<long double, any_balls>;

/// A(beta) of §11.3 (ball rows multiplied by s_i'); symmetric positive definite.
DofMatrix<long double, any_balls> unround_mass_matrix(const LongParamsN& p, const RaceShape& race,
                                                      const Coordinates<long double, any_balls>& s);
/// b(s, s') of §11.3; friction F_i = F^{§4}(nu_i) with nu_i = s_i' beta_i' / l_i (§11.2).
Coordinates<long double, any_balls> unround_generalized_forces(const LongParamsN& p, const RaceShape& race,
                                                               const State<long double, any_balls>& x);
/// The linearization at a state at rest (s' = 0; s'' = 0 at an equilibrium), §11.5:
/// mass A, damping D = -db/ds', stiffness E = -db/ds. With a round race this is
/// linearize() of model.hpp at rest.
Linearization<long double, any_balls> unround_linearization(const LongParamsN& p, const RaceShape& race,
                                                            const Coordinates<long double, any_balls>& s);

}  // namespace abu
