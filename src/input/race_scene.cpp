// The [race] table: unround race harmonics (race_scene.hpp, model.md §11.1).
#include "abu/input/race_scene.hpp"

#include <set>

#include "race_reading.hpp"

namespace abu {

bool RaceSpec::round() const {
  auto zero = [](const RaceHarmonicsInput& in) {
    return std::all_of(in.harmonics.begin(), in.harmonics.end(),
                       [](const RaceHarmonic& h) { return h.amplitude == 0.0; });
  };
  if (all && !zero(*all)) return false;
  return std::all_of(per_ball.begin(), per_ball.end(), [&](const auto& b) { return zero(b.second); });
}

namespace {
const RaceHarmonicsInput* input_of(const RaceSpec& spec, int ball) {
  for (const auto& [i, in] : spec.per_ball)
    if (i == ball) return &in;
  return spec.all ? &*spec.all : nullptr;
}
}  // namespace

RaceShape race_shape(const Scene& scene) {
  RaceShape shape;
  for (std::size_t i = 0; i < scene.balls.size(); ++i) {
    const auto& b = scene.balls[i];
    const RaceHarmonicsInput* in = input_of(scene.race, int(i) + 1);
    if (!in) {
      shape.balls.emplace_back();
      continue;
    }
    RaceHarmonics h = in->surface ? surface_to_path(in->harmonics, b.race_radius, b.radius) : in->harmonics;
    if (auto bad = path_violation(h, b.race_radius, b.radius))
      throw InputError(scene.file, in->line, in->key, fmt::format("ball {}: {}", i + 1, *bad));
    shape.balls.push_back(std::move(h));
  }
  return shape;
}

RaceShape checked_scaled_race(const Scene& scene, const RaceShape& race, double factor, const std::string& option) {
  const RaceShape out = scaled_race(race, factor);
  for (std::size_t i = 0; i < out.balls.size() && i < scene.balls.size(); ++i)
    if (const auto why = path_violation(out.balls[i], scene.balls[i].race_radius, scene.balls[i].radius))
      throw InputError(option, 0, kUnroundnessParam,
                       fmt::format("at unroundness factor {} ball {}'s race breaks a rule of model.md §11.1: {}", factor,
                                   i + 1, *why));
  return out;
}

namespace scene_reading {

namespace {
constexpr int kMaxOrder = 64;

std::optional<RaceHarmonicsInput> read_list(Problems& p, const toml::node& node, const std::string& key,
                                            toml::source_position pos, bool surface) {
  const toml::array* array = node.as_array();
  if (!array) {
    p.add(pos, key,
          fmt::format("must be an array of harmonics [{{ order = 2, amplitude = 1e-3, phase = 0.3 }}, ...], got {}",
                      describe(node)));
    return std::nullopt;
  }
  RaceHarmonicsInput in;
  in.surface = surface;
  in.line = int(pos.line);
  in.key = key;
  std::set<std::int64_t> orders;
  bool ok = true;
  int index = 0;
  for (const auto& element : *array) {
    ++index;
    const std::string path = fmt::format("{}[{}]", key, index);
    const auto epos = element.source().begin;
    const toml::table* t = element.as_table();
    if (!t) {
      p.add(epos, path, fmt::format("must be a table {{ order = K, amplitude = EPS, phase = PHI }}, got {}",
                                    describe(element)));
      ok = false;
      continue;
    }
    RaceHarmonic h;
    bool has_order = false, has_amplitude = false;
    for (auto&& [k, v] : *t) {
      const std::string name(k.str());
      const std::string vkey = path + "." + name;
      const auto vpos = k.source().begin;
      if (name == "order") {
        has_order = true;
        if (const auto order = read_integer(p, vkey, v, vpos, "the harmonic's order, 1..64")) {
          if (*order < 1 || *order > kMaxOrder) {
            p.add(vpos, vkey,
                  fmt::format("must be an integer 1..{} (1: the race centre's offset, 2: oval, 3: three lobes), got "
                              "{}",
                              kMaxOrder, *order));
            ok = false;
          } else if (!orders.insert(*order).second) {
            p.add(vpos, vkey, fmt::format("order {} appears twice in this list (give each order once)", *order));
            ok = false;
          } else {
            h.order = int(*order);
          }
        } else {
          ok = false;
        }
      } else if (name == "amplitude" || name == "phase") {
        has_amplitude = has_amplitude || name == "amplitude";
        const std::optional<double> value = number_value(p, vkey, v, vpos);
        if (!value) {
          ok = false;
          continue;
        }
        const double x = *value;
        if (!std::isfinite(x)) {
          p.add(vpos, vkey, "must be finite");
          ok = false;
        } else if (name == "amplitude" && !(x >= 0 && x < 1)) {
          p.add(vpos, vkey,
                fmt::format("must be in [0, 1) (relative to the radius; a sign is a phase: use phase + pi/order), "
                            "got {}",
                            x));
          ok = false;
        } else if (name == "amplitude") {
          h.amplitude = x;
        } else {
          h.phase = x;
        }
      } else {
        p.add(vpos, vkey,
              unknown_name_rule("unknown key", closest_name(name, {"order", "amplitude", "phase"}), "a harmonic has",
                                "order, amplitude, phase"));
        ok = false;
      }
    }
    if (!has_order) p.add_missing(epos, path + ".order", "missing required key");
    if (!has_amplitude) p.add_missing(epos, path + ".amplitude", "missing required key");
    ok = ok && has_order && has_amplitude;
    in.harmonics.push_back(h);
  }
  if (!ok) return std::nullopt;
  return in;
}

// unroundness or surface_unroundness (exactly one) of a table.
std::optional<RaceHarmonicsInput> read_harmonics_key(Problems& p, std::string_view name, const toml::node& node,
                                                     const std::string& key, toml::source_position pos,
                                                     std::optional<RaceHarmonicsInput>& slot) {
  if (slot) {
    p.add(pos, key,
          fmt::format("give one of unroundness (path radius) and surface_unroundness (race surface), not both (the "
                      "other at line {})",
                      slot->line));
    return std::nullopt;
  }
  return read_list(p, node, key, pos, name == "surface_unroundness");
}
}  // namespace

void read_race(Problems& p, const toml::table& table, std::size_t n_balls, RaceSpec& out) {
  std::set<std::int64_t> balls_seen;
  for (auto&& [k, node] : table) {
    const std::string name(k.str());
    const std::string key = "race." + name;
    const auto pos = k.source().begin;
    if (name == "unroundness" || name == "surface_unroundness") {
      std::optional<RaceHarmonicsInput> slot = out.all;
      if (auto in = read_harmonics_key(p, name, node, key, pos, slot)) out.all = std::move(in);
    } else if (name == "ball") {
      const toml::array* array = node.as_array();
      if (!array || !all_tables(array)) {
        p.add(pos, key, fmt::format("must be an array of tables ([[race.ball]]), got {}", describe(node)));
        continue;
      }
      int index = 0;
      for (const auto& element : *array) {
        ++index;
        const toml::table& t = *element.as_table();
        const std::string path = fmt::format("race.ball[{}]", index);
        std::optional<std::int64_t> ball;
        std::optional<RaceHarmonicsInput> list;
        bool list_seen = false;
        for (auto&& [bk, bnode] : t) {
          const std::string bname(bk.str());
          const std::string bkey = path + "." + bname;
          const auto bpos = bk.source().begin;
          if (bname == "ball") {
            ball = read_integer(p, bkey, bnode, bpos, "the ball's 1-based index");
            if (ball && (*ball < 1 || (n_balls > 0 && std::uint64_t(*ball) > n_balls))) {
              p.add(bpos, bkey, fmt::format("must be a ball index 1..{}, got {}", n_balls, *ball));
              ball.reset();
            } else if (ball && !balls_seen.insert(*ball).second) {
              p.add(bpos, bkey, fmt::format("ball {} has a [[race.ball]] table already", *ball));
              ball.reset();
            }
          } else if (bname == "unroundness" || bname == "surface_unroundness") {
            if (list_seen) {
              p.add(bpos, bkey,
                    "give one of unroundness (path radius) and surface_unroundness (race surface), not both");
              continue;
            }
            list_seen = true;
            list = read_list(p, bnode, bkey, bpos, bname == "surface_unroundness");
          } else {
            p.add(bpos, bkey,
                  unknown_name_rule("unknown key", closest_name(bname, {"ball", "unroundness", "surface_unroundness"}),
                                    "allowed here", "ball, unroundness, surface_unroundness"));
          }
        }
        if (!t.contains("ball")) p.add_missing(t.source().begin, path + ".ball", "missing required key");
        if (!list_seen)
          p.add_missing(t.source().begin, path + ".unroundness", "missing key (or surface_unroundness)");
        if (ball && list) out.per_ball.emplace_back(int(*ball), std::move(*list));
      }
    } else {
      p.add(pos, key,
            unknown_name_rule(node.is_table() ? "unknown table" : "unknown key",
                              closest_name(name, {"unroundness", "surface_unroundness", "ball"}), "allowed here",
                              "unroundness or surface_unroundness, [[race.ball]]"));
    }
  }
}

void check_race(const Scene& scene) {
  if (!scene.race.round()) (void)race_shape(scene);
}

}  // namespace scene_reading
}  // namespace abu

namespace abu {

void scale_race(Scene& scene, double factor, const std::string& origin) {
  if (scene.race.round())
    throw InputError(origin, 0, "unroundness",
                     scene.file + " has a round race: give its largest runout in [race] (model.md §11.1) to scale it");
  if (!(factor >= 0 && factor <= 1))
    throw InputError(origin, 0, "unroundness",
                     fmt::format("the factor scales the scene's [race] (its largest runout) within [0, 1], got {}", factor));
  const auto scale = [factor](RaceHarmonicsInput& in) {
    for (auto& h : in.harmonics) h.amplitude *= factor;
  };
  if (scene.race.all) scale(*scene.race.all);
  for (auto& b : scene.race.per_ball) scale(b.second);
}

}  // namespace abu
