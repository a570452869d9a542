// The sweep of an unround race on an anisotropic support (docs/model.md §20.6) in its two
// limits, each against the sweep of the single part at the same values:
//  * a race round to rounding (amplitudes 1e-30, which take the unround race's formulas): its
//    orbits at the balanced states are those states (q = 0), whose multipliers the anisotropic
//    support's sweep (floquet_sweep, Hill's method cross-checked by Magnus) gives;
//  * an isotropic support in the anisotropic form: every orbit is an equilibrium of the race,
//    its multipliers' moduli exp(Re lambda pi/omega) of the unround race's eigenvalues (§11.5).
// And the tracks: an orbit followed by Newton from the previous value (forced_orbit_near) is
// the one `equilibria` finds there by the continuation in delta. Last, the map's cells (§20.7).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "abu/analysis/composed_map.hpp"
#include "abu/analysis/composed_sweep.hpp"
#include "abu/analysis/floquet_sweep.hpp"
#include "abu/equilibria/unround_equilibria.hpp"

#include "composed_params.hpp"

using namespace abu;

namespace {

// tests/scenes/composed/oval_anisotropic.toml at its mean support (k_bar = 10500, c_bar = 3.25).
ParamsN composed_sweep_params() { return test::composed_mean_params(); }

RaceShape composed_sweep_race(double amplitude_factor) {
  const RaceHarmonics h{{2, 3e-5 * amplitude_factor, 0.4}, {1, 1e-5 * amplitude_factor, 1.1}};
  return RaceShape{{h, h}};
}

ComposedAt composed_omega_at(const ParamsN& base, const RaceShape& race) {
  return [base, race](double w) {
    ParamsN p = base;
    p.omega = w;
    return ComposedMachineAt{p, race};
  };
}

std::vector<std::complex<double>> composed_by_modulus(std::vector<std::complex<double>> v) {
  std::sort(v.begin(), v.end(), [](auto a, auto b) {
    return std::abs(a) != std::abs(b) ? std::abs(a) > std::abs(b) : std::arg(a) > std::arg(b);
  });
  return v;
}

bool composed_same_angles(const std::vector<double>& state0, const EquilibriumN& e) {
  for (int i = 0; i < 2; ++i)
    if (std::abs(std::remainder(state0[std::size_t(2 + i)] - double(e.position(2 + i)), 2 * std::numbers::pi)) > 1e-6)
      return false;
  return true;
}

}  // namespace

TEST_CASE("composed sweep: a race round to rounding gives the anisotropic support's sweep", "[composed_sweep]") {
  // Both multiplier sets are accurate to ~1e-10 (Hill/Magnus cross-checked to 1e-6 relative
  // at worst, typically 1e-11; the orbit's discretization target 1e-10): they agree to 1e-7 of
  // max(|rho|, 1e-6), the acceptance's figure.
  const ParamsN p = composed_sweep_params();
  const AnisotropicSupport support{12000.0, 9000.0, -800.0, 4.0, 2.5, 0.6};
  const std::vector<double> values{900.0, 1100.0, 1300.0};
  const ComposedSweep composed = composed_sweep(support, composed_omega_at(p, composed_sweep_race(1e-30 / 3e-5)), values);
  const FloquetSweep alone = floquet_sweep(p, support, *parse_param("omega", 2), values, {});
  INFO(composed.status.reason);
  REQUIRE(composed.status.ok());
  int compared = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    REQUIRE(alone.points[i].balanced.size() == 2);  // the mirror pair of two unequal balls (model.md §5)
    for (std::size_t k = 0; k < alone.points[i].balanced.size(); ++k) {
      const EquilibriumN& e = alone.points[i].balanced[k];
      const auto row = std::find_if(composed.points[i].rows.begin(), composed.points[i].rows.end(),
                                    [&](const ComposedOrbitRow& r) { return composed_same_angles(r.orbit.state0, e); });
      REQUIRE(row != composed.points[i].rows.end());
      CHECK(row->orbit.q_abs_max <= 1e-20);  // the balanced state: q = 0 (to the race's 1e-30)
      const auto a = composed_by_modulus(alone.points[i].floquet[k].multipliers), b = composed_by_modulus(row->orbit.multipliers);
      REQUIRE(a.size() == b.size());
      for (std::size_t m = 0; m < a.size(); ++m) CHECK(std::abs(a[m] - b[m]) <= 1e-7 * std::max(std::abs(a[m]), 1e-6));
      ++compared;
    }
  }
  CHECK(compared == 6);
}

