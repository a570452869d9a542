// Continuation of equilibrium branches (continuation.hpp) and of their fold and Hopf
// points in a second parameter (boundaries.hpp), against results derived by hand here:
//
//  - the folds of the together family in omega, from the existence condition of its
//    closed form (model.md §5), a quadratic in omega^2;
//  - the branch point at U = m1 l1 + m2 l2 where the balanced family merges with the
//    together one, and at omega = omega_n the together fold sitting on it;
//  - the Hopf points of the balanced state, from its characteristic polynomial derived
//    by hand (continuation_reference.hpp: an 8th-degree polynomial in lambda, no matrix);
//  - the two-parameter curves: friction does not move equilibria, so fold curves in
//    (omega, d) are vertical, and every point of a Hopf curve has a pair +-i omega_H.
//
// Expected values never come from the program's output; where the program's value seeds
// an independent Newton solve, the solve's answer does not depend on the seed. Runs as a
// whole (failure, eigenvalue tracking): test_continuation_tracking.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "abu/continuation/boundaries.hpp"
#include "abu/continuation/continuation.hpp"
#include "abu/core/errors.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/model.hpp"
#include "abu/core/params.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/scan/scan.hpp"
#include "continuation_reference.hpp"
#include "scene_texts.hpp"

using namespace continuation_reference;

// ---------------------------------------------------------------------------------------
// 1. Folds of the together family in omega.
//
// Tolerance 1e-10 relative. The located fold solves the augmented system (F, g) by Newton
// in long double down to steps of 64 eps_ld ~ 7e-18 in the scaled unknowns; the parameter
// is scaled by the interval (7.8 omega_n ~ 8 omega_fold), and the static equations lose
// at most k / |K| digits to the cancellation in K = k - omega^2 M (printed below: <= 9
// for c = 2, ~350 for c = 0.05): the fold is good to ~1e-14. The closed form is
// evaluated in long double: K's cancellation costs k / |K| * eps_ld ~ 4e-17, and the
// roots, relatively 3e-3 apart at worst (c = 0.05), amplify the coefficients' rounding
// by ~1 / 3e-3: ~1e-16. 1e-10 leaves four orders for anything not foreseen.
TEST_CASE("folds of the together family in omega at the closed-form roots", "[continuation]") {
  quiet_gsl();
  for (const double c : {2.0, 0.05}) {
    abu::Params p = base_params();
    p.rotor.damping = c;
    const double wn = omega_n(p);
    p.omega = 0.2 * wn;
    const double to = 8 * wn;
    const auto roots = together_fold_omegas(p);
    INFO("c = " << c);
    REQUIRE(roots.size() == 2);
    // Both roots in the interval; at c = 0.05 they straddle omega_n within 0.2%.
    for (const ld w : roots) {
      REQUIRE(w > ld(p.omega));
      REQUIRE(w < ld(to));
      const ld K = ld(p.rotor.stiffness) - w * w * total_mass(p);
      MARGIN("c = " << c << ": closed-form fold at omega = " << double(w) << ", k/|K| = " << double(p.rotor.stiffness / std::abs(K)));
    }
    const abu::ContinuationRun run = abu::continue_branches(p, param("omega"), to, abu::ContinuationOptions{});
    std::vector<bool> found(roots.size(), false);
    int lp_count = 0;
    for (const auto& b : run.branches) {
      for (const auto& sp : b.specials) {
        if (sp.label != Label::LP) continue;
        ++lp_count;
        INFO("LP at omega = " << double(sp.parameter) << " on a " << to_string(b.family) << " branch");
        CHECK(b.family == Family::together);
        CHECK(sp.family == Family::together);
        CHECK(sp.converged);
        ld best = std::numeric_limits<ld>::infinity();
        std::size_t which = 0;
        for (std::size_t r = 0; r < roots.size(); ++r)
          if (relative(sp.parameter, roots[r]) < best) best = relative(sp.parameter, roots[r]), which = r;
        MARGIN("c = " << c << ": LP rel err " << double(best) << " vs tol 1e-10");
        CHECK(best <= 1e-10L);
        if (best <= 1e-10L) found[which] = true;
      }
    }
    // An LP at every root, and none anywhere else (the balanced family does not depend on
    // omega; the opposite family, equal balls, has two roots at every omega).
    CHECK(lp_count == int(roots.size()));
    for (std::size_t r = 0; r < roots.size(); ++r) CHECK(found[r]);
  }
}

