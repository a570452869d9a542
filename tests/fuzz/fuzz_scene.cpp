// libFuzzer target for the scene parser and --set (docs/robustness.md "Fuzzing").
// Input: a scene's TOML text, then optionally a NUL byte and `--set` assignments, one per
// line. Bad input must end in InputError / NotSupportedError (exit 2 in the CLI); any
// other exception, a crash, a sanitizer report or an assertion is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "abu/core/errors.hpp"
#include "abu/core/params.hpp"
#include "abu/input/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const auto nul = input.find('\0');
  const std::string_view text = input.substr(0, nul);
  const std::string_view sets = nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1);
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
  } catch (const abu::InputError&) {
  } catch (const abu::NotSupportedError&) {
  }
  return 0;
}
