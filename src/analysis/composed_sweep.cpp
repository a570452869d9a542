// The sweep of an unround race on an anisotropic support (composed_sweep.hpp, docs/model.md §20.6).
#include "abu/analysis/composed_sweep.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "abu/analysis/floquet_states.hpp"
#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/equilibria/unround_equilibria.hpp"
#include "abu/model/model.hpp"

namespace abu {

namespace {

// ln max|rho| and the largest multiplier of a converged orbit (log_moduli: exact also where
// |rho| underflows).
GrowthSample composed_growth(const ForcedOrbit& o) { return {o.log_moduli.front(), o.multipliers.front()}; }


// The orbit `from` (at value a) continued to value b by Newton (forced_orbit_near); where
// Newton fails over the whole step, in 2, 4, ... 16 equal sub-steps (natural-parameter
// continuation: a long grid step near a resonance, where the orbits move fast).
ForcedOrbit composed_orbit_continued(const ForcedOrbit& from, double a, double b, const AnisotropicSupport& support,
                            const ComposedAt& at, const ComposedSweepOptions& o) {
  ForcedOrbit last;
  for (int parts = 1; parts <= 16; parts *= 2) {
    last = from;
    for (int k = 1; k <= parts; ++k) {
      const ComposedMachineAt m = at(k == parts ? b : a + (b - a) * k / parts);
      last = forced_orbit_near(m.params, RigidMachine{&m.race, &support}, last, from.kind, o.orbit);
      if (!composed_orbit_usable(last)) break;
    }
    if (composed_orbit_usable(last)) return last;
  }
  return last;
}

// Gives this point's orbits the tracks of the previous point's: each previous orbit continued
// to this value (composed_orbit_continued) and matched to this value's orbit at the same x(0); a
// previous orbit that does not continue, or continues to none of them, is a lost row. The
// orbits left unmatched start new tracks.
void follow_composed_tracks(const ComposedSweepPoint& previous, ComposedSweepPoint& point, const AnisotropicSupport& support,
                   const ComposedAt& at, const ComposedSweepOptions& o, int& tracks) {
  const ParamsN params = at(point.value).params;
  std::vector<ComposedOrbitRow> lost;
  for (const ComposedOrbitRow& before : previous.rows) {
    if (before.lost || before.track == 0) continue;
    throw_if_stopped("sweep: composed orbits");
    const ForcedOrbit next = composed_orbit_continued(before.orbit, previous.value, point.value, support, at, o);
    ComposedOrbitRow* match = nullptr;
    if (composed_orbit_usable(next))
      for (ComposedOrbitRow& row : point.rows)
        if (row.track == 0 && composed_orbit_usable(row.orbit) &&
            composed_orbit_distance(params, next.state0, row.orbit.state0) <= o.match_tolerance)
          match = &row;
    if (match) {
      match->track = before.track;
      continue;
    }
    ComposedOrbitRow row{before.track, 0, true, {}};
    row.orbit.kind = before.orbit.kind;
    row.orbit.period = next.period;
    const std::string why =
        composed_orbit_usable(next) ? fmt::format("it continues (Newton from the orbit at {}) to an orbit that none of this value's "
                                   "equilibria continues to in delta",
                                   previous.value)
                     : fmt::format("Newton from the orbit at {} fails here, also in 16 sub-steps ({}): no orbit "
                                   "continues it (a fold of the orbit family between the two values)",
                                   previous.value, next.reason);
    row.orbit.status.merge(Outcome::not_converged, "see reason");
    row.orbit.reason = fmt::format("track {} ({} at {}) lost between {} and {}: {}", before.track, before.orbit.kind,
                                   previous.value, previous.value, point.value, why);
    lost.push_back(std::move(row));
  }
  for (ComposedOrbitRow& row : point.rows)
    if (row.track == 0 && composed_orbit_usable(row.orbit)) row.track = ++tracks;
  for (ComposedOrbitRow& row : lost) point.rows.push_back(std::move(row));
}

const ComposedOrbitRow* find_composed_track(const ComposedSweepPoint& point, int track) {
  for (const ComposedOrbitRow& row : point.rows)
    if (!row.lost && row.track == track) return &row;
  return nullptr;
}

// The crossings of |rho| = 1 between neighbouring values, each track by bisection with the
// orbit at a bisection point continued by Newton from the last one computed (the bracket
// shrinks around it).
void locate_composed_crossings(ComposedSweep& s, const AnisotropicSupport& support, const ComposedAt& at,
                               const ComposedSweepOptions& o) {
  for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
    for (const ComposedOrbitRow& row : s.points[i].rows) {
      if (row.lost || row.track == 0 || !composed_orbit_usable(row.orbit)) continue;
      const ComposedOrbitRow* next = find_composed_track(s.points[i + 1], row.track);
      if (!next || !composed_orbit_usable(next->orbit)) continue;
      const GrowthSample a = composed_growth(row.orbit), b = composed_growth(next->orbit);
      if (!((a.growth < 0.0 && b.growth > 0.0) || (a.growth > 0.0 && b.growth < 0.0))) continue;
      ForcedOrbit guess = row.orbit;
      std::string failure;
      const GrowthAt growth_at = [&](double value) -> std::optional<GrowthSample> {
        throw_if_stopped("sweep: composed crossing");
        const ComposedMachineAt m = at(value);
        ForcedOrbit orbit = forced_orbit_near(m.params, RigidMachine{&m.race, &support}, guess, guess.kind, o.orbit);
        if (!composed_orbit_usable(orbit)) {
          failure = orbit.reason;
          return std::nullopt;
        }
        guess = std::move(orbit);
        return composed_growth(guess);
      };
      double lost_at = 0.0;
      std::optional<FloquetCrossing> c =
          bisect_unit_circle(s.values[i], s.values[i + 1], a, b, growth_at, o.crossing, &lost_at);
      if (c) {
        c->member = row.track;
        s.crossings.push_back(*c);
        continue;
      }
      const std::string why = fmt::format("track {}: ln max|rho| changes sign between {} and {}, but the orbit was "
                                          "lost at {} in the bisection: {}",
                                          row.track, s.values[i], s.values[i + 1], lost_at, failure);
      s.status.merge(Outcome::not_converged, why);
      s.unlocated.push_back({row.track, s.values[i], s.values[i + 1], lost_at, why});
    }
  }
}

}  // namespace