// ---------------------------------------------------------------------------------------
// 2. The branch point at U = m1 l1 + m2 l2 = a.
//
// At omega = 900 the two balanced points (b = pi -+ phi, cos phi = U / a) form one smooth
// curve U = a cos phi through phi = 0, which turns back in U there; phi = 0 is b1 = b2 = pi,
// q = 0, which also solves the together equation at U = a (K U sin pi + C U cos pi + C a = 0).
// The together branch crosses it transversally (dU != 0 since K != 0): a pitchfork. So the
// balanced family must stop at U = a and come back (both mirror points on one branch), and
// the together branch must report the BP at U = a.
//
// Tolerance 1e-10 for the BP: located (whether as a root of det [F_u; t^T] along the
// branch or as a singular point of F_s with F_p in its range), it solves its defining
// equations to the rounding of the scaled unknowns, the parameter scaled by the interval
// (a): ~1e-15 relative. Symmetry helps: the together branch is the invariant subspace
// b1 = b2, where the point is a regular zero.
TEST_CASE("branch point where the balanced family meets the together family (U = 2ml)", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  const ld a = capacity(p);
  const double a_double = 2 * p.balls[0].mass * p.balls[0].race_radius;
  p.rotor.unbalance = 0.5 * a_double;
  const abu::ContinuationRun run =
      abu::continue_branches(p, param("U"), 1.5 * a_double, abu::ContinuationOptions{});

  // The BP on the together branch.
  int bps = 0;
  for (const auto& b : run.branches) {
    if (b.family != Family::together) continue;
    for (const auto& sp : b.specials) {
      if (sp.label != Label::BP) continue;
      ++bps;
      CHECK(sp.converged);
      MARGIN("U: together BP rel err " << double(relative(sp.parameter, a)) << " vs tol 1e-10");
      CHECK(relative(sp.parameter, a) <= 1e-10L);
    }
  }
  CHECK(bps == 1);  // one together member passes through b = pi at U = a, the other does not

  // The balanced branch: one branch carries both mirror points; it never exceeds U = a
  // (beyond it no balanced point exists: a point there could exceed a only by the
  // corrector's rounding, 1e-15) and comes back to the start value.
  std::vector<const abu::Branch*> balanced;
  for (const auto& b : run.branches)
    if (b.family == Family::balanced) balanced.push_back(&b);
  REQUIRE(balanced.size() == 1);
  const abu::Branch& bal = *balanced[0];
  ld top = 0;
  for (const auto& pt : bal.points) {
    CHECK(pt.family == Family::balanced);
    top = std::max(top, pt.parameter);
  }
  MARGIN("U: highest balanced point at " << double(top / a) << " a");
  CHECK(top <= a * (1 + 1e-12L));
  CHECK(bal.stop[0] == abu::StopReason::end_of_range);
  CHECK(bal.stop[1] == abu::StopReason::end_of_range);
  REQUIRE(bal.points.size() >= 3);
  const auto& first = bal.points.front();
  const auto& last = bal.points.back();
  CHECK(relative(first.parameter, ld(p.rotor.unbalance)) <= 1e-15L);
  CHECK(relative(last.parameter, ld(p.rotor.unbalance)) <= 1e-15L);
  // The far end is the mirror point: the balls' angles swapped (1e-12: both are polished
  // equilibria, angles to rounding).
  CHECK(angle_difference(first.position(2), last.position(3)) <= 1e-12L);
  CHECK(angle_difference(first.position(3), last.position(2)) <= 1e-12L);
  // It turns exactly once.
  int turns = 0;
  for (std::size_t i = 1; i < bal.points.size(); ++i)
    turns += (bal.points[i - 1].tangent_parameter > 0) != (bal.points[i].tangent_parameter > 0);
  CHECK(turns == 1);
  // What the balanced branch reports at its turn: the fold there is also the branch point,
  // where the fold's augmented system is singular; whatever is reported must lie at U <= a
  // within one grid step (1e-2), and say so when it is not located.
  CHECK(!bal.specials.empty());
  for (const auto& sp : bal.specials) {
    INFO(to_string(sp.label) << " at U = " << double(sp.parameter / a) << " a, converged " << sp.converged << ": "
                             << sp.note);
    MARGIN("U: balanced branch reports " << to_string(sp.label) << " at " << double(sp.parameter / a)
                                       << " a, converged " << sp.converged);
    CHECK(sp.parameter <= a * (1 + 1e-10L));
    CHECK(sp.parameter >= a * (1 - 1e-2L));
    if (sp.converged) CHECK(relative(sp.parameter, a) <= 1e-10L);
    if (!sp.converged) CHECK(!sp.note.empty());
  }
}

