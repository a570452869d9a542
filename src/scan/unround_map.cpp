// Maps of an unround race (unround_map.hpp, model.md §11.10).
#include "abu/scan/unround_map.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/scan/summary_map_text.hpp"
#include "abu/linear/unround_spectrum.hpp"

namespace abu {

std::string unround_map_manifest(const UnroundMapJob& job) {
  return summary_map_manifest(unround_map_header(job), job.xs, job.ys);
}

std::string unround_map_header(const UnroundMapJob& job) {
  return job.provenance +
         fmt::format("# unround race map (model.md §11.10): x = {} [{}], {} values; y = {} [{}], {} values; per cell the "
                     "complete search of §11.4: equilibria, stable ones, best_q_abs = |q| of the best stable state [m] "
                     "(fixed-frame whirl radius; empty: none stable), lambda of §11.6, first_order = lambda <= {}, "
                     "complete = no unresolved leaf and index sum 0; cells in order ix outer, iy inner\n"
                     "{},{},equilibria,stable,best_q_abs,lambda,first_order,complete\n",
                     job.x_name, job.x_unit, job.xs.size(), job.y_name, job.y_unit, job.ys.size(), kFirstOrderLambda,
                     job.x_name, job.y_name);
}

TileText compute_unround_map_tile(const UnroundMapJob& job, int tile) {
  TileText text;
  const int ix = tile;
  for (int iy = 0; iy < int(job.ys.size()); ++iy) {
    const MapCellPlace cell{"unround map", job.x_name, job.xs[std::size_t(ix)], job.y_name, job.ys[std::size_t(iy)]};
    throw_if_stopped("unround map tile");
    const auto [p, race] = job.cell_input(ix, iy);
    const UnroundResult r = find_unround_equilibria(p, race);
    long stable = 0;
    for (const auto& e : r.list) stable += e.spectrum.stability == Stability::stable ? 1 : 0;
    const double lambda = unround_lambda(p, race);
    text.summary += fmt::format(
        "{},{},{},{},{},{},{},{}\n", cell_number(job.xs[std::size_t(ix)], cell, "x"),
        cell_number(job.ys[std::size_t(iy)], cell, "y"), r.list.size(), stable,
        r.best_stable ? cell_number(r.list[*r.best_stable].amplitude, cell, "|q|") : std::string(),
        cell_number(lambda, cell, "Lambda"), lambda <= kFirstOrderLambda ? 1 : 0, r.doubt.empty() ? 1 : 0);
    ++text.cells;
    text.equilibria += long(r.list.size());
  }
  return text;
}

MapRunStats compute_unround_map_tiles(const UnroundMapJob& job, const std::vector<int>& tiles,
                                      const MapRunOptions& options, const TileSink& sink) {
  return run_text_tiles(tiles, options, sink, [&](int tile) { return compute_unround_map_tile(job, tile); });
}

}  // namespace abu
