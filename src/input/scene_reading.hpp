// The reading machinery shared by the scene parser (scene.cpp, support_reading.cpp), the
// [balls] ring (ball_ring.cpp) and the parameters set after parsing (scene_parameters.cpp):
// private to src/input. Every rule is collected with its source position and the first in
// the file is reported (scene.cpp's header says why).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "abu/core/errors.hpp"
#include "abu/core/suggest.hpp"
#include "abu/input/scene.hpp"

namespace abu::scene_reading {

inline constexpr double kRollingJ = 7.0 / 5.0;  // solid sphere: 1 + (2/5 m r^2) / (m r^2)
inline constexpr double kSlidingJ = 1.0;        // point mass that slides
inline constexpr std::string_view kBallKeysHelp =
    "mass, race_radius, radius, diameter, density, surface_radius, rolling, mu, f, d, mu_c, mu_s, v_s, sigma0, sigma1, "
    "sigma2";

// The friction coefficients; their TOML keys are their model.md symbols. kappa is
// global (the law's sharpness), the others may be overridden per ball.
struct Coefficient {
  std::string_view name;
  Quantity quantity;
};
inline constexpr Coefficient kCoefficients[] = {{"mu", Quantity::mu},     {"f", Quantity::rolling_length},
                                                {"d", Quantity::d},
                                                {"mu_c", Quantity::mu_c}, {"mu_s", Quantity::mu_s},
                                                {"v_s", Quantity::v_s},   {"sigma0", Quantity::sigma0},
                                                {"sigma1", Quantity::sigma1}, {"sigma2", Quantity::sigma2},
                                                {"kappa", Quantity::kappa}};

// The numeric per-ball keys, as TOML names them, as model.md does, and as BallField does.
struct BallKey {
  std::string_view name;
  Quantity quantity;
  BallField field;
};
inline constexpr BallKey kBallKeys[] = {{"mass", Quantity::ball_mass, BallField::mass},
                                        {"race_radius", Quantity::race_radius, BallField::race_radius},
                                        {"radius", Quantity::ball_radius, BallField::radius},
                                        {"mu", Quantity::mu, BallField::mu},
                                        {"d", Quantity::d, BallField::d},
                                        {"mu_c", Quantity::mu_c, BallField::mu_c},
                                        {"mu_s", Quantity::mu_s, BallField::mu_s},
                                        {"v_s", Quantity::v_s, BallField::v_s},
                                        {"sigma0", Quantity::sigma0, BallField::sigma0},
                                        {"sigma1", Quantity::sigma1, BallField::sigma1},
                                        {"sigma2", Quantity::sigma2, BallField::sigma2},
                                        {"density", Quantity::density, BallField::density},
                                        {"f", Quantity::rolling_length, BallField::rolling_length},
                                        {"surface_radius", Quantity::surface_radius, BallField::surface_radius}};

inline const BallKey& ball_key(BallField f) {
  for (const auto& k : kBallKeys)
    if (k.field == f) return k;
  return kBallKeys[0];  // inertia_factor has no numeric key; callers handle it first
}
inline BallField field_of(Quantity q) {
  for (const auto& k : kBallKeys)
    if (k.quantity == q) return k.field;
  return BallField::mass;  // only called for per-ball quantities
}
// The field that gives the same model value in the other form (model.md §1.1): mass and
// density, mu and f, race_radius and surface_radius; f itself for any other field.
inline BallField specification_partner(BallField f) {
  switch (f) {
    case BallField::mass: return BallField::density;
    case BallField::density: return BallField::mass;
    case BallField::mu: return BallField::rolling_length;
    case BallField::rolling_length: return BallField::mu;
    case BallField::race_radius: return BallField::surface_radius;
    case BallField::surface_radius: return BallField::race_radius;
    default: return f;
  }
}
inline std::string_view field_name(BallField f) {
  return f == BallField::inertia_factor ? "rolling" : ball_key(f).name;
}

inline double& field(BallT<double>& b, BallField f) {
  switch (f) {
    case BallField::mass: return b.mass;
    case BallField::race_radius: return b.race_radius;
    case BallField::radius: return b.radius;
    case BallField::inertia_factor: return b.inertia_factor;
    case BallField::mu: return b.mu;
    case BallField::d: return b.d;
    case BallField::mu_c: return b.mu_c;
    case BallField::mu_s: return b.mu_s;
    case BallField::sigma0: return b.sigma0;
    case BallField::sigma1: return b.sigma1;
    case BallField::sigma2: return b.sigma2;
    case BallField::density: return b.density;
    case BallField::rolling_length: return b.rolling_length;
    case BallField::surface_radius: return b.surface_radius;
    case BallField::v_s: break;
  }
  return b.v_s;
}

// The bound on the number of balls, as one rule for files, rings and set_ball_count.
inline std::optional<std::string> ball_count_violation(std::int64_t n) {
  if (n < kSceneMinBalls) return fmt::format("at least {} balls are required, got {}", kSceneMinBalls, n);
  if (n > kSceneMaxBalls)
    return fmt::format("at most {} balls (the analyzer's bound; model.md §13), got {}", kSceneMaxBalls, n);
  return std::nullopt;
}

inline bool before(toml::source_position a, toml::source_position b) {
  return std::tie(a.line, a.column) < std::tie(b.line, b.column);
}

struct Problem {
  int line;
  int column;
  int seq;  // order of detection: the last tie-breaker, for determinism
  std::string key;
  std::string rule;
  bool missing = false;  // a required key or table absent (add_missing, add_absent)
};

class Problems {
 public:
  Problems(std::string file, int last_line) : file_(std::move(file)), last_line_(last_line) {}