// At omega = omega_n (K = k - omega^2 M is rounding, |K| / C ~ 1e-14): the together roots
// exist iff |C a| <= U sqrt(K^2 + C^2), i.e. U >= a C / sqrt(K^2 + C^2) = a (1 - O(1e-28)):
// only for U >= a, where cos b = -a / U gives b = pi -+ arccos(a / U), the two roots merging
// at b = pi, q = 0 when U = a. That is the balanced merge point too. So the together branch
// (which starts at the far end, U = 1.5 a) turns at U = a exactly where the balanced curve,
// turning too, touches it. Both tangents there have dU = 0: F_s has rank 2 (its q1 and beta
// columns are parallel when K = 0) and F_u rank 3. The point is at once a fold of each
// branch and their crossing, so a program may call it LP or BP; what matters is that the
// together branch reports it, located. Tolerance 1e-8: the fold's augmented system is
// singular at a branch point, where Newton may stop at the square root of the rounding
// level (sqrt(eps_ld) ~ 3e-10).
TEST_CASE("at omega = omega_n the together fold sits on the branch point", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  p.omega = omega_n(p);
  const ld a = capacity(p);
  const double a_double = 2 * p.balls[0].mass * p.balls[0].race_radius;
  p.rotor.unbalance = 0.5 * a_double;
  const abu::ContinuationRun run =
      abu::continue_branches(p, param("U"), 1.5 * a_double, abu::ContinuationOptions{});
  int located = 0, together_branches = 0;
  for (const auto& b : run.branches) {
    for (const auto& pt : b.points) {
      // The families exist on either side of U = a only (1e-12: the corrector's rounding).
      if (pt.family == Family::together) CHECK(pt.parameter >= a * (1 - 1e-12L));
      if (b.family == Family::balanced) CHECK(pt.parameter <= a * (1 + 1e-12L));
    }
    if (b.family != Family::together) continue;
    ++together_branches;
    for (const auto& sp : b.specials) {
      INFO(to_string(sp.label) << " at U = " << double(sp.parameter / a) << " a, converged " << sp.converged << " "
                               << sp.note);
      CHECK((sp.label == Label::LP || sp.label == Label::BP));
      MARGIN("omega_n: together branch " << to_string(sp.label) << " rel err " << double(relative(sp.parameter, a))
                                         << " vs tol 1e-8");
      if (sp.converged && relative(sp.parameter, a) <= 1e-8L) ++located;
    }
  }
  CHECK(together_branches == 1);  // both roots on one branch, through its turn
  CHECK(located >= 1);
}

