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

namespace abu {
namespace {

constexpr double kRollingJ = 7.0 / 5.0;  // solid sphere: 1 + (2/5 m r^2) / (m r^2)
constexpr double kSlidingJ = 1.0;        // point mass that slides
constexpr std::string_view kLawNames = "none, viscous, coulomb or stribeck";
constexpr std::string_view kBallKeysHelp = "mass, race_radius, radius, rolling, mu, d, mu_c, mu_s, v_s";

// The friction coefficients; their TOML keys are their model.md symbols. kappa is
// global (the law's sharpness), the others may be overridden per ball.
struct Coefficient {
  std::string_view name;
  Quantity quantity;
};
constexpr Coefficient kCoefficients[] = {{"mu", Quantity::mu},     {"d", Quantity::d},     {"mu_c", Quantity::mu_c},
                                         {"mu_s", Quantity::mu_s}, {"v_s", Quantity::v_s}, {"kappa", Quantity::kappa}};

// The numeric per-ball keys, as TOML names them, as model.md does, and as BallField does.
struct BallKey {
  std::string_view name;
  Quantity quantity;
  BallField field;
};
constexpr BallKey kBallKeys[] = {{"mass", Quantity::ball_mass, BallField::mass},
                                 {"race_radius", Quantity::race_radius, BallField::race_radius},
                                 {"radius", Quantity::ball_radius, BallField::radius},
                                 {"mu", Quantity::mu, BallField::mu},
                                 {"d", Quantity::d, BallField::d},
                                 {"mu_c", Quantity::mu_c, BallField::mu_c},
                                 {"mu_s", Quantity::mu_s, BallField::mu_s},
                                 {"v_s", Quantity::v_s, BallField::v_s}};

const BallKey& ball_key(BallField f) {
  for (const auto& k : kBallKeys)
    if (k.field == f) return k;
  return kBallKeys[0];  // inertia_factor has no numeric key; callers handle it first
}
BallField field_of(Quantity q) {
  for (const auto& k : kBallKeys)
    if (k.quantity == q) return k.field;
  return BallField::mass;  // only called for per-ball quantities
}
std::string_view field_name(BallField f) { return f == BallField::inertia_factor ? "rolling" : ball_key(f).name; }

double& field(BallT<double>& b, BallField f) {
  switch (f) {
    case BallField::mass: return b.mass;
    case BallField::race_radius: return b.race_radius;
    case BallField::radius: return b.radius;
    case BallField::inertia_factor: return b.inertia_factor;
    case BallField::mu: return b.mu;
    case BallField::d: return b.d;
    case BallField::mu_c: return b.mu_c;
    case BallField::mu_s: return b.mu_s;
    case BallField::v_s: break;
  }
  return b.v_s;
}

std::string law_mismatch(FrictionLaw law, Quantity q) {
  std::string used;
  for (const auto& c : kCoefficients)
    if (law_uses(law, c.quantity)) used += fmt::format("{}{}", used.empty() ? "" : ", ", c.name);
  return fmt::format("friction law '{}' does not use '{}' ({})", to_string(law), to_string(ParamRef{q, -1}),
                     used.empty() ? std::string("it uses no coefficients") : "it uses " + used);
}

// The bound on the number of balls, as one rule for files, rings and set_ball_count.
std::optional<std::string> ball_count_violation(std::int64_t n) {
  if (n < kSceneMinBalls) return fmt::format("at least {} balls are required, got {}", kSceneMinBalls, n);
  if (n > kSceneMaxBalls)
    return fmt::format("at most {} balls (the analyzer's bound; model.md §13), got {}", kSceneMaxBalls, n);
  return std::nullopt;
}

bool before(toml::source_position a, toml::source_position b) {
  return std::tie(a.line, a.column) < std::tie(b.line, b.column);
}

struct Problem {
  int line;
  int column;
  int seq;  // order of detection: the last tie-breaker, for determinism
  std::string key;
  std::string rule;
};

class Problems {
 public:
  Problems(std::string file, int last_line) : file_(std::move(file)), last_line_(last_line) {}

