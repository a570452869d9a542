// libFuzzer target for the scene parser, --set and the checks and machine building that
// follow them in every command (docs/robustness.md "Fuzzing").
// Input: a scene's TOML text, then optionally a NUL byte and `--set` assignments, one per
// line, then optionally another NUL byte and option values, one per line, each read as every
// command's own value parsers read theirs (a list of reals, a cell grid, a ramp, a parameter
// name; the options' syntax itself is CLI11's, fuzzed upstream). Bad input must end in
// InputError / NotSupportedError (exit 2 in the CLI); any other exception, a crash, a
// sanitizer report or an assertion is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "abu/core/errors.hpp"
#include "abu/core/params.hpp"
#include "abu/input/option_values.hpp"
#include "abu/input/plausibility.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/ranges.hpp"
#include "abu/input/scene.hpp"
#include "abu/input/shaft_scene.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/model/speed_profile.hpp"

namespace {
// One option value through each parser that reads such values; a ramp is also evaluated as
// a run would use it.
void option_value(const std::string& value) {
  try {
    (void)abu::parse_real_list(value, "--balls");
  } catch (const abu::InputError&) {
  }
  try {
    (void)abu::parse_cell_grid(value, "--grid");
  } catch (const abu::InputError&) {
  }
  try {
    const abu::SpeedProfile ramp = abu::SpeedProfile::parse_ramp(value);
    const double t = 2 * ramp.end_of_change() + 1;
    if (std::isfinite(t)) {  // a run's t_end is finite (--t-end is checked)
      (void)ramp.angle(t);
      (void)ramp.omega_dot(t / 3);
      (void)ramp.crossings(0.5 * (ramp.min_omega() + ramp.max_omega()), t);
    }
    (void)ramp.describe();
  } catch (const abu::InputError&) {
  }
  for (int n : {2, 3, 12}) (void)abu::parse_param(value, n);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const auto nul = input.find('\0');
  const std::string_view text = input.substr(0, nul);
  std::string_view sets = nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1);
  const auto nul2 = sets.find('\0');
  const std::string_view values = nul2 == std::string_view::npos ? std::string_view() : sets.substr(nul2 + 1);
  sets = sets.substr(0, nul2);
  for (std::size_t start = 0; start < values.size();) {
    const auto end = std::min(values.find('\n', start), values.size());
    option_value(std::string(values.substr(start, end - start)));
    start = end + 1;
  }
  try {
    abu::Scene scene = abu::parse_scene(text, "fuzz.toml");
    std::size_t start = 0;
    while (start < sets.size()) {
      const auto end = std::min(sets.find('\n', start), sets.size());
      abu::apply_override(scene, sets.substr(start, end - start));
      start = end + 1;
    }
    if (scene.balls.size() == 2) (void)abu::params_of<2>(scene);
    (void)abu::params_of<abu::any_balls>(scene);
    // What every command does next with the scene's parts (the race, the shaft, the support,
    // the [simulate] table, a ring): the checks and the building of the machine.
    (void)abu::implausible_values(scene);
    (void)abu::numerical_range_violation(scene);
    if (!scene.race.round()) (void)abu::race_shape(scene);
    if (scene.shaft) {
      (void)abu::shaft_warnings(scene);
      abu::check_shaft_range(scene, "fuzz");
      // As the commands build it (analysis/shaft_states.cpp shaft_system_of: a model rule the
      // reader missed is bad input there too), bounded work per input.
      if (scene.shaft->nodes() <= 64) try {
          (void)abu::make_shaft_system(abu::shaft_spec_of(scene), abu::params_of<abu::any_balls>(scene));
        } catch (const std::invalid_argument&) {
        }
    }
  } catch (const abu::InputError&) {
  } catch (const abu::NotSupportedError&) {
  }
  return 0;
}
