// The stability ranges of a sweep, a continuation or a map (docs/views.md; declared in
// report_views.hpp): where a balanced state is stable and where nothing is, each end located,
// a grid bracket or the interval's; as text and in summary_NAME.json.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abu/output/format.hpp"
#include "abu/output/report_views.hpp"
#include "json_quantity.hpp"

namespace abu {

using detail::json_quantity;

namespace {
// Maximal runs of consecutive values where `flag` holds; ends are grid brackets.
std::vector<Range> runs(const std::vector<double>& values, const std::vector<bool>& flag) {
  std::vector<Range> out;
  for (std::size_t i = 0; i < values.size();) {
    if (!flag[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < values.size() && flag[j + 1]) ++j;
    Range r;
    r.from = values[i], r.to = values[j];
    r.from_kind = i == 0 ? "interval" : "grid";
    r.to_kind = j + 1 == values.size() ? "interval" : "grid";
    if (i > 0) r.from_outside = values[i - 1];
    if (j + 1 < values.size()) r.to_outside = values[j + 1];
    out.push_back(r);
    i = j + 1;
  }
  return out;
}

template <class A>
StableAt stable_flags(const A& a) {
  StableAt at;
  const auto points = a.equilibria.points();
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (a.spectra[k].stability != Stability::stable) continue;
    at.some = true;
    if (points[k].family == Family::balanced || points[k].on_balanced_set) at.balanced = true;
  }
  return at;
}

template <class S>
StabilityRanges sweep_ranges(const S& s) {
  std::vector<StableAt> flags;
  for (const auto& a : s.points) flags.push_back(stable_flags(a));
  return stability_ranges(s.values, flags);
}

// Union of intervals (from <= to), merged where they touch or overlap.
std::vector<Range> merged(std::vector<Range> v) {
  std::sort(v.begin(), v.end(), [](const Range& a, const Range& b) { return a.from < b.from; });
  std::vector<Range> out;
  for (const auto& r : v) {
    if (!out.empty() && r.from <= out.back().to) {
      if (r.to > out.back().to) {
        out.back().to = r.to, out.back().to_kind = r.to_kind, out.back().to_outside = r.to_outside;
      }
      continue;
    }
    out.push_back(r);
  }
  return out;
}

// The complement of sorted disjoint `stable` in [lo, hi]. A stable range's "grid" end
// lies between its value and its outer neighbour, which is the complement's first
// (last) value inside, with the stable value as its own outer neighbour.
std::vector<Range> complement(const std::vector<Range>& stable, double lo, double hi) {
  std::vector<Range> out;
  Range gap;
  gap.from = lo, gap.from_kind = "interval";
  for (const auto& r : stable) {
    if (r.from > gap.from || (r.from_kind == "grid" && r.from_outside)) {
      gap.to = r.from, gap.to_kind = r.from_kind, gap.to_outside = std::nullopt;
      if (r.from_kind == "grid" && r.from_outside) gap.to = *r.from_outside, gap.to_outside = r.from;
      if (gap.to > gap.from || (gap.to == gap.from && gap.from_kind == "grid")) out.push_back(gap);
    }
    gap = Range{};
    gap.from = r.to, gap.from_kind = r.to_kind;
    if (r.to_kind == "grid" && r.to_outside) gap.from = *r.to_outside, gap.from_outside = r.to;
  }
  if (gap.from < hi) {
    gap.to = hi, gap.to_kind = "interval";
    out.push_back(gap);
  }
  return out;
}

// Stable segments of one branch: consecutive stable points (of the family `balanced_only`
// asks for), their ends at a located special point between the bracketing points if there
// is one (model.md §13.7), else at the last stable point (a grid end).
void branch_segments(const Branch& b, bool balanced_only, double lo, double hi, std::vector<Range>& out) {
  const auto ok = [&](const BranchPoint& pt) {
    return pt.spectrum.stability == Stability::stable && (!balanced_only || pt.family == Family::balanced);
  };
  const auto located = [&](double a, double c) -> std::optional<double> {
    for (const auto& sp : b.specials) {
      const double x = double(sp.parameter);
      // Between the two points, or (a fold: the parameter turns back between them) the
      // special point bracketed by exactly these two points.
      const double f = double(sp.bracket_from), t = double(sp.bracket_to);
      const bool bracketed = (f == a && t == c) || (f == c && t == a);
      if (sp.converged && ((x >= std::min(a, c) && x <= std::max(a, c)) || bracketed) &&
          (sp.label == Label::HB || sp.label == Label::LP || sp.label == Label::BP))
        return x;
    }
    return std::nullopt;
  };
  const auto& pts = b.points;
  for (std::size_t i = 0; i < pts.size();) {
    if (!ok(pts[i])) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < pts.size() && ok(pts[j + 1])) ++j;
    struct End { double value; std::string kind; std::optional<double> outside; };
    const auto end_at = [&](std::size_t inside, bool first) -> End {
      const bool at_end = first ? inside == 0 : inside + 1 == pts.size();
      const double x = double(pts[inside].parameter);
      if (at_end) {
        const bool interval = x <= lo || x >= hi;
        return {x, interval ? "interval" : "branch_end", std::nullopt};
      }
      const double y = double(pts[first ? inside - 1 : inside + 1].parameter);
      if (const auto z = located(x, y)) return {*z, "located", std::nullopt};
      return {x, "grid", y};
    };
    const End a = end_at(i, true), c = end_at(j, false);
    Range r;
    if (a.value <= c.value) {
      r = {a.value, c.value, a.kind, c.kind, a.outside, c.outside};
    } else {
      r = {c.value, a.value, c.kind, a.kind, c.outside, a.outside};
    }
    out.push_back(r);
    i = j + 1;
  }
}
}  // namespace

