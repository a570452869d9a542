// Units in which a speed (omega) is typed and displayed: rad/s (the model's, SI), rpm or
// Hz (docs/views.md). The model, the CSV columns named `omega` and every JSON value named
// by a model.md symbol stay in rad/s; a unit only converts at the edges.
//
//   auto u = abu::speed_unit_from_string("rpm");        // SpeedUnit::rpm
//   double w = abu::to_rad_per_s(3000.0, *u);           // 314.159... rad/s
#pragma once

#include <numbers>
#include <optional>
#include <string_view>

namespace abu {

enum class SpeedUnit { rad_per_s, rpm, hz };

/// "rad/s", "rpm", "Hz" (the spelling of outputs).
constexpr std::string_view to_string(SpeedUnit u) {
  switch (u) {
    case SpeedUnit::rad_per_s: return "rad/s";
    case SpeedUnit::rpm: return "rpm";
    case SpeedUnit::hz: return "Hz";
  }
  return "rad/s";
}

/// "rad/s", "rpm", "hz" or "Hz"; nullopt otherwise.
constexpr std::optional<SpeedUnit> speed_unit_from_string(std::string_view s) {
  if (s == "rad/s") return SpeedUnit::rad_per_s;
  if (s == "rpm") return SpeedUnit::rpm;
  if (s == "hz" || s == "Hz") return SpeedUnit::hz;
  return std::nullopt;
}

/// rad/s in one unit: 1, 2 pi / 60, 2 pi.
constexpr double rad_per_s_per_unit(SpeedUnit u) {
  switch (u) {
    case SpeedUnit::rad_per_s: return 1.0;
    case SpeedUnit::rpm: return 2 * std::numbers::pi / 60;
    case SpeedUnit::hz: return 2 * std::numbers::pi;
  }
  return 1.0;
}
constexpr double to_rad_per_s(double value, SpeedUnit u) { return value * rad_per_s_per_unit(u); }
constexpr double from_rad_per_s(double omega, SpeedUnit u) { return omega / rad_per_s_per_unit(u); }

}  // namespace abu
