// n-ball continuation (branches_n.hpp, model.md §13.7) against the closed forms: every
// point of every aligned branch is one of the equilibria that find_equilibria computes
// afresh at that point's parameter (an independent path: closed forms and polish, no
// continuation), and every balanced sample's branch in a parameter that does not move
// the set (omega) keeps its state.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "abu/continuation/branches_n.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/scan/map.hpp"
#include "abu/scan/scan.hpp"

using namespace abu;

namespace {

ParamsN unequal_ring(int n) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 600;
  p.law = FrictionLaw::viscous;
  p.balls.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const double f = 1 + 0.09 * i;  // unequal balls: no permutation images
    p.balls[std::size_t(i)] = {3.3e-5 * f, 0.018, 1e-3, 1.4, 0.002, 1e-4 * f, 0.001, 0.003, 0.1};
  }
  return p;
}

// Max-norm distance of two configurations, q in units of `length`, angles mod 2 pi.
double config_distance(const Coordinates<long double, any_balls>& a, const Coordinates<long double, any_balls>& b,
                       double length) {
  double d = std::max(std::abs(double(a(0) - b(0))), std::abs(double(a(1) - b(1)))) / length;
  for (Eigen::Index i = 2; i < a.size(); ++i)
    d = std::max(d, std::abs(std::remainder(double(a(i) - b(i)), 2 * std::numbers::pi)));
  return d;
}

}  // namespace

TEST_CASE("n-ball aligned branches pass through the closed-form equilibria", "[n-balls][continuation]") {
  for (int n : {3, 4}) {
    const ParamsN p = unequal_ring(n);
    const ParamRef omega{Quantity::omega, 0};
    ContinuationOptions options;
    options.ds_max = 0.05;
    const ContinuationRunN run = continue_branches(p, omega, 150.0, options, BalancedSampling{8});
    const double length = double(displacement_scale(p.cast<long double>()));
    int checked = 0;
    for (const auto& b : run.branches) {
      if (b.family != Family::aligned) continue;
      for (std::size_t i = 0; i < b.points.size(); i += 7) {
        const BranchPointN& pt = b.points[i];
        ParamsN at = p;
        set(at, omega, double(pt.parameter));
        const EquilibriumSetN set = find_equilibria(at, BalancedSampling{8});
        double best = 1e300;
        for (const auto& e : set.points())
          if (e.family == Family::aligned) best = std::min(best, config_distance(e.position, pt.position, length));
        // The branch point is a Newton solution of the scaled equations to ~1e-15 at a
        // long-double parameter, the closed form is polished at that parameter rounded to
        // double (relative 1e-16 of omega): they agree to ~1e-12 unless the branch point is
        // no equilibrium at all (then the distance is O(1e-3) or more).
        CHECK(best < 1e-9);
        ++checked;
      }
    }
    CHECK(checked > 20);
    // Both ends: every aligned equilibrium at the start value lies on some branch.
    const EquilibriumSetN start = find_equilibria(p, BalancedSampling{8});
    for (const auto& e : start.points()) {
      if (e.family != Family::aligned) continue;
      double best = 1e300;
      for (const auto& b : run.branches)
        for (const auto& pt : b.points)
          if (std::abs(double(pt.parameter) - p.omega) < 1e-9 * p.omega)
            best = std::min(best, config_distance(e.position, pt.position, length));
      CHECK(best < 1e-9);
    }
  }
}

TEST_CASE("a balanced sample's branch in omega keeps its state, with n - 2 structural zeros", "[n-balls][continuation]") {
  const ParamsN p = unequal_ring(4);
  const ContinuationRunN run = continue_branches(p, ParamRef{Quantity::omega, 0}, 1200.0, {}, BalancedSampling{8});
  int samples = 0;
  for (const auto& b : run.branches) {
    if (b.family != Family::balanced) continue;
    ++samples;
    for (const auto& pt : b.points) {
      // q = 0 and the angles of the start: the set does not move with omega (model.md §13.4).
      CHECK(std::hypot(double(pt.position(0)), double(pt.position(1))) < 1e-18);
      CHECK(config_distance(pt.position, b.points.front().position, 1.0) < 1e-12);
      CHECK(pt.spectrum.n_structural == 2);
    }
  }
  CHECK(samples == run.balanced_set.samples);
  CHECK(samples > 0);
  REQUIRE(!run.envelope.intervals.empty());
  CHECK(run.envelope.intervals.front().from == Approx(600.0));
  CHECK(run.envelope.intervals.back().to == Approx(1200.0));
}