std::vector<Range> grid_ranges(const std::vector<double>& values, const std::vector<bool>& flag) {
  return runs(values, flag);
}

StableAt stable_at(const Analysis& a) { return stable_flags(a); }
StableAt stable_at(const AnalysisN& a) { return stable_flags(a); }

StabilityRanges stability_ranges(const std::vector<double>& values, const std::vector<StableAt>& flags) {
  std::vector<bool> balanced(values.size()), none(values.size()), some(values.size());
  for (std::size_t i = 0; i < flags.size() && i < values.size(); ++i) {
    balanced[i] = flags[i].balanced;
    some[i] = flags[i].some;
    none[i] = !flags[i].some;
  }
  return {runs(values, balanced), runs(values, none), runs(values, some)};
}

StabilityRanges stability_ranges(const SweepResult& s) { return sweep_ranges(s); }
StabilityRanges stability_ranges(const SweepResultN& s) { return sweep_ranges(s); }

StabilityRanges stability_ranges(const ContinuationRun& run) {
  const double lo = std::min(run.from, run.to), hi = std::max(run.from, run.to);
  std::vector<Range> balanced, some;
  for (const auto& b : run.branches) {
    branch_segments(b, true, lo, hi, balanced);
    branch_segments(b, false, lo, hi, some);
  }
  StabilityRanges r;
  r.balanced_stable = merged(balanced);
  r.some_stable = merged(some);
  r.nothing_stable = complement(r.some_stable, lo, hi);
  return r;
}

namespace {
std::string range_text(const Range& r, std::string_view param, std::string_view param_unit, SpeedUnit unit,
                       double omega_n) {
  const auto end = [](double x, const std::string& kind, const std::optional<double>& outside) {
    std::string s = fmt::format("{:.9g}", x);
    if (kind == "grid" && outside) s += fmt::format(" (grid: next value {:.9g})", *outside);
    if (kind == "located") s += " (located)";
    return s;
  };
  std::string s = fmt::format("{} .. {} {}", end(r.from, r.from_kind, r.from_outside), end(r.to, r.to_kind, r.to_outside),
                              param_unit);
  if (param == "omega" && unit != SpeedUnit::rad_per_s)
    s += fmt::format(" = {:.6g} .. {:.6g} {}", from_rad_per_s(r.from, unit), from_rad_per_s(r.to, unit), to_string(unit));
  if (param == "omega" && omega_n > 0) s += fmt::format(" ({:.4g} .. {:.4g} omega_n)", r.from / omega_n, r.to / omega_n);
  return s;
}

// omega_n > 0 (an omega range): the ends also as multiples of omega_n.
std::string ranges_json(const std::vector<Range>& v, double omega_n = 0) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& r = v[i];
    s += fmt::format("{}{{\"from\": {}, \"to\": {}, \"from_end\": \"{}\", \"to_end\": \"{}\", \"from_outside\": {}, "
                     "\"to_outside\": {}}}",
                     i ? ", " : "", format_number(r.from, "range"), format_number(r.to, "range"), r.from_kind,
                     r.to_kind,
                     r.from_outside ? format_number(*r.from_outside, "range") : std::string("null"),
                     r.to_outside ? format_number(*r.to_outside, "range") : std::string("null"));
    if (omega_n > 0)
      s.insert(s.size() - 1, fmt::format(", \"from_over_omega_n\": {}, \"to_over_omega_n\": {}",
                                         format_number(r.from / omega_n, "ratio"),
                                         format_number(r.to / omega_n, "ratio")));
  }
  return s + "]";
}
}  // namespace