  void add(toml::source_position pos, std::string key, std::string rule) {
    list_.push_back({int(pos.line), int(pos.column), int(list_.size()), std::move(key), std::move(rule)});
  }
  // Something absent from the file has no position of its own. It is reported at the
  // last line (after everything present), where the user would append it.
  void add_absent(std::string key, std::string rule) {
    list_.push_back({last_line_, std::numeric_limits<int>::max(), int(list_.size()), std::move(key),
                     std::move(rule)});
  }
  void throw_first() const {
    if (list_.empty()) return;
    const auto& first = *std::min_element(list_.begin(), list_.end(), [](const Problem& a, const Problem& b) {
      return std::tie(a.line, a.column, a.seq) < std::tie(b.line, b.column, b.seq);
    });
    throw InputError(file_, first.line, first.key, first.rule);
  }

 private:
  std::string file_;
  int last_line_;
  std::vector<Problem> list_;
};

std::string describe(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return fmt::format("the string \"{}\"", node.as_string()->get());
    case toml::node_type::boolean: return fmt::format("the boolean {}", node.as_boolean()->get());
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::none: break;
  }
  return "nothing";
}

// Integers are accepted where reals are expected (`stiffness = 7500`); booleans and
// strings are not numbers. The range rule (including finiteness) is range_violation's.
std::optional<double> read_number(Problems& p, const std::string& key, const toml::node& node,
                                  toml::source_position pos, Quantity q) {
  double x = 0.0;
  if (const auto* i = node.as_integer()) {
    x = double(i->get());
  } else if (const auto* f = node.as_floating_point()) {
    x = f->get();
  } else {
    p.add(pos, key, fmt::format("must be a number, got {}", describe(node)));
    return std::nullopt;
  }
  if (auto bad = range_violation(q, x)) {
    p.add(pos, key, *bad);
    return std::nullopt;
  }
  return x;
}

// A count or an index: a TOML integer only (11.0 is a floating-point number, not a count).
std::optional<std::int64_t> read_integer(Problems& p, const std::string& key, const toml::node& node,
                                         toml::source_position pos, std::string_view what) {
  if (const auto* i = node.as_integer()) return i->get();
  std::string got = describe(node);
  if (const auto* f = node.as_floating_point()) {
    const double x = f->get();
    const bool whole = std::isfinite(x) && x == std::floor(x) && std::abs(x) < 1e15;  // show 11.0 as "11.0"
    got = whole ? fmt::format("the floating-point number {:.1f}", x) : fmt::format("the floating-point number {}", x);
  }
  p.add(pos, key, fmt::format("must be an integer ({}), got {}", what, got));
  return std::nullopt;
}

std::optional<bool> read_bool(Problems& p, const std::string& key, const toml::node& node,
                              toml::source_position pos) {
  if (const auto* b = node.as_boolean()) return b->get();
  p.add(pos, key, fmt::format("must be true or false, got {}", describe(node)));
  return std::nullopt;
}

// One numeric key of a table: whether it was there, where, under which dotted key, and
// its value if valid. For a ring ball, `from_override` says that an override set it.
struct Slot {
  Slot(std::string_view name_, Quantity quantity_, bool required_)
      : name(name_), quantity(quantity_), required(required_) {}
  std::string_view name;
  Quantity quantity;
  bool required;
  bool seen = false;
  std::optional<double> value;
  toml::source_position pos{};
  std::string key;
  bool from_override = false;
};

Slot* find(std::vector<Slot>& slots, std::string_view name) {
  auto it = std::find_if(slots.begin(), slots.end(), [&](const Slot& s) { return s.name == name; });
  return it == slots.end() ? nullptr : &*it;
}
const Slot* find(const std::vector<Slot>& slots, std::string_view name) {
  auto it = std::find_if(slots.begin(), slots.end(), [&](const Slot& s) { return s.name == name; });
  return it == slots.end() ? nullptr : &*it;
}
double value(const std::vector<Slot>& slots, std::string_view name) { return find(slots, name)->value.value_or(0.0); }

// Everything a slot holds about where its value came from (not its name or rules).
void take(Slot& to, const Slot& from) {
  to.seen = from.seen;
  to.value = from.value;
  to.pos = from.pos;
  to.key = from.key;
  to.from_override = from.from_override;
}

// Reads `table` (addressed as `path`): numeric keys into `slots`, any other key goes to
// `other(name, node, key, pos)`, which returns false if it does not know the key.
// Required slots that are absent are reported at the table's header line.
template <class Other>
void read_table(Problems& p, const toml::table& table, const std::string& path, std::vector<Slot>& slots,
                std::string_view known, Other&& other) {
  for (auto&& [k, node] : table) {
    const std::string key = fmt::format("{}.{}", path, k.str());
    const auto pos = k.source().begin;
    if (Slot* slot = find(slots, k.str())) {
      slot->seen = true;
      slot->pos = pos;
      slot->key = key;
      slot->value = read_number(p, key, node, pos, slot->quantity);
    } else if (!other(k.str(), node, key, pos)) {
      p.add(pos, key, fmt::format("unknown key; allowed here: {}", known));
    }
  }
  for (const Slot& s : slots)
    if (s.required && !s.seen) p.add(table.source().begin, fmt::format("{}.{}", path, s.name), "missing required key");
}

auto no_other = [](std::string_view, const toml::node&, const std::string&, toml::source_position) { return false; };

void add_coefficient_slots(std::vector<Slot>& slots, bool with_kappa) {
  for (const auto& c : kCoefficients)
    if (with_kappa || c.quantity != Quantity::kappa) slots.push_back({c.name, c.quantity, false});
}

// The keys of one ball: geometry (required in a [[ball]] table) and the coefficients.
std::vector<Slot> ball_slots(bool geometry_required) {
  std::vector<Slot> slots{{"mass", Quantity::ball_mass, geometry_required},
                          {"race_radius", Quantity::race_radius, geometry_required},
                          {"radius", Quantity::ball_radius, geometry_required}};
  add_coefficient_slots(slots, false);  // kappa is global: [friction] only
  return slots;
}

bool all_tables(const toml::array* array) {
  return array && std::all_of(array->begin(), array->end(), [](const toml::node& e) { return e.is_table(); });
}

// One ball as the rules see it: a [[ball]] table, or a ball of the expanded ring.
struct BallInput {
  std::vector<Slot> slots;
  std::optional<bool> rolling;
  std::string path;    // for messages: "ball[2]", "ball 4 of the [balls] ring"
  int ring_index = 0;  // 1-based ball of the ring; 0 for a [[ball]] table
};

// One [[balls.override]] table.
struct OverrideInput {
  std::vector<Slot> slots;
  std::optional<bool> rolling;
  toml::source_position rolling_pos{};
  std::optional<std::int64_t> ball;  // the 1-based index, if an integer
  toml::source_position ball_pos{};
  bool valid_ball = false;  // in range and not repeated
  std::string path;         // "balls.override[1]"
};

// The [balls] table.
struct RingInput {
  std::vector<Slot> slots;  // mass total_mass race_radius radius and the coefficients
  std::optional<bool> rolling;
  std::optional<int> count;  // if valid
  std::vector<OverrideInput> overrides;
};

RingInput read_ring(Problems& p, const toml::table& table) {
  RingInput ring;
  ring.slots = {{"mass", Quantity::ball_mass, false},
                {"total_mass", Quantity::ball_mass, false},
                {"race_radius", Quantity::race_radius, true},
                {"radius", Quantity::ball_radius, true}};
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
             "count, mass, total_mass, race_radius, radius, rolling, mu, d, mu_c, mu_s, v_s, override", other);

