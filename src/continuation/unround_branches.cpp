// model.md §11.10: branches of the unround race's equilibria in the unroundness factor e
// (see the header for the method).
#include "abu/continuation/unround_branches.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"

namespace abu {

namespace {
using L = long double;
constexpr L kTwoPi = 2 * std::numbers::pi_v<L>;

// Branch unknowns (beta_1..beta_n, e / e_max): bounded dynamic, on the stack.
using Vec = Eigen::Matrix<L, Eigen::Dynamic, 1, 0, max_balls + 1, 1>;
using Jac = Eigen::Matrix<L, Eigen::Dynamic, Eigen::Dynamic, 0, max_balls, max_balls + 1>;

L angle_gap(L a, L b) {
  L x = std::fmod(std::abs(a - b), kTwoPi);
  return std::min(x, kTwoPi - x);
}

// The reduced conditions g(beta; e) of §11.4 with the race scaled by e (§11.10).
struct FactorSystem {
  using Vec = abu::Vec;
  using Jacobian = Jac;
  const LongParamsN& p;
  const RaceShape& race;
  L factor_max;
  mutable RaceShape scratch;  // the scaled race, rewritten in place (no allocation per step)

  int n() const { return p.n_balls(); }
  const RaceShape& at(L factor) const {
    for (std::size_t i = 0; i < race.balls.size(); ++i)
      for (std::size_t k = 0; k < race.balls[i].size(); ++k)
        scratch.balls[i][k].amplitude = double(L(race.balls[i][k].amplitude) * factor);
    return scratch;
  }
  L factor(const Vec& u) const { return u(n()) * factor_max; }
  UnroundAngles angles(const Vec& u) const { return u.head(n()); }

  UnroundAngles residual(const Vec& u) const { return unround_reduced(p, at(factor(u)), angles(u)).g; }
  Jacobian jacobian(const Vec& u) const {
    const int m = n();
    Jacobian J(m, m + 1);
    J.leftCols(m) = unround_reduced(p, at(factor(u)), angles(u)).dg;
    // dg/d(e / e_max) by central differences in long double: the amplitudes enter the
    // offset circle (order 1) nonlinearly; the truncation error h^2 ~ 1e-12 and rounding
    // 1e-19 / h ~ 1e-13 only slow Newton's last digit, not the point it converges to.
    const L h = 1e-6L;
    Vec up = u, down = u;
    up(m) += h;
    down(m) -= h;
    J.col(m) = (residual(up) - residual(down)) / (2 * h);
    return J;
  }
  L residual_size(const Vec& u) const { return residual(u).cwiseAbs().maxCoeff(); }
  static arclength::NewtonSettings newton() {
    arclength::NewtonSettings s;
    s.residual_tolerance = 1e-14L;  // g is O(eps) and its rounding ~1e-19: far below
    return s;
  }
};

UnroundBranchPoint point_at(const FactorSystem& sys, const Vec& u) {
  UnroundBranchPoint pt;
  pt.factor = double(sys.factor(u));
  pt.state = unround_equilibrium_at(sys.p, sys.at(sys.factor(u)), sys.angles(u));
  // The angles as continued (not wrapped): the branch is a curve in R^n; wrap for display.
  for (int i = 0; i < sys.n(); ++i) pt.state.position(2 + i) = std::fmod(u(i), kTwoPi) + (u(i) < 0 ? kTwoPi : 0);
  return pt;
}

L determinant(const FactorSystem& sys, const Vec& u) {
  return unround_reduced(sys.p, sys.at(sys.factor(u)), sys.angles(u)).dg.fullPivLu().determinant();
}

// One run of the engine: the points it accepts, the special points it locates.
struct FactorProblem : FactorSystem {
  static constexpr std::size_t test_count = 2;  // det dg/dbeta (LP), spectral abscissa (stability)
  std::vector<UnroundBranchPoint> points;
  std::vector<UnroundSpecialPoint> specials;
  UnroundBranchPoint pending;