std::string ranges_text(const StabilityRanges& r, std::string_view param, std::string_view param_unit, SpeedUnit unit,
                        double omega_n) {
  std::string out;
  const auto list = [&](std::string_view what, const std::vector<Range>& v) {
    if (v.empty()) {
      out += fmt::format("{}: nowhere in the range\n", what);
      return;
    }
    for (const auto& x : v) out += fmt::format("{}: {} = {}\n", what, param, range_text(x, param, param_unit, unit, omega_n));
  };
  list("balanced state stable", r.balanced_stable);
  list("no stable state", r.nothing_stable);
  return out;
}

template <int N>
std::string summary_json(std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p,
                         std::string_view param, std::string_view param_unit, double from, double to,
                         const StabilityRanges& r, const std::vector<CriticalSpeed>& critical, SpeedUnit unit) {
  std::string out = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                                ABU_VERSION, json_string(command_line), json_string(scene_file));
  out += fmt::format("  \"parameters\": {},\n", parameters_json(p));
  out += fmt::format("  \"swept\": {{\"name\": {}, \"unit\": {}, \"from\": {}, \"to\": {}}},\n", json_string(param),
                     json_string(param_unit), format_number(from, "from"), format_number(to, "to"));
  out += fmt::format("  \"display_unit\": {},\n", json_string(to_string(unit)));
  out += fmt::format("  \"omega_n\": {},\n  \"capacity\": {},\n  \"unbalance\": {},\n  \"capacity_exceeded\": {},\n",
                     json_quantity(natural_frequency(p), "rad/s", "omega_n"),
                     json_quantity(ball_capacity_of(p), "kg m", "capacity"),
                     json_quantity(p.rotor.unbalance, "kg m", "U"), p.rotor.unbalance > ball_capacity_of(p));
  out += fmt::format("  \"ranges_note\": {},\n",
                     json_string("ranges of the swept parameter, in its unit; an end is 'located' (a special point of "
                                 "the continuation), 'grid' (the true end lies between the value and *_outside), "
                                 "'interval' (the end of the computed interval) or 'branch_end' (a branch stopped)"));
  out += fmt::format("  \"balanced_stable\": {},\n  \"nothing_stable\": {},\n  \"some_stable\": {},\n",
                     ranges_json(r.balanced_stable, param == "omega" ? natural_frequency(p) : 0),
                     ranges_json(r.nothing_stable, param == "omega" ? natural_frequency(p) : 0),
                     ranges_json(r.some_stable, param == "omega" ? natural_frequency(p) : 0));
  out += "  \"critical_speeds\": [";
  for (std::size_t i = 0; i < critical.size(); ++i) {
    const auto& c = critical[i];
    out += fmt::format("{}{{\"equilibrium\": {}, \"omega\": {}, \"speed\": {}, \"omega_over_omega_n\": {}, "
                       "\"bracket\": [{}, {}], \"damping_ratio\": {}}}",
                       i ? ",\n    " : "\n    ", json_string(c.series), json_quantity(c.omega, "rad/s", "omega"),
                       json_quantity(from_rad_per_s(c.omega, unit), to_string(unit), "speed"),
                       format_number(c.omega / c.omega_n, "ratio"), format_number(c.bracket_from, "bracket"),
                       format_number(c.bracket_to, "bracket"),
                       format_number(c.damping_ratio, "zeta"));
  }
  out += critical.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}