// ---------------------------------------------------------------------------------------
// 3. Stiff Hopf point (model.md §8): coulomb kappa = 1e6.
//
// In the quasi-static limit (quasi_static_hopf_frequency) the Hopf point is omega_n and
// omega_H = pi m omega_n |sin D| / (2 mu kappa c); the corrections are of relative order
// |lambda| / omega and M |lambda| / c (~1e-8 and 3e-7 here), so the Hopf point lies within
// a few omega_H of omega_n. The exact values come from Phi(i nu; w) = 0 (Newton in long
// double, seeded by the quasi-static point).
TEST_CASE("stiff friction puts the balanced Hopf point a hair above omega_n", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  p.kappa = 1e6;
  const double wn = omega_n(p);
  p.omega = 0.8 * wn;
  const abu::ContinuationRun run = abu::continue_branches(p, param("omega"), 1.5 * wn, abu::ContinuationOptions{},
                                                          abu::StartSelection{Family::balanced, std::nullopt});
  const BalancedScene scene = balanced_scene(p);
  const ld nu0 = quasi_static_hopf_frequency(p);
  // The exact Hopf point, Newton on Phi seeded by the quasi-static one (omega_n, nu0).
  const HopfPoint exact = balanced_hopf(scene, std::sqrt(scene.k / scene.M), nu0);
  REQUIRE(exact.converged);
  REQUIRE(run.branches.size() == 2);
  std::vector<double> lyapunov;
  for (const auto& b : run.branches) {
    REQUIRE(b.family == Family::balanced);
    REQUIRE(b.specials.size() == 1);
    const auto& sp = b.specials[0];
    CHECK(sp.label == Label::HB);  // a complex pair crossing, not a real one
    REQUIRE(sp.converged);
    CHECK(sp.family == Family::balanced);
    CHECK(std::abs(sp.n_unstable_before - sp.n_unstable_after) == 2);
    // A hair above omega_n.
    CHECK(sp.parameter > ld(wn));
    CHECK(sp.parameter < ld(wn) * (1 + 1e-3L));
    MARGIN("stiff: (omega_HB - omega_n) / omega_n = " << double((sp.parameter - wn) / wn) << ", omega_H / omega_n = "
                                                    << sp.frequency / wn);
    // The frequency: ~1e-8 omega_n. The quasi-static formula goes as 1 / kappa: five orders
    // below omega_n at the default kappa = 1e3, eight at kappa = 1e6.
    CHECK(sp.frequency > 1e-9 * wn);
    CHECK(sp.frequency < 1e-7 * wn);
    // Its neglected terms are of relative order M omega_H / c ~ 3e-7: 1e-5.
    MARGIN("stiff: omega_H vs quasi-static formula rel " << double(relative(sp.frequency, nu0)) << " vs tol 1e-5");
    CHECK(relative(sp.frequency, nu0) <= 1e-5L);
    check_hopf_point(p, sp, exact, "stiff");
    lyapunov.push_back(sp.lyapunov);
  }
  // The two balanced points are one configuration with the balls swapped: same l1 in exact
  // arithmetic. l1 comes from exact Taylor coefficients (model.md (6.8)-(6.10)); the two
  // values differ only through the two Hopf points' location (~1e-15 relative) times l1's
  // condition, which the mpmath check (tests/reference/check_lyapunov.py) puts near 1e6 at
  // kappa = 1e6: measured 8e-13 apart, tolerance 1e-9 (the finite differences used
  // before gave 2e-3).
  REQUIRE(lyapunov.size() == 2);
  CHECK(lyapunov[0] * lyapunov[1] > 0);
  const double diff = std::abs(lyapunov[0] - lyapunov[1]) / std::abs(lyapunov[0]);
  MARGIN("stiff: l1 = " << lyapunov[0] << ", " << lyapunov[1] << " rel diff " << diff << " vs tol 1e-9");
  CHECK(diff <= 1e-9);
}