TEST_CASE("images under permutations of equal balls are traced once, and counted", "[n-balls][continuation]") {
  // An equal-ball ring (images traced once) against the same ring with every ball's mass
  // moved by a few 1e-13 relative (no two balls equal: every equilibrium traced). The
  // perturbation moves the Hopf points by ~1e-13 relative, far below the 1e-9 compared
  // here, so the envelopes must agree piece by piece and the special points one to one.
  ParamsN equal = unequal_ring(4);
  equal.law = FrictionLaw::coulomb;
  equal.kappa = 1e3;
  for (auto& b : equal.balls) b = equal.balls[0];
  ParamsN perturbed = equal;
  for (int i = 0; i < 4; ++i) perturbed.balls[std::size_t(i)].mass *= 1 + 3e-13 * (i + 1);
  const ParamRef omega{Quantity::omega, 0};
  const ContinuationRunN a = continue_branches(equal, omega, 150.0, {}, BalancedSampling{16});
  const ContinuationRunN b = continue_branches(perturbed, omega, 150.0, {}, BalancedSampling{16});
  CHECK(a.branches.size() < b.branches.size());
  int images = 0;
  for (const auto& br : a.branches) images += br.images;
  CHECK(images > 0);
  REQUIRE(a.envelope.samples == b.envelope.samples);
  // Pieces: the perturbed run cuts the interval at every sample's own Hopf point, the
  // equal run at the classes' (images share theirs): compare the fraction stable at the
  // middle of every piece of the finer one.
  const auto fraction_at = [](const BalancedEnvelope& env, long double x) {
    for (const auto& iv : env.intervals)
      if (iv.from <= x && x <= iv.to) return iv.samples ? double(iv.stable) / iv.samples : -1.0;
    return -2.0;
  };
  for (const auto& iv : b.envelope.intervals) {
    if (iv.to - iv.from < 1e-9L * iv.to) continue;  // a sliver between images' Hopf points
    const long double mid = (iv.from + iv.to) / 2;
    CHECK(fraction_at(a.envelope, mid) == Approx(fraction_at(b.envelope, mid)));
  }
  // Every Hopf parameter of the equal run is one of the perturbed run's, to 1e-9.
  for (const auto& br : a.branches)
    for (const auto& sp : br.specials) {
      if (sp.label != Label::HB) continue;
      double best = 1e300;
      for (const auto& other : b.branches)
        for (const auto& sq : other.specials)
          if (sq.label == Label::HB) best = std::min(best, std::abs(double(sq.parameter - sp.parameter)));
      CHECK(best < 1e-9 * double(sp.parameter));
    }
}

TEST_CASE("an n-ball map cell is the analysis at the cell's parameters", "[n-balls][map]") {
  // CellAnalyzerN (map.hpp) against analyze (scan.hpp) run afresh at the cell's
  // parameters: the same algorithm on the same doubles, so counts and verdicts agree
  // exactly and |q| to rounding (1e-12 relative). Keeps the map cell path under the
  // sanitizers (the CLI map contract is too slow there).
  const ParamsN p = unequal_ring(3);
  Axis x{ParamRef{Quantity::omega, -1}, 150.0, 900.0, 3, false};
  Axis y{ParamRef{Quantity::d, -1}, 1e-5, 1e-3, 2, true};
  CellAnalyzerN cells(p, {}, x, y, BalancedSampling{8});
  MapCellN cell;
  for (int ix = 0; ix < 3; ++ix)
    for (int iy = 0; iy < 2; ++iy) {
      cells.analyze(ix, iy, cell);
      const AnalysisN a = analyze(cells.cell_params(ix, iy), BalancedSampling{8});
      REQUIRE(cell.equilibria.size() == a.equilibria.list.size());
      int aligned = 0, stable = 0;
      for (std::size_t k = 0; k < a.equilibria.list.size(); ++k) {
        const auto& e = a.equilibria.list[k];
        aligned += e.family == Family::aligned;
        stable += e.family == Family::aligned && a.spectra[k].stability == Stability::stable;
        CHECK(cell.equilibria[k].stable == (a.spectra[k].stability == Stability::stable));
        CHECK(cell.equilibria[k].q_abs ==
              Approx(std::hypot(double(e.position(0)), double(e.position(1)))).epsilon(1e-12).margin(1e-300));
      }
      CHECK(cell.aligned == aligned);
      CHECK(cell.aligned_stable == stable);
    }
}
