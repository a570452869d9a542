// Scene files: TOML parsing and validation (the schema is documented in scene.hpp).
//
// Validation collects every violation together with its source position and then
// reports the one that comes first in the file. toml++ iterates table keys in sorted
// order, so throwing at the first problem met would report `damping` before a bad
// `mass` three lines above it; choosing by position makes the report independent of
// the iteration order and of the order of the checks below.
//
// A [balls] ring is expanded into one BallInput per ball before the per-ball rules run,
// each value keeping the position and key it was read at (the template's, or an
// override's), so that the rules of [[ball]] tables apply to a ring unchanged and report
// at the key that set the offending value.
#include "abu/io/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <tuple>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "abu/core/errors.hpp"
#include "abu/core/speed_units.hpp"
#include "abu/core/suggest.hpp"
#include "scene_reading.hpp"
#include "toml_guard.hpp"

namespace abu {

namespace scene_reading {

Slot* find(std::vector<Slot>& slots, std::string_view name) {
  auto it = std::find_if(slots.begin(), slots.end(), [&](const Slot& s) { return s.name == name; });
  return it == slots.end() ? nullptr : &*it;
}
const Slot* find(const std::vector<Slot>& slots, std::string_view name) {
  auto it = std::find_if(slots.begin(), slots.end(), [&](const Slot& s) { return s.name == name; });
  return it == slots.end() ? nullptr : &*it;
}
double value(const std::vector<Slot>& slots, std::string_view name) { return find(slots, name)->value.value_or(0.0); }

}  // namespace scene_reading

namespace {

using namespace scene_reading;

constexpr std::string_view kLawNames = "none, viscous, coulomb, stribeck or coulomb-set";

std::string law_mismatch(FrictionLaw law, Quantity q) {
  std::string used;
  for (const auto& c : kCoefficients)
    if (law_uses(law, c.quantity)) used += fmt::format("{}{}", used.empty() ? "" : ", ", c.name);
  return fmt::format("friction law '{}' does not use '{}' ({})", to_string(law), to_string(ParamRef{q, -1}),
                     used.empty() ? std::string("it uses no coefficients") : "it uses " + used);
}

// Cross rule: the ball must fit inside its race (r = l would put it on the axis).
// Reported at the radius, unless only the race radius came from a ring override.
void check_fit(Problems& p, const BallInput& b) {
  const Slot* r = find(b.slots, "radius");
  const Slot* l = find(b.slots, "race_radius");
  if (!r->value || !l->value || *r->value < *l->value) return;
  const bool overridden = b.ring_index && (r->from_override || l->from_override);
  const std::string which = overridden ? fmt::format(" for ball {} of the ring", b.ring_index) : "";
  if (l->from_override && !r->from_override)
    p.add(l->pos, l->key,
          fmt::format("must be > radius, as radius < race_radius (got race_radius {} <= radius {}){}", *l->value,
                      *r->value, which));
  else
    p.add(r->pos, r->key,
          fmt::format("must be < race_radius (got radius {} >= race_radius {}){}", *r->value, *l->value, which));
}

int count_lines(std::string_view text) {
  const auto n = int(std::count(text.begin(), text.end(), '\n'));
  return std::max(1, (text.empty() || text.back() == '\n') ? n : n + 1);
}

toml::table parse_toml(std::string_view text, const std::string& file) {
  detail::prevalidate_toml(text, file);  // inputs toml++ 3.3 does not refuse cleanly
#if TOML_EXCEPTIONS
  try {
    return toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    throw InputError(file, int(e.source().begin.line), "", fmt::format("TOML syntax error: {}", e.description()));
  }
#else
  auto result = toml::parse(text, std::string_view(file));
  if (!result) {
    const auto& e = result.error();
    throw InputError(file, int(e.source().begin.line), "", fmt::format("TOML syntax error: {}", e.description()));
  }
  return std::move(result).table();
#endif
}

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

Scene parse_scene(std::string_view text, const std::string& file) {
  const toml::table root = parse_toml(text, file);
  Problems p(file, count_lines(text));

  // --- Top level: which tables are there (and of the right kind).
  bool rolling = true;
  struct Part {
    const toml::table* table = nullptr;
    bool seen = false;
  } rotor, friction, speed, ring;
  toml::source_position ring_pos{};
  const toml::array* ball_array = nullptr;
  bool balls_seen = false;
  toml::source_position balls_pos{};
  for (auto&& [k, node] : root) {
    const std::string name(k.str());
    const auto pos = k.source().begin;
    Part* part = name == "rotor"      ? &rotor
                 : name == "friction" ? &friction
                 : name == "speed"    ? &speed
                 : name == "balls"    ? &ring
                                      : nullptr;
    if (name == "rolling") {
      rolling = read_bool(p, name, node, pos).value_or(true);
    } else if (part) {
      part->seen = true;
      part->table = node.as_table();
      if (part == &ring) ring_pos = pos;
      if (!part->table) p.add(pos, name, fmt::format("must be a table ([{}]), got {}", name, describe(node)));
    } else if (name == "ball") {
      balls_seen = true;
      balls_pos = pos;
      ball_array = node.as_array();
      if (!all_tables(ball_array)) {
        const std::string got = node.is_table() ? std::string("a single table [ball]") : describe(node);
        p.add(pos, name, fmt::format("must be an array of tables ([[ball]], one per ball), got {}", got));
        ball_array = nullptr;
      }
    } else {
      p.add(pos, name,
            unknown_name_rule(node.is_table() ? "unknown table" : "unknown key",
                              closest_name(name, {"rolling", "rotor", "ball", "balls", "friction", "speed"}),
                              "the top level has", "rolling, [rotor], [[ball]] or [balls], [friction], [speed]"));
    }
  }
  for (auto [part, name] : {std::pair{&rotor, "rotor"}, {&friction, "friction"}, {&speed, "speed"}})
    if (!part->seen) p.add_absent(name, fmt::format("missing table [{}]", name));
  // The balls are given one way: reported at whichever of the two comes later.
  if (balls_seen && ring.seen) {
    if (before(balls_pos, ring_pos))
      p.add(ring_pos, "balls",
            fmt::format("a [balls] ring and [[ball]] tables (line {}) exclude each other: give one or the other",
                        balls_pos.line));
    else
      p.add(balls_pos, "ball",
            fmt::format("[[ball]] tables and a [balls] ring (line {}) exclude each other: give one or the other",
                        ring_pos.line));
  }

  // --- [rotor], [speed]
  std::vector<Slot> rotor_slots{{"mass", Quantity::rotor_mass, true},
                                {"stiffness", Quantity::stiffness, true},
                                {"damping", Quantity::damping, true},
                                {"unbalance", Quantity::unbalance, true}};
  if (rotor.table) read_table(p, *rotor.table, "rotor", rotor_slots, "mass, stiffness, damping, unbalance", no_other);
  // [speed] gives omega [rad/s] or rpm [1/min] (docs/views.md), exactly one of them.
  std::vector<Slot> speed_slots{{"omega", Quantity::omega, false}, {"rpm", Quantity::omega, false}};
  if (speed.table) {
    read_table(p, *speed.table, "speed", speed_slots, "omega or rpm", no_other);
    const Slot* omega_slot = find(speed_slots, "omega");
    const Slot* rpm_slot = find(speed_slots, "rpm");
    if (omega_slot->seen && rpm_slot->seen)
      p.add(rpm_slot->pos, rpm_slot->key, "give exactly one of omega [rad/s] and rpm [1/min] (got both)");
    else if (!omega_slot->seen && !rpm_slot->seen)
      p.add(speed.table->source().begin, "speed.omega", "missing required key (or rpm, the speed in 1/min)");
  }

  // --- [[ball]]: geometry, and per-ball overrides of rolling and friction coefficients.
  std::vector<BallInput> listed;
  if (ball_array) {
    for (const auto& element : *ball_array) {
      const toml::table& t = *element.as_table();
      if (listed.size() == std::size_t(kSceneMaxBalls))
        p.add(t.source().begin, "ball", *ball_count_violation(std::int64_t(ball_array->size())));
      BallInput b;
      b.path = fmt::format("ball[{}]", listed.size() + 1);
      b.slots = ball_slots(true);
      auto other = [&](std::string_view key_name, const toml::node& node, const std::string& key,
                       toml::source_position pos) {
        if (key_name != "rolling") return false;
        b.rolling = read_bool(p, key, node, pos);
        return true;
      };
      read_table(p, t, b.path, b.slots, kBallKeysHelp, other);
      listed.push_back(std::move(b));
    }
  }
  if (ball_array && listed.size() < std::size_t(kSceneMinBalls))
    p.add(balls_pos, "ball", *ball_count_violation(std::int64_t(listed.size())));
  else if (!balls_seen && !ring.seen)
    p.add_absent("ball", "at least 2 balls are required ([[ball]] tables or a [balls] ring), got 0");

  // --- [balls]: the ring, expanded into its balls (unless [[ball]] tables are there too).
  std::optional<RingInput> ring_in;
  std::vector<BallInput> expanded;
  if (ring.table) {
    ring_in = read_ring(p, *ring.table);
    if (ring_in->count && !balls_seen) expanded = expand(*ring_in);
  }
  const std::vector<BallInput>& balls = ring_in && !balls_seen ? expanded : listed;
  for (const BallInput& b : balls) check_fit(p, b);

  // --- [friction]: the law, its coefficients, and the per-ball overrides against it.
  std::vector<Slot> friction_slots;
  add_coefficient_slots(friction_slots, true);
  std::optional<FrictionLaw> law;
  bool law_seen = false;
  if (friction.table) {
    auto other = [&](std::string_view key_name, const toml::node& node, const std::string& key,
                     toml::source_position pos) {
      if (key_name != "law") return false;
      law_seen = true;
      const auto* s = node.as_string();
      if (!s) {
        p.add(pos, key, fmt::format("must be a string ({}), got {}", kLawNames, describe(node)));
      } else if (law = friction_law_from_string(s->get()); !law) {
        p.add(pos, key, fmt::format("unknown friction law '{}'; expected {}", s->get(), kLawNames));
      }
      return true;
    };
    read_table(p, *friction.table, "friction", friction_slots, "law, mu, d, kappa, mu_c, mu_s, v_s", other);
    if (!law_seen) p.add_missing(friction.table->source().begin, "friction.law", "missing required key");
  }
  if (law) {
    // Per-ball coefficients as written: [[ball]] tables, [balls] and its overrides.
    std::vector<const std::vector<Slot>*> written{&friction_slots};
    for (const BallInput& b : listed) written.push_back(&b.slots);
    if (ring_in) {
      written.push_back(&ring_in->slots);
      for (const OverrideInput& o : ring_in->overrides) written.push_back(&o.slots);
    }
    for (const auto* slots : written)
      for (const Slot& s : *slots)
        if (s.seen && !law_uses(*law, s.quantity)) p.add(s.pos, s.key, law_mismatch(*law, s.quantity));
    // A coefficient the law needs comes from [friction], or from every ball's own value.
    for (const Slot& s : friction_slots) {
      if (s.seen || !law_uses(*law, s.quantity)) continue;
      auto has_own = [&](const BallInput& b) {
        const Slot* own = find(b.slots, s.name);
        return own && own->seen;
      };
      const auto lacking = std::find_if_not(balls.begin(), balls.end(), has_own);
      if (balls.empty() || lacking != balls.end()) {
        const std::string why =
            std::none_of(balls.begin(), balls.end(), has_own)
                ? fmt::format("missing key (friction law '{}' requires it)", to_string(*law))
                : fmt::format("missing key (friction law '{}' requires it; per-ball values replace it only "
                              "if every ball has one, and {} has none)",
                              to_string(*law), lacking->path);
        p.add_missing(friction.table->source().begin, "friction." + std::string(s.name), why);
      }
    }
  }

  p.throw_first();

  // --- Everything is valid: assemble. Per-ball coefficients override [friction]'s.
  Scene scene;
  scene.file = file;
  scene.rotor = {value(rotor_slots, "mass"), value(rotor_slots, "stiffness"), value(rotor_slots, "damping"),
                 value(rotor_slots, "unbalance")};
  scene.omega = find(speed_slots, "rpm")->seen ? to_rad_per_s(value(speed_slots, "rpm"), SpeedUnit::rpm)
                                               : value(speed_slots, "omega");
  scene.law = *law;
  scene.kappa = value(friction_slots, "kappa");
  if (ring_in) {
    scene.ring = make_ring(*ring_in, friction_slots, *law, rolling, file);
    scene.balls = ring_balls(*scene.ring);
    return scene;
  }
  for (const BallInput& in : listed) {
    BallT<double> b;
    b.mass = value(in.slots, "mass");
    b.race_radius = value(in.slots, "race_radius");
    b.radius = value(in.slots, "radius");
    b.inertia_factor = in.rolling.value_or(rolling) ? kRollingJ : kSlidingJ;
    for (const auto& c : kCoefficients) {
      if (c.quantity == Quantity::kappa) continue;
      const Slot* own = find(in.slots, c.name);
      ball_field(b, c.quantity) = own->seen ? *own->value : value(friction_slots, c.name);
    }
    scene.balls.push_back(b);
  }
  return scene;
}

Scene load_scene(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, 0, "", "cannot read file: it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw InputError(path, 0, "",
                     fmt::format("cannot read file: {}", err ? std::generic_category().message(err) : "open failed"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "", "cannot read file: read error");
  return parse_scene(text.str(), path);
}

void set_checked(Scene& scene, ParamRef ref, double value, const std::string& origin) {
  const std::string key = to_string(ref);
  const auto n = scene.balls.size();
  if (is_per_ball(ref.quantity) && ref.ball >= int(n)) throw InputError(origin, 0, key, index_out_of_range(key, n));
  if (!law_uses(scene.law, ref.quantity)) throw InputError(origin, 0, key, law_mismatch(scene.law, ref.quantity));
  if (auto bad = range_violation(ref.quantity, value)) throw InputError(origin, 0, key, *bad);

  // The balls this touches: one, all, or (for a global quantity) none.
  std::size_t first = 0, last = 0;
  if (is_per_ball(ref.quantity)) {
    first = ref.ball < 0 ? 0 : std::size_t(ref.ball);
    last = ref.ball < 0 ? n : first + 1;
  }
  // Cross rule r_i < l_i, checked for every ball before anything changes.
  for (std::size_t i = first; i < last; ++i) {
    const auto& b = scene.balls[i];
    if (ref.quantity == Quantity::ball_radius && !(value < b.race_radius))
      throw InputError(origin, 0, key,
                       fmt::format("must be < race_radius (l{} = {}, got {})", i + 1, b.race_radius, value));
    if (ref.quantity == Quantity::race_radius && !(b.radius < value))
      throw InputError(origin, 0, key,
                       fmt::format("must be > ball radius, as radius < race_radius (r{} = {}, got {})", i + 1,
                                   b.radius, value));
  }
  if (!is_per_ball(ref.quantity)) {
    global_field(scene, ref.quantity) = value;
    return;
  }
  for (std::size_t i = first; i < last; ++i) ball_field(scene.balls[i], ref.quantity) = value;

  // The ring follows: every ball -> the template (no ball differs in this field any more,
  // active or not); one ball -> that ball's override.
  if (!scene.ring) return;
  BallRing& ring = *scene.ring;
  const BallField f = field_of(ref.quantity);
  auto& overrides = ring.overrides;
  if (ref.ball < 0) {
    field(ring.ball, f) = value;
    std::erase_if(overrides, [&](const RingOverride& o) { return o.field == f; });
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
