// A flexible-rotor scene: [shaft], [[disc]], [[bearing]] (include/abu/input/shaft_scene.hpp,
// docs/model.md §18.10–§18.12). Every rule is added to the scene parser's problem list with
// its position, so that the first in the file is reported (scene.cpp says why).
#include "abu/input/shaft_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <tuple>

#include "abu/input/ranges.hpp"
#include "abu/input/scene.hpp"
#include "bearing_reading.hpp"
#include "shaft_reading.hpp"

namespace abu {

const ShaftSpec& shaft_spec_of(const Scene& scene) {
  if (!scene.shaft)
    throw NotSupportedError(fmt::format("{} is a rigid rotor (no [shaft] table): this needs a flexible shaft "
                                        "(model.md §18)",
                                        scene.file));
  return *scene.shaft;
}

std::vector<double> node_positions(const ShaftSpec& spec) {
  std::vector<double> x(std::size_t(spec.nodes()), 0.0);
  for (std::size_t e = 0; e < spec.elements.size(); ++e) x[e + 1] = x[e] + spec.elements[e].length;
  return x;
}

double shaft_mass(const ShaftSpec& spec) {
  double m = 0.0;
  for (const auto& e : spec.elements)
    m += e.density * std::numbers::pi / 4.0 *
         (e.outer_diameter * e.outer_diameter - e.inner_diameter * e.inner_diameter) * e.length;
  for (const auto& d : spec.discs) m += d.mass;
  return m;
}

std::vector<std::string> shaft_warnings(const Scene& scene) {
  std::vector<std::string> out;
  if (!scene.shaft) return out;
  const ShaftSpec& s = *scene.shaft;
  // One warning per kind (the first element that shows it): a 1000-element shaft with one
  // slip would otherwise print a thousand lines.
  auto first = [&](auto&& bad) -> int {
    for (std::size_t e = 0; e < s.elements.size(); ++e)
      if (bad(s.elements[e])) return int(e);
    return -1;
  };
  if (const int e = first([](const ShaftElement& x) { return x.shear_modulus == 0.0 && x.length < x.outer_diameter; });
      e >= 0)
    out.push_back(fmt::format(
        "shaft element {} (after segments) is shorter ({} m) than its diameter ({} m) and has no shear_modulus: an Euler–Bernoulli "
        "element that short overestimates the stiffness (shear deformation, model.md §18.1); give shear_modulus for "
        "Timoshenko elements",
        e + 1, s.elements[std::size_t(e)].length, s.elements[std::size_t(e)].outer_diameter));
  if (const int e = first([](const ShaftElement& x) { return x.density > 0.0 && x.density < 100.0; }); e >= 0)
    out.push_back(fmt::format("shaft element {} (after segments): density {} kg/m^3 is below any solid's: g/cm^3 typed as kg/m^3? "
                              "(steel is 7850 kg/m^3)",
                              e + 1, s.elements[std::size_t(e)].density));
  if (const int e = first([](const ShaftElement& x) { return x.youngs_modulus < 1e8; }); e >= 0)
    out.push_back(fmt::format("shaft element {} (after segments): youngs_modulus {} Pa is below a soft polymer's: GPa typed as Pa? "
                              "(steel is 2.1e11 Pa)",
                              e + 1, s.elements[std::size_t(e)].youngs_modulus));
  if (const int e = first([](const ShaftElement& x) { return x.outer_diameter > 2.0; }); e >= 0)
    out.push_back(fmt::format("shaft element {} (after segments): outer_diameter {} m is above 2 m: millimetres typed "
                              "as metres?", e + 1,
                              s.elements[std::size_t(e)].outer_diameter));
  return out;
}

void check_shaft_range(const Scene& scene, const std::string& origin) {
  check_numerical_range(scene, origin);  // on a shaft only the unbalance's rule (model.md §18.11, rule 9)
}

namespace scene_reading {

namespace {

enum class Kind { real, integer };

// One key of a shaft table and its rule (nullopt: the value is fine).
struct KeyRule {
  std::string_view name;
  Kind kind;
  bool required;
  std::optional<std::string> (*rule)(double);
};

// The value read for one KeyRule.
struct KeyValue {
  bool seen = false;
  std::optional<double> value;  // set iff present and valid
  toml::source_position pos{};
  std::string key;
};

std::optional<std::string> positive(double x) {
  if (x > 0) return std::nullopt;
  return fmt::format("must be > 0 (got {})", x);
}
std::optional<std::string> non_negative(double x) {
  if (x >= 0) return std::nullopt;
  return fmt::format("must be >= 0 (got {})", x);
}
std::optional<std::string> node_index(double x) {
  if (x >= 0) return std::nullopt;
  return fmt::format("must be a node index >= 0 (node 0 is the shaft's first end), got {}", x);
}
std::optional<std::string> segment_count(double x) {
  if (x >= 1 && x <= kMaxShaftSegments) return std::nullopt;
  return fmt::format("must be an integer 1..{} (the section is cut into that many equal elements), got {}",
                     kMaxShaftSegments, x);
}
std::optional<std::string> density_rule(double x) {
  if (x >= 0) return std::nullopt;
  return fmt::format("must be >= 0 (got {}; 0 is a massless shaft)", x);
}

std::string names_of(const std::vector<KeyRule>& rules) {
  std::string s;
  for (const auto& r : rules) s += fmt::format("{}{}", s.empty() ? "" : ", ", r.name);
  return s;
}

// Reads every key of `table` (addressed as `path`) against `rules`; unknown keys are
// problems with the nearest known name. Required keys that are absent are reported at the
// table's header, after everything present (Problems::add_missing).
std::vector<KeyValue> read_keys(Problems& p, const toml::table& table, const std::string& path,
                                const std::vector<KeyRule>& rules, std::string_view why_required = "") {
  std::vector<KeyValue> out(rules.size());
  const std::string help = names_of(rules);
  for (auto&& [k, node] : table) {
    const std::string name(k.str());
    const std::string key = fmt::format("{}.{}", path, name);
    const auto pos = k.source().begin;
    const auto it = std::find_if(rules.begin(), rules.end(), [&](const KeyRule& r) { return r.name == name; });
    if (it == rules.end()) {
      p.add(pos, key, unknown_name_rule(node.is_table() ? "unknown table" : "unknown key",
                                        closest_name(name, split_names(help)), "allowed here", help));
      continue;
    }
    KeyValue& v = out[std::size_t(it - rules.begin())];
    v.seen = true, v.pos = pos, v.key = key;
    std::optional<double> x;
    if (it->kind == Kind::integer) {
      if (const auto i = read_integer(p, key, node, pos, it->name == "segments" ? "a count" : "a node index"))
        x = double(*i);
    } else {
      x = number_value(p, key, node, pos);
      if (x && !std::isfinite(*x)) {
        p.add(pos, key, fmt::format("must be a finite number (got {})", *x));
        x.reset();
      }
    }
    if (!x) continue;
    if (auto bad = it->rule(*x)) {
      p.add(pos, key, *bad);
      continue;
    }
    v.value = x;
  }
  for (std::size_t i = 0; i < rules.size(); ++i)
    if (rules[i].required && !out[i].seen)
      p.add_missing(table.source().begin, fmt::format("{}.{}", path, rules[i].name),
                    fmt::format("missing required key{}", why_required.empty() ? "" : fmt::format(" ({})", why_required)));
  return out;
}

const KeyValue& at(const std::vector<KeyValue>& values, const std::vector<KeyRule>& rules, std::string_view name) {
  const auto it = std::find_if(rules.begin(), rules.end(), [&](const KeyRule& r) { return r.name == name; });
  return values[std::size_t(it - rules.begin())];
}
double value_or(const std::vector<KeyValue>& values, const std::vector<KeyRule>& rules, std::string_view name,
                double fallback) {
  return at(values, rules, name).value.value_or(fallback);
}

const std::vector<KeyRule> kElementRules{{"length", Kind::real, true, positive},
                                         {"outer_diameter", Kind::real, true, positive},
                                         {"inner_diameter", Kind::real, false, non_negative},
                                         {"youngs_modulus", Kind::real, true, positive},
                                         {"density", Kind::real, true, density_rule},
                                         {"shear_modulus", Kind::real, false, positive},
                                         {"segments", Kind::integer, false, segment_count}};
const std::vector<KeyRule> kDiscRules{{"node", Kind::integer, true, node_index},
                                      {"mass", Kind::real, true, positive},
                                      {"polar_inertia", Kind::real, true, non_negative},
                                      {"transverse_inertia", Kind::real, true, non_negative}};
std::optional<std::string> matrix_entry(double) { return std::nullopt; }  // the matrix's rules: bearing_reading.cpp
// stiffness, damping or the anisotropic bearing's matrix keys: one form required (read_bearing_support).
const std::vector<KeyRule> kBearingRules{{"node", Kind::integer, true, node_index},
                                         {"stiffness", Kind::real, false, non_negative},
                                         {"damping", Kind::real, false, non_negative},
                                         {"tilt_stiffness", Kind::real, false, non_negative},
                                         {"tilt_damping", Kind::real, false, non_negative},
                                         {"stiffness_x", Kind::real, false, matrix_entry},
                                         {"stiffness_y", Kind::real, false, matrix_entry},
                                         {"stiffness_xy", Kind::real, false, matrix_entry},
                                         {"damping_x", Kind::real, false, matrix_entry},
                                         {"damping_y", Kind::real, false, matrix_entry},
                                         {"damping_xy", Kind::real, false, matrix_entry}};

// An array of tables under `name` ([[shaft.element]], [[disc]], [[bearing]]), or a problem.
const toml::array* tables_of(Problems& p, const toml::node& node, toml::source_position pos, const std::string& name) {
  const toml::array* a = node.as_array();
  if (all_tables(a)) return a;
  const std::string got = node.is_table() ? fmt::format("a single table [{}]", name) : describe(node);
  p.add(pos, name, fmt::format("must be an array of tables ([[{}]], one per entry), got {}", name, got));
  return nullptr;
}

// A node index read from a table, with where it was written.
struct NodeRef {
  int node = -1;  // -1: absent or invalid (reported already)
  toml::source_position pos{};
  std::string key;
};

NodeRef node_of(const std::vector<KeyValue>& values, const std::vector<KeyRule>& rules) {
  const KeyValue& v = at(values, rules, "node");
  return {v.value && *v.value <= double(std::numeric_limits<int>::max()) ? int(*v.value) : -1, v.pos, v.key};
}

std::string node_range_rule(int node, int elements) {
  return fmt::format("must be a node index 0..{} (the shaft's {} element{}, after segments, join nodes 0..{}; node 0 "
                     "is the first section's left end), got {}",
                     elements, elements, elements == 1 ? "" : "s", elements, node);
}

}  // namespace

bool take_shaft_key(ShaftInput& in, std::string_view name, const toml::node& node, toml::source_position pos) {
  if (name == "shaft") {
    in.shaft = &node, in.shaft_pos = pos;
  } else if (name == "disc") {
    in.discs = &node, in.discs_pos = pos;
  } else if (name == "bearing") {
    in.bearings = &node, in.bearings_pos = pos;
  } else {
    return false;
  }
  return true;
}

void read_shaft_rotor(Problems& p, const toml::table& table, std::vector<Slot>& rotor_slots) {
  std::vector<Slot> slots{{"unbalance", Quantity::unbalance, true}};
  auto other = [&](std::string_view name, const toml::node&, const std::string& key, toml::source_position pos) {
    if (name == "mass") {
      p.add(pos, key,
            "a shaft scene's rotating mass is its discs' ([[disc]] mass, polar_inertia, transverse_inertia) and its "
            "shaft's ([[shaft.element]] density): [rotor] gives only the unbalance (model.md §18.10)");
      return true;
    }
    if (name == "stiffness" || name == "damping" || name.starts_with("stiffness_") || name.starts_with("damping_")) {
      p.add(pos, key,
            "a shaft scene's support is its bearings' ([[bearing]] stiffness, damping, tilt_stiffness, tilt_damping, "
            "or an anisotropic bearing's stiffness_x, stiffness_y, stiffness_xy, damping_x, damping_y, damping_xy): "
            "[rotor] gives only the unbalance (model.md §18.10, §18.19)");
      return true;
    }
    return false;
  };
  read_table(p, table, "rotor", slots, "unbalance (a shaft scene's [rotor] gives only the unbalance)", other);
  take(*find(rotor_slots, "unbalance"), slots.front());
}

std::optional<ShaftSpec> read_shaft(Problems& p, const ShaftInput& in) {
  if (!in.shaft) {
    for (auto [node, pos, name] : {std::tuple{in.discs, in.discs_pos, "disc"}, {in.bearings, in.bearings_pos, "bearing"}})
      if (node)
        p.add(pos, name,
              fmt::format("[[{}]] belongs to a flexible rotor: add [shaft] with its [[shaft.element]] tables "
                          "(model.md §18.10); the rigid rotor's mass and support are in [rotor]",
                          name));
    return std::nullopt;
  }
  const toml::table* shaft = in.shaft->as_table();
  if (!shaft) {
    p.add(in.shaft_pos, "shaft", fmt::format("must be a table ([shaft]), got {}", describe(*in.shaft)));
    return std::nullopt;
  }
  bool ok = true;
  ShaftSpec spec;

  // --- [shaft]: the balancer node and the elements.
  std::optional<NodeRef> balancer;
  const toml::array* elements = nullptr;
  bool elements_seen = false;
  for (auto&& [k, node] : *shaft) {
    const std::string name(k.str());
    const std::string key = "shaft." + name;
    const auto pos = k.source().begin;
    if (name == "balancer_node") {
      NodeRef r{-1, pos, key};
      if (const auto i = read_integer(p, key, node, pos, "the node of the balancer's disc")) {
        if (*i < 0)
          p.add(pos, key, fmt::format("must be a node index >= 0 (node 0 is the shaft's first end), got {}", *i));
        else if (*i <= std::numeric_limits<int>::max())
          r.node = int(*i);
        else
          p.add(pos, key, fmt::format("must be a node index 0..{}, got {}", kMaxShaftElements, *i));
      }
      balancer = r;
    } else if (name == "element") {
      elements_seen = true;
      elements = tables_of(p, node, pos, "shaft.element");
    } else {
      p.add(pos, key,
            unknown_name_rule(node.is_table() ? "unknown table" : "unknown key",
                              closest_name(name, {"balancer_node", "element"}), "allowed here",
                              "balancer_node, [[shaft.element]] (discs and bearings are top-level [[disc]], [[bearing]])"));
    }
  }
  if (!balancer)
    p.add_missing(shaft->source().begin, "shaft.balancer_node",
                  "missing required key (the node whose [[disc]] carries the balancer's race and balls)");
  // No [[shaft.element]]: one node (0), the rigid rotor with a tilt (model.md §18.9).
  if (elements_seen && !elements) ok = false;

  long long total = 0;
  bool elements_ok = !elements_seen || elements != nullptr;
  std::vector<std::pair<KeyValue, int>> densities;  // each section's density key and its first element
  if (elements) {
    int index = 0;
    for (const auto& e : *elements) {
      ++index;
      const toml::table& t = *e.as_table();
      const std::string path = fmt::format("shaft.element[{}]", index);
      const auto v = read_keys(p, t, path, kElementRules);
      const bool complete = std::all_of(kElementRules.begin(), kElementRules.end(), [&](const KeyRule& r) {
        const KeyValue& x = at(v, kElementRules, r.name);
        return x.seen ? x.value.has_value() : !r.required;
      });
      if (!complete) {
        elements_ok = false;
        continue;
      }
      ShaftElement el;
      el.outer_diameter = value_or(v, kElementRules, "outer_diameter", 0);
      el.inner_diameter = value_or(v, kElementRules, "inner_diameter", 0);
      el.youngs_modulus = value_or(v, kElementRules, "youngs_modulus", 0);
      el.density = value_or(v, kElementRules, "density", 0);
      el.shear_modulus = value_or(v, kElementRules, "shear_modulus", 0);
      // Poisson's ratio nu = E/(2G) - 1 of an isotropic solid lies in (-1, 0.5): G > E/3 (the
      // shear coefficient (18.1.2) needs it; nu > -1 holds for any G > 0).
      if (el.shear_modulus > 0 && !(el.shear_modulus > el.youngs_modulus / 3.0)) {
        const KeyValue& g = at(v, kElementRules, "shear_modulus");
        p.add(g.pos, g.key,
              fmt::format("must be > youngs_modulus / 3 = {} Pa: Poisson's ratio E/(2G) - 1 = {} must be < 0.5 "
                          "(model.md (18.1.2); steel: G = 8.1e10 Pa, E = 2.1e11 Pa)",
                          el.youngs_modulus / 3.0, el.youngs_modulus / (2.0 * el.shear_modulus) - 1.0));
        elements_ok = false;
        continue;
      }
      if (!(el.inner_diameter < el.outer_diameter)) {
        const KeyValue& inner = at(v, kElementRules, "inner_diameter");
        const KeyValue& outer = at(v, kElementRules, "outer_diameter");
        const KeyValue& later = before(outer.pos, inner.pos) ? inner : outer;
        p.add(later.pos, later.key,
              fmt::format("inner_diameter {} m must be < outer_diameter {} m (a tube needs a wall)", el.inner_diameter,
                          el.outer_diameter));
        elements_ok = false;
        continue;
      }
      const int segments = int(value_or(v, kElementRules, "segments", 1));
      total += segments;
      if (total > kMaxShaftElements) {
        const KeyValue& s = at(v, kElementRules, "segments");
        p.add(s.seen ? s.pos : t.source().begin, s.seen ? s.key : path,
              fmt::format("the shaft would have {} elements or more; at most {} (4 degrees of freedom per node)",
                          total, kMaxShaftElements));
        elements_ok = false;
        break;
      }
      el.length = value_or(v, kElementRules, "length", 0) / segments;
      densities.emplace_back(at(v, kElementRules, "density"), int(spec.elements.size()));
      for (int s = 0; s < segments; ++s) spec.elements.push_back(el);
    }
  }
  if (!elements_ok) ok = false;
  const int n_elements = int(spec.elements.size());
  // Node ranges can be judged only once every element is known.
  auto check_node = [&](const NodeRef& r) {
    if (r.node < 0 || !elements_ok) return r.node >= 0;
    if (r.node > n_elements) {
      p.add(r.pos, r.key, node_range_rule(r.node, n_elements));
      return false;
    }
    return true;
  };

  // --- [[disc]]
  std::vector<std::pair<ShaftDisc, NodeRef>> discs;
  if (in.discs) {
    if (const toml::array* a = tables_of(p, *in.discs, in.discs_pos, "disc")) {
      int index = 0;
      for (const auto& e : *a) {
        ++index;
        const toml::table& t = *e.as_table();
        const std::string path = fmt::format("disc[{}]", index);
        const auto v = read_keys(p, t, path, kDiscRules, "the node the disc sits on, 0..E");
        const NodeRef node = node_of(v, kDiscRules);
        if (!check_node(node)) {
          ok = false;
          continue;
        }
        ShaftDisc d{node.node, value_or(v, kDiscRules, "mass", 0), value_or(v, kDiscRules, "polar_inertia", 0),
                    value_or(v, kDiscRules, "transverse_inertia", 0)};
        const KeyValue& ip = at(v, kDiscRules, "polar_inertia");
        const KeyValue& id = at(v, kDiscRules, "transverse_inertia");
        if (!at(v, kDiscRules, "mass").value || !ip.value || !id.value) {
          ok = false;
          continue;
        }
        // Principal moments of a rigid body: I_3 <= I_1 + I_2, here I_p <= 2 I_d (equality for a
        // thin disc); a relative 1e-9 allows the rounding of values typed from I_p = m r^2/2, I_d = m r^2/4.
        if (d.polar_inertia > 2.0 * d.transverse_inertia * (1.0 + 1e-9)) {
          const KeyValue& later = before(ip.pos, id.pos) ? id : ip;
          p.add(later.pos, later.key,
                fmt::format("polar_inertia {} kg m^2 exceeds 2 transverse_inertia = {} kg m^2: no rigid body has that "
                            "(I_p <= 2 I_d, equality for a thin disc; swapped values?)",
                            d.polar_inertia, 2.0 * d.transverse_inertia));
          ok = false;
          continue;
        }
        const auto same = std::find_if(discs.begin(), discs.end(), [&](const auto& x) { return x.first.node == d.node; });
        if (same != discs.end()) {
          p.add(node.pos, node.key,
                fmt::format("node {} has a disc already ({}, line {}): give one [[disc]] per node, with the summed "
                            "mass and inertias",
                            d.node, same->second.key, same->second.pos.line));
          ok = false;
          continue;
        }
        discs.emplace_back(d, node);
      }
    } else {
      ok = false;
    }
  }

  // --- [[bearing]]
  std::vector<std::pair<ShaftBearing, NodeRef>> bearings;
  if (in.bearings) {
    if (const toml::array* a = tables_of(p, *in.bearings, in.bearings_pos, "bearing")) {
      int index = 0;
      for (const auto& e : *a) {
        ++index;
        const toml::table& t = *e.as_table();
        const std::string path = fmt::format("bearing[{}]", index);
        const auto v = read_keys(p, t, path, kBearingRules, "the node the bearing holds, 0..E");
        const NodeRef node = node_of(v, kBearingRules);
        const bool complete = std::all_of(kBearingRules.begin(), kBearingRules.end(), [&](const KeyRule& r) {
          const KeyValue& x = at(v, kBearingRules, r.name);
          return x.seen ? x.value.has_value() : !r.required;
        });
        std::vector<BearingKey> support_keys;  // isotropic or anisotropic (model.md §18.19)
        for (std::string_view name : kBearingSupportKeys) {
          const KeyValue& x = at(v, kBearingRules, name);
          support_keys.push_back({name, x.seen, x.value, x.pos, x.key});
        }
        const auto support = read_bearing_support(p, support_keys, t.source().begin, path);
        if (!check_node(node) || !complete || !support) {
          ok = false;
          continue;
        }
        bearings.emplace_back(ShaftBearing{node.node, support->stiffness, support->damping,
                                           value_or(v, kBearingRules, "tilt_stiffness", 0),
                                           value_or(v, kBearingRules, "tilt_damping", 0), support->anisotropic},
                              node);
      }
    } else {
      ok = false;
    }
  } else {
    p.add_absent("bearing",
                 "a shaft scene needs at least one [[bearing]] (node, stiffness, damping): a free shaft moves as a "
                 "rigid body, its stiffness matrix is singular and it has no equilibrium to analyse (model.md §18.11)");
    ok = false;
  }

  // --- The balancer's disc.
  if (balancer && balancer->node >= 0 && check_node(*balancer) && ok) {
    if (std::none_of(discs.begin(), discs.end(), [&](const auto& d) { return d.first.node == balancer->node; })) {
      std::string at_nodes;
      for (const auto& d : discs) at_nodes += fmt::format("{}{}", at_nodes.empty() ? "" : ", ", d.first.node);
      p.add(balancer->pos, balancer->key,
            fmt::format("node {} has no [[disc]]: the balancer's race and balls sit on a disc ({})", balancer->node,
                        at_nodes.empty() ? std::string("the scene has no [[disc]]") : "discs at nodes " + at_nodes));
      ok = false;
    }
  } else if (!balancer || balancer->node < 0) {
    ok = false;
  }

  // --- The bearings hold the shaft (model.md §18.11): a rigid-body motion u(x) = a + b x,
  // psi = b in one plane meets a translational spring at x_j (a + b x_j = 0) or a tilt spring
  // (b = 0); both a and b are held iff the springs' rows (1, x_j) and (0, 1) span the plane:
  // translational stiffness at two different positions, or at one with a tilt stiffness anywhere.
  if (ok && !bearings.empty()) {
    std::set<int> held;  // nodes with translational stiffness (distinct nodes: distinct positions, L > 0)
    bool tilt = false;
    for (const auto& [b, ref] : bearings) {
      if (b.stiffness > 0) held.insert(b.node);
      tilt = tilt || b.tilt_stiffness > 0;
    }
    const bool holds = held.size() >= 2 || (held.size() == 1 && tilt);
    if (!holds) {
      const NodeRef& first = bearings.front().second;
      p.add(first.pos, "bearing",
            held.empty()
                ? std::string("no bearing has stiffness > 0: the shaft is free to translate as a rigid body (a "
                              "singular stiffness matrix, no equilibrium to analyse; model.md §18.11)")
                : fmt::format("the bearings' stiffness acts at node {} only and no bearing has tilt_stiffness > 0: the "
                              "shaft is free to tilt about that node as a rigid body (a singular stiffness matrix; "
                              "model.md §18.11); add a bearing at another node or a tilt_stiffness",
                              *held.begin()));
      ok = false;
    }
  }
  // --- Every dof has inertia (model.md §18.9: massless dofs are not condensed): a node's
  // translations need an adjacent element with density > 0 or a disc (mass > 0), its tilts an
  // adjacent element with density > 0 or a disc with transverse_inertia > 0.
  if (ok) {
    const int nodes = n_elements + 1;
    std::vector<char> massive(std::size_t(nodes), 0);
    for (int e = 0; e < n_elements; ++e)
      if (spec.elements[std::size_t(e)].density > 0) massive[std::size_t(e)] = massive[std::size_t(e) + 1] = 1;
    for (int k = 0; k < nodes && ok; ++k) {
      if (massive[std::size_t(k)]) continue;
      const auto d = std::find_if(discs.begin(), discs.end(), [&](const auto& x) { return x.first.node == k; });
      if (d != discs.end() && d->first.transverse_inertia > 0) continue;
      const std::string what =
          d == discs.end() ? "no disc" : "a disc with transverse_inertia 0 (no inertia on its tilts)";
      const std::string rule = fmt::format(
          "node {} has no inertia: its elements are massless (density 0) and it has {}; a massless node is not "
          "condensed (model.md §18.9): give the section a density or put a disc with mass and transverse_inertia there",
          k, what);
      if (d != discs.end()) {
        p.add(d->second.pos, d->second.key, rule);
      } else {
        // At the density key of the section holding node k (its first massless element's).
        const KeyValue* at_key = nullptr;
        for (const auto& [kv, first] : densities)
          if (first <= std::max(0, k - 1)) at_key = &kv;
        if (at_key)
          p.add(at_key->pos, at_key->key, rule);
        else
          p.add(shaft->source().begin, "shaft", rule);
      }
      ok = false;
    }
  }
  if (!ok) return std::nullopt;
  for (auto& [d, ref] : discs) spec.discs.push_back(d);
  for (auto& [b, ref] : bearings) spec.bearings.push_back(b);
  spec.balancer_node = balancer->node;
  return spec;
}

}  // namespace scene_reading
}  // namespace abu
