// The [uncertain] table of a scene: see uncertain_table.hpp.
#include "uncertain_table.hpp"

#include <cmath>

namespace abu::scene_reading {

std::vector<SceneUncertainty> read_uncertain_table(Problems& p, const toml::table& table, int n_balls) {
  std::vector<SceneUncertainty> out;
  for (auto&& [k, node] : table) {
    const std::string name(k.str());
    const std::string key = "uncertain." + name;
    const auto pos = k.source().begin;
    if (name == "omega") {
      p.add(pos, key, "the speed is the run's profile ([speed], [simulate] ramp), not an uncertain input");
      continue;
    }
    if (name != "unroundness" && !parse_param(name, n_balls)) {
      p.add(pos, key, "names no parameter (a --set symbol: U k c M_r mu m l r f ..., or unroundness)");
      continue;
    }
    const auto* a = node.as_array();
    if (!a || a->size() != 2) {
      p.add(pos, key, fmt::format("must be an array [LOW, HIGH] of two numbers, got {}", describe(node)));
      continue;
    }
    const toml::node* first = a->get(0);
    const toml::node* second = a->get(1);
    if (!first || !second) continue;  // size 2 checked above
    const auto low = number_value(p, key, *first, pos), high = number_value(p, key, *second, pos);
    if (!low || !high) continue;
    if (!(std::isfinite(*low) && std::isfinite(*high) && *low <= *high)) {
      p.add(pos, key, fmt::format("the range [{}, {}] must be finite with LOW <= HIGH", *low, *high));
      continue;
    }
    out.push_back({name, *low, *high, int(pos.line)});
  }
  return out;
}

}  // namespace abu::scene_reading
