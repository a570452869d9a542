// The [balls] ring of a scene: reading the table and its [[balls.override]] tables,
// expanding it into balls, and changing its ball count (ball_ring.hpp; the file format
// is documented in scene.hpp).
#include "abu/input/ball_ring.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"
#include "scene_reading.hpp"

namespace abu {

namespace scene_reading {

RingInput read_ring(Problems& p, const toml::table& table) {
  RingInput ring;
  ring.slots = {{"mass", Quantity::ball_mass, false},
                {"total_mass", Quantity::ball_mass, false},
                {"race_radius", Quantity::race_radius, false},
                {"radius", Quantity::ball_radius, false}};
  add_specification_slots(ring.slots);
  add_coefficient_slots(ring.slots, false);
  bool count_seen = false;
  std::optional<std::int64_t> count;
  toml::source_position count_pos{};
  const toml::array* override_array = nullptr;
  auto other = [&](std::string_view name, const toml::node& node, const std::string& key, toml::source_position pos) {
    if (name == "count") {
      count_seen = true;
      count_pos = pos;
      count = read_integer(p, key, node, pos, fmt::format("{}..{}", kSceneMinBalls, kSceneMaxBalls));
    } else if (name == "rolling") {
      ring.rolling = read_bool(p, key, node, pos);
    } else if (name == "override") {
      override_array = node.as_array();
      if (!all_tables(override_array)) {
        const std::string got = node.is_table() ? std::string("a single table [balls.override]") : describe(node);
        p.add(pos, key,
              fmt::format("must be an array of tables ([[balls.override]], one per ball that differs), got {}", got));
        override_array = nullptr;
      }
    } else {
      return false;
    }
    return true;
  };
  read_table(p, table, "balls", ring.slots,
             "count, mass, total_mass, race_radius, radius, diameter, density, surface_radius, rolling, mu, f, d, mu_c, "
             "mu_s, v_s, sigma0, sigma1, sigma2, override",
             other);
  // Each geometry value in one of its forms (model.md §1.1; both forms: check_ball_form).
  for (auto [key, alternative] : {std::pair{"race_radius", "surface_radius"}, {"radius", "diameter"}})
    if (!find(ring.slots, key)->seen && !find(ring.slots, alternative)->seen)
      p.add_missing(table.source().begin, fmt::format("balls.{}", key),
                    fmt::format("missing required key (or {})", alternative));

  if (!count_seen) {
    p.add_missing(table.source().begin, "balls.count", "missing required key");
  } else if (count) {
    if (auto bad = ball_count_violation(*count))
      p.add(count_pos, "balls.count", *bad);
    else
      ring.count = int(*count);
  }

  // Exactly one of mass and total_mass.
  const Slot* mass = find(ring.slots, "mass");
  const Slot* total = find(ring.slots, "total_mass");
  if (mass->seen && total->seen) {
    const Slot* later = before(mass->pos, total->pos) ? total : mass;
    const Slot* earlier = later == mass ? total : mass;
    p.add(later->pos, later->key,
          fmt::format("give either mass (per ball) or total_mass (of the ring), not both ({} is at line {})",
                      earlier->name, earlier->pos.line));
  } else if (!mass->seen && !total->seen && !find(ring.slots, "diameter")->seen) {
    p.add_missing(table.source().begin, "balls.mass",
                  "missing required key: mass (per ball) or total_mass (of the ring), or diameter (with density)");
  } else if (total->value && ring.count) {
    // m = total_mass / count must itself be a valid mass (it is unless total_mass is denormal).
    if (auto bad = range_violation(Quantity::ball_mass, *total->value / *ring.count))
      p.add(total->pos, total->key, fmt::format("total_mass / count: {}", *bad));
  }

  if (override_array) {
    for (const auto& element : *override_array) {
      const toml::table& t = *element.as_table();
      OverrideInput o;
      o.path = fmt::format("balls.override[{}]", ring.overrides.size() + 1);
      o.slots = ball_slots();
      bool ball_seen = false;
      auto other_key = [&](std::string_view name, const toml::node& node, const std::string& key,
                           toml::source_position pos) {
        if (name == "ball") {
          ball_seen = true;
          o.ball_pos = pos;
          o.ball = read_integer(p, key, node, pos, "a 1-based ball index");
        } else if (name == "rolling") {
          o.rolling = read_bool(p, key, node, pos);
          o.rolling_pos = pos;
        } else {
          return false;
        }
        return true;
      };
      read_table(p, t, o.path, o.slots, fmt::format("ball, {}", kBallKeysHelp), other_key);
      const std::string key = o.path + ".ball";
      if (!ball_seen) {
        p.add_missing(t.source().begin, key, "missing required key");
      } else if (o.ball) {
        const auto same = std::find_if(ring.overrides.begin(), ring.overrides.end(), [&](const OverrideInput& e) {
          return e.valid_ball && *e.ball == *o.ball;
        });
        if (*o.ball < 1 || (ring.count && *o.ball > *ring.count))
          p.add(o.ball_pos, key,
                ring.count ? fmt::format("must be 1..{} (a ball of the ring, 1-based), got {}", *ring.count, *o.ball)
                           : fmt::format("must be >= 1 (a ball of the ring, 1-based), got {}", *o.ball));
        else if (same != ring.overrides.end())
          p.add(o.ball_pos, key,
                fmt::format("ball {} is already overridden at line {}: at most one [[balls.override]] per ball",
                            *o.ball, same->ball_pos.line));
        else
          o.valid_ball = true;
      }
      ring.overrides.push_back(std::move(o));
    }
  }
  return ring;
}

std::vector<BallInput> expand(const RingInput& ring) {
  const Slot& mass = *find(ring.slots, "mass");
  const Slot& total = *find(ring.slots, "total_mass");
  std::vector<BallInput> balls;
  for (int i = 1; i <= *ring.count; ++i) {
    BallInput b;
    b.path = fmt::format("ball {} of the [balls] ring", i);
    b.ring_index = i;
    b.slots = ball_slots();
    for (Slot& s : b.slots) {
      if (s.name == "mass") {
        take(s, total.seen ? total : mass);
        if (total.seen && s.value) s.value = *s.value / *ring.count;
      } else {
        take(s, *find(ring.slots, s.name));
      }
    }
    b.rolling = ring.rolling;
    for (const OverrideInput& o : ring.overrides) {
      if (!o.valid_ball || *o.ball != i) continue;
      for (const Slot& s : o.slots) {
        if (!s.seen) continue;
        Slot& to = *find(b.slots, s.name);
        take(to, s);
        to.from_override = true;
      }
      if (o.rolling) b.rolling = o.rolling;
    }
    balls.push_back(std::move(b));
  }
  return balls;
}

BallRing make_ring(const RingInput& in, const std::vector<Slot>& friction_slots, FrictionLaw law, bool rolling,
                   const std::string& file) {
  BallRing ring;
  ring.count = *in.count;
  const Slot& total = *find(in.slots, "total_mass");
  ring.total_mass_held = total.seen;
  ring.total_mass = total.seen ? *total.value : 0.0;
  ring.ball.inertia_factor = in.rolling.value_or(rolling) ? kRollingJ : kSlidingJ;
  for (const auto& c : kCoefficients) {
    if (c.quantity == Quantity::kappa) continue;
    const Slot& own = *find(in.slots, c.name);
    const Slot& global = *find(friction_slots, c.name);
    double& v = field(ring.ball, field_of(c.quantity));
    if (own.seen)
      v = *own.value;
    else if (global.seen)
      v = *global.value;
    else  // only overrides give it (f never stands alone: it gives mu)
      v = law_uses(law, c.quantity) && c.quantity != Quantity::rolling_length ? std::numeric_limits<double>::quiet_NaN()
                                                                               : 0.0;
    if (c.quantity == Quantity::rolling_length && (own.seen || global.seen))
      ring.ball.specified |= specified::rolling_length;
  }
  assemble_geometry(ring.ball, in.slots);  // r, then m, mu, l from it (model.md §1.1)
  if (total.seen) ring.ball.mass = ring.total_mass / ring.count;
  for (const OverrideInput& o : in.overrides) {
    const int ball = int(*o.ball) - 1;
    for (const Slot& s : o.slots) {
      if (!s.seen) continue;
      const bool diameter = s.name == "diameter";  // kept as the radius it gives
      ring.overrides.push_back(
          {ball, field_of(s.quantity), diameter ? *s.value / 2.0 : *s.value, file, int(s.pos.line), s.key});
    }
    if (o.rolling)
      ring.overrides.push_back({ball, BallField::inertia_factor, *o.rolling ? kRollingJ : kSlidingJ, file,
                                int(o.rolling_pos.line), o.path + ".rolling"});
  }
  return ring;
}

}  // namespace scene_reading

namespace {

using namespace scene_reading;

// Where the value of ball i's field came from in a ring, for messages: "" for the
// template, else "radius set by balls.override[1].radius (ring.toml:25)".
std::string set_by(const BallRing& ring, int i, BallField f) {
  const RingOverride* last = nullptr;
  for (const auto& o : ring.overrides)
    if (o.ball == i && o.field == f) last = &o;
  if (!last) return "";
  return last->line > 0 ? fmt::format("{} set by {} ({}:{})", field_name(f), last->key, last->origin, last->line)
                        : fmt::format("{} set by {} ({})", field_name(f), last->key, last->origin);
}

// Every rule of a ball on the balls of a ring (for set_ball_count), as one message.
std::optional<std::string> ring_violation(const BallRing& ring, const std::vector<BallT<double>>& balls,
                                          FrictionLaw law) {
  auto sources = [&](int i, std::initializer_list<BallField> fields) {
    std::string s;
    for (BallField f : fields)
      if (auto by = set_by(ring, i, f); !by.empty()) s += (s.empty() ? "" : "; ") + by;
    return s.empty() ? s : " (" + s + ")";
  };
  for (int i = 0; i < int(balls.size()); ++i) {
    BallT<double> b = balls[std::size_t(i)];
    for (const auto& k : kBallKeys) {
      if (!law_uses(law, k.quantity) || k.quantity == Quantity::rolling_length) continue;
      if (k.quantity == Quantity::density || k.quantity == Quantity::surface_radius) continue;  // gave m, l
      const double v = field(b, k.field);
      if (std::isnan(v) && k.quantity != Quantity::ball_mass && k.quantity != Quantity::race_radius &&
          k.quantity != Quantity::ball_radius)
        return fmt::format(
            "with n = {}, ball {} has no {}: neither [friction] nor [balls] gives one, only [[balls.override]] tables",
            ring.count, i + 1, k.name);
      if (auto bad = range_violation(k.quantity, v))
        return fmt::format("with n = {}, ball {} {}: {}{}", ring.count, i + 1, k.name, *bad, sources(i, {k.field}));
    }
    if (!(b.radius < b.race_radius))
      return fmt::format("with n = {}, ball {}: radius must be < race_radius (got radius {} >= race_radius {}){}",
                         ring.count, i + 1, b.radius, b.race_radius,
                         sources(i, {BallField::radius, BallField::race_radius}));
  }
  return std::nullopt;
}

}  // namespace

std::vector<BallT<double>> ring_balls(const BallRing& ring) {
  BallT<double> ball = ring.ball;
  if (ring.total_mass_held && ring.count > 0) ball.mass = ring.total_mass / ring.count;
  std::vector<BallT<double>> balls(std::size_t(std::max(ring.count, 0)), ball);
  for (const auto& o : ring.overrides) {
    if (o.ball < 0 || o.ball >= ring.count) continue;
    BallT<double>& b = balls[std::size_t(o.ball)];
    if (o.field == BallField::inertia_factor)
      b.inertia_factor = o.value;
    else
      set_ball(b, ball_key(o.field).quantity, o.value);  // the specification's values follow (model.md §1.1)
  }
  return balls;
}

void set_ball_count(Scene& scene, int count, const std::string& origin) {
  if (!scene.ring)
    throw InputError(origin, 0, "n",
                     "the ball count is a study parameter only for a [balls] ring scene (this scene lists "
                     "[[ball]] tables)");
  if (auto bad = ball_count_violation(count)) throw InputError(origin, 0, "n", *bad);
  BallRing ring = *scene.ring;
  ring.count = count;
  if (ring.total_mass_held) ring.ball.mass = ring.total_mass / count;
  std::vector<BallT<double>> balls = ring_balls(ring);
  if (auto bad = ring_violation(ring, balls, scene.law)) throw InputError(origin, 0, "n", *bad);
  scene.ring = std::move(ring);
  scene.balls = std::move(balls);
}

}  // namespace abu
