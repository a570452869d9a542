// Scene files: TOML parsing and validation (the schema is documented in scene.hpp).
//
// Validation collects every violation together with its source position and then
// reports the one that comes first in the file. toml++ iterates table keys in sorted
// order, so throwing at the first problem met would report `damping` before a bad
// `mass` three lines above it; choosing by position makes the report independent of
// the iteration order and of the order of the checks below.
#include "abu/io/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
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

// The friction coefficients; their TOML keys are their model.md symbols. kappa is
// global (the law's sharpness), the others may be overridden per ball.
struct Coefficient {
  std::string_view name;
  Quantity quantity;
};
constexpr Coefficient kCoefficients[] = {{"mu", Quantity::mu},     {"d", Quantity::d},     {"mu_c", Quantity::mu_c},
                                         {"mu_s", Quantity::mu_s}, {"v_s", Quantity::v_s}, {"kappa", Quantity::kappa}};

std::string law_mismatch(FrictionLaw law, Quantity q) {
  std::string used;
  for (const auto& c : kCoefficients)
    if (law_uses(law, c.quantity)) used += fmt::format("{}{}", used.empty() ? "" : ", ", c.name);
  return fmt::format("friction law '{}' does not use '{}' ({})", to_string(law), to_string(ParamRef{q, -1}),
                     used.empty() ? std::string("it uses no coefficients") : "it uses " + used);
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

std::optional<bool> read_bool(Problems& p, const std::string& key, const toml::node& node,
                              toml::source_position pos) {
  if (const auto* b = node.as_boolean()) return b->get();
  p.add(pos, key, fmt::format("must be true or false, got {}", describe(node)));
  return std::nullopt;
}

// One numeric key of a table: whether it was there, where, and its value if valid.
struct Slot {
  Slot(std::string_view name_, Quantity quantity_, bool required_)
      : name(name_), quantity(quantity_), required(required_) {}
  std::string_view name;
  Quantity quantity;
  bool required;
  bool seen = false;
  std::optional<double> value;
  toml::source_position pos{};
};

Slot* find(std::vector<Slot>& slots, std::string_view name) {
  auto it = std::find_if(slots.begin(), slots.end(), [&](const Slot& s) { return s.name == name; });
  return it == slots.end() ? nullptr : &*it;
}
double value(std::vector<Slot>& slots, std::string_view name) { return find(slots, name)->value.value_or(0.0); }

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

struct BallInput {
  std::vector<Slot> slots;
  std::optional<bool> rolling;
  std::string path;
};

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
double& ball_field(BallT<double>& b, Quantity q) {
  switch (q) {
    case Quantity::ball_mass: return b.mass;
    case Quantity::race_radius: return b.race_radius;
    case Quantity::ball_radius: return b.radius;
    case Quantity::mu: return b.mu;
    case Quantity::d: return b.d;
    case Quantity::mu_c: return b.mu_c;
    case Quantity::mu_s: return b.mu_s;
    default: return b.v_s;
  }
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
  } rotor, friction, speed;
  const toml::array* ball_array = nullptr;
  bool balls_seen = false;
  toml::source_position balls_pos{};
  for (auto&& [k, node] : root) {
    const std::string name(k.str());
    const auto pos = k.source().begin;
    Part* part = name == "rotor" ? &rotor : name == "friction" ? &friction : name == "speed" ? &speed : nullptr;
    if (name == "rolling") {
      rolling = read_bool(p, name, node, pos).value_or(true);
    } else if (part) {
      part->seen = true;
      part->table = node.as_table();
      if (!part->table) p.add(pos, name, fmt::format("must be a table ([{}]), got {}", name, describe(node)));
    } else if (name == "ball") {
      balls_seen = true;
      balls_pos = pos;
      ball_array = node.as_array();
      const bool all_tables =
          ball_array && std::all_of(ball_array->begin(), ball_array->end(), [](const toml::node& e) { return e.is_table(); });
      if (!all_tables) {
        const std::string got = node.is_table() ? std::string("a single table [ball]") : describe(node);
        p.add(pos, name, fmt::format("must be an array of tables ([[ball]], one per ball), got {}", got));
        ball_array = nullptr;
      }
    } else {
      p.add(pos, name,
            fmt::format("unknown {}; the top level has: rolling, [rotor], [[ball]], [friction], [speed]",
                        node.is_table() ? "table" : "key"));
    }
  }
  for (auto [part, name] : {std::pair{&rotor, "rotor"}, {&friction, "friction"}, {&speed, "speed"}})
    if (!part->seen) p.add_absent(name, fmt::format("missing table [{}]", name));

  // --- [rotor], [speed]
  std::vector<Slot> rotor_slots{{"mass", Quantity::rotor_mass, true},
                                {"stiffness", Quantity::stiffness, true},
                                {"damping", Quantity::damping, true},
                                {"unbalance", Quantity::unbalance, true}};
  if (rotor.table) read_table(p, *rotor.table, "rotor", rotor_slots, "mass, stiffness, damping, unbalance", no_other);
  std::vector<Slot> speed_slots{{"omega", Quantity::omega, true}};
  if (speed.table) read_table(p, *speed.table, "speed", speed_slots, "omega", no_other);

  // --- [[ball]]: geometry, and per-ball overrides of rolling and friction coefficients.
  std::vector<BallInput> balls;
  if (ball_array) {
    for (const auto& element : *ball_array) {
      BallInput b;
      b.path = fmt::format("ball[{}]", balls.size() + 1);
      b.slots = {{"mass", Quantity::ball_mass, true},
                 {"race_radius", Quantity::race_radius, true},
                 {"radius", Quantity::ball_radius, true}};
      add_coefficient_slots(b.slots, false);  // kappa is global: [friction] only
      auto other = [&](std::string_view key_name, const toml::node& node, const std::string& key,
                       toml::source_position pos) {
        if (key_name != "rolling") return false;
        b.rolling = read_bool(p, key, node, pos);
        return true;
      };
      read_table(p, *element.as_table(), b.path, b.slots,
                 "mass, race_radius, radius, rolling, mu, d, mu_c, mu_s, v_s", other);
      // Cross rule: the ball must fit inside its race (r = l would put it on the axis).
      Slot* r = find(b.slots, "radius");
      Slot* l = find(b.slots, "race_radius");
      if (r->value && l->value && !(*r->value < *l->value))
        p.add(r->pos, b.path + ".radius",
              fmt::format("must be < race_radius (got radius {} >= race_radius {})", *r->value, *l->value));
      balls.push_back(std::move(b));
    }
  }
  if (ball_array && balls.size() < 2)
    p.add(balls_pos, "ball", fmt::format("at least 2 balls are required, got {}", balls.size()));
  else if (!balls_seen)
    p.add_absent("ball", "at least 2 balls are required ([[ball]] tables), got 0");

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
    for (const Slot& s : friction_slots)
      if (s.seen && !law_uses(*law, s.quantity)) p.add(s.pos, "friction." + std::string(s.name), law_mismatch(*law, s.quantity));
    for (const BallInput& b : balls)
      for (const Slot& s : b.slots)
        if (s.seen && !law_uses(*law, s.quantity)) p.add(s.pos, b.path + "." + std::string(s.name), law_mismatch(*law, s.quantity));
    // A coefficient the law needs comes from [friction], or from every ball's override.
    for (const Slot& s : friction_slots) {
      if (s.seen || !law_uses(*law, s.quantity)) continue;
      auto has_own = [&](BallInput& b) {
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
  for (BallInput& in : balls) {
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
  if (is_per_ball(ref.quantity) && ref.ball >= int(n))
    throw InputError(origin, 0, key, fmt::format("ball index out of range: the scene has {} balls", n));
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
  } else {
    for (std::size_t i = first; i < last; ++i) ball_field(scene.balls[i], ref.quantity) = value;
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
                     index_too_large ? fmt::format("ball index out of range: the scene has {} balls", n)
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
