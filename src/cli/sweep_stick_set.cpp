// `sweep` of a coulomb-set scene: the stick set of every value (model.md §14) as one CSV
// row each and a chart of V, V_E, the rotor without balls and the area.
#include <fmt/format.h>

#include "abu/analysis/scene_stick_set.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/linear/unround_stick_set.hpp"
#include "abu/output/chart_labels.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report_stick_set.hpp"
#include "cli.hpp"
#include "stick_options.hpp"

namespace abu::cli {

int sweep_stick_set(const Scene& scene, const StickSweepInput& in) {
  StickSetOptions options = in.stick;
  options.trace = false;  // the boundary curves are not part of a sweep's figures
  // Every value's set must be defined (mu > 0, not K = C = 0, on a shaft no undamped critical
  // speed) before any work: refused, nothing computed or written.
  for (std::size_t i = 0; i < in.scenes.size(); ++i) {
    try {
      check_scene_stick_set_defined(in.scenes[i]);
    } catch (const NotSupportedError& e) {
      throw NotSupportedError(fmt::format("at {}={}: {}", in.name, in.values[i], e.what()));
    }
  }
  std::vector<StickSet> sets;
  std::vector<ShaftStickFigures> shaft;  // a flexible shaft's figures per value (model.md §18.17)
  sets.reserve(in.values.size());
  ParamsN first;
  for (std::size_t i = 0; i < in.scenes.size(); ++i) {
    throw_if_stopped("sweep");
    try {
      // on the race's paths when the race is unround (§20.5), through the shaft on a shaft (§18.17)
      SceneStickSet s = scene_stick_set(in.scenes[i], options);
      if (i == 0) first = s.params;
      sets.push_back(std::move(s.set));
      if (s.shaft) shaft.push_back(std::move(*s.shaft));
    } catch (const NotSupportedError& e) {
      throw NotSupportedError(fmt::format("at {}={}: {}", in.name, in.values[i], e.what()));
    }
    if (!sets.back().status.ok())
      fmt::print(stderr, "stability-scan: note: at {}={}: {}\n", in.name, in.values[i], sets.back().status.reason);
  }
  const std::string header = provenance_header(command_line(), scene.file, first);
  const std::filesystem::path dir(in.output_dir);
  const auto csv_path = dir / fmt::format("sweep_stick_{}.csv", in.name);
  const auto png_path = dir / fmt::format("sweep_stick_{}.png", in.name);
  OutputTransaction out;
  const auto staged = out.stage(csv_path, stick_sweep_csv(in.name, in.unit, in.values, sets, header,
                                                          scene.shaft ? &shaft : nullptr));
  if (in.chart)
    run_gnuplot(plots_dir() / "stick_set_sweep.gp",
                {{"csv", staged.string()},
                 {"png", out.reserve(png_path).string()},
                 {"param", in.name},
                 {"unit", in.unit},
                 {"logx", in.logarithmic ? "1" : "0"},
                 {"nballs", std::to_string(first.n_balls())},
                 {"anchor", sets.front().unround_race ? "the least-|q| stable equilibrium of the race" : "balance"},
                 {"title", fmt::format("{}: stick set of coulomb-set friction{}, sweep of {}", scene.file,
                                       sets.front().unround_race ? " on the paths of an unround race"
                                       : scene.shaft             ? " on a flexible shaft (|q| at the balancer node)"
                                                                 : "",
                                       in.name)},
                 {"subtitle", chart_subtitle(scene, in.overrides, {{in.name, in.values.front(), in.values.back(), in.unit}})}});
  out.commit();
  fmt::print(stderr, "wrote {} ({} values){}\n", csv_path.string(), sets.size(),
             in.chart && std::filesystem::exists(png_path) ? fmt::format(" and {}", png_path.string()) : std::string());
  return exit_ok;
}

}  // namespace abu::cli