  arclength::Crossing crossing(const Vec&, const Vec& to) const { return arclength::box_crossing(to, {n()}); }
  arclength::Evaluation<L, test_count> evaluate(const Vec& u, const Vec&, const Jacobian&, arclength::Stage) {
    pending = point_at(*this, u);
    arclength::Evaluation<L, test_count> e;
    e.tests = {determinant(*this, u), L(pending.state.spectrum.abscissa)};
    return e;
  }
  // Bisection on the secant: each trial point corrected onto the branch with the secant's
  // direction fixed, 40 halvings (the segment is < ds_max long: below 1e-12 of it).
  void locate(unsigned changed, const arclength::Segment<Vec>& seg) {
    const Vec secant = (seg.to - seg.from).normalized();
    for (int test = 0; test < 2; ++test) {
      if (!(changed & (1u << test))) continue;
      const auto value = [&](const Vec& u) {
        return test == 0 ? determinant(*this, u) : L(point_at(*this, u).state.spectrum.abscissa);
      };
      Vec a = seg.from, b = seg.to;
      const bool sign_a = value(a) > 0;
      bool ok = true;
      for (int k = 0; k < 40 && ok; ++k) {
        const auto c = arclength::correct(static_cast<const FactorSystem&>(*this), Vec((a + b) / 2), secant);
        if (!c.converged()) {
          ok = false;
          break;
        }
        ((value(c.u) > 0) == sign_a ? a : b) = c.u;
      }
      UnroundSpecialPoint s;
      s.point = point_at(*this, (a + b) / 2);
      if (test == 0) {
        // The index changes sign: where the branch turns back in e (the tangent's e
        // component changes sign) a fold; where it goes on through, a branch point (the
        // mirror-symmetric pitchforks of two equal balls, where a pair of mirror states
        // meets the symmetric branch).
        s.kind = (seg.from_tangent(n()) > 0) != (seg.to_tangent(n()) > 0) ? "LP" : "BP";
      } else {
        // The eigenvalue on the imaginary axis: a complex pair (Hopf) or a real one.
        const auto& sp = s.point.state.spectrum;
        std::complex<double> top = sp.eigenvalues[0];
        for (int j = 0; j < sp.count; ++j)
          if (sp.eigenvalues[std::size_t(j)].real() > top.real()) top = sp.eigenvalues[std::size_t(j)];
        s.kind = std::abs(top.imag()) > 1e-6 * std::max(1.0, std::abs(top)) ? "HB" : "ST";
        // A real eigenvalue through zero at an index change is that point (already located).
        if (changed & 1u && s.kind == "ST") continue;
      }
      specials.push_back(std::move(s));
    }
  }
  void commit(Vec&, Vec&, arclength::Stage) { points.push_back(pending); }
  L distance(const Vec& a, const Vec& b) const {
    L d = std::abs(a(n()) - b(n()));
    for (int i = 0; i < n(); ++i) d = std::max(d, angle_gap(a(i), b(i)));
    return d;
  }
};

// True if the equilibrium at angles beta, factor e, lies on a traced branch: a segment
// that straddles e, its point at e (corrected with e fixed) within 1e-8 rad of beta.
bool on_branch(const FactorSystem& sys, const UnroundBranch& br, const UnroundAngles& beta, L factor) {
  const int n = sys.n();
  const L target = factor / sys.factor_max;
  for (std::size_t k = 0; k + 1 < br.points.size(); ++k) {
    const L f0 = br.points[k].factor / sys.factor_max, f1 = br.points[k + 1].factor / sys.factor_max;
    if ((f0 - target) * (f1 - target) > 0) continue;
    Vec a(n + 1), b(n + 1);
    for (int i = 0; i < n; ++i) a(i) = br.points[k].state.position(2 + i), b(i) = br.points[k + 1].state.position(2 + i);
    a(n) = f0, b(n) = f1;
    // Both ends wrapped into [0, 2 pi): bring b next to a.
    for (int i = 0; i < n; ++i) b(i) = a(i) + std::remainder(b(i) - a(i), kTwoPi);
    const L theta = f1 == f0 ? 0.5L : (target - f0) / (f1 - f0);
    Vec guess = a + theta * (b - a);
    guess(n) = target;
    Vec e = Vec::Zero(n + 1);
    e(n) = 1;
    const auto c = arclength::correct(sys, guess, e);
    if (!c.converged()) continue;
    L d = 0;
    for (int i = 0; i < n; ++i) d = std::max(d, angle_gap(c.u(i), beta(i)));
    if (d < 1e-8L) return true;
  }
  return false;
}

}  // namespace

UnroundBranches continue_unround(const ParamsN& pd, const RaceShape& race, double factor_max,
                                 const ContinuationOptions& options) {
  const int n = pd.n_balls();
  if (!(factor_max > 0)) throw InputError("--to", 0, "unroundness", "the unroundness factor's end must be > 0");
  const LongParamsN p = pd.cast<L>();
  UnroundBranches out;
  out.factor_max = factor_max;

  struct Seed {
    UnroundAngles beta;
    double factor;
  };
  std::vector<Seed> seeds;
  std::vector<std::string> doubts;
  std::vector<std::pair<double, std::size_t>> counts;  // (e on an edge, equilibria found there)
  const auto add_seeds = [&](double factor) {
    const UnroundResult r = find_unround_equilibria(pd, scaled_race(race, factor));
    if (!r.doubt.empty()) doubts.push_back(fmt::format("starts at e = {}: {}", factor, r.doubt));
    for (const auto& e : r.list) seeds.push_back({e.position.tail(n), factor});
    if (factor == 0 || factor == factor_max) counts.emplace_back(factor, r.list.size());
  };
  // Steps of at most 0.05 in the scaled unknowns (angles in rad): with longer ones a
  // corrector can land on a neighbouring branch where two pass close (seen at 0.2 on the
  // oval of tests/test_unround.cpp); the edge count below would then disagree.
  ContinuationOptions numerics = options;
  numerics.ds_max = std::min(numerics.ds_max, 0.05);
  numerics.ds = std::min(numerics.ds, numerics.ds_max);
  if (n == 2) add_seeds(0.0);
  if (factor_max > 1) add_seeds(1.0);
  add_seeds(factor_max);

  for (const Seed& seed : seeds) {
    throw_if_stopped("continue: unroundness");
    FactorProblem fwd{{p, race, factor_max, race}, {}, {}, {}};
    const bool known = std::any_of(out.branches.begin(), out.branches.end(), [&](const UnroundBranch& br) {
      return on_branch(fwd, br, seed.beta, seed.factor);
    });
    if (known) continue;
    FactorProblem bwd = fwd;
    Vec u0(n + 1);
    u0.head(n) = seed.beta;
    u0(n) = L(seed.factor / factor_max);
    Vec inward = Vec::Zero(n + 1);
    inward(n) = 1;
    const bool on_edge = seed.factor == 0 || seed.factor == factor_max;
    if (seed.factor == factor_max) inward(n) = -1;
    const auto s = arclength::start(fwd, u0, inward, on_edge);
    const auto runs = arclength::trace_both_ways(fwd, bwd, s, numerics);
    UnroundBranch br;
    br.start_factor = seed.factor;
    br.end_forward = std::string(arclength::to_string(runs.forward.end));
    if (runs.backward_traced) {
      br.end_backward = std::string(arclength::to_string(runs.backward.end));
      // Backward run reversed (its first point is the start, also the forward run's first).
      br.points.assign(bwd.points.rbegin(), bwd.points.rend() - 1);
      br.specials = bwd.specials;
    }
    br.points.insert(br.points.end(), fwd.points.begin(), fwd.points.end());
    br.specials.insert(br.specials.end(), fwd.specials.begin(), fwd.specials.end());
    for (const auto* run : {&runs.forward, &runs.backward}) {
      if (run == &runs.backward && !runs.backward_traced) continue;
      if (run->status != arclength::Status::converged)
        doubts.push_back(fmt::format("a branch from e = {} ended early ({}: {})", seed.factor,
                                     arclength::to_string(run->end), run->reason));
    }
    out.branches.push_back(std::move(br));
  }
  // Every equilibrium on an edge of the interval is a branch's end there, once (a check
  // that no run jumped to another branch, which would end it twice at one point).
  for (const auto& [factor, count] : counts) {
    std::size_t ends = 0;
    for (const auto& br : out.branches)
      for (const auto* pt : {&br.points.front(), &br.points.back()})
        if (pt->factor == factor) ++ends;
    if (ends != count)
      doubts.push_back(fmt::format("{} branch ends at e = {} against {} equilibria there: a branch may have been "
                                   "traced twice or jumped (try a smaller --ds-max)",
                                   ends, factor, count));
  }
  for (std::size_t k = 0; k < doubts.size(); ++k) out.doubt += (k ? "; " : "") + doubts[k];
  return out;
}

}  // namespace abu