// ---------------------------------------------------------------------------------------
// 4. The Hopf point of the balanced state at the default kappa = 1e3.
TEST_CASE("the balanced Hopf point has a pair on the axis and one l1 on both mirror branches", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  const double wn = omega_n(p);
  p.omega = 0.2 * wn;
  const abu::ContinuationRun run = abu::continue_branches(p, param("omega"), 8 * wn, abu::ContinuationOptions{},
                                                          abu::StartSelection{Family::balanced, std::nullopt});
  REQUIRE(run.branches.size() == 2);
  // The exact Hopf point, Newton on Phi seeded by the quasi-static one (see test 3; at
  // kappa = 1e3 it is good to ~1e-5 relative).
  const BalancedScene scene = balanced_scene(p);
  const HopfPoint exact = balanced_hopf(scene, std::sqrt(scene.k / scene.M), quasi_static_hopf_frequency(p));
  REQUIRE(exact.converged);
  std::vector<double> lyapunov;
  for (const auto& b : run.branches) {
    REQUIRE(b.specials.size() == 1);
    const auto& sp = b.specials[0];
    REQUIRE(sp.label == Label::HB);
    REQUIRE(sp.converged);
    check_hopf_point(p, sp, exact, "kappa 1e3");
    lyapunov.push_back(sp.lyapunov);
  }
  // l1 is identical in exact arithmetic on the two mirror branches (ball swap symmetry);
  // computed from exact Taylor coefficients, the two values differ only through the
  // location of the two Hopf points (~1e-15 relative, condition ~1e2 at kappa = 1e3):
  // measured 9e-16 apart; tolerance 1e-12 (finite differences gave 1e-5).
  REQUIRE(lyapunov.size() == 2);
  CHECK(lyapunov[0] * lyapunov[1] > 0);
  const double diff = std::abs(lyapunov[0] - lyapunov[1]) / std::abs(lyapunov[0]);
  MARGIN("kappa 1e3: l1 = " << lyapunov[0] << ", " << lyapunov[1] << " rel diff " << diff << " vs tol 1e-12");
  CHECK(diff <= 1e-12);
}

// ---------------------------------------------------------------------------------------
// 5. The same family continued forwards and backwards gives the same special points.
// Tolerance 1e-10: each is located by its augmented system to ~1e-14 (see test 1),
// independently of the grid that bracketed it.
TEST_CASE("forwards and backwards continuation find the same special points", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params();
  const double wn = omega_n(p);
  const abu::StartSelection together{Family::together, std::nullopt};
  p.omega = 0.2 * wn;
  const abu::ContinuationRun forward = abu::continue_branches(p, param("omega"), 8 * wn, {}, together);
  p.omega = 8 * wn;
  const abu::ContinuationRun backward = abu::continue_branches(p, param("omega"), 0.2 * wn, {}, together);
  const auto collect = [](const abu::ContinuationRun& run) {
    std::vector<std::pair<Label, ld>> out;
    for (const auto& b : run.branches)
      for (const auto& sp : b.specials) out.emplace_back(sp.label, sp.parameter);
    std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
    return out;
  };
  const auto f = collect(forward), b = collect(backward);
  CHECK(f.size() == 2);  // the two folds of test 1
  REQUIRE(f.size() == b.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    CHECK(f[i].first == b[i].first);
    MARGIN("forward/backward " << to_string(f[i].first) << " rel diff " << double(relative(b[i].second, f[i].second))
                             << " vs tol 1e-10");
    CHECK(relative(b[i].second, f[i].second) <= 1e-10L);
  }
}