  if (!count_seen) {
    p.add(table.source().begin, "balls.count", "missing required key");
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
  } else if (!mass->seen && !total->seen) {
    p.add(table.source().begin, "balls.mass", "missing required key: mass (per ball) or total_mass (of the ring)");
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
      o.slots = ball_slots(false);
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
        p.add(t.source().begin, key, "missing required key");
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

// The ring as one BallInput per ball (ring.count must be valid): the template's slots,
// then the ball's override; `rolling` stays unset where neither gives it.
std::vector<BallInput> expand(const RingInput& ring) {
  const Slot& mass = *find(ring.slots, "mass");
  const Slot& total = *find(ring.slots, "total_mass");
  std::vector<BallInput> balls;
  for (int i = 1; i <= *ring.count; ++i) {
    BallInput b;
    b.path = fmt::format("ball {} of the [balls] ring", i);
    b.ring_index = i;
    b.slots = ball_slots(false);
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

// The BallRing of a valid [balls] table, friction resolved against [friction].
BallRing make_ring(const RingInput& in, const std::vector<Slot>& friction_slots, FrictionLaw law, bool rolling,
                   const std::string& file) {
  BallRing ring;
  ring.count = *in.count;
  const Slot& total = *find(in.slots, "total_mass");
  ring.total_mass_held = total.seen;
  ring.total_mass = total.seen ? *total.value : 0.0;
  ring.ball.mass = total.seen ? ring.total_mass / ring.count : value(in.slots, "mass");
  ring.ball.race_radius = value(in.slots, "race_radius");
  ring.ball.radius = value(in.slots, "radius");
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
    else
      v = law_uses(law, c.quantity) ? std::numeric_limits<double>::quiet_NaN() : 0.0;  // only overrides give it
  }
  for (const OverrideInput& o : in.overrides) {
    const int ball = int(*o.ball) - 1;
    for (const Slot& s : o.slots)
      if (s.seen) ring.overrides.push_back({ball, field_of(s.quantity), *s.value, file, int(s.pos.line), s.key});
    if (o.rolling)
      ring.overrides.push_back({ball, BallField::inertia_factor, *o.rolling ? kRollingJ : kSlidingJ, file,
                                int(o.rolling_pos.line), o.path + ".rolling"});
  }
  return ring;
}

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
      if (!law_uses(law, k.quantity)) continue;
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

int count_lines(std::string_view text) {
  const auto n = int(std::count(text.begin(), text.end(), '\n'));
  return std::max(1, (text.empty() || text.back() == '\n') ? n : n + 1);
}

toml::table parse_toml(std::string_view text, const std::string& file) {
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
            fmt::format("unknown {}; the top level has: rolling, [rotor], [[ball]] or [balls], [friction], [speed]",
                        node.is_table() ? "table" : "key"));
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
  std::vector<Slot> speed_slots{{"omega", Quantity::omega, true}};
  if (speed.table) read_table(p, *speed.table, "speed", speed_slots, "omega", no_other);

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
        p.add(pos, key,
              s->get() == "coulomb-set"
                  ? std::string("'coulomb-set' (kappa -> infinity) is not a smooth vector field and cannot be "
                                "linearized; use 'coulomb' with a large kappa")
                  : fmt::format("unknown friction law '{}'; expected {}", s->get(), kLawNames));
      }
      return true;
    };
    read_table(p, *friction.table, "friction", friction_slots, "law, mu, d, kappa, mu_c, mu_s, v_s", other);
    if (!law_seen) p.add(friction.table->source().begin, "friction.law", "missing required key");
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
        p.add(friction.table->source().begin, "friction." + std::string(s.name), why);
      }
    }
  }

  p.throw_first();

  // --- Everything is valid: assemble. Per-ball coefficients override [friction]'s.
  Scene scene;
  scene.file = file;
  scene.rotor = {value(rotor_slots, "mass"), value(rotor_slots, "stiffness"), value(rotor_slots, "damping"),
                 value(rotor_slots, "unbalance")};
  scene.omega = value(speed_slots, "omega");
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

std::vector<BallT<double>> ring_balls(const BallRing& ring) {
  BallT<double> ball = ring.ball;
  if (ring.total_mass_held && ring.count > 0) ball.mass = ring.total_mass / ring.count;
  std::vector<BallT<double>> balls(std::size_t(std::max(ring.count, 0)), ball);
  for (const auto& o : ring.overrides)
    if (o.ball >= 0 && o.ball < ring.count) field(balls[std::size_t(o.ball)], o.field) = o.value;
  return balls;
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
                                     : fmt::format("unknown parameter; known: {}", param_symbols_help()));
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
