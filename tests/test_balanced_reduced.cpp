// Equal balls (model.md §13.9): the balanced set's normal spectrum from the reduced
// problem in g against the full deflated normal spectrum (§13.5, a second algorithm on the
// (n + 2)-dof problem), on random points of the set; the claim that the normal spectrum
// depends on the arrangement only through g; permutation classes of equilibria.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>

#include "abu/equilibria/ball_permutations.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/balanced_reduced.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/linear/spectrum_verdict.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/scan.hpp"
#include "equal_ring.hpp"
#include "qep_residual.hpp"

using namespace abu;

namespace {

using ld = long double;
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;

using test::equal_ring;

// A random point of the balanced set: free angles beta_3..beta_n uniform, balls 1 and 2
// closing the polygon (model.md (13.4.11)) in long double: W = 0 to a few long-double
// roundings, enough for the deflation (13.4.9), and both spectra are taken at this point.
bool random_sample(const ParamsN& p, std::mt19937& rng, EquilibriumN& e) {
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
  const int n = p.n_balls();
  const ld a = ld(p.balls[0].mass) * ld(p.balls[0].race_radius);
  std::complex<ld> R = p.rotor.unbalance;
  e.position = Coordinates<ld, any_balls>::Zero(n + 2);
  for (int j = 2; j < n; ++j) {
    e.position(2 + j) = angle(rng);
    R += a * std::polar(ld(1), e.position(2 + j));
  }
  const ld rho = std::abs(R);
  if (rho >= 2 * a * (1 - 1e-3L) || rho <= 1e-3L * a) return false;  // away from the collinear edge
  const ld gamma = std::acos(rho / (2 * a)), theta = std::arg(-R);
  e.position(2) = wrap_angle(theta - gamma);
  e.position(3) = wrap_angle(theta + gamma);
  e.family = Family::balanced;
  e.on_balanced_set = true;
  e.converged = true;
  e.structural_zeros = p.law == FrictionLaw::none ? 2 * (n - 2) : n - 2;
  return true;
}

}  // namespace

