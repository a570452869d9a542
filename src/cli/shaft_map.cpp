// `map` on a flexible-shaft scene (shaft_commands.hpp, docs/model.md §18.13): the balanced
// state's stability over two parameters. The axes are the shaft scene's own parameters:
// every symbol the shaft model reads (omega, U, the balls' m l mu d ..., kappa) and the
// bearings' k and c (bearing_k, bearing_c: every bearing; bearing2_k: the second in file
// order). The rigid rotor's k, c and M_r are refused: the shaft scene has none. Cells from
// scan/shaft_map.hpp, tiles through the map's TileStore and thread pool (resume, threads).
#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>


#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/analysis/map_setup.hpp"
#include "abu/output/files.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/input/scene.hpp"
#include "abu/input/shaft_scene.hpp"
#include "abu/scan/shaft_map.hpp"
#include "shaft_commands.hpp"
#include "tiled_run.hpp"

namespace abu::cli {

namespace {

// One axis of a shaft map: a scene parameter or the bearings' k or c.
struct ShaftAxis {
  enum class Kind { param, bearing_k, bearing_c } kind = Kind::param;
  int bearing = -1;  // 0-based; -1: every bearing
  Axis axis;         // the values (axis.param only for Kind::param)
  std::string name, unit;
};

std::vector<std::string> fields(const std::string& s) {
  std::vector<std::string> out;
  for (std::size_t pos = 0;;) {
    const auto end = s.find(':', pos);
    out.push_back(s.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
    if (end == std::string::npos) return out;
    pos = end + 1;
  }
}

// Applies an axis's value to a scene copy and a spec copy.
void apply(const ShaftAxis& a, double v, Scene& scene, ShaftSpec& spec, const std::string& origin) {
  if (a.kind == ShaftAxis::Kind::param) return set_checked(scene, a.axis.param, v, origin);
  for (std::size_t i = 0; i < spec.bearings.size(); ++i)
    if (a.bearing < 0 || std::size_t(a.bearing) == i)
      (a.kind == ShaftAxis::Kind::bearing_k ? spec.bearings[i].stiffness : spec.bearings[i].damping) = v;
}

// The scene reader's rule (shaft_scene.cpp, model.md §18.11), for specs a bearing axis
// changed: translational stiffness at two nodes, or at one with a tilt stiffness. The model
// itself accepts free shafts (the free-free beam checks), so the rule lives with the scenes.
std::optional<std::string> unheld(const ShaftSpec& spec) {
  std::set<int> held;
  bool tilt = false;
  for (const auto& b : spec.bearings) {
    if (b.stiffness > 0) held.insert(b.node);
    tilt = tilt || b.tilt_stiffness > 0;
  }
  if (held.size() >= 2 || (held.size() == 1 && tilt)) return std::nullopt;
  return std::string("the bearings no longer hold the shaft (translational stiffness at two nodes, or at one with a "
                     "tilt stiffness, model.md §18.11): a rigid-body motion is free, no equilibrium to analyse");
}

ShaftSystem system_at(const Scene& scene, const ShaftAxis& x, double xv, const ShaftAxis& y, double yv,
                      const std::string& origin) {
  Scene s = scene;
  ShaftSpec spec = *scene.shaft;
  apply(x, xv, s, spec, origin);
  apply(y, yv, s, spec, origin);
  if (const auto rule = unheld(spec)) throw InputError(origin, 0, fmt::format("{}={}, {}={}", x.name, xv, y.name, yv), *rule);
  try {
    return make_shaft_system(spec, params_of<any_balls>(s));
  } catch (const std::invalid_argument& e) {
    throw InputError(origin, 0, fmt::format("{}={}, {}={}", x.name, xv, y.name, yv), e.what());
  }
}

ShaftAxis shaft_axis(const std::string& text, const Scene& scene, const std::string& origin) {
  const auto fail = [&](const std::string& rule) -> ShaftAxis { throw InputError(origin, 0, text, rule); };
  const std::vector<std::string> parts = fields(text);
  if (parts.size() != 4 && parts.size() != 5) return fail("expected NAME:FROM:TO:N or NAME:FROM:TO:N:log");
  ShaftAxis a;
  a.name = parts[0];
  const int bearings = int(scene.shaft->bearings.size());
  const std::string& n = parts[0];
  if (n.rfind("bearing", 0) == 0 && (n.ends_with("_k") || n.ends_with("_c"))) {
    a.kind = n.ends_with("_k") ? ShaftAxis::Kind::bearing_k : ShaftAxis::Kind::bearing_c;
    a.unit = a.kind == ShaftAxis::Kind::bearing_k ? "N/m" : "N s/m";
    const std::string index = n.substr(7, n.size() - 9);
    if (!index.empty()) {
      int i = 0;
      const auto [ptr, ec] = std::from_chars(index.data(), index.data() + index.size(), i);
      if (ec != std::errc() || ptr != index.data() + index.size() || i < 1 || i > bearings)
        return fail(fmt::format("'{}': the bearing number must be 1..{} (the [[bearing]] tables in file order)", n,
                                bearings));
      a.bearing = i - 1;
    }
  } else {
    const auto ref = parse_param(n, int(scene.balls.size()));
    if (!ref)
      return fail(fmt::format("unknown parameter '{}' for a flexible shaft; known: bearing_k, bearing_c (every "
                              "bearing), bearingN_k, bearingN_c (the N-th [[bearing]]), and {}",
                              n, param_symbols_help()));
    const Quantity q = ref->quantity;
    if (q == Quantity::stiffness || q == Quantity::damping || q == Quantity::rotor_mass)
      return fail(fmt::format("a flexible shaft has no rotor '{}' (model.md §18.10: its [[bearing]] and [[disc]] "
                              "tables replace the rigid rotor's k, c and M_r); use bearing_k or bearing_c",
                              n));
    if (q == Quantity::ball_radius) return fail("the ball radius does not enter the equations of motion (model.md §3)");
    if (is_per_ball(q) && q != Quantity::ball_mass && q != Quantity::race_radius && !law_uses(scene.law, q))
      return fail(fmt::format("the scene's friction law does not use '{}'", n));
    a.axis.param = *ref;
    a.unit = std::string(unit(q));
  }
  const auto number = [&](const std::string& s, const char* what) {
    const auto v = finite_number(s);
    if (!v) fail(fmt::format("{} '{}' is not a finite number", what, s));
    return *v;
  };
  a.axis.from = number(parts[1], "FROM");
  a.axis.to = number(parts[2], "TO");
  int count = 0;
  {
    const auto [ptr, ec] = std::from_chars(parts[3].data(), parts[3].data() + parts[3].size(), count);
    if (ec != std::errc() || ptr != parts[3].data() + parts[3].size())
      return fail(fmt::format("N '{}' is not an integer", parts[3]));
  }
  if (count < 1 || count > kMaxAxisCount) return fail(fmt::format("N must be in [1, {}] (got {})", kMaxAxisCount, count));
  a.axis.count = count;
  if (parts.size() == 5) {
    if (parts[4] != "log") return fail(fmt::format("the fifth field must be 'log' (got '{}')", parts[4]));
    if (!(a.axis.from > 0 && a.axis.to > 0))
      return fail(fmt::format("a log axis needs both ends > 0 (got {} .. {})", a.axis.from, a.axis.to));
    a.axis.logarithmic = true;
  }
  if (a.axis.count > 1 && a.axis.from == a.axis.to) return fail("FROM and TO are equal but N > 1");
  if (a.kind != ShaftAxis::Kind::param && (a.axis.from < 0 || a.axis.to < 0))
    return fail(fmt::format("a bearing's {} must be >= 0 (got {} .. {})",
                            a.kind == ShaftAxis::Kind::bearing_k ? "stiffness" : "damping", a.axis.from, a.axis.to));
  // Both ends in the scene's ranges (set_checked's rules, the shaft's U range).
  for (double v : {a.axis.from, a.axis.to}) {
    if (a.kind != ShaftAxis::Kind::param) continue;
    Scene probe = scene;
    set_checked(probe, a.axis.param, v, origin);
    check_shaft_range(probe, origin);
  }
  return a;
}

}  // namespace

int map_shaft(const Scene& scene, const ShaftMapRequest& request) {
  const ShaftAxis x = shaft_axis(request.x, scene, "--x"), y = shaft_axis(request.y, scene, "--y");
  if (x.name == y.name || (x.kind != ShaftAxis::Kind::param && x.kind == y.kind &&
                           (x.bearing < 0 || y.bearing < 0)))
    throw InputError("--y", 0, request.y, "the two axes set the same value");
  if (x.kind == ShaftAxis::Kind::param && y.kind == ShaftAxis::Kind::param && x.axis.param.quantity == y.axis.param.quantity &&
      (x.axis.param.ball < 0 || y.axis.param.ball < 0 || x.axis.param.ball == y.axis.param.ball))
    throw InputError("--y", 0, request.y, "the two axes set the same value");
  if (long(x.axis.count) * long(y.axis.count) > kMaxCells)
    throw InputError("--y", 0, request.y, fmt::format("the map would have {} x {} cells; at most {} are allowed",
                                                      x.axis.count, y.axis.count, kMaxCells));
  // Every corner's system is valid (the bearings still hold the shaft, ...) before any work.
  for (double xv : {x.axis.from, x.axis.to})
    for (double yv : {y.axis.from, y.axis.to}) (void)system_at(scene, x, xv, y, yv, "--x/--y");
  ShaftMapJob job;
  job.x_name = x.name, job.y_name = y.name, job.x_unit = x.unit, job.y_unit = y.unit;
  for (int i = 0; i < x.axis.count; ++i) job.xs.push_back(x.axis.value(i));
  for (int i = 0; i < y.axis.count; ++i) job.ys.push_back(y.axis.value(i));
  job.cell_system = [&scene, &x, &y, &job](int ix, int iy) {
    return system_at(scene, x, job.xs[std::size_t(ix)], y, job.ys[std::size_t(iy)], "--x/--y");
  };
  job.spectrum.eigenvalues = request.spectrum.eigenvalues;
  job.spectrum.band = request.spectrum.band;
  job.spectrum.sampling = request.sampling;
  // The shaft's numbers too: the tiles' manifest is this header, so --resume refuses a changed shaft.
  job.provenance = provenance_header(request.command_line, scene.file, params_of<any_balls>(scene)) +
                   describe_shaft(*scene.shaft, "# ");
  // The rigid chart_subtitle would print the unused rotor k, c, M_r: the shaft's own line.
  std::string subtitle = fmt::format("{} nodes, {} bearings, balancer at node {}; {} balls, U = {} kg m",
                                     scene.shaft->nodes(), scene.shaft->bearings.size(), scene.shaft->balancer_node,
                                     scene.balls.size(), params_of<any_balls>(scene).rotor.unbalance);
  for (const auto& o : request.overrides) subtitle += " --set " + o;
  SummaryMapRun run{request.output_dir, "shaft_map", "shaft_map", x.name, y.name, int(job.xs.size()),
                    shaft_map_manifest(job), shaft_map_header(job),
                    {request.resume, request.fresh, request.progress, request.quiet, request.threads}, request.chart,
                    "shaft_map.gp", axes_chart_variables(x.name, x.unit, x.axis.logarithmic, y.name, y.unit,
                                                         y.axis.logarithmic),
                    "balanced states"};
  run.chart_variables.insert(run.chart_variables.end(),
                             {{"title", fmt::format("{}: flexible shaft, balanced state", scene.file)},
                              {"subtitle", subtitle}});
  return run_summary_map(run, [&job](const auto& missing, const auto& run_options, const auto& sink) {
    return compute_shaft_map_tiles(job, missing, run_options, sink);
  });
}

}  // namespace abu::cli
