#include "abu/continuation/special_rows.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include "abu/continuation/tracking.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/model/model.hpp"
#include "abu/model/static_equations.hpp"

namespace abu {

namespace {
using ld = long double;

// The index i of the two consecutive points (i, i + 1) that bracket the special point.
std::optional<std::size_t> bracket_of(const Branch& b, const SpecialPoint& sp) {
  for (std::size_t i = 0; i + 1 < b.points.size(); ++i) {
    const ld p0 = b.points[i].parameter, p1 = b.points[i + 1].parameter;
    if ((p0 == sp.bracket_from && p1 == sp.bracket_to) || (p0 == sp.bracket_to && p1 == sp.bracket_from)) return i;
  }
  return std::nullopt;
}

// The special point as a branch point, its eigenvalues in the modes of the branch: each
// mode predicted by interpolating between the bracketing points in the parameter.
BranchPoint point_at(const StaticEquations& eq, const SpecialPoint& sp, const BranchPoint& a, const BranchPoint& c) {
  BranchPoint row;
  row.parameter = sp.parameter;
  row.position = sp.position;
  row.family = sp.family;
  row.label = sp.label;
  row.spectrum = compute_spectrum(eq.linearization(eq.scaled(sp.position, sp.parameter)));
  const ld span = c.parameter - a.parameter;
  const double t = span != 0 ? std::clamp(double((sp.parameter - a.parameter) / span), 0.0, 1.0) : 0.0;
  const double length = double(eq.length());
  const auto scaled = [length](const Vec4c& v) {
    return Vec4c(v(0) / length, v(1) / length, v(2), v(3)).normalized();
  };
  ModePrediction predicted;
  for (std::size_t k = 0; k < 8; ++k) {
    predicted.values[k] = a.modes[k] + t * (c.modes[k] - a.modes[k]);
    predicted.vectors[k] = scaled(a.mode_vectors[k]);
    predicted.si_vectors[k] = a.mode_vectors[k];
  }
  std::array<Vec4c, 8> vectors{};
  for (std::size_t k = 0; k < 8; ++k) vectors[k] = scaled(row.spectrum.vectors[k]);
  std::array<int, 8> source{};
  track(predicted, row.spectrum, vectors, row.modes, source);
  for (std::size_t k = 0; k < 8; ++k) row.mode_vectors[k] = row.spectrum.vectors[std::size_t(source[k])];
  // The test functions vanish at the point they locate; the other one is interpolated.
  row.tangent_parameter =
      sp.label == Label::LP ? 0.0 : a.tangent_parameter + t * (c.tangent_parameter - a.tangent_parameter);
  row.branch_test = sp.label == Label::BP ? 0.0 : a.branch_test + t * (c.branch_test - a.branch_test);
  return row;
}

// Points of the branch between a Hopf point and a bracketing point, at 30 %, 10 % and 2 %
// of the way from the Hopf point to `side` in the parameter (in the order met going from
// `side` to the Hopf point), so that a chart of the spectral abscissa follows its curve
// into the crossing instead of a chord across the bracket. Each is the equilibrium at
// that parameter (Newton on the static equations, the parameter held, from the state
// interpolated along the chord: the equilibrium is regular at a Hopf point, so Newton
// stays on the branch) with its own spectrum and verdict; none where Newton fails.
std::vector<BranchPoint> near_hopf(const StaticEquations& eq, const SpecialPoint& sp, const BranchPoint& side,
                                   const BranchPoint& a, const BranchPoint& c) {
  std::vector<BranchPoint> out;
  for (const double f : {0.3, 0.1, 0.02}) {
    const ld parameter = sp.parameter + ld(f) * (side.parameter - sp.parameter);
    Coordinates<ld, 2> guess = sp.position + ld(f) * (side.position - sp.position);
    auto z = eq.scaled(guess, parameter);
    bool converged = false;
    for (int it = 0; it < 30 && !converged; ++it) {
      const auto F = eq.residual(z);
      if (F.norm() <= 1e-14L) {
        converged = true;
        break;
      }
      const Eigen::Matrix<ld, 4, 4> J = eq.jacobian(z).template leftCols<4>();
      z.head<4>() -= J.partialPivLu().solve(F);
    }
    if (!converged) continue;
    SpecialPoint at = sp;
    at.parameter = parameter;
    at.position = eq.position(z);
    at.family = classify(eq.base(), at.position);
    at.label = Label::none;
    out.push_back(point_at(eq, at, a, c));
  }
  return out;
}

// `row` with the stability verdict of `side` (the eigenvalues stay the point's own).
BranchPoint with_side(BranchPoint row, const BranchPoint& side) {
  row.spectrum.stability = side.spectrum.stability;
  row.spectrum.n_unstable = side.spectrum.n_unstable;
  return row;
}

}  // namespace

void insert_special_rows(const Params& p, ContinuationRun& run) {
  const StaticEquations eq(p, run.param, run.from, ld(run.to) - ld(run.from));
  for (auto& b : run.branches) {
    // Rows to insert after point i, in the order met along the branch.
    std::vector<std::vector<std::pair<ld, const SpecialPoint*>>> after(b.points.size());
    for (const auto& sp : b.specials) {
      if (!sp.converged) continue;
      const auto i = bracket_of(b, sp);
      if (!i) continue;
      const auto& a = b.points[*i];
      const ld from_a = (eq.scaled(sp.position, sp.parameter) - eq.scaled(a.position, a.parameter)).norm();
      after[*i].emplace_back(from_a, &sp);
    }
    std::vector<BranchPoint> points;
    points.reserve(b.points.size() + 2 * b.specials.size());
    for (std::size_t i = 0; i < b.points.size(); ++i) {
      points.push_back(b.points[i]);
      auto& here = after[i];
      if (here.empty()) continue;
      std::sort(here.begin(), here.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      const BranchPoint& a = b.points[i];
      const BranchPoint& c = b.points[i + 1];
      const bool flips = a.spectrum.stability != c.spectrum.stability || a.spectrum.n_unstable != c.spectrum.n_unstable;
      for (const auto& [distance, sp] : here) {
        const BranchPoint row = point_at(eq, *sp, a, c);
        const bool refine = sp->label == Label::HB && here.size() == 1;
        if (refine)
          for (auto& pt : near_hopf(eq, *sp, a, a, c)) points.push_back(std::move(pt));
        if (!flips) {
          points.push_back(with_side(row, a));  // the same verdict on both sides
        } else if (here.size() == 1) {
          points.push_back(with_side(row, a));
          points.push_back(with_side(row, c));
        } else {
          // Two special points between the same two points (rare): the side of each is
          // not known from the grid; the row carries the verdict at the point itself.
          points.push_back(row);
        }
        if (refine) {
          auto towards_c = near_hopf(eq, *sp, c, a, c);
          for (auto it = towards_c.rbegin(); it != towards_c.rend(); ++it) points.push_back(std::move(*it));
        }
      }
    }
    b.points = std::move(points);
  }
}

ContinuationRun with_special_rows(const Params& p, ContinuationRun run) {
  insert_special_rows(p, run);
  return run;
}

void insert_special_rows(const ParamsN& p, ContinuationRunN& run) {
  const StaticEquationsN eq(p, run.param, run.from, ld(run.to) - ld(run.from));
  for (auto& b : run.branches) {
    std::vector<std::vector<const SpecialPointN*>> after(b.points.size());
    for (const auto& sp : b.specials) {
      // next_point is the bracketing point after it along the branch.
      if (!sp.converged || sp.next_point < 1 || std::size_t(sp.next_point) >= b.points.size()) continue;
      after[std::size_t(sp.next_point) - 1].push_back(&sp);
    }
    std::vector<BranchPointN> points;
    std::vector<std::size_t> added(b.points.size(), 0);  // rows inserted after point i
    points.reserve(b.points.size() + 2 * b.specials.size());
    for (std::size_t i = 0; i < b.points.size(); ++i) {
      points.push_back(b.points[i]);
      const auto& here = after[i];
      if (here.empty()) continue;
      const std::size_t before = points.size();
      const BranchPointN& a = b.points[i];
      const BranchPointN& c = b.points[i + 1];
      const bool flips = a.spectrum.stability != c.spectrum.stability || a.spectrum.n_unstable != c.spectrum.n_unstable;
      for (const SpecialPointN* sp : here) {
        BranchPointN row;
        row.parameter = sp->parameter;
        row.position = sp->position;
        row.label = sp->label;
        const auto z = eq.scaled(sp->position, sp->parameter);
        const Linearization<ld, any_balls> lin = eq.linearization(z);
        row.spectrum = b.family == Family::balanced
                           ? compute_normal_spectrum(lin, balanced_tangent_basis(eq.params(z), sp->position))
                           : compute_spectrum<any_balls>(lin);
        row.residual = static_residual<any_balls>(eq.params(z), sp->position);
        const auto side = [&](const BranchPointN& s) {
          BranchPointN r = row;
          r.spectrum.stability = s.spectrum.stability;
          r.spectrum.n_unstable = s.spectrum.n_unstable;
          return r;
        };
        if (!flips) {
          points.push_back(side(a));
        } else if (here.size() == 1) {
          points.push_back(side(a));
          points.push_back(side(c));
        } else {
          points.push_back(row);
        }
      }
      added[i] = points.size() - before;
    }
    // next_point indexes the points: shift it past the rows inserted before it.
    for (auto& sp : b.specials) {
      std::size_t inserted = 0;
      for (std::size_t i = 0; i < std::size_t(std::max(sp.next_point, 0)) && i < added.size(); ++i) inserted += added[i];
      sp.next_point += int(inserted);
    }
    b.points = std::move(points);
  }
}

ContinuationRunN with_special_rows(const ParamsN& p, ContinuationRunN run) {
  insert_special_rows(p, run);
  return run;
}

}  // namespace abu
