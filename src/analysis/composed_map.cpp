// Maps of an unround race on an anisotropic support (composed_map.hpp, model.md §20.7).
#include "abu/analysis/composed_map.hpp"

#include <fmt/format.h>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/scan/summary_map_text.hpp"

namespace abu {

ComposedCell composed_cell(const ComposedSweepPoint& point) {
  ComposedCell c;
  c.equilibria = point.equilibria;
  c.complete = point.search_doubt.empty();
  for (const ComposedOrbitRow& row : point.rows) {
    const ForcedOrbit& o = row.orbit;
    if (!composed_orbit_usable(o)) {
      ++c.failed;
      continue;
    }
    ++c.orbits;
    switch (o.verdict) {
      case Stability::stable:
        ++c.stable;
        if (!c.best_q_abs || o.q_abs_max < *c.best_q_abs) c.best_q_abs = o.q_abs_max;
        break;
      case Stability::unstable: ++c.unstable; break;
      case Stability::marginal: ++c.marginal; break;
    }
  }
  return c;
}

std::string composed_map_manifest(const ComposedMapJob& job) {
  return summary_map_manifest(composed_map_header(job), job.xs, job.ys);
}

std::string composed_map_header(const ComposedMapJob& job) {
  return job.provenance +
         fmt::format("# unround race on an anisotropic support, map (model.md §20.7): x = {} [{}], {} values; y = {} "
                     "[{}], {} values; per cell the race's equilibria on the mean support, each continued in the "
                     "anisotropy to a pi/omega-periodic orbit (§20.4) and judged by its 2n + 4 Floquet multipliers "
                     "(rotating frame; {} shooting intervals, multipliers to {:g}): equilibria (of the race on the "
                     "mean support), orbits (converged), stable, unstable, marginal (ln max|rho| inside the "
                     "discretization's band), failed (not converged: no verdict); best_q_abs = the largest |q| over "
                     "the period of the stable orbit whose largest |q| is least [m] (empty: none stable); complete = "
                     "the race's box search (§11.4) proved its list complete; cells in order ix outer, iy inner\n"
                     "{},{},equilibria,orbits,stable,unstable,marginal,failed,best_q_abs,complete\n",
                     job.x_name, job.x_unit, job.xs.size(), job.y_name, job.y_unit, job.ys.size(), job.orbit.intervals,
                     job.orbit.accuracy, job.x_name, job.y_name);
}

TileText compute_composed_map_tile(const ComposedMapJob& job, int tile) {
  TileText text;
  const int ix = tile;
  for (int iy = 0; iy < int(job.ys.size()); ++iy) {
    const MapCellPlace cell{"composed map", job.x_name, job.xs[std::size_t(ix)], job.y_name, job.ys[std::size_t(iy)]};
    throw_if_stopped("composed map tile");
    ComposedSweepPoint point;
    try {
      point = composed_orbits_at(job.support, job.cell_input(ix, iy), job.xs[std::size_t(ix)], job.orbit);
    } catch (const NumericalError& e) {  // an equilibrium of the race that is not one: name the cell
      throw NumericalError(fmt::format("{}: {}", cell_label(cell), e.what()));
    }
    const ComposedCell c = composed_cell(point);
    text.summary += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", cell_number(job.xs[std::size_t(ix)], cell, "x"),
                                cell_number(job.ys[std::size_t(iy)], cell, "y"), c.equilibria, c.orbits, c.stable,
                                c.unstable, c.marginal, c.failed,
                                c.best_q_abs ? cell_number(*c.best_q_abs, cell, "|q|") : std::string(),
                                c.complete ? 1 : 0);
    ++text.cells;
    text.equilibria += c.orbits + c.failed;
  }
  return text;
}

MapRunStats compute_composed_map_tiles(const ComposedMapJob& job, const std::vector<int>& tiles,
                                       const MapRunOptions& options, const TileSink& sink) {
  return run_text_tiles(tiles, options, sink, [&](int tile) { return compute_composed_map_tile(job, tile); });
}

}  // namespace abu