  void add(toml::source_position pos, std::string key, std::string rule) {
    list_.push_back({int(pos.line), int(pos.column), int(list_.size()), std::move(key), std::move(rule)});
  }
  // A required key that is absent, reported at `pos` (its table's header). Absent keys
  // come after every other problem: a misspelled key (`stifness`) is an unknown key
  // *and* leaves the right one missing, and the unknown key is the one to report.
  void add_missing(toml::source_position pos, std::string key, std::string rule) {
    list_.push_back({int(pos.line), int(pos.column), int(list_.size()), std::move(key), std::move(rule), true});
  }
  // Something absent from the file has no position of its own. It is reported at the
  // last line (after everything present), where the user would append it.
  void add_absent(std::string key, std::string rule) {
    list_.push_back({last_line_, std::numeric_limits<int>::max(), int(list_.size()), std::move(key),
                     std::move(rule), true});
  }
  // The first problem in the file; absent keys and tables only when nothing else is wrong.
  void throw_first() const {
    if (list_.empty()) return;
    const auto& first = *std::min_element(list_.begin(), list_.end(), [](const Problem& a, const Problem& b) {
      return std::tie(a.missing, a.line, a.column, a.seq) < std::tie(b.missing, b.line, b.column, b.seq);
    });
    throw InputError(file_, first.line, first.key, first.rule);
  }