double composed_orbit_distance(const ParamsN& p, const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.empty()) return std::numeric_limits<double>::infinity();
  const int n = p.n_balls();
  const double L = displacement_scale(p), w = p.omega;
  double worst = 0.0;
  for (int i = 0; i < 2 * n + 4; ++i) {
    double diff = a[std::size_t(i)] - b[std::size_t(i)];
    if (i >= 2 && i < n + 2) diff = std::remainder(diff, 2.0 * std::numbers::pi);
    const double scale = i < 2 ? L : i < n + 2 ? 1.0 : i < n + 4 ? L * w : w;
    worst = std::max(worst, std::abs(diff) / scale);
  }
  return worst;
}

bool composed_orbit_usable(const ForcedOrbit& o) { return o.status.ok() && !o.multipliers.empty(); }

ComposedSweepPoint composed_orbits_at(const AnisotropicSupport& support, const ComposedMachineAt& m, double value,
                                      const ForcedOrbitOptions& o) {
  ComposedSweepPoint point;
  point.value = value;
  const UnroundResult mean = find_unround_equilibria(m.params, m.race);
  for (const auto& e : mean.list)
    if (!(e.residual <= 1e-8))
      throw NumericalError(fmt::format("value {}: an equilibrium of the unround race has residual {:.3g}: it is not an "
                                       "equilibrium",
                                       value, e.residual));
  point.equilibria = int(mean.list.size());
  point.search_doubt = mean.doubt;
  ForcedOrbitAnalysis a = analyze_unround_orbits(m.params, support, m.race, mean, o);
  for (std::size_t k = 0; k < a.orbits.size(); ++k) point.rows.push_back({0, int(k) + 1, false, std::move(a.orbits[k])});
  return point;
}

ComposedSweep composed_sweep(const AnisotropicSupport& support, const ComposedAt& at, const std::vector<double>& values,
                             const ComposedSweepOptions& o) {
  ComposedSweep s;
  s.values = values;
  for (std::size_t i = 0; i < values.size(); ++i) {
    throw_if_stopped("sweep: composed orbits");
    const ComposedMachineAt m = at(values[i]);
    ComposedSweepPoint point = composed_orbits_at(support, m, values[i], o.orbit);
    if (i == 0) {
      for (ComposedOrbitRow& row : point.rows)
        if (composed_orbit_usable(row.orbit)) row.track = ++s.tracks;
    } else {
      follow_composed_tracks(s.points.back(), point, support, at, o, s.tracks);
    }
    for (const ComposedOrbitRow& row : point.rows)
      if (!row.orbit.status.ok())
        s.status.merge(row.orbit.status.outcome,
                       fmt::format("at {}: {}: {}", values[i], row.orbit.kind, row.orbit.reason));
    s.points.push_back(std::move(point));
  }
  locate_composed_crossings(s, support, at, o);
  return s;
}

}  // namespace abu