TEST_CASE("composed sweep: an isotropic support in the anisotropic form gives the unround race's sweep",
          "[composed_sweep]") {
  // Each orbit is its equilibrium (no forcing): the moduli of its multipliers over pi/omega are
  // exp(Re lambda pi/omega) of the equilibrium's refined eigenvalues, to 1e-7 relative (the
  // acceptance's figure; the shooting's own error is ~1e-10).
  const ParamsN p = composed_sweep_params();
  const AnisotropicSupport isotropic{10500.0, 10500.0, 0.0, 3.25, 3.25, 0.0};
  const RaceShape race = composed_sweep_race(1.0);
  const std::vector<double> values{900.0, 1100.0, 1300.0};
  const ComposedSweep s = composed_sweep(isotropic, composed_omega_at(p, race), values);
  INFO(s.status.reason);
  REQUIRE(s.status.ok());
  for (std::size_t i = 0; i < values.size(); ++i) {
    ParamsN pv = p;
    pv.omega = values[i];
    const UnroundResult found = find_unround_equilibria(pv, race);
    REQUIRE(int(found.list.size()) == s.points[i].equilibria);
    REQUIRE(s.points[i].rows.size() == found.list.size());  // none lost
    const double period = std::numbers::pi / values[i];
    for (const ComposedOrbitRow& row : s.points[i].rows) {
      REQUIRE(row.equilibrium >= 1);
      const SpectrumN& spectrum = found.list[std::size_t(row.equilibrium - 1)].spectrum;
      std::vector<double> want, got;
      for (int k = 0; k < spectrum.count; ++k) want.push_back(std::exp(spectrum.eigenvalues[std::size_t(k)].real() * period));
      for (const auto& r : row.orbit.multipliers) got.push_back(std::abs(r));
      std::sort(want.rbegin(), want.rend());
      std::sort(got.rbegin(), got.rend());
      REQUIRE(want.size() == got.size());
      for (std::size_t k = 0; k < want.size(); ++k) CHECK(std::abs(got[k] - want[k]) <= 1e-7 * want[k]);
    }
  }
}

TEST_CASE("composed sweep: an orbit followed from the previous value is the one continued in delta there",
          "[composed_sweep]") {
  // Newton from the neighbouring value's orbit and the continuation in delta from this value's
  // equilibrium are two routes to one orbit: x(0) agrees to the shooting's accuracy (Newton to
  // 1e-13 scaled, both refined to the 1e-10 target), far inside the match tolerance 1e-6, and the
  // largest multiplier to 1e-9 relative.
  const ParamsN p = composed_sweep_params();
  const AnisotropicSupport support{12000.0, 9000.0, -800.0, 4.0, 2.5, 0.6};
  const RaceShape race = composed_sweep_race(1.0);
  const ComposedSweep s = composed_sweep(support, composed_omega_at(p, race), {1000.0, 1100.0});
  REQUIRE(s.status.ok());
  REQUIRE(s.points[0].rows.size() == 8);
  CHECK(s.tracks == 8);  // every orbit at 1000 continues to one at 1100, none lost, none new
  for (const ComposedOrbitRow& row : s.points[1].rows) {
    CHECK_FALSE(row.lost);
    const auto before = std::find_if(s.points[0].rows.begin(), s.points[0].rows.end(),
                                     [&](const ComposedOrbitRow& r) { return r.track == row.track; });
    REQUIRE(before != s.points[0].rows.end());
    ParamsN p1 = p;
    p1.omega = 1100.0;
    const ForcedOrbit near = forced_orbit_near(p1, RigidMachine{&race, &support}, before->orbit, "near");
    INFO(near.reason);
    REQUIRE(near.status.ok());
    for (std::size_t k = 0; k < near.state0.size(); ++k) {
      const double scale = k < 2 ? 1e-6 : k < 4 ? 1.0 : k < 6 ? 1e-6 * 1100.0 : 1100.0;
      double diff = near.state0[k] - row.orbit.state0[k];
      if (k == 2 || k == 3) diff = std::remainder(diff, 2 * std::numbers::pi);  // ball angles
      CHECK(std::abs(diff) <= 1e-8 * scale);
    }
    CHECK(std::abs(near.multipliers.front()) == Approx(std::abs(row.orbit.multipliers.front())).epsilon(1e-9));
  }
}

