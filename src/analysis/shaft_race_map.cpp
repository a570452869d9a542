// Maps of an unround race on a flexible shaft (shaft_race_map.hpp, model.md §18.18).
#include "abu/analysis/shaft_race_map.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/scan/summary_map_text.hpp"
#include "abu/analysis/shaft_race_sweep.hpp"

namespace abu {

std::string shaft_race_map_manifest(const ShaftRaceMapJob& job) {
  return summary_map_manifest(shaft_race_map_header(job), job.xs, job.ys);
}

std::string shaft_race_map_header(const ShaftRaceMapJob& job) {
  return job.provenance +
         fmt::format("# unround race on a flexible shaft, map (model.md §18.18): x = {} [{}], {} values; y = {} [{}], "
                     "{} values; per cell the race's equilibria on the shaft, each judged by its {} rightmost "
                     "eigenvalues with |Im| <= {} (ARPACK, rotating frame, §18.12): equilibria, stable, unstable, "
                     "undetermined; best_q_abs = |q| at the balancer node of the least-|q| stable state [m] (empty: "
                     "none stable); q_bare = omega^2 U |h|, the node's whirl with the balls held there [m] (empty at "
                     "an undamped critical speed); complete = the race's box search (§11.4) proved its list "
                     "complete; cells in order ix outer, iy inner\n"
                     "{},{},equilibria,stable,unstable,undetermined,best_q_abs,q_bare,complete\n",
                     job.x_name, job.x_unit, job.xs.size(), job.y_name, job.y_unit, job.ys.size(),
                     job.spectrum.eigenvalues,
                     job.spectrum.band > 0 ? fmt::format("{} 1/s", job.spectrum.band) : std::string("10 omega"),
                     job.x_name, job.y_name);
}

TileText compute_shaft_race_map_tile(const ShaftRaceMapJob& job, int tile) {
  TileText text;
  const int ix = tile;
  for (int iy = 0; iy < int(job.ys.size()); ++iy) {
    const MapCellPlace cell{"shaft race map", job.x_name, job.xs[std::size_t(ix)], job.y_name, job.ys[std::size_t(iy)]};
    throw_if_stopped("shaft race map tile");
    const auto [sys, race] = job.cell_input(ix, iy);
    const ShaftStates st = analyze_shaft_race_states(sys, race, job.spectrum);
    int stable = 0, unstable = 0;
    for (const auto& s : st.states) stable += s.verdict == "stable", unstable += s.verdict == "unstable";
    const auto best = least_stable_state(st.states);
    const auto bare = balls_held_whirl(sys);
    text.summary += fmt::format("{},{},{},{},{},{},{},{},{}\n", cell_number(job.xs[std::size_t(ix)], cell, "x"),
                                cell_number(job.ys[std::size_t(iy)], cell, "y"), st.states.size(), stable, unstable,
                                int(st.states.size()) - stable - unstable,
                                best ? cell_number(st.states[*best].q_abs, cell, "|q|") : std::string(),
                                bare ? cell_number(*bare, cell, "q_bare") : std::string(), st.race_complete ? 1 : 0);
    ++text.cells;
    text.equilibria += long(st.states.size());
  }
  return text;
}

MapRunStats compute_shaft_race_map_tiles(const ShaftRaceMapJob& job, const std::vector<int>& tiles,
                                         const MapRunOptions& options, const TileSink& sink) {
  return run_text_tiles(tiles, options, sink, [&](int tile) { return compute_shaft_race_map_tile(job, tile); });
}

}  // namespace abu