// ---------------------------------------------------------------------------------------
// 6. Two parameters: the viscous twin's fold and Hopf points continued in d.
TEST_CASE("fold curves are vertical in omega-d and the balanced Hopf curve reaches d = 1e-3", "[continuation]") {
  quiet_gsl();
  abu::Params p = base_params(true);
  const double wn = omega_n(p);
  p.omega = 0.2 * wn;
  const abu::ContinuationRun run = abu::continue_branches(p, param("omega"), 8 * wn, {});
  const double d_end = 1e-3;
  const abu::BoundaryRun curves = abu::continue_boundaries(p, run, param("d"), d_end, {});
  REQUIRE(!curves.curves.empty());

  // Fold curves: F does not depend on d (friction vanishes at rest, model.md §4), so the
  // fold stays at the same omega: every point to 1e-12 relative (the curve corrector's
  // convergence, 1e-12 in the scaled unknowns, times the interval / omega ~ 8).
  const auto fold_roots = together_fold_omegas(p);
  int folds = 0;
  for (const auto& c : curves.curves) {
    if (c.kind != Label::LP) continue;
    ++folds;
    REQUIRE(!c.points.empty());
    const ld w0 = c.points.front().parameter;
    ld worst = 0;
    for (const auto& pt : c.points) worst = std::max(worst, relative(pt.parameter, w0));
    MARGIN("fold curve at omega = " << double(w0) << ": omega spread " << double(worst) << " vs tol 1e-12");
    CHECK(worst <= 1e-12L);
    // ... and it is one of the closed-form folds (1e-10 as in test 1).
    ld best = std::numeric_limits<ld>::infinity();
    for (const ld w : fold_roots) best = std::min(best, relative(w0, w));
    CHECK(best <= 1e-10L);
    // It spans the whole d interval.
    ld dmin = std::numeric_limits<ld>::infinity(), dmax = 0;
    for (const auto& pt : c.points) dmin = std::min(dmin, pt.parameter2), dmax = std::max(dmax, pt.parameter2);
    CHECK(relative(dmin, ld(p.balls[0].d)) <= 1e-12L);
    CHECK(relative(dmax, ld(d_end)) <= 1e-12L);
  }
  CHECK(folds == 2);

  // The Hopf curve from the balanced HB (its mirror is skipped as the same curve).
  const abu::BoundaryCurve* hopf = nullptr;
  int balanced_hopf_curves = 0;
  for (const auto& c : curves.curves) {
    REQUIRE(c.source_branch >= 1);
    REQUIRE(c.source_branch <= int(run.branches.size()));
    if (c.kind == Label::HB && run.branches[std::size_t(c.source_branch - 1)].family == Family::balanced) {
      hopf = &c;
      ++balanced_hopf_curves;
    }
  }
  CHECK(balanced_hopf_curves == 1);
  REQUIRE(hopf != nullptr);
  REQUIRE(hopf->points.size() >= 3);
  const auto& far = hopf->points.back();
  CHECK(far.label == Label::EP);
  CHECK(relative(far.parameter2, ld(d_end)) <= 1e-12L);
  CHECK(relative(hopf->points.front().parameter2, ld(p.balls[0].d)) <= 1e-12L);
  // It starts at the run's balanced HB (1e-12: the same point, refined by the curve's
  // corrector to 1e-12 in the scaled unknowns).
  const auto& source = run.branches[std::size_t(hopf->source_branch - 1)];
  REQUIRE(source.specials.size() == 1);
  CHECK(relative(hopf->points.front().parameter, source.specials[0].parameter) <= 1e-12L);

  // A few sampled points (ends included) are Hopf points: a pair +-i omega_H in the
  // spectrum recomputed at (omega, d, position). The curve's points are converged to 1e-12
  // in the scaled unknowns; the pair then sits on the axis to ~1e-12 relative: 1e-8.
  const std::size_t n = hopf->points.size();
  for (const std::size_t i : {std::size_t(0), n / 4, n / 2, 3 * n / 4, n - 1}) {
    const auto& pt = hopf->points[i];
    INFO("Hopf curve point " << i << " at omega = " << double(pt.parameter) << ", d = " << double(pt.parameter2));
    CHECK(pt.family == Family::balanced);
    abu::ParamsT<ld, 2> pl = p.cast<ld>();
    pl.omega = pt.parameter;
    for (auto& ball : pl.balls) ball.d = pt.parameter2;
    const abu::Spectrum s = spectrum_at(pl, pt.position);
    const double f = double(pt.frequency);
    const cd up = nearest(s, cd(0, f));
    MARGIN("Hopf curve point " << i << ": |Re|/|lambda| " << std::abs(up.real()) / std::abs(up) << ", Im rel err "
                             << std::abs(up.imag() - f) / f << " (tol 1e-8)");
    CHECK(std::abs(up.real()) <= 1e-8 * std::abs(up));
    CHECK(std::abs(up.imag() - f) <= 1e-8 * f);
  }
  // The far end against the hand-derived characteristic polynomial at d = 1e-3 (viscous:
  // rho = d / m). Tolerance 1e-8: the curve point is converged to 1e-12 in the scaled
  // unknowns; Phi's root to rounding.
  abu::Params pd = p;
  for (auto& ball : pd.balls) ball.d = d_end;
  // Newton on Phi from the curve's end point moved by 1e-3 (the root does not depend on
  // the seed; the move makes Newton find it rather than accept the seed).
  const HopfPoint exact =
      balanced_hopf(balanced_scene(pd), far.parameter * (1 + 1e-3L), far.frequency * (1 - 1e-3L));
  REQUIRE(exact.converged);
  MARGIN("Hopf curve far end: omega rel err vs Phi root " << double(relative(far.parameter, exact.omega))
                                                        << ", omega_H rel err "
                                                        << double(relative(far.frequency, exact.frequency))
                                                        << " (tol 1e-8)");
  CHECK(relative(far.parameter, exact.omega) <= 1e-8L);
  CHECK(relative(far.frequency, exact.frequency) <= 1e-8L);
}

