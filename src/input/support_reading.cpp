// [rotor]'s support in a rigid-rotor scene: the isotropic stiffness and damping, or the
// fixed-frame matrices of an anisotropic support (docs/model.md §10.1); see support_reading.hpp.
#include "support_reading.hpp"

#include <cmath>

#include <fmt/format.h>

namespace abu::scene_reading {

// [rotor]: the isotropic stiffness/damping, or the fixed-frame matrices of an anisotropic
// support (docs/model.md §10.1), never both; the matrices' definiteness is checked here.
std::optional<AnisotropicSupport> read_support(Problems& p, const toml::table& table, std::vector<Slot>& slots) {
  std::vector<Slot> matrix{{"stiffness_x", Quantity::stiffness, false},
                           {"stiffness_y", Quantity::stiffness, false},
                           {"damping_x", Quantity::damping, false},
                           {"damping_y", Quantity::damping, false}};
  struct Cross {
    bool seen = false;
    double value = 0.0;
    toml::source_position pos{};
    std::string key;
  } k_xy, c_xy;
  auto other = [&](std::string_view name, const toml::node& node, const std::string& key, toml::source_position pos) {
    if (Slot* s = find(matrix, name)) {
      s->seen = true, s->pos = pos, s->key = key;
      s->value = read_number(p, key, node, pos, s->quantity);
      return true;
    }
    Cross* x = name == "stiffness_xy" ? &k_xy : name == "damping_xy" ? &c_xy : nullptr;
    if (!x) return false;
    x->seen = true, x->pos = pos, x->key = key;
    if (const auto* i = node.as_integer()) x->value = double(i->get());
    else if (const auto* f = node.as_floating_point()) x->value = f->get();
    else p.add(pos, key, fmt::format("must be a number, got {}", describe(node)));
    if (!std::isfinite(x->value)) p.add(pos, key, fmt::format("must be a finite number (got {})", x->value));
    return true;
  };
  read_table(p, table, "rotor", slots,
             "mass, stiffness, damping, unbalance, stiffness_x, stiffness_y, stiffness_xy, damping_x, damping_y, "
             "damping_xy",
             other);
  const Slot* k = find(slots, "stiffness");
  const Slot* c = find(slots, "damping");
  // The last key of each form, for "both forms" (reported at the later of the two).
  const Slot* iso = nullptr;
  for (const Slot* s : {k, c})
    if (s->seen && (!iso || before(iso->pos, s->pos))) iso = s;
  std::optional<std::pair<toml::source_position, std::string>> aniso;
  for (const Slot& s : matrix)
    if (s.seen && (!aniso || before(aniso->first, s.pos))) aniso = {s.pos, s.key};
  for (const Cross* x : {&k_xy, &c_xy})
    if (x->seen && (!aniso || before(aniso->first, x->pos))) aniso = {x->pos, x->key};
  const auto header = table.source().begin;
  if (iso && aniso) {
    if (before(iso->pos, aniso->first))
      p.add(aniso->first, aniso->second,
            fmt::format("the fixed-frame support matrix keys and the isotropic stiffness/damping ({}, line {}) exclude "
                        "each other: give one form",
                        iso->key, iso->pos.line));
    else
      p.add(iso->pos, iso->key,
            fmt::format("the isotropic stiffness/damping and the fixed-frame support matrix keys ({}, line {}) "
                        "exclude each other: give one form",
                        aniso->second, aniso->first.line));
    return std::nullopt;
  }
  if (!aniso) {
    for (const Slot* s : {k, c})
      if (!s->seen)
        p.add_missing(header, fmt::format("rotor.{}", s->name),
                      "missing required key (or the anisotropic support's stiffness_x, stiffness_y, damping_x, "
                      "damping_y)");
    return std::nullopt;
  }
  bool complete = true;
  for (const Slot& s : matrix) {
    if (!s.seen)
      p.add_missing(header, fmt::format("rotor.{}", s.name),
                    "missing required key (an anisotropic support gives stiffness_x, stiffness_y, damping_x, "
                    "damping_y; stiffness_xy, damping_xy default to 0)");
    complete = complete && s.value.has_value();
  }
  if (!complete) return std::nullopt;
  AnisotropicSupport s{*find(matrix, "stiffness_x")->value, *find(matrix, "stiffness_y")->value, k_xy.value,
                       *find(matrix, "damping_x")->value,   *find(matrix, "damping_y")->value,   c_xy.value};
  // Reported at the last key of the matrix in the file.
  auto last_of = [&](std::string_view a, std::string_view b, const Cross& x) {
    const Slot* sa = find(matrix, a);
    const Slot* sb = find(matrix, b);
    std::pair<toml::source_position, std::string> at{sa->pos, sa->key};
    if (before(at.first, sb->pos)) at = {sb->pos, sb->key};
    if (x.seen && before(at.first, x.pos)) at = {x.pos, x.key};
    return at;
  };
  bool ok = true;
  if (auto bad = stiffness_matrix_violation(s.k_x, s.k_y, s.k_xy)) {
    const auto at = last_of("stiffness_x", "stiffness_y", k_xy);
    p.add(at.first, at.second, *bad);
    ok = false;
  }
  if (auto bad = damping_matrix_violation(s.c_x, s.c_y, s.c_xy)) {
    const auto at = last_of("damping_x", "damping_y", c_xy);
    p.add(at.first, at.second, *bad);
    ok = false;
  }
  if (!ok) return std::nullopt;
  return s;
}

}  // namespace abu::scene_reading