// The map's cells (docs/model.md §20.7): a cell's counts by verdict, its failed orbits and its
// design figure from a fabricated list (what composed_cell decides), then a tile of two cells
// against the orbits composed_orbits_at gives at those points. cli/composed_map checks the whole
// command against `equilibria`; this runs the tile's code under the sanitizers at CI's cost.
TEST_CASE("composed map: a cell counts its orbits by verdict and keeps the least peak |q| of the stable ones",
          "[composed_map]") {
  ComposedSweepPoint point;
  point.equilibria = 5;
  const auto orbit = [](Stability verdict, double q_abs_max, bool converged) {
    ForcedOrbit o;
    o.verdict = verdict;
    o.q_abs_max = q_abs_max;
    o.multipliers = {{0.5, 0.0}};
    if (!converged) o.status.outcome = Outcome::not_converged;
    return ComposedOrbitRow{0, 1, false, o};
  };
  point.rows = {orbit(Stability::stable, 2e-6, true), orbit(Stability::unstable, 1e-7, true),
                orbit(Stability::stable, 1.5e-6, true), orbit(Stability::marginal, 1e-8, true),
                orbit(Stability::stable, 1e-9, false)};  // not converged: no verdict, not the best
  const ComposedCell c = composed_cell(point);
  CHECK(c.equilibria == 5);
  CHECK(c.orbits == 4);
  CHECK(c.stable == 2);
  CHECK(c.unstable == 1);
  CHECK(c.marginal == 1);
  CHECK(c.failed == 1);
  REQUIRE(c.best_q_abs.has_value());
  CHECK(*c.best_q_abs == 1.5e-6);  // exact: a copy of the stable orbit's value
  CHECK(c.complete);
  point.search_doubt = "a leaf without an equilibrium";
  point.rows = {orbit(Stability::unstable, 1e-7, true)};
  const ComposedCell none = composed_cell(point);
  CHECK_FALSE(none.best_q_abs.has_value());
  CHECK_FALSE(none.complete);
}

TEST_CASE("composed map: a tile's rows are its cells' orbits at their points", "[composed_map]") {
  const ParamsN base = composed_sweep_params();
  const RaceShape race = composed_sweep_race(1.0);
  ComposedMapJob job{"omega", "U", "rad/s", "kg m", {}, {}, {}, {}, {}, {}};
  job.xs = {1100.0};
  job.ys = {4e-7, 8e-7};
  job.support = AnisotropicSupport{12000.0, 9000.0, -800.0, 4.0, 2.5, 0.6};
  job.cell_input = [&](int ix, int iy) {
    ParamsN p = base;
    p.omega = job.xs[std::size_t(ix)];
    p.rotor.unbalance = job.ys[std::size_t(iy)];
    return ComposedMachineAt{p, race};
  };
  const TileText tile = compute_composed_map_tile(job, 0);
  CHECK(tile.cells == 2);
  std::string expected;
  long orbits = 0;
  for (int iy = 0; iy < 2; ++iy) {
    const ComposedSweepPoint point = composed_orbits_at(job.support, job.cell_input(0, iy), 1100.0);
    int stable = 0, unstable = 0, marginal = 0, failed = 0;
    std::optional<double> best;
    for (const auto& row : point.rows) {
      if (!row.orbit.status.ok()) {
        ++failed;
        continue;
      }
      stable += row.orbit.stable(), unstable += row.orbit.verdict == Stability::unstable,
          marginal += row.orbit.verdict == Stability::marginal;
      if (row.orbit.stable() && (!best || row.orbit.q_abs_max < *best)) best = row.orbit.q_abs_max;
    }
    REQUIRE(best.has_value());  // the scene has stable orbits at 1100 rad/s: the figure is checked
    orbits += long(point.rows.size());
    expected += fmt::format("1100,{},{},{},{},{},{},{},{},{}\n", job.ys[std::size_t(iy)], point.equilibria,
                            int(point.rows.size()) - failed, stable, unstable, marginal, failed, *best,
                            point.search_doubt.empty() ? 1 : 0);
  }
  CHECK(tile.summary == expected);
  CHECK(tile.equilibria == orbits);
  // The manifest ties the tiles to the axes' values.
  CHECK(composed_map_manifest(job).find("\ny 8e-07\n") != std::string::npos);
}