 private:
  std::string file_;
  int last_line_;
  std::vector<Problem> list_;
};

inline std::string describe(const toml::node& node) {
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

// A number node's value: integers are accepted where reals are expected (`stiffness =
// 7500`); booleans and strings are not numbers (a problem at `key`, nullopt). Not checked
// for finiteness: that is the caller's rule.
inline std::optional<double> number_value(Problems& p, const std::string& key, const toml::node& node,
                                          toml::source_position pos) {
  if (const auto* i = node.as_integer()) return double(i->get());
  if (const auto* f = node.as_floating_point()) return f->get();
  p.add(pos, key, fmt::format("must be a number, got {}", describe(node)));
  return std::nullopt;
}

// A parameter's number; the range rule (including finiteness) is range_violation's.
inline std::optional<double> read_number(Problems& p, const std::string& key, const toml::node& node,
                                  toml::source_position pos, Quantity q) {
  const std::optional<double> value = number_value(p, key, node, pos);
  if (!value) return std::nullopt;
  const double x = *value;
  if (auto bad = range_violation(q, x)) {
    p.add(pos, key, *bad);
    return std::nullopt;
  }
  return x;
}

// A count or an index: a TOML integer only (11.0 is a floating-point number, not a count).
inline std::optional<std::int64_t> read_integer(Problems& p, const std::string& key, const toml::node& node,
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

inline std::optional<bool> read_bool(Problems& p, const std::string& key, const toml::node& node,
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

// The slot named `name`, nullptr if there is none (scene.cpp; out of line, so that the
// callers' dereferences of slots they created are not flagged by -Wnull-dereference).
Slot* find(std::vector<Slot>& slots, std::string_view name);
const Slot* find(const std::vector<Slot>& slots, std::string_view name);
double value(const std::vector<Slot>& slots, std::string_view name);

// Everything a slot holds about where its value came from (not its name or rules).
inline void take(Slot& to, const Slot& from) {
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
inline void read_table(Problems& p, const toml::table& table, const std::string& path, std::vector<Slot>& slots,
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
      p.add(pos, key, unknown_name_rule("unknown key", closest_name(k.str(), split_names(known)), "allowed here", known));
    }
  }
  for (const Slot& s : slots)
    if (s.required && !s.seen)
      p.add_missing(table.source().begin, fmt::format("{}.{}", path, s.name), "missing required key");
}

inline const auto no_other = [](std::string_view, const toml::node&, const std::string&, toml::source_position) {
  return false;
};

// The geometry keys of a ball as an engineer gives them (model.md §1.1), besides mass,
// race_radius and radius.
inline void add_specification_slots(std::vector<Slot>& slots) {
  slots.push_back({"diameter", Quantity::ball_radius, false});
  slots.push_back({"density", Quantity::density, false});
  slots.push_back({"surface_radius", Quantity::surface_radius, false});
}

inline void add_coefficient_slots(std::vector<Slot>& slots, bool with_kappa) {
  for (const auto& c : kCoefficients)
    if (with_kappa || c.quantity != Quantity::kappa) slots.push_back({c.name, c.quantity, false});
}

// The keys of one ball: geometry, in either form (mass radius race_radius, or diameter
// density surface_radius, model.md §1.1; which ones are required is check_ball_form's),
// and the coefficients.
inline std::vector<Slot> ball_slots() {
  std::vector<Slot> slots{{"mass", Quantity::ball_mass, false},
                          {"race_radius", Quantity::race_radius, false},
                          {"radius", Quantity::ball_radius, false}};
  add_specification_slots(slots);
  add_coefficient_slots(slots, false);  // kappa is global: [friction] only
  return slots;
}

inline bool all_tables(const toml::array* array) {
  return array && std::all_of(array->begin(), array->end(), [](const toml::node& e) { return e.is_table(); });
}

// One ball as the rules see it: a [[ball]] table, or a ball of the expanded ring.
struct BallInput {
  std::vector<Slot> slots;
  toml::source_position header{};  // the [[ball]] table's header line (where a missing key is reported)
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

// The two forms of a ball's geometry (model.md §1.1): never both for one ball, density
// only with a diameter; for a [[ball]] table (`listed`) also that one form is complete.
void check_ball_form(Problems& p, const BallInput& b, bool listed);
// The ball's specification and the values it gives: r = diameter/2, m from density
// (default steel), l = surface_radius - r; mass, radius, race_radius as given otherwise.
// The slots must have passed check_ball_form. Friction is not touched.
void assemble_geometry(BallT<double>& ball, const std::vector<Slot>& slots);

// Rules of both the parser and set_checked (scene.cpp): the message for a coefficient the law
// does not use, and LuGre's levels mu_c > 0, mu_c <= mu_s (model.md §12.1; nullopt: obeyed).
std::string law_mismatch(FrictionLaw law, Quantity q);
std::optional<std::string> lugre_level_violation(double mu_c, double mu_s);

// The [balls] table read, its rules checked (ball_ring.cpp).
RingInput read_ring(Problems& p, const toml::table& table);
// The ring as one BallInput per ball (ring.count must be valid): the template's slots,
// then the ball's override; `rolling` stays unset where neither gives it.
std::vector<BallInput> expand(const RingInput& ring);
// The BallRing of a valid [balls] table, friction resolved against [friction].
BallRing make_ring(const RingInput& in, const std::vector<Slot>& friction_slots, FrictionLaw law, bool rolling,
                   const std::string& file);

}  // namespace abu::scene_reading
