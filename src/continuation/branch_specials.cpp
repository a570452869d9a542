// The special points of an equilibrium branch flagged by its test functions
// (branch_tracer.hpp), located by augmented systems (bifurcation.hpp), not on the grid.
#include <Eigen/SVD>
#include <cmath>
#include <optional>

#include "abu/continuation/bifurcation.hpp"
#include "abu/core/bracketed_root.hpp"
#include "branch_tracer.hpp"

namespace abu {

namespace {

using ld = long double;
using Vec5 = StaticEquations::Vec5;
using Mat45 = StaticEquations::Mat45;

// The eigenvalue of `sp` nearest to `target`.
std::complex<double> nearest(const Spectrum& sp, std::complex<double> target) {
  std::complex<double> best = sp.eigenvalues[0];
  for (const auto& l : sp.eigenvalues)
    if (std::abs(l - target) < std::abs(best - target)) best = l;
  return best;
}

// A located point must lie on the piece of branch it was bracketed on (within a
// margin of the chord), else the augmented Newton wandered off.
bool inside(const Vec5& za, const Vec5& zb, const Vec5& z) {
  const ld chord = distance(za, zb);
  return distance(z, za) <= 2 * chord && distance(z, zb) <= 2 * chord;
}

}  // namespace

void BranchTracer::locate(unsigned changed, const arclength::Segment<Vec5>& between) {
  const Bracket br{points.back(), pending_, between.from, between.to, between.from_tangent};
  // Both mark a point where F_s is singular; along the fork of a pitchfork both change
  // sign at once (the fork turns there): one singular point, classified when located.
  if (changed & (lp_test | bp_test)) locate_singular_between(br, (changed & lp_test) != 0);
  if (changed & hb_test) locate_hopf_between(br);
}

SpecialPoint BranchTracer::special_at(Label label, const Vec5& z, const Bracket& br) const {
  SpecialPoint sp;
  sp.label = label;
  sp.parameter = eq.parameter(z);
  sp.position = eq.position(z);
  sp.family = classify(eq.base(), sp.position);
  sp.n_unstable_before = br.a.spectrum.n_unstable;
  sp.n_unstable_after = br.b.spectrum.n_unstable;
  sp.bracket_from = br.a.parameter;
  sp.bracket_to = br.b.parameter;
  return sp;
}

void BranchTracer::locate_singular_between(const Bracket& br, bool fold_test) {
  // The singular point solves the fold's augmented system (F = 0, F_s singular); where
  // that fails (fold and branch point coinciding, F_s of rank 2) the test function's root
  // on the branch is found by Brent's method instead. Then: a fold if F_p is outside the
  // range of F_s (w^T F_p != 0, w its left null vector), a branch point if inside.
  const ld fa = fold_test ? ld(br.a.tangent_parameter) : ld(br.a.branch_test);
  const ld fb = fold_test ? ld(br.b.tangent_parameter) : ld(br.b.branch_test);
  const Vec5 guess = br.za + (fa / (fa - fb)) * (br.zb - br.za);
  const Located f = locate_fold(eq, guess);
  std::optional<Vec5> z;
  if (f.converged && inside(br.za, br.zb, f.z)) z = f.z;
  if (!z) z = root_on_branch(br, fold_test);
  if (!z) {
    SpecialPoint sp = special_at(fold_test ? Label::LP : Label::BP, guess, br);
    sp.eigenvalue = nearest(compute_spectrum(eq.linearization(guess)), 0.0);
    sp.note = "a singular point was detected here but could not be located (neither its augmented system nor the "
              "test function's root on the branch converged)";
    specials.push_back(sp);
    return;
  }
  const Mat45 DF = eq.jacobian(*z);
  const Eigen::JacobiSVD<Eigen::Matrix<ld, 4, 4>> svd(DF.leftCols<4>(), Eigen::ComputeFullU);
  const ld in_range = std::abs(svd.matrixU().col(3).dot(DF.col(4))) / DF.col(4).norm();
  // w^T F_p / |F_p|: 0 at a branch point, of order 1 at a fold. Measured: 1e-22 where a
  // branch crosses a branch point, 2e-7 on the fork of a pitchfork (whose location is
  // exact in the parameter, uncertain by ~1e-8 along the null direction), 0.999 at the
  // folds of the together family. 1e-5 separates them by orders of magnitude.
  SpecialPoint sp = special_at(in_range <= 1e-5L ? Label::BP : Label::LP, *z, br);
  sp.converged = true;
  sp.eigenvalue = nearest(compute_spectrum(eq.linearization(*z)), 0.0);
  specials.push_back(sp);
}

std::optional<Vec5> BranchTracer::root_on_branch(const Bracket& br, bool fold_test) const {
  // The test function (t_p, or det [F_u; t^T]) along the chord from z_a to z_b, each value
  // on the branch (the corrector with the chord as constraint direction); Brent (GSL).
  const Vec5 za = br.za;
  const ld length = (br.zb - za).norm();
  const Vec5 d = (br.zb - za) / length;
  const auto test = [&](double sigma) -> std::optional<double> {
    const Corrected on = correct(eq, za + ld(sigma) * d, d);
    if (!on.converged()) return std::nullopt;
    const Vec5 t = arclength::tangent(on.jacobian, br.ta);
    return fold_test ? double(t(4)) : double(arclength::bordered_determinant(on.jacobian, t));
  };
  // A bracket of 1e-15 relative to sigma (in [0, |z_b - z_a|]): down to rounding, the test
  // function being smooth here; 200 iterations at most, the last estimate taken after them.
  RootSearch search;
  search.relative_width = 1e-15;
  const BracketedRoot found = bracketed_root(test, 0.0, double(length), search);
  if (!found.converged() && found.end != BracketedRoot::End::max_iterations) return std::nullopt;
  const Corrected on = correct(eq, za + ld(found.root) * d, d);
  if (!(on.converged() && inside(br.za, br.zb, on.u))) return std::nullopt;
  return on.u;
}

void BranchTracer::locate_hopf_between(const Bracket& br) {
  // Narrow the bracket on the branch (bisection on the test function's sign, each point
  // corrected onto the branch) until the crossing pair is complex at both ends: a Hopf
  // pair can be complex only in a sliver of the step (near omega_n with coulomb
  // friction its frequency is 1e-5 omega_n). Then solve the Hopf system from there.
  Vec5 za = br.za, zb = br.zb;
  Spectrum sa = br.a.spectrum, sb = br.b.spectrum;
  // A neutral saddle (a real pair lambda, -lambda: one eigenvalue on each side of the
  // axis) changes the test function's sign but not the number of unstable eigenvalues;
  // a Hopf crossing changes it by two. Only the latter is worth locating.
  if (std::abs(sa.n_unstable - sb.n_unstable) != 2) return;
  const int sign_a = hopf_test_sign(sa);
  // One halving of the bracket on the test function's sign, the midpoint corrected onto the branch.
  const auto halve = [&] {
    const Corrected mid = correct(eq, (za + zb) / 2, (zb - za).normalized());
    if (!mid.converged()) return false;
    const Spectrum sm = compute_spectrum(eq.linearization(mid.u));
    if (hopf_test_sign(sm) == sign_a) {
      za = mid.u, sa = sm;
    } else {
      zb = mid.u, sb = sm;
    }
    return true;
  };
  std::optional<std::pair<std::complex<double>, std::complex<double>>> pair;
  for (int it = 0; it < 90 && !(pair = crossing_pair(sa, sb)); ++it)
    if (distance(za, zb) < 1e-15L || !halve()) break;
  if (!pair) {
    // The sign change came from a real pair lambda, -lambda: a neutral saddle, not a
    // Hopf point (or a crossing too close to a coalescence to resolve): not reported.
    return;
  }
  // Newton on the Hopf system from the pair's linear interpolation; where the pair's real part
  // is far from linear over the bracket (a long step across a crossing whose eigenvalues are
  // small beside the others: the default scene continued in k at 300 rad/s), the bracket is
  // halved on the test function's sign, the pair complex at both ends, and Newton tried again
  // from the narrower one, down to 1e-12 of the parameter's scale.
  Vec5 guess;
  ld omega_guess = 0;
  Located h;
  bool ok = false;
  for (int it = 0; it < 60; ++it) {
    const auto [la, lb] = *pair;
    const double theta = la.real() / (la.real() - lb.real());
    guess = za + ld(theta) * (zb - za);
    omega_guess = la.imag() + theta * (lb.imag() - la.imag());
    h = locate_hopf(eq, guess, omega_guess);
    ok = h.converged && inside(br.za, br.zb, h.z);
    if (ok || distance(za, zb) < 1e-12L || !halve()) break;
    const auto narrower = crossing_pair(sa, sb);
    if (!narrower) break;
    pair = narrower;
  }
  SpecialPoint sp = special_at(Label::HB, ok ? h.z : guess, br);
  sp.converged = ok;
  sp.frequency = double(ok ? h.frequency : omega_guess);
  const Spectrum s = compute_spectrum(eq.linearization(ok ? h.z : guess));
  sp.eigenvalue = nearest(s, std::complex<double>(0, sp.frequency));
  if (ok) {
    sp.lyapunov = first_lyapunov_coefficient(eq.params(h.z), eq.position(h.z), h.frequency);
    if (sp.lyapunov == 0) sp.note = "degenerate Hopf point (l1 = 0 within its accuracy)";
  } else {
    sp.note = "Hopf crossing detected but its augmented system did not converge";
  }
  specials.push_back(sp);
}

}  // namespace abu
