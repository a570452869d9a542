// Continuation runs as a whole (continuation.hpp): a run that cannot finish says why and keeps
// the parameters physical, and the eigenvalues tracked along a branch are its spectrum, never
// swapped with their conjugates (regressions included). References: continuation_reference.hpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "abu/continuation/continuation.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/params.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/scan/scan.hpp"
#include "continuation_reference.hpp"

using namespace continuation_reference;

// ---------------------------------------------------------------------------------------
// Failure is explicit.
TEST_CASE("a continuation that cannot finish says why and parameters stay physical", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  const double wn = omega_n(p);
  {
    p.omega = 0.2 * wn;
    abu::ContinuationOptions o;
    o.max_steps = 3;
    REQUIRE_FALSE(abu::options_violation(o).has_value());
    const abu::ContinuationRun run = abu::continue_branches(p, param("omega"), 8 * wn, o);
    REQUIRE(!run.branches.empty());
    for (const auto& b : run.branches) {
      // Every start is at an end of the interval: the branch runs one way, and stops short.
      CHECK(b.stop[1] == abu::StopReason::max_steps);
      CHECK(!b.stop_detail[1].empty());
      CHECK(b.points.size() <= 4);  // the start and at most 3 steps
      for (const auto& pt : b.points) CHECK(finite(pt));
    }
  }
  {
    // m from its default down to a tiny positive value: every point keeps m > 0.
    p = base_params();
    const double to = 1e-8;
    const abu::ContinuationRun run = abu::continue_branches(p, param("m"), to, {});
    REQUIRE(!run.branches.empty());
    bool reaches_end = false;
    for (const auto& b : run.branches) {
      for (const auto& pt : b.points) {
        CHECK(finite(pt));
        CHECK(pt.parameter > 0);
        CHECK(pt.parameter >= ld(to) * (1 - 1e-15L));
        CHECK(pt.parameter <= ld(p.balls[0].mass) * (1 + 1e-15L));
        reaches_end = reaches_end || (pt.label == Label::EP && relative(pt.parameter, ld(to)) <= 1e-15L);
      }
      for (std::size_t end = 0; end < 2; ++end)
        if (b.stop[end] != abu::StopReason::end_of_range) CHECK(!b.stop_detail[end].empty());
    }
    CHECK(reaches_end);  // the together and opposite families exist down to m -> 0
  }
}

// Regression tests for three defects found while writing these tests (now fixed):
//  a) the range check came before the end-of-interval check in the step loop: a step
//     that overshot the end value m = 1e-8 into m < 0 stopped the branch with
//     invalid_parameter instead of landing on the end value;
//  b) at the pitchfork m = U / (2 l) the balanced branch's branch-point locator could
//     wander off (its corrector was not confined to the bracket) and report m = 0;
//  c) an end value outside the physical range was not refused by the library.
TEST_CASE("continuing m towards a tiny positive value ends at that value", "[continuation]") {
  quiet_gsl();
  const abu::Params p = base_params();
  SECTION("to m = 1e-8") {
    const double to = 1e-8;
    const abu::ContinuationRun run = abu::continue_branches(p, param("m"), to, {});
    for (const auto& b : run.branches) {
      INFO(to_string(b.family) << " " << b.member << ": " << b.stop_detail[0] << " | " << b.stop_detail[1]);
      // The interval [1e-8, 3.3e-5] is physical throughout: no end may stop on the range rule.
      for (std::size_t end = 0; end < 2; ++end) CHECK(b.stop[end] != abu::StopReason::invalid_parameter);
      for (const auto& sp : b.specials) {
        INFO(to_string(sp.label) << " at m = " << double(sp.parameter) << ": " << sp.note);
        CHECK(sp.parameter >= ld(to));
        CHECK(sp.parameter <= ld(p.balls[0].mass));
      }
    }
  }
  SECTION("to m = -1e-5 is refused") {
    CHECK_THROWS_AS(abu::continue_branches(p, param("m"), -1e-5, {}), abu::InputError);
  }
}

