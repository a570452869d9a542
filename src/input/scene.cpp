// Scene files: TOML parsing and validation (the schema is documented in scene.hpp); [rotor]'s
// support is read in support_reading.cpp, parameters set after parsing in scene_parameters.cpp.
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
#include "abu/input/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <system_error>
#include <tuple>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "abu/core/errors.hpp"
#include "abu/core/text_file.hpp"
#include "race_reading.hpp"
#include "abu/core/speed_units.hpp"
#include "abu/core/suggest.hpp"
#include "abu/model/shaft.hpp"
#include "scene_reading.hpp"
#include "shaft_reading.hpp"
#include "simulate_table.hpp"
#include "uncertain_table.hpp"
#include "support_reading.hpp"
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

void check_ball_form(Problems& p, const BallInput& b, bool listed) {
  const Slot* diameter = find(b.slots, "diameter");
  const Slot* density = find(b.slots, "density");
  const Slot* surface = find(b.slots, "surface_radius");
  // Two keys that give the same value: reported at the later (a ring ball's keys may be
  // the template's and an override's).
  auto exclusive = [&](std::string_view direct, const Slot* specified, std::string_view why) {
    const Slot* d = find(b.slots, direct);
    if (!d->seen || !specified->seen) return;
    const Slot* later = before(d->pos, specified->pos) ? specified : d;
    const Slot* earlier = later == d ? specified : d;
    const std::string which = b.ring_index ? fmt::format(" for ball {} of the ring", b.ring_index) : "";
    p.add(later->pos, later->key,
          fmt::format("give either {} or {}, not both{} ({} is at line {}; {}, model.md §1.1)", direct, specified->name,
                      which, earlier->key, earlier->pos.line, why));
  };
  exclusive("mass", diameter, "a ball given by its diameter has the mass rho pi d^3/6 of its density");
  exclusive("radius", diameter, "r = diameter/2");
  exclusive("race_radius", surface, "l = surface_radius - r");
  if (density->seen && !diameter->seen)
    p.add(density->pos, density->key,
          "density needs the ball's diameter (m = density pi diameter^3/6, model.md (1.1.1)): give diameter instead of "
          "mass and radius");
  if (!listed) return;
  auto missing = [&](std::string_view key, const Slot* other, std::string_view alternative) {
    if (!find(b.slots, key)->seen && !other->seen)
      p.add_missing(b.header, fmt::format("{}.{}", b.path, key), fmt::format("missing required key (or {})", alternative));
  };
  missing("mass", diameter, "diameter, with density");
  missing("race_radius", surface, "surface_radius");
  missing("radius", diameter, "diameter");
}

void assemble_geometry(BallT<double>& ball, const std::vector<Slot>& slots) {
  const Slot* diameter = find(slots, "diameter");
  if (diameter->seen) {
    ball.radius = value(slots, "diameter") / 2.0;
    const Slot* density = find(slots, "density");
    ball.density = density->seen ? value(slots, "density") : kSteelDensity;
    ball.specified |= specified::density;
  } else {
    ball.mass = value(slots, "mass");
    ball.radius = value(slots, "radius");
  }
  if (find(slots, "surface_radius")->seen) {
    ball.surface_radius = value(slots, "surface_radius");
    ball.specified |= specified::surface_radius;
  } else {
    ball.race_radius = value(slots, "race_radius");
  }
  derive_specified(ball);
}

std::string law_mismatch(FrictionLaw law, Quantity q) {
  std::string used;
  for (const auto& c : kCoefficients)
    if (law_uses(law, c.quantity)) used += fmt::format("{}{}", used.empty() ? "" : ", ", c.name);
  return fmt::format("friction law '{}' does not use '{}' ({})", to_string(law), to_string(ParamRef{q, -1}),
                     used.empty() ? std::string("it uses no coefficients") : "it uses " + used);
}

// LuGre's levels (model.md §12.1): g(v) = mu_c + (mu_s - mu_c) exp(-(v/v_s)^2) divides the
// bristle rate, so mu_c > 0 keeps it away from 0 at every speed, and mu_c <= mu_s makes
// |z| <= mu_s / sigma0 invariant (§12.1). Judged per ball on its effective values, and
// reported at the key that set the offending one (the ball's own, else [friction]'s).
std::optional<std::string> lugre_level_violation(double mu_c, double mu_s) {
  if (!(mu_c > 0.0)) return fmt::format("must be > 0 for friction law 'lugre' (got {}): the Stribeck level g(v) "
                                        "divides the bristle rate (model.md §12.1)", mu_c);
  if (mu_c > mu_s)
    return fmt::format("must be <= mu_s for friction law 'lugre' (got mu_c {} > mu_s {}): the Coulomb level "
                       "cannot exceed the breakaway level (model.md §12.1)", mu_c, mu_s);
  return std::nullopt;
}

}  // namespace scene_reading

