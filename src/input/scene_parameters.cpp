// Setting a scene's parameters after parsing (--set NAME=VALUE, continuation; the rules of
// scene.cpp's parser, each at once) and the model parameters of a scene (params_of).
#include <algorithm>
#include <charconv>
#include <limits>
#include <system_error>

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include "abu/core/suggest.hpp"
#include "abu/input/scene.hpp"
#include "scene_reading.hpp"

namespace abu {

namespace {

using namespace scene_reading;

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

double& global_field(Scene& scene, Quantity q) {
  switch (q) {
    case Quantity::unbalance: return scene.rotor.unbalance;
    case Quantity::stiffness: return scene.rotor.stiffness;
    case Quantity::damping: return scene.rotor.damping;
    case Quantity::rotor_mass: return scene.rotor.mass;
    case Quantity::kappa: return scene.kappa;
    default: return scene.omega;
  }
}

// "ball index out of range: the scene has 3 balls (m1..m3)".
std::string index_out_of_range(std::string_view symbol, std::size_t n) {
  std::size_t digits = symbol.size();
  while (digits > 0 && symbol[digits - 1] >= '0' && symbol[digits - 1] <= '9') --digits;
  const auto base = symbol.substr(0, digits);
  return fmt::format("ball index out of range: the scene has {} balls ({}1..{}{})", n, base, base, n);
}

}  // namespace

void set_checked(Scene& scene, ParamRef ref, double value, const std::string& origin) {
  const std::string key = to_string(ref);
  const auto n = scene.balls.size();
  if (scene.support && (ref.quantity == Quantity::stiffness || ref.quantity == Quantity::damping))
    throw InputError(origin, 0, key,
                     "the scene's support is anisotropic (stiffness_x, ... in [rotor], docs/model.md §10): k and c are "
                     "its means and cannot be set alone; edit the matrix keys in the scene");
  if (scene.shaft && (ref.quantity == Quantity::stiffness || ref.quantity == Quantity::damping ||
                      ref.quantity == Quantity::rotor_mass))
    throw InputError(origin, 0, key,
                     "the scene is a flexible shaft ([shaft], model.md §18.10): its mass is the discs' and the shaft's "
                     "and its support the bearings'; edit [[disc]], [[shaft.element]] or [[bearing]] in the scene");
  if (is_per_ball(ref.quantity) && ref.ball >= int(n)) throw InputError(origin, 0, key, index_out_of_range(key, n));
  if (!law_uses(scene.law, ref.quantity)) throw InputError(origin, 0, key, law_mismatch(scene.law, ref.quantity));
  if (auto bad = range_violation(ref.quantity, value)) throw InputError(origin, 0, key, *bad);
  if (scene.law == FrictionLaw::lugre && (ref.quantity == Quantity::mu_c || ref.quantity == Quantity::mu_s)) {
    const std::size_t from = ref.ball < 0 ? 0 : std::size_t(ref.ball);
    const std::size_t to = ref.ball < 0 ? n : from + 1;
    for (std::size_t i = from; i < to; ++i) {
      const auto& b = scene.balls[i];
      const double mu_c = ref.quantity == Quantity::mu_c ? value : b.mu_c;
      const double mu_s = ref.quantity == Quantity::mu_s ? value : b.mu_s;
      if (auto bad = lugre_level_violation(mu_c, mu_s)) throw InputError(origin, 0, key, *bad + fmt::format(" (ball {})", i + 1));
    }
  }

  // The balls this touches: one, all, or (for a global quantity) none.
  std::size_t first = 0, last = 0;
  if (is_per_ball(ref.quantity)) {
    first = ref.ball < 0 ? 0 : std::size_t(ref.ball);
    last = ref.ball < 0 ? n : first + 1;
  }
  // Cross rule r_i < l_i, checked for every ball before anything changes, on the ball as
  // it would be (with R_s given, r moves l = R_s - r; model.md (1.1.3)).
  for (std::size_t i = first; i < last; ++i) {
    const auto& b = scene.balls[i];
    BallT<double> changed = b;
    set_ball(changed, ref.quantity, value);
    if (changed.radius < changed.race_radius) continue;
    if (ref.quantity == Quantity::ball_radius && !(b.specified & specified::surface_radius))
      throw InputError(origin, 0, key,
                       fmt::format("must be < race_radius (l{} = {}, got {})", i + 1, b.race_radius, value));
    if (ref.quantity == Quantity::race_radius)
      throw InputError(origin, 0, key,
                       fmt::format("must be > ball radius, as radius < race_radius (r{} = {}, got {})", i + 1,
                                   b.radius, value));
    throw InputError(origin, 0, key,
                     fmt::format("gives ball {} l = R_s - r = {} m, which must be > r = {} m (got {}; model.md (1.1.3))",
                                 i + 1, changed.race_radius, changed.radius, value));
  }
  if (!is_per_ball(ref.quantity)) {
    global_field(scene, ref.quantity) = value;
    return;
  }
  for (std::size_t i = first; i < last; ++i) set_ball(scene.balls[i], ref.quantity, value);

  // The ring follows: every ball -> the template (no ball differs in this field any more,
  // active or not); one ball -> that ball's override.
  if (!scene.ring) return;
  BallRing& ring = *scene.ring;
  const BallField f = field_of(ref.quantity);
  auto& overrides = ring.overrides;
  if (ref.ball < 0) {
    set_ball(ring.ball, ref.quantity, value);
    // The value and the specification that gives it are one field (m and rho, mu and f,
    // l and R_s): an override of either would undo the every-ball setting for its ball.
    const BallField partner = specification_partner(f);
    std::erase_if(overrides, [&](const RingOverride& o) { return o.field == f || o.field == partner; });
    if (f == BallField::mass) {
      ring.total_mass_held = false;
      ring.total_mass = 0.0;
    }
  } else {
    const auto same = std::find_if(overrides.begin(), overrides.end(),
                                   [&](const RingOverride& o) { return o.ball == ref.ball && o.field == f; });
    RingOverride o{ref.ball, f, value, origin, 0, key};
    if (same != overrides.end())
      *same = std::move(o);
    else
      overrides.push_back(std::move(o));
  }
}

void apply_override(Scene& scene, std::string_view assignment) {
  const auto eq = assignment.find('=');
  const auto name = trim(assignment.substr(0, eq));
  const auto text = eq == std::string_view::npos ? std::string_view() : trim(assignment.substr(eq + 1));
  if (name.empty() || text.empty()) throw InputError("--set", 0, std::string(assignment), "expected NAME=VALUE");

  const int n = int(scene.balls.size());
  const auto ref = parse_param(name, n);
  if (!ref) {
    // Tell a known symbol with a ball index beyond this scene apart from a typo.
    const bool index_too_large = parse_param(name, std::numeric_limits<int>::max()).has_value();
    throw InputError("--set", 0, std::string(name),
                     index_too_large ? index_out_of_range(name, std::size_t(n))
                                     : unknown_name_rule("unknown parameter", closest_param(name), "known",
                                                         param_symbols_help()));
  }
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ptr != end || (ec != std::errc() && ec != std::errc::result_out_of_range))
    throw InputError("--set", 0, std::string(name), fmt::format("not a number (got '{}')", text));
  if (ec == std::errc::result_out_of_range)
    throw InputError("--set", 0, std::string(name), fmt::format("must be a finite number (got '{}')", text));
  set_checked(scene, *ref, value, "--set");
}

template <int N>
ParamsT<double, N> params_of(const Scene& scene) {
  if constexpr (N == any_balls) {
    if (scene.balls.size() > std::size_t(max_balls))  // the parser refuses such scenes already
      throw NotSupportedError(fmt::format("scene has {} balls; at most {} are supported", scene.balls.size(), max_balls));
  } else if (scene.balls.size() != std::size_t(N)) {
    throw NotSupportedError(fmt::format("scene has {} balls: not supported yet by this command ({} balls only)",
                                        scene.balls.size(), N));
  }
  ParamsT<double, N> p;
  if constexpr (N == any_balls) p.balls.resize(scene.balls.size());
  p.rotor = scene.rotor;
  p.omega = scene.omega;
  p.law = scene.law;
  p.kappa = scene.kappa;
  std::copy(scene.balls.begin(), scene.balls.end(), p.balls.begin());
  return p;
}

template ParamsT<double, 2> params_of<2>(const Scene&);
template ParamsT<double, 3> params_of<3>(const Scene&);
template ParamsT<double, any_balls> params_of<any_balls>(const Scene&);

}  // namespace abu