// Both spectra are refined in long double on their own problems; each eigenvalue's
// error estimate is error[k] (condition x backward error, spectrum.hpp). Two correct
// computations therefore agree to error_full + error_reduced, plus the rounding of each to
// double (2^-53 |lambda|): the tolerance is 4 times that sum. It is also required to be
// below 1e-8 |lambda| (the accuracy the CSV promises). The fast ball modes reach 7e5 1/s,
// the creep-like ones 1e-3: the tolerance is relative to each eigenvalue, not the spectrum.
TEST_CASE("the reduced problem in g gives the balanced set's normal spectrum", "[n-balls][reduced]") {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> speed(120, 2500), unbalance(0.05, 2.5);
  int compared = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const int n = 3 + trial % 10;
    const FrictionLaw law = trial % 3 == 0 ? FrictionLaw::viscous : trial % 3 == 1 ? FrictionLaw::coulomb
                                                                                     : FrictionLaw::none;
    const ParamsN p = equal_ring(n, law, speed(rng), unbalance(rng) * 5.94e-7);
    if (!balanced_set_exists(p)) continue;
    EquilibriumN e;
    if (!random_sample(p, rng, e)) continue;
    const BalancedReduction r = balanced_reduction(p);
    REQUIRE(r.applies);
    REQUIRE(reducible(r, e));
    const SpectrumN full = compute_normal_spectrum(linearize(p.cast<ld>(), e.state()), balanced_tangent_basis(p, e.position));
    const SpectrumN reduced = reduced_normal_spectrum(r, p, e);
    INFO("n = " << n << ", law " << int(law) << ", omega = " << p.omega << ", g = " << arrangement_of(e.position).g);
    REQUIRE(full.count == reduced.count);
    CHECK(full.n_structural == reduced.n_structural);
    CHECK(full.stability == reduced.stability);
    CHECK(full.n_unstable == reduced.n_unstable);
    // Pair every eigenvalue with the nearest unused one (relative distance).
    std::array<bool, SpectrumN::capacity> used{};
    for (int k = 0; k < reduced.count; ++k) {
      const auto z = reduced.eigenvalues[std::size_t(k)];
      int best = -1;
      double best_d = std::numeric_limits<double>::infinity();
      for (int j = 0; j < full.count; ++j) {
        if (used[std::size_t(j)] || full.structural[std::size_t(j)] != reduced.structural[std::size_t(k)]) continue;
        const double dist = std::abs(full.eigenvalues[std::size_t(j)] - z);
        if (dist < best_d) best_d = dist, best = j;
      }
      REQUIRE(best >= 0);
      used[std::size_t(best)] = true;
      if (reduced.structural[std::size_t(k)]) continue;  // both exactly 0
      const double scale = std::abs(z);
      const double tolerance = 4 * (full.error[std::size_t(best)] + reduced.error[std::size_t(k)] + 2 * kU * scale);
      INFO("lambda = " << z << " against " << full.eigenvalues[std::size_t(best)]);
      CHECK(best_d <= tolerance);
      CHECK(best_d <= 1e-8 * scale);
      ++compared;
    }
    // The map's verdict from the degree-8 polynomial in g (first call: the refined reduced
    // spectrum; then the root followed and certified from there): the same verdict, and
    // the abscissa to the full spectrum's tolerance (the rightmost eigenvalue's own).
    {
      const ReducedPolynomials corners = reduced_polynomials(r);
      std::complex<double> root;
      bool tracked = false;
      const double g = double(arrangement_of(e.position).g);
      // The rightmost normal eigenvalue's tolerance as above, plus 1e-12 of it for the
      // polynomial root in double (degree 8, coefficients to ~1e-16 relative: model.md §13.8).
      std::size_t right = 0;
      while (full.structural[right]) ++right;  // (sorted: the first normal one is the rightmost)
      const double size = std::abs(full.eigenvalues[right]);
      const double tolerance = 4 * (full.error[right] + 2 * kU * size) + 1e-12 * size;
      for (const double at : {g, g}) {  // untracked, then tracked from its own root
        const NormalVerdict v = reduced_normal_verdict(r, corners, at, root, tracked);
        CHECK(v.stability == full.stability);
        CHECK(v.n_unstable == full.n_unstable);
        CHECK(v.n_structural == full.n_structural);
        CHECK(std::abs(v.abscissa - full.abscissa) <= tolerance);
      }
    }
    // The mapped eigenvectors are eigenvectors of the full problem: the residual of
    // T(lambda) x relative to (|lambda|^2 |A| + |lambda| |C| + |K|) |x| at the rounding of
    // x to double (the vectors are stored in double): 1e-12 leaves a factor 1e3 for sums.
    const auto lin = linearize(p.cast<ld>(), e.state());
    for (int k = 0; k < reduced.count; ++k) {
      if (reduced.structural[std::size_t(k)]) continue;
      const ld worst = test::qep_residual(lin, reduced.eigenvalues[std::size_t(k)], reduced.vectors[std::size_t(k)]);
      INFO("eigenvector " << k << " of lambda = " << reduced.eigenvalues[std::size_t(k)]);
      CHECK(double(worst) <= 1e-12);
    }
  }
  CHECK(compared > 400);  // the loop did compare (about 70 samples x 8 or more)
}

// The claim itself, without the reduced problem: two different arrangements with the same
// g (a sample and its mirror beta -> -beta, which is on the set too since U is real, and
// which is no permutation of it) have the same full normal spectrum, while a sample with
// another g has another one.
TEST_CASE("the normal spectrum depends on the arrangement only through g", "[n-balls][reduced]") {
  std::mt19937 rng(99);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 3 + trial % 5;
    const ParamsN p = equal_ring(n, FrictionLaw::viscous, 700 + 40 * trial, 6e-7);
    EquilibriumN e, mirror;
    if (!random_sample(p, rng, e)) continue;
    mirror = e;
    for (int i = 0; i < n; ++i) mirror.position(2 + i) = wrap_angle(-e.position(2 + i));
    const auto spectrum = [&](const EquilibriumN& x) {
      return compute_normal_spectrum(linearize(p.cast<ld>(), x.state()), balanced_tangent_basis(p, x.position));
    };
    const SpectrumN a = spectrum(e), b = spectrum(mirror);
    REQUIRE(a.count == b.count);
    for (int k = 0; k < a.count; ++k) {
      const auto za = a.eigenvalues[std::size_t(k)], zb = b.eigenvalues[std::size_t(k)];
      // (sorted alike; same tolerance argument as above)
      CHECK(std::abs(za - zb) <= 4 * (a.error[std::size_t(k)] + b.error[std::size_t(k)] + 2 * kU * std::abs(za)));
    }
    ++checked;
  }
  CHECK(checked > 20);
}