namespace {

using namespace scene_reading;

constexpr std::string_view kLawNames = "none, viscous, coulomb, stribeck, lugre or coulomb-set";

// Cross rule: the ball must fit inside its race (r = l would put it on the axis).
// Reported at the radius, unless only the race radius came from a ring override. A ball
// given by its diameter and the race by its surface radius (model.md §1.1): r = diameter/2,
// l = surface_radius - r, and the rule reads surface_radius > diameter.
void check_fit(Problems& p, const BallInput& b) {
  const Slot* diameter = find(b.slots, "diameter");
  const Slot* surface = find(b.slots, "surface_radius");
  const Slot* r = find(b.slots, "radius");
  const Slot* l = find(b.slots, "race_radius");
  const bool overridden = b.ring_index && (r->from_override || l->from_override || diameter->from_override ||
                                           surface->from_override);
  const std::string which = overridden ? fmt::format(" for ball {} of the ring", b.ring_index) : "";
  if (diameter->seen || surface->seen) {
    if (r->seen && diameter->seen) return;  // check_ball_form reports both
    if (l->seen && surface->seen) return;
    const Slot* r_at = diameter->seen ? diameter : r;
    const Slot* l_at = surface->seen ? surface : l;
    if (!r_at->value || !l_at->value) return;
    const double radius = diameter->seen ? *r_at->value / 2.0 : *r_at->value;
    const double race_radius = surface->seen ? *l_at->value - radius : *l_at->value;
    if (radius < race_radius) return;
    const Slot* at = l_at->from_override && !r_at->from_override ? l_at : r_at;
    p.add(at->pos, at->key,
          fmt::format("the ball does not fit its race: r = {} m{} and l = {} m{} need r < l (model.md §1.1){}", radius,
                      diameter->seen ? " (diameter/2)" : "", race_radius,
                      surface->seen ? " (surface_radius - r)" : "", which));
    return;
  }
  if (!r->value || !l->value || *r->value < *l->value) return;
  if (l->from_override && !r->from_override)
    p.add(l->pos, l->key,
          fmt::format("must be > radius, as radius < race_radius (got race_radius {} <= radius {}){}", *l->value,
                      *r->value, which));
  else
    p.add(r->pos, r->key,
          fmt::format("must be < race_radius (got radius {} >= race_radius {}){}", *r->value, *l->value, which));
}

void check_lugre_levels(Problems& p, const std::vector<BallInput>& balls, const std::vector<Slot>& friction_slots) {
  auto effective = [&](const BallInput& b, std::string_view name) -> const Slot* {
    const Slot* own = find(b.slots, name);
    return own && own->seen ? own : find(friction_slots, name);
  };
  for (const BallInput& b : balls) {
    const Slot* c = effective(b, "mu_c");
    const Slot* s = effective(b, "mu_s");
    if (!c || !s || !c->seen || !s->seen || !c->value || !s->value) continue;  // reported elsewhere
    if (auto bad = lugre_level_violation(*c->value, *s->value)) {
      // mu_c <= 0 at mu_c; mu_c > mu_s at mu_s if only the ball's own mu_s differs from [friction]'s.
      const bool own_s_only = s != find(friction_slots, "mu_s") && c == find(friction_slots, "mu_c");
      const Slot* at = *c->value > 0.0 && own_s_only ? s : c;
      // A ring's ball is named (its keys are the template's or an override's); a [[ball]]
      // table's key or [friction]'s names the place already.
      const std::string which = b.ring_index ? fmt::format(" (ball {} of the ring)", b.ring_index) : std::string();
      const std::string rule =
          at == s ? fmt::format("must be >= mu_c for friction law 'lugre' (got mu_s {} < mu_c {}): the breakaway level "
                                "cannot be below the Coulomb level (model.md §12.1)",
                                *s->value, *c->value)
                  : *bad;
      p.add(at->pos, at->key, rule + which);
    }
  }
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
    const int line = int(e.source().begin.line);
    throw InputError(file, line, detail::key_at_line(text, line), fmt::format("TOML syntax error: {}", e.description()));
  }
#else
  auto result = toml::parse(text, std::string_view(file));
  if (!result) {
    const auto& e = result.error();
    const int line = int(e.source().begin.line);
    throw InputError(file, line, detail::key_at_line(text, line), fmt::format("TOML syntax error: {}", e.description()));
  }
  return std::move(result).table();
#endif
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
  } rotor, friction, speed, ring, simulate, race, uncertain;
  toml::source_position ring_pos{};
  const toml::array* ball_array = nullptr;
  bool balls_seen = false;
  toml::source_position balls_pos{};
  ShaftInput shaft_in;  // [shaft], [[disc]], [[bearing]]: a flexible rotor (shaft_scene.hpp)
  for (auto&& [k, node] : root) {
    const std::string name(k.str());
    const auto pos = k.source().begin;
    Part* part = name == "rotor"      ? &rotor
                 : name == "friction" ? &friction
                 : name == "speed"    ? &speed
                 : name == "balls"    ? &ring
                 : name == "simulate" ? &simulate
                 : name == "race"     ? &race
                 : name == "uncertain" ? &uncertain
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
    } else if (take_shaft_key(shaft_in, name, node, pos)) {
    } else {
      p.add(pos, name,
            unknown_name_rule(node.is_table() ? "unknown table" : "unknown key",
                              closest_name(name, {"rolling", "rotor", "ball", "balls", "friction", "speed", "simulate",
                                                  "race", "shaft", "disc", "bearing", "uncertain"}),
                              "the top level has",
                              "rolling, [rotor], [[ball]] or [balls], [friction], [speed], [simulate], [race], [shaft], "
                              "[[disc]], [[bearing]], [uncertain]"));
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
                                {"stiffness", Quantity::stiffness, false},
                                {"damping", Quantity::damping, false},
                                {"unbalance", Quantity::unbalance, true}};
  // A shaft scene's [rotor] gives the unbalance only (shaft_scene.hpp).
  if (rotor.table && shaft_in.present()) read_shaft_rotor(p, *rotor.table, rotor_slots);
  const std::optional<AnisotropicSupport> support =
      rotor.table && !shaft_in.present() ? read_support(p, *rotor.table, rotor_slots) : std::nullopt;
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
      b.header = t.source().begin;
      b.slots = ball_slots();
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
  for (const BallInput& b : balls) {
    check_ball_form(p, b, !b.ring_index);
    check_fit(p, b);
  }

  // --- [race] (optional): an unround race (model.md §11), checked on the balls below.
  RaceSpec race_spec;
  if (race.table) scene_reading::read_race(p, *race.table, balls.size(), race_spec);

  // --- [friction]: the law, its coefficients, and the per-ball overrides against it.
  std::vector<Slot> friction_slots;
  add_coefficient_slots(friction_slots, true);
  std::optional<FrictionLaw> law;
  bool law_seen = false;
  int law_line = 0;
  if (friction.table) {
    auto other = [&](std::string_view key_name, const toml::node& node, const std::string& key,
                     toml::source_position pos) {
      if (key_name != "law") return false;
      law_seen = true;
      law_line = int(pos.line);
      const auto* s = node.as_string();
      if (!s) {
        p.add(pos, key, fmt::format("must be a string ({}), got {}", kLawNames, describe(node)));
      } else if (law = friction_law_from_string(s->get()); !law) {
        p.add(pos, key, fmt::format("unknown friction law '{}'; expected {}", s->get(), kLawNames));
      }
      return true;
    };
    read_table(p, *friction.table, "friction", friction_slots,
               "law, mu, f, d, kappa, mu_c, mu_s, v_s, sigma0, sigma1, sigma2", other);
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
    // mu or the rolling-resistance length f (mu = f / r, model.md (1.1.2)): one form per scene.
    const Slot* first_mu = nullptr;
    const Slot* first_f = nullptr;
    for (const auto* slots : written)
      for (const Slot& s : *slots)
        for (auto [name, first] : {std::pair{"mu", &first_mu}, {"f", &first_f}})
          if (s.seen && s.name == name && (!*first || before(s.pos, (*first)->pos))) *first = &s;
    if (first_mu && first_f) {
      const Slot* later = before(first_mu->pos, first_f->pos) ? first_f : first_mu;
      const Slot* earlier = later == first_f ? first_mu : first_f;
      p.add(later->pos, later->key,
            fmt::format("give the Coulomb level either as mu or as the rolling-resistance length f (mu = f / r, model.md "
                        "(1.1.2)), not both in one scene ({} is at line {})",
                        earlier->key, earlier->pos.line));
    }
    // A coefficient the law needs comes from [friction], or from every ball's own value;
    // mu may come as f.
    const Slot* friction_f = find(friction_slots, "f");
    for (const Slot& s : friction_slots) {
      if (s.seen || !law_uses(*law, s.quantity) || s.quantity == Quantity::rolling_length) continue;
      const bool as_f = s.quantity == Quantity::mu;
      if (as_f && friction_f->seen) continue;
      auto has_own = [&](const BallInput& b) {
        const Slot* own = find(b.slots, s.name);
        const Slot* own_f = find(b.slots, "f");
        return (own && own->seen) || (as_f && own_f->seen);
      };
      const auto lacking = std::find_if_not(balls.begin(), balls.end(), has_own);
      if (balls.empty() || lacking != balls.end()) {
        const std::string why =
            std::none_of(balls.begin(), balls.end(), has_own)
                ? fmt::format("missing key (friction law '{}' requires it{})", to_string(*law),
                              as_f ? ", or the rolling-resistance length f" : "")
                : fmt::format("missing key (friction law '{}' requires it; per-ball values replace it only "
                              "if every ball has one, and {} has none)",
                              to_string(*law), lacking->path);
        p.add_missing(friction.table->source().begin, "friction." + std::string(s.name), why);
      }
    }
  }

  if (law == FrictionLaw::lugre) check_lugre_levels(p, balls, friction_slots);

  // --- [simulate]: run-up and integration settings (simulate_table.hpp).
  std::optional<SimulateSettings> simulate_settings;
  if (simulate.table) simulate_settings = read_simulate_table(p, *simulate.table, file, int(balls.size()));
  // --- [uncertain]: inputs known within a range (uncertain_table.hpp, model.md §21.2).
  std::vector<SceneUncertainty> uncertain_inputs;
  if (uncertain.table) uncertain_inputs = read_uncertain_table(p, *uncertain.table, int(balls.size()));

  // --- [shaft], [[disc]], [[bearing]]: a flexible rotor (shaft_scene.hpp).
  std::optional<ShaftSpec> shaft_spec;
  if (shaft_in.present() || shaft_in.discs || shaft_in.bearings) shaft_spec = read_shaft(p, shaft_in);

  p.throw_first();

  // --- Everything is valid: assemble. Per-ball coefficients override [friction]'s.
  Scene scene;
  scene.file = file;
  scene.rotor = {value(rotor_slots, "mass"), value(rotor_slots, "stiffness"), value(rotor_slots, "damping"),
                 value(rotor_slots, "unbalance")};
  if (support) {  // the mean system (docs/model.md §10.5)
    scene.support = support;
    scene.rotor.stiffness = support->mean_stiffness();
    scene.rotor.damping = support->mean_damping();
  }
  scene.omega = find(speed_slots, "rpm")->seen ? to_rad_per_s(value(speed_slots, "rpm"), SpeedUnit::rpm)
                                               : value(speed_slots, "omega");
  scene.law = *law;
  scene.law_line = law_line;
  scene.kappa = value(friction_slots, "kappa");
  scene.simulate = std::move(simulate_settings);
  scene.uncertain = std::move(uncertain_inputs);
  scene.race = std::move(race_spec);
  if (shaft_spec) scene.shaft = std::make_shared<const ShaftSpec>(std::move(*shaft_spec));
  if (ring_in) {
    scene.ring = make_ring(*ring_in, friction_slots, *law, rolling, file);
    scene.balls = ring_balls(*scene.ring);
    scene_reading::check_race(scene);
    return scene;
  }
  for (const BallInput& in : listed) {
    BallT<double> b;
    b.inertia_factor = in.rolling.value_or(rolling) ? kRollingJ : kSlidingJ;
    for (const auto& c : kCoefficients) {
      if (c.quantity == Quantity::kappa) continue;
      const Slot* own = find(in.slots, c.name);
      ball_field(b, c.quantity) = own->seen ? *own->value : value(friction_slots, c.name);
      if (c.quantity == Quantity::rolling_length && (own->seen || find(friction_slots, c.name)->seen))
        b.specified |= specified::rolling_length;
    }
    assemble_geometry(b, in.slots);  // r first, then m, mu, l from it (1.1.1)-(1.1.3)
    scene.balls.push_back(b);
  }
  scene_reading::check_race(scene);
  return scene;
}

Scene load_scene(const std::string& path) {
  return parse_scene(read_text_file(path, scene_size_limit, "scene"), path);
}

}  // namespace abu
