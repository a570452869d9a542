// The periodic states of an unround race on an anisotropic support (docs/model.md §20.4) in
// their two limits, each against the code of the single part (the acceptance's reductions):
//  * a race round to rounding (amplitudes 1e-30, which take the unround race's formulas) gives
//    the anisotropic support's orbits of model.md §10.14, continued from the same aligned
//    equilibrium by the round-race code: the same multipliers;
//  * an isotropic support written in the anisotropic form gives the unround race's equilibria
//    as constant orbits, whose multipliers over pi/omega are exp(lambda pi/omega) of their
//    eigenvalues (model.md §11.5, refined spectra).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "abu/analysis/floquet_states.hpp"
#include "abu/dynamics/forced_orbits.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/unround_spectrum.hpp"

#include "composed_params.hpp"

using namespace abu;

namespace {

// The viscous two-ball scene of tests/scenes/anisotropic/ref_viscous.toml at its mean support.
ParamsN unequal_balls() { return test::composed_mean_params(); }

// Multipliers sorted by modulus, then argument: the two lists pair up in order.
std::vector<std::complex<double>> sorted(std::vector<std::complex<double>> v) {
  std::sort(v.begin(), v.end(), [](auto a, auto b) {
    return std::abs(a) != std::abs(b) ? std::abs(a) > std::abs(b) : std::arg(a) > std::arg(b);
  });
  return v;
}

}  // namespace

TEST_CASE("composed orbits: a race round to rounding gives the anisotropic support's orbits", "[composed]") {
  // Both orbits are converged to the multipliers' discretization target 1e-10 (§10.18) by two
  // codes of one field (machine_field on circles and on the 1e-30 race): they agree to 1e-7
  // of max(|rho|, 1e-6), the acceptance's figure, with a wide margin.
  const ParamsN p = unequal_balls();
  const AnisotropicSupport s{12000.0, 9000.0, -800.0, 4.0, 2.5, 0.6};
  const EquilibriumSetN mean = find_equilibria(p);
  RaceShape nearly_round;
  for (int i = 0; i < 2; ++i) nearly_round.balls.push_back({{2, 1e-30, 0.4}, {1, 1e-30, 1.1}});
  int compared = 0;
  for (const EquilibriumN& e : mean.points()) {
    if (e.family == Family::balanced) continue;
    const ForcedOrbit alone = forced_orbit(p, s, e, {});
    const ForcedOrbit composed =
        forced_orbit(p, RigidMachine{&nearly_round, &s}, at_rest<double, any_balls>(e.position_si()), "composed", {});
    INFO(alone.kind << ": " << alone.reason << composed.reason);
    REQUIRE(alone.status.ok());
    REQUIRE(composed.status.ok());
    const auto a = sorted(alone.multipliers), b = sorted(composed.multipliers);
    REQUIRE(a.size() == b.size());
    for (std::size_t k = 0; k < a.size(); ++k) CHECK(std::abs(a[k] - b[k]) <= 1e-7 * std::max(std::abs(a[k]), 1e-6));
    CHECK(std::abs(alone.q_abs_max - composed.q_abs_max) <= 1e-9 * alone.q_abs_max);
    ++compared;
  }
  CHECK(compared == 4);  // the four aligned states of two unequal balls (model.md §5)
}

TEST_CASE("composed orbits: an isotropic support in the anisotropic form gives the unround race's spectra",
          "[composed]") {
  // The orbits are the equilibria themselves (no forcing); their multipliers over pi/omega
  // must be exp(lambda pi/omega) of the equilibria's refined eigenvalues: moduli to 1e-7
  // relative (the acceptance's figure; the shooting's own error is ~1e-10).
  ParamsN p = unequal_balls();
  const AnisotropicSupport isotropic{10500.0, 10500.0, 0.0, 3.25, 3.25, 0.0};
  const RaceShape race{{{{2, 3e-5, 0.4}, {1, 1e-5, 1.1}}, {{2, 3e-5, 0.4}, {1, 1e-5, 1.1}}}};
  const UnroundResult found = find_unround_equilibria(p, race);
  REQUIRE(found.list.size() >= 4);
  const ForcedOrbitAnalysis orbits = analyze_unround_orbits(p, isotropic, race, found);
  REQUIRE(orbits.orbits.size() == found.list.size());
  const double period = std::numbers::pi / p.omega;
  for (std::size_t k = 0; k < found.list.size(); ++k) {
    const ForcedOrbit& o = orbits.orbits[k];
    INFO(o.kind << ": " << o.reason);
    REQUIRE(o.status.ok());
    std::vector<double> want, got;
    const SpectrumN& spectrum = found.list[k].spectrum;
    for (int i = 0; i < spectrum.count; ++i) want.push_back(std::exp(spectrum.eigenvalues[std::size_t(i)].real() * period));
    for (const auto& r : o.multipliers) got.push_back(std::abs(r));
    std::sort(want.rbegin(), want.rend());
    std::sort(got.rbegin(), got.rend());
    REQUIRE(want.size() == got.size());
    for (std::size_t i = 0; i < want.size(); ++i) CHECK(std::abs(got[i] - want[i]) <= 1e-7 * want[i]);
    CHECK(o.q_abs_max == Approx(found.list[k].amplitude).epsilon(1e-9));
  }
}