// Permutation classes: an 11-ball ring at 900 rad/s has 2048 aligned equilibria in 12
// classes (k balls opposite, k and 11 - k the same states, two roots each) and 420 samples
// in 2 classes (9 free balls at 0 or pi, 3 or 4 of them at 0; the two sheets swap balls 1
// and 2); every image's spectrum equals its representative's own to its error estimate.
TEST_CASE("permutation classes of an equal-ball ring", "[n-balls][reduced]") {
  const ParamsN p = equal_ring(11, FrictionLaw::coulomb, 900, 6e-7);
  const EquilibriumSetN set = find_equilibria(p);
  PermutationClasses classes;
  find_permutation_classes(ball_kinds(p), set.points(), classes);
  CHECK(set.points().size() == 2468);
  CHECK(classes.representatives == 14);
  // One ball heavier: classes only among the ten equal ones.
  ParamsN unequal = p;
  unequal.balls[4].mass *= 1.01;
  const EquilibriumSetN set_u = find_equilibria(unequal);
  PermutationClasses classes_u;
  find_permutation_classes(ball_kinds(unequal), set_u.points(), classes_u);
  // (the ten equal balls still form classes; ball 5 is always its own image)
  CHECK(classes_u.representatives > classes.representatives);
  CHECK(classes_u.representatives < int(set_u.points().size()));
  for (const auto& image : classes_u.images) CHECK(image.ball_of[4] == 4);
  // An image's own spectrum against the copy, on a few images (the n = 11 spectrum is ms).
  const auto points = set.points();
  int checked = 0;
  for (std::size_t k = 0; k < points.size() && checked < 6; k += 397) {
    const auto& image = classes.images[k];
    if (image.representative == int(k)) continue;
    const SpectrumN own = equilibrium_spectrum(p, points[k]);
    const SpectrumN rep = equilibrium_spectrum(p, points[std::size_t(image.representative)]);
    REQUIRE(own.count == rep.count);
    for (int i = 0; i < own.count; ++i) {
      const auto a = own.eigenvalues[std::size_t(i)], b = rep.eigenvalues[std::size_t(i)];
      CHECK(std::abs(a - b) <= 4 * (own.error[std::size_t(i)] + rep.error[std::size_t(i)] + 2 * kU * std::abs(a)));
    }
    CHECK(own.stability == rep.stability);
    ++checked;
  }
  CHECK(checked >= 3);
}

// The map's verdict with refinement only where needed (spectrum_verdict.hpp) against the
// whole refined spectrum, on every aligned equilibrium of rings of n = 3 .. 8 equal and
// unequal balls at speeds below and above resonance: the same stability and number of
// unstable eigenvalues, and the abscissa to the bit (the same refinement's value) but where
// compute_spectrum retried another eigenvalue.
TEST_CASE("a verdict refined where needed equals the refined spectrum's", "[n-balls][verdict]") {
  int checked = 0, partial = 0, exact = 0;
  for (int n = 3; n <= 8; ++n)
    for (const double omega : {150.0, 240.0, 900.0, 2500.0})
      for (const bool unequal : {false, true}) {
        ParamsN p = equal_ring(n, n % 2 ? FrictionLaw::coulomb : FrictionLaw::viscous, omega, 6e-7);
        if (unequal) p.balls[1].mass *= 1.3;
        const EquilibriumSetN set = find_equilibria(p);
        for (const auto& e : set.points()) {
          if (e.on_balanced_set) continue;
          const auto lin = linearize(p.cast<ld>(), e.state());
          const SpectrumN full = compute_spectrum(lin, SpectrumMethod::refined, e.structural_zeros);
          const SpectrumVerdict v = spectrum_verdict(lin, e.structural_zeros);
          INFO("n = " << n << ", omega = " << omega << ", pattern " << e.pattern << " member " << e.member);
          CHECK(v.stability == full.stability);
          CHECK(v.n_unstable == full.n_unstable);
          // The same refinement gives the same bits; where compute_spectrum retried an
          // eigenvalue this path did not need (from shifted inverses, restarting every one
          // from its refined value) the abscissa is refined twice: equal to its accuracy.
          CHECK(std::abs(v.abscissa - full.abscissa) <= 1e-12 * std::abs(full.abscissa));
          exact += v.abscissa == full.abscissa;
          ++checked;
          partial += v.refined < full.count;
        }
      }
  CHECK(checked > 500);
  CHECK(exact >= checked * 99 / 100);
  CHECK(partial > checked / 2);  // the point of it: most refine only part of the spectrum
}