template <int N>
MapRangesOutput map_ranges(const MapVerdicts& v, std::string_view x, std::string_view y,
                           std::string_view command_line, std::string_view scene_file, const ParamsT<double, N>& p,
                           SpeedUnit unit, int max_lines) {
  MapRangesOutput result;
  if ((x != "omega" && y != "omega") || v.cells.empty() || v.cells.size() != v.x.size() * v.y.size()) return result;
  const std::string_view other = x == "omega" ? y : x;
  const bool omega_is_x = x == "omega";
  const std::vector<double>& omegas = omega_is_x ? v.x : v.y;
  const std::vector<double>& others = omega_is_x ? v.y : v.x;
  // omega ascending, whichever way the axis runs
  std::vector<std::size_t> order(omegas.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return omegas[a] < omegas[b]; });
  std::vector<double> omega(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) omega[k] = omegas[order[k]];
  std::vector<bool> balanced(order.size()), none(order.size());
  std::string json_rows;
  int lines = 0;
  for (std::size_t r = 0; r < others.size(); ++r) {
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t cell = omega_is_x ? order[k] * v.y.size() + r : r * v.y.size() + order[k];
      balanced[k] = (v.cells[cell] & MapVerdicts::balanced_stable) != 0;
      none[k] = (v.cells[cell] & MapVerdicts::some_stable) == 0;
    }
    StabilityRanges ranges;
    ranges.balanced_stable = runs(omega, balanced);
    ranges.nothing_stable = runs(omega, none);
    json_rows += fmt::format("{}{{{}: {}, \"balanced_stable\": {}, \"nothing_stable\": {}}}", r ? ",\n    " : "\n    ",
                             json_string(other), format_number(others[r], "axis"),
                             ranges_json(ranges.balanced_stable, natural_frequency(p)),
                             ranges_json(ranges.nothing_stable, natural_frequency(p)));
    if (lines < max_lines) {
      result.text += fmt::format("at {} = {:.6g}:\n", other, others[r]);
      const std::string block = ranges_text(ranges, "omega", "rad/s", unit, natural_frequency(p));
      for (std::size_t b = 0; b < block.size();) {
        const auto e = block.find('\n', b);
        result.text += "  " + block.substr(b, e - b + 1);
        b = e == std::string::npos ? block.size() : e + 1;
      }
      ++lines;
    }
  }
  if (int(others.size()) > max_lines)
    result.text += fmt::format("... {} more values of {} in the summary JSON\n", int(others.size()) - max_lines, other);
  result.json = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                            ABU_VERSION, json_string(command_line), json_string(scene_file));
  result.json += fmt::format("  \"parameters\": {},\n  \"omega_n\": {},\n  \"capacity\": {},\n  \"unbalance\": {},\n",
                             parameters_json(p), json_quantity(natural_frequency(p), "rad/s", "omega_n"),
                             json_quantity(ball_capacity_of(p), "kg m", "capacity"),
                             json_quantity(p.rotor.unbalance, "kg m", "U"));
  result.json += fmt::format("  \"speed_axis\": \"omega\",\n  \"speed_unit\": \"rad/s\",\n  \"other_axis\": {},\n", json_string(other));
  result.json += fmt::format("  \"ranges_note\": {},\n  \"rows\": [{}\n  ]\n}}\n",
                             json_string("per value of the other axis, the omega ranges on the map's grid where a "
                                         "balanced state is stable and where nothing is; an end is 'grid' (the true "
                                         "end lies between the value and *_outside) or 'interval'"),
                             json_rows);
  return result;
}
template MapRangesOutput map_ranges<2>(const MapVerdicts&, std::string_view, std::string_view, std::string_view,
                                       std::string_view, const Params&, SpeedUnit, int);
template MapRangesOutput map_ranges<any_balls>(const MapVerdicts&, std::string_view, std::string_view,
                                               std::string_view, std::string_view, const ParamsN&, SpeedUnit, int);

template std::string summary_json<2>(std::string_view, std::string_view, const Params&, std::string_view,
                                     std::string_view, double, double, const StabilityRanges&,
                                     const std::vector<CriticalSpeed>&, SpeedUnit);
template std::string summary_json<any_balls>(std::string_view, std::string_view, const ParamsN&, std::string_view,
                                             std::string_view, double, double, const StabilityRanges&,
                                             const std::vector<CriticalSpeed>&, SpeedUnit);

}  // namespace abu