// ---------------------------------------------------------------------------------------
// Eigenvalue tracking: nothing lost, no jumps between conjugates.
//
// A mode's imaginary part may change sign between two grid points without either being
// near the real axis: the balanced branch in omega has few points (its equilibria do not
// move) and its rotor mode -zeta omega_n + i (omega_d - omega) (model.md §7) passes
// through Im = 0 at omega_d between omega = 186 and 342. What must not happen is a swap
// with the conjugate. The eigenvectors tell them apart: conjugation flips the whirl
// (q ~ (1, +-i)), so a mode that kept its identity has an eigenvector (q in the
// displacement scale, unit norm) close to its previous one (overlap >= 0.9) and far from
// that one's conjugate (<= 0.5); a swap gives the reverse.
TEST_CASE("tracked modes are the spectrum and never swap with their conjugates", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  const double wn = omega_n(p);
  p.omega = 0.2 * wn;
  const abu::ContinuationRun run = abu::continue_branches(p, param("omega"), 8 * wn, {});
  REQUIRE(!run.branches.empty());
  const double length = double((ld(p.rotor.unbalance) + capacity(p)) / total_mass(p));  // model.hpp's scale
  using Vec4c = Eigen::Matrix<cd, 4, 1>;
  const auto shape = [length](Vec4c v) {
    v(0) /= length;
    v(1) /= length;
    return Vec4c(v.normalized());
  };
  double worst_set = 0, worst_own = 1, worst_conj = 0;
  int steps = 0, crossings = 0;
  for (const auto& b : run.branches) {
    INFO(to_string(b.family) << " branch, member " << b.member);
    for (std::size_t i = 0; i < b.points.size(); ++i) {
      const auto& pt = b.points[i];
      // The tracked modes are a permutation of the sorted eigenvalues (copies: 1e-14 is
      // only a guard against a recomputation in between).
      auto modes = pt.modes;
      auto sorted = pt.spectrum.eigenvalues;
      const auto order = [](cd x, cd y) { return x.real() != y.real() ? x.real() < y.real() : x.imag() < y.imag(); };
      std::sort(modes.begin(), modes.end(), order);
      std::sort(sorted.begin(), sorted.end(), order);
      for (std::size_t k = 0; k < 8; ++k) {
        const double d = std::abs(modes[k] - sorted[k]) / std::abs(sorted[k]);
        worst_set = std::max(worst_set, d);
        CHECK(d <= 1e-14);
      }
      if (i == 0) continue;
      const auto& prev = b.points[i - 1];
      for (std::size_t k = 0; k < 8; ++k) {
        ++steps;
        const cd x = prev.modes[k], y = pt.modes[k];
        if (!((x.imag() > 0 && y.imag() < 0) || (x.imag() < 0 && y.imag() > 0))) continue;
        // Through the real axis at one of the points: nothing to tell apart.
        if (std::min(std::abs(x.imag()) / std::abs(x), std::abs(y.imag()) / std::abs(y)) <= 1e-6) continue;
        ++crossings;
        const Vec4c va = shape(prev.mode_vectors[k]), vb = shape(pt.mode_vectors[k]);
        const double own = std::abs(va.dot(vb)), conj = std::abs(va.dot(Vec4c(vb.conjugate())));
        INFO("mode " << k << " from " << x << " at " << double(prev.parameter) << " to " << y << " at "
                     << double(pt.parameter) << ": overlap " << own << ", with the conjugate " << conj);
        CHECK(own >= 0.9);
        CHECK(conj <= 0.5);
        worst_own = std::min(worst_own, own);
        worst_conj = std::max(worst_conj, conj);
      }
    }
  }
  MARGIN("tracking: modes vs spectrum worst rel diff " << worst_set << " (tol 1e-14); " << steps << " mode steps, "
                                                     << crossings << " crossings of the real axis between points, "
                                                     << "overlap >= " << worst_own << " (tol 0.9), with conjugate <= "
                                                     << worst_conj << " (tol 0.5)");
}

// Regression: at mu = 1e-4 the balanced branch's unstable complex pair crosses the axis at
// the Hopf point and, a few rad/s later, splits into two real eigenvalues; a long step
// (the balanced state does not move with omega) jumped over both. Newton from the
// extrapolated complex pair stalled between the two real eigenvalues and was taken as
// converged, so the tracked spectrum was wrong and the Hopf point was missed.
TEST_CASE("tracked spectra agree with fresh ones where a complex pair splits (mu = 1e-4)", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  abu::set(p, param("mu"), 1e-4);
  p.omega = 150;
  const abu::ContinuationRun run = abu::continue_branches(p, param("omega"), 600, abu::ContinuationOptions{},
                                                          abu::StartSelection{Family::balanced, std::nullopt});
  REQUIRE(run.branches.size() == 2);
  double worst = 0;
  for (const auto& b : run.branches) {
    for (const auto& pt : b.points) {
      abu::Params q = p;
      q.omega = double(pt.parameter);
      abu::Equilibrium e;
      e.position = pt.position;
      const abu::Spectrum fresh = abu::equilibrium_spectrum(q, e);
      // Both are refined to ~1e-12 of |lambda| (the 40-digit reference tests hold them to
      // 1e-8); 1e-8 separates that from a wrong eigenvalue (here off by 20 %).
      for (const auto& f : fresh.eigenvalues) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const auto& t : pt.spectrum.eigenvalues) nearest = std::min(nearest, std::abs(t - f) / std::abs(f));
        INFO("omega " << double(pt.parameter) << ": fresh eigenvalue " << f);
        CHECK(nearest <= 1e-8);
        worst = std::max(worst, nearest);
      }
    }
    // The Hopf point (n_unstable 2 -> 0) is found on both mirror branches.
    REQUIRE(b.specials.size() == 1);
    CHECK(b.specials[0].label == Label::HB);
    CHECK(b.specials[0].parameter > 249);
    CHECK(b.specials[0].parameter < 251);
  }
  MARGIN("tracked vs fresh spectra at mu = 1e-4: worst relative difference " << worst << " (tol 1e-8)");
}