// ---------------------------------------------------------------------------------------
// A Hopf point across a long step whose crossing pair is small beside the other eigenvalues
// (the default scene continued in k at 300 rad/s, U = 9e-7: the trivial balanced branch is
// crossed in steps of 2000 N/m, the pair's real part far from linear over one). The linear
// interpolation's guess (10208 N/m) left Newton on the Hopf system unconverged; the bracket is
// now halved until Newton converges. Independent check: the balanced state's refined spectrum
// (`equilibria`'s, not the continuation's) is stable 1e-6 below the located point and unstable
// 1e-6 above it (relative).
TEST_CASE("a Hopf point behind a long step is located, where equilibria says the balanced state changes stability",
          "[continuation]") {
  quiet_gsl();
  abu::Scene scene = abu::parse_scene(abu::testing::kBase, "default.toml");  // data/scenes/default.toml
  abu::apply_override(scene, "U=9e-7");
  abu::apply_override(scene, "omega=300");
  abu::Params p = abu::params_of<2>(scene);
  const abu::ContinuationRun run = abu::continue_branches(p, param("k"), 20000.0, abu::ContinuationOptions{},
                                                          abu::StartSelection{Family::balanced, std::nullopt});
  int hopf = 0;
  for (const auto& b : run.branches)
    for (const auto& sp : b.specials) {
      if (sp.label != Label::HB) continue;
      ++hopf;
      INFO(sp.note);
      REQUIRE(sp.converged);
      const double k = double(sp.parameter);
      const auto balanced_stable = [&](double kv) {
        abu::Params q = p;
        q.rotor.stiffness = kv;
        const abu::Analysis a = abu::analyze(q);
        bool any = false, stable = true;
        for (std::size_t i = 0; i < a.equilibria.points().size(); ++i)
          if (a.equilibria.points()[i].family == Family::balanced) {
            any = true;
            stable = stable && a.spectra[i].stability == abu::Stability::stable;
          }
        REQUIRE(any);
        return stable;
      };
      CHECK(balanced_stable(k * (1 - 1e-6)));
      CHECK_FALSE(balanced_stable(k * (1 + 1e-6)));
    }
  CHECK(hopf == 2);  // the two mirror balanced branches
}
