// `sweep` and `continue` on an unround race (model.md §11.10): the glue between the
// command line and the complete search (§11.4) / the branches in the unroundness factor.
// Private to the CLI.
#pragma once

#include <filesystem>
#include <string>

#include "abu/continuation/arclength.hpp"
#include "abu/input/race_scene.hpp"  // kUnroundnessParam, checked_scaled_race
#include "abu/model/unround_race.hpp"
#include "abu/scan/map.hpp"
#include "cli.hpp"

namespace abu::cli {

/// The files of a sweep over NAME: sweep_NAME.csv, summary_NAME.csv, summary_NAME.png
/// (the n-ball sweep and the unround race's).
struct SweepPaths {
  std::filesystem::path csv, summary, png;
};
SweepPaths sweep_paths(const std::filesystem::path& dir, const std::string& name);


struct UnroundGrid {
  std::string param;  ///< "unroundness" or a parameter symbol (omega, U, ...)
  double from = 0, to = 0;
  int steps = 0;
  bool logarithmic = false;
  bool chart = true;
  std::string output_dir;
};

/// The values of a sweep on an unround race (the unroundness factor, or a parameter of the
/// scene) with each value's scene and race, checked before any work.
struct UnroundValues {
  std::string name, unit;
  std::vector<double> values;
  std::vector<Scene> scenes;
  std::vector<RaceShape> races;
};
UnroundValues unround_values(const Scene& scene, const UnroundGrid& grid);

/// sweep_NAME.csv (every equilibrium per value), summary_NAME.csv and summary_NAME.png.
int sweep_unround(const Scene& scene, const SceneOptions& options, const UnroundGrid& grid);
/// branch_unroundness.csv, special_unroundness.csv and branch_unroundness.png.
int continue_unroundness(const Scene& scene, const SceneOptions& options, double to, const ContinuationOptions& numerics,
                         bool chart, const std::string& output_dir);

/// One axis of an unround map: the unroundness factor (unroundness:FROM:TO:N[:log], each end's
/// race checked against §11.1), or a parameter of the scene (parse_axis).
struct UnroundAxis {
  Axis axis;
  bool factor = false;  ///< the unroundness factor
  std::string name, unit;
};
UnroundAxis unround_axis(const std::string& spec, const Scene& scene, const RaceShape& race, const std::string& origin);
/// The two axes of an unround-race map (unround_axis each) and their values; the same parameter
/// twice and more than kMaxCells cells are refused (--y).
struct UnroundMapAxes {
  UnroundAxis x, y;
  std::vector<double> xs, ys;
};
UnroundMapAxes unround_map_axes(const std::string& x_spec, const std::string& y_spec, const Scene& scene,
                                const RaceShape& race);
/// A map cell's machine: the scene with each parameter axis's value set (checked, at --x/--y)
/// and the unroundness factor (1 without a factor axis). The race at the cell is
/// scaled_race(race_shape(scene), factor): re-read, as surface harmonics follow l and r.
struct UnroundCell {
  Scene scene;
  double factor = 1;
};
UnroundCell unround_cell(const Scene& scene, const UnroundAxis& x, double xv, const UnroundAxis& y, double yv);

struct UnroundMapRequest {
  std::string x, y;  ///< NAME:FROM:TO:N[:log] (omega already in rad/s), NAME a parameter or "unroundness"
  std::string command_line;  ///< what determines the bytes (no threads, resume, output directory)
  int threads = 1;
  bool resume = false, fresh = false, progress = false, quiet = false, chart = true;
  std::string output_dir;
};
/// summary_X_Y.csv and summary_X_Y.png: per cell the count of equilibria and stable ones,
/// the best stable |q|, Lambda and the first-order flag (scan/unround_map.hpp).
int map_unround(const Scene& scene, const SceneOptions& options, const UnroundMapRequest& request);

}  // namespace abu::cli
