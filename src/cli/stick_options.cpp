// The stick set's resolution options (see the header).
#include "stick_options.hpp"

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include "commands.hpp"

namespace abu::cli {

void add_dry_rows_option(CLI::App& sub, DryRows& rows) {
  sub.add_option_function<std::string>(
         "--dry",
         [&rows](const std::string& v) { rows = v == "on" ? DryRows::on : v == "off" ? DryRows::off : DryRows::automatic; },
         fmt::format("coulomb / stribeck: the rows' dry figures (dry_* columns, a stick set at each value, "
                     "model.md §14.10): auto (unless more than {} values, {} for 3-12 balls, need a scan of the "
                     "torus), on, off",
                     kDryAutomaticScans, kDryAutomaticScansN))
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->default_str("auto");
}

void add_stick_resolution_options(CLI::App& sub, StickSetOptions& options) {
  sub.add_option("--stick-columns", options.columns,
                 "coulomb-set, two balls: beta_1 columns of the stick set's scan (and twice as many beta_2 samples per "
                 "column), besides the dense ones at the smooth equilibria (model.md §14.3)")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  sub.add_option("--stick-area-tolerance", options.area_tolerance,
                 "coulomb-set, two balls: absolute error [rad^2] per radian of beta_1 of the adaptive Simpson rule for "
                 "the stick set's area and |q| integral")
      ->check(tolerance_range(1e-14, 1e-2))
      ->capture_default_str();
  sub.add_option("--stick-grid", options.grid_budget,
                 "coulomb-set, n >= 3 balls: at most this many grid points on the torus (G = floor(B^(1/n)) per angle)")
      ->check(CLI::Range(1L << 10, 1L << 26))
      ->capture_default_str();
}

StickSetOptions stick_resolution(StickSetOptions options) {
  options.samples = 2 * options.columns;
  return options;
}

}  // namespace abu::cli
