#include "abu/input/plausibility.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace abu {

namespace {

// Where a per-ball value comes from, as the user wrote it: the model.md symbol (`m`
// when every ball has the value, `m2` for one ball) and the scene key.
struct BallValue {
  std::string symbol;
  std::string key;
  double value;
  std::size_t ball;  // 0-based, the first ball with it
};

// The distinct values of one ball field: one entry if every ball has it.
// `shared_key` names the key when every ball has the value (default: the ball tables').
template <class Get>
std::vector<BallValue> ball_values(const Scene& scene, std::string_view symbol, std::string_view key, Get get,
                                   std::string shared_key = {}) {
  std::vector<BallValue> out;
  const auto& balls = scene.balls;
  bool all_equal = true;
  for (const auto& b : balls) all_equal = all_equal && get(b) == get(balls.front());
  if (shared_key.empty()) shared_key = scene.ring ? fmt::format("balls.{}", key) : fmt::format("[[ball]] {}", key);
  if (all_equal) {
    out.push_back({std::string(symbol), shared_key, get(balls.front()), 0});
    return out;
  }
  for (std::size_t i = 0; i < balls.size(); ++i) {
    bool seen = false;
    for (std::size_t j = 0; j < i; ++j) seen = seen || get(balls[j]) == get(balls[i]);
    if (!seen)
      out.push_back({fmt::format("{}{}", symbol, i + 1),
                     scene.ring ? fmt::format("balls.{} (ball {})", key, i + 1)
                                : fmt::format("ball[{}].{}", i + 1, key),
                     get(balls[i]), i});
  }
  return out;
}

std::string g(double v) { return fmt::format("{:.4g}", v); }

}  // namespace

std::vector<std::string> implausible_values(const Scene& scene) {
  std::vector<std::string> out;
  const auto& rotor = scene.rotor;
  double ball_mass = 0, capacity = 0;
  for (const auto& b : scene.balls) ball_mass += b.mass, capacity += b.mass * b.race_radius;
  const double omega_n = std::sqrt(rotor.stiffness / (rotor.mass + ball_mass));

  for (const auto& v : ball_values(scene, "m", "mass", [](const auto& b) { return b.mass; }))
    if (v.value > rotor.mass)
      out.push_back(fmt::format("{} = {} kg ({}) is more than the rotor's mass M_r = {} kg: grams typed as kilograms?",
                                v.symbol, g(v.value), v.key, g(rotor.mass)));
  // A ball of steel (7850 kg/m^3) or tungsten carbide (15600) or even plastic (~1000):
  // a density outside 300 .. 30000 kg/m^3 is a mass or a radius in the wrong unit.
  for (std::size_t i = 0; i < scene.balls.size(); ++i) {
    const auto& b = scene.balls[i];
    bool same_as_before = false;
    for (std::size_t j = 0; j < i; ++j)
      same_as_before = same_as_before || (scene.balls[j].mass == b.mass && scene.balls[j].radius == b.radius);
    if (same_as_before) continue;
    const double density = b.mass / (4.0 / 3.0 * std::numbers::pi * b.radius * b.radius * b.radius);
    if (density >= 300 && density <= 30000) continue;
    bool every_ball = true;
    for (const auto& o : scene.balls) every_ball = every_ball && o.mass == b.mass && o.radius == b.radius;
    const std::string which = every_ball ? "" : fmt::format("{}", i + 1);
    out.push_back(fmt::format(
        "m{} = {} kg with r{} = {} m makes a ball of {} kg/m^3 (steel 7850): {}?", which, g(b.mass), which,
        g(b.radius), g(density),
        density > 30000 ? "the mass in grams typed as kilograms, or the radius divided by 1000 once too often"
                        : "the radius in millimetres typed as metres, or the mass divided by 1000 once too often"));
  }
  for (const auto& v : ball_values(scene, "l", "race_radius", [](const auto& b) { return b.race_radius; })) {
    if (v.value > 1.0)
      out.push_back(fmt::format("{} = {} m ({}) is a race radius above 1 m: millimetres typed as metres?", v.symbol,
                                g(v.value), v.key));
    else if (v.value < 1e-3)
      out.push_back(fmt::format("{} = {} m ({}) is a race radius below 1 mm: is it in metres (18 mm = 0.018)?",
                                v.symbol, g(v.value), v.key));
  }
  for (const auto& v : ball_values(scene, "r", "radius", [](const auto& b) { return b.radius; }))
    if (v.value > 0.1)
      out.push_back(fmt::format("{} = {} m ({}) is a ball radius above 10 cm: millimetres typed as metres?", v.symbol,
                                g(v.value), v.key));
  if (rotor.mass > 1000)
    out.push_back(fmt::format("M_r = {} kg (rotor.mass) is a rotor above a tonne: grams typed as kilograms?",
                              g(rotor.mass)));
  if (omega_n < 1)
    out.push_back(fmt::format(
        "omega_n = sqrt(k / (M_r + sum m)) = {} rad/s is below 1 rad/s (k = {} N/m, rotor.stiffness): is k in N/m "
        "(1 kN/m = 1000 N/m, 1 N/mm = 1000 N/m) and the masses in kg?",
        g(omega_n), g(rotor.stiffness)));
  if (rotor.unbalance > 10 * capacity)
    out.push_back(fmt::format(
        "U = {} kg m (rotor.unbalance) is {} times what the balls can cancel, sum m_i l_i = {} kg m: U is m_u e in "
        "kg m (1 g mm = 1e-6 kg m); grams or millimetres typed as kg or m?",
        g(rotor.unbalance), g(rotor.unbalance / capacity), g(capacity)));
  if (omega_n >= 1 && scene.omega > 100 * omega_n)
    out.push_back(fmt::format("omega = {} rad/s (speed.omega) is {} omega_n (omega_n = {} rad/s): rpm typed as rad/s "
                              "(1 rpm = 0.1047 rad/s)?",
                              g(scene.omega), g(scene.omega / omega_n), g(omega_n)));
  if (scene.law == FrictionLaw::coulomb || scene.law == FrictionLaw::stribeck || scene.law == FrictionLaw::lugre) {
    const bool coulomb = scene.law == FrictionLaw::coulomb;
    const auto check = [&](std::string_view symbol, auto get) {
      for (const auto& v : ball_values(scene, symbol, symbol, get, fmt::format("friction.{}", symbol)))
        if (v.value > 0.5)
          out.push_back(fmt::format(
              "{} = {} ({}) is large for a rolling resistance: mu = f / r, the lever arm f of rolling friction over "
              "the ball radius, is 1e-4 .. 1e-2 for balls in a race; a sliding friction coefficient?",
              v.symbol, g(v.value), v.key));
    };
    if (coulomb) {
      check("mu", [](const auto& b) { return b.mu; });
    } else {
      check("mu_c", [](const auto& b) { return b.mu_c; });
      check("mu_s", [](const auto& b) { return b.mu_s; });
    }
  }
  return out;
}

}  // namespace abu
