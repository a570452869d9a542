// A [[bearing]]'s spring and damper, isotropic or anisotropic (bearing_reading.hpp, model.md §18.19).
#include "bearing_reading.hpp"

#include <algorithm>
#include <span>

namespace abu::scene_reading {

namespace {

const BearingKey& key_of(const std::vector<BearingKey>& keys, std::string_view name) {
  return *std::find_if(keys.begin(), keys.end(), [&](const BearingKey& k) { return k.name == name; });
}

// The key of `names` written last in the file (nullptr if none is present).
const BearingKey* last_of(const std::vector<BearingKey>& keys, std::span<const std::string_view> names) {
  const BearingKey* last = nullptr;
  for (std::string_view n : names)
    if (const BearingKey& k = key_of(keys, n); k.seen && (!last || before(last->pos, k.pos))) last = &k;
  return last;
}

constexpr std::string_view kIsotropic[] = {"stiffness", "damping"};
constexpr std::string_view kMatrix[] = {"stiffness_x", "stiffness_y", "stiffness_xy",
                                        "damping_x",   "damping_y",   "damping_xy"};
constexpr std::string_view kStiffnessMatrix[] = {"stiffness_x", "stiffness_y", "stiffness_xy"};
constexpr std::string_view kDampingMatrix[] = {"damping_x", "damping_y", "damping_xy"};

}  // namespace

std::optional<BearingSupport> read_bearing_support(Problems& p, const std::vector<BearingKey>& keys,
                                                   toml::source_position header, const std::string& path) {
  const BearingKey* iso = last_of(keys, kIsotropic);
  const BearingKey* matrix = last_of(keys, kMatrix);
  if (iso && matrix) {  // as the rigid [rotor] (support_reading.cpp): at the later of the two forms
    const bool matrix_later = before(iso->pos, matrix->pos);
    const BearingKey& later = matrix_later ? *matrix : *iso;
    const BearingKey& earlier = matrix_later ? *iso : *matrix;
    p.add(later.pos, later.key,
          fmt::format("the isotropic stiffness/damping and the anisotropic bearing's fixed-frame matrix keys "
                      "(stiffness_x, ...) exclude each other ({}, line {}): give one form (model.md §18.19)",
                      earlier.key, earlier.pos.line));
    return std::nullopt;
  }
  bool complete = true;
  const auto need = [&](std::string_view name, std::string_view why) {
    const BearingKey& k = key_of(keys, name);
    if (!k.seen) p.add_missing(header, fmt::format("{}.{}", path, name), std::string(why));
    complete = complete && k.value.has_value();
  };
  if (!matrix) {
    for (std::string_view n : kIsotropic)
      need(n, "missing required key (or an anisotropic bearing's stiffness_x, stiffness_y, damping_x, damping_y)");
    if (!complete) return std::nullopt;
    return BearingSupport{*key_of(keys, "stiffness").value, *key_of(keys, "damping").value, std::nullopt};
  }
  for (std::string_view n : {"stiffness_x", "stiffness_y", "damping_x", "damping_y"})
    need(n, "missing required key (an anisotropic bearing gives stiffness_x, stiffness_y, damping_x, damping_y; "
            "stiffness_xy, damping_xy default to 0)");
  for (std::string_view n : {"stiffness_xy", "damping_xy"})  // optional, but invalid if given wrong
    complete = complete && (!key_of(keys, n).seen || key_of(keys, n).value);
  if (!complete) return std::nullopt;
  const auto value = [&](std::string_view n) { return key_of(keys, n).value.value_or(0.0); };
  const AnisotropicSupport s{value("stiffness_x"), value("stiffness_y"), value("stiffness_xy"),
                             value("damping_x"),   value("damping_y"),   value("damping_xy")};
  bool ok = true;
  if (auto bad = stiffness_matrix_violation(s.k_x, s.k_y, s.k_xy)) {
    const BearingKey* at = last_of(keys, kStiffnessMatrix);
    p.add(at->pos, at->key, *bad);
    ok = false;
  }
  if (auto bad = damping_matrix_violation(s.c_x, s.c_y, s.c_xy)) {
    const BearingKey* at = last_of(keys, kDampingMatrix);
    p.add(at->pos, at->key, *bad);
    ok = false;
  }
  if (!ok) return std::nullopt;
  return BearingSupport{s.mean_stiffness(), s.mean_damping(), s};
}

}  // namespace abu::scene_reading
