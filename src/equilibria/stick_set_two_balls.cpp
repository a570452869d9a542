// Two balls: the stick set from the column scan (model.md §14.3): area and integral of |q|
// by adaptive Simpson over beta_1, the components' areas, maxima and seeds, the spreads of
// the balanced components, the totals V, V_E, mean |q|.
#include "stick_set_model.hpp"

#include <algorithm>
#include <utility>
#include <unordered_map>

#include "abu/core/cancel.hpp"

namespace abu::stick_detail {

StickSet two_ball_set(const StickModel& m, const StickSetOptions& o,
                      std::vector<StickSeed> seeds) {
  StickSet S;
  S.n_balls = 2;
  S.seeds = std::move(seeds);
  // island widths at the seeds, from the Jacobian of s (model.md §14.3)
  std::vector<std::pair<double, double>> win1, win2;
  double smallest_width = two_pi / o.columns;
  for (const auto& sd : S.seeds) {
    const double b[2] = {sd.beta[0], sd.beta[1]};
    const auto J = s_jacobian(m, b);
    const double row = std::max(std::fabs(J[0][0]) + std::fabs(J[0][1]), std::fabs(J[1][0]) + std::fabs(J[1][1]));
    const double width = row > 0 ? std::min(1.0, 1.0 / row) : 1.0;
    smallest_width = std::min(smallest_width, width / 24.0);
    win1.push_back({sd.beta[0], width});
    win2.push_back({sd.beta[1], width});
  }
  const std::vector<double> cols1 = sample_positions(o.columns, win1);
  const std::vector<double> samp2 = sample_positions(o.samples, win2);
  const TwoBallScan scan1(m, 0, samp2);
  AxisAnalysis A = analyze_axis(scan1, cols1);
  S.resolution = smallest_width;

  // --- components: the linked arcs of the scan (stick_set_columns.cpp)
  std::unordered_map<int, int> comp_of_root;
  for (auto& col : A.columns)
    for (int node : col.node) {
      const int r = A.uf.find(node);
      if (!comp_of_root.count(r)) {
        comp_of_root[r] = int(S.components.size());
        S.components.emplace_back();
      }
    }
  std::vector<int> root_of_comp(S.components.size());
  for (const auto& [r, c] : comp_of_root) root_of_comp[std::size_t(c)] = r;
  S.whole_torus = std::all_of(A.columns.begin(), A.columns.end(), [](const ColumnData& c) {
    return c.arcs.size() == 1 && c.arcs[0].length() >= two_pi;
  });
  const int n_comp = int(S.components.size());

  // --- area and integral of |q|: adaptive Simpson over beta_1 on each panel between two scan
  // columns, of E and of each component in the same panels (model.md §14.3); the error test
  // holds for each component's area, not only for their sum. An arc on a column inside a panel
  // belongs to the component of an arc on the panel's end columns it overlaps or is linked to
  // (the test that joins neighbouring columns, component_of below). The components' areas were
  // the columns' trapezoid, rescaled to the total: an island wider in beta_1 than the dense
  // columns around its seed (an "opposite" one; its mirror is the wider in beta_2) has arcs on
  // its last dense column, next to a uniform gap, and the trapezoid gave them half that gap
  // (4e-3 rad; the island is 2e-4 rad wide at mu = 1e-8): it came out 25 % larger than its
  // mirror at mu = 1e-6 and 23 times at 1e-8, the rescaling moving the excess onto the others.
  // (verdict_only: the |q| integrals stay 0; the panels are the same)
  const bool integrals = !o.verdict_only;
  std::vector<int> comp_of_node(A.uf.parent.size());
  for (auto& col : A.columns)
    for (int node : col.node) comp_of_node[std::size_t(node)] = comp_of_root[A.uf.find(node)];
  // one column's values: the totals (length of E on it, integral of |q|) and per component
  struct Values {
    std::array<double, 2> total{0.0, 0.0};
    std::vector<std::pair<int, std::array<double, 2>>> part;  // (component, its values); -1: none
    void add(int c, double length, double q) {
      total[0] += length;
      total[1] += q;
      for (auto& [k, v] : part)
        if (k == c) {
          v[0] += length, v[1] += q;
          return;
        }
      part.push_back({c, {length, q}});
    }
    std::array<double, 2> of(int c) const {
      for (const auto& [k, v] : part)
        if (k == c) return v;
      return {0.0, 0.0};
    }
  };
  std::vector<Values> at_column(A.columns.size());
  for (std::size_t j = 0; j < A.columns.size(); ++j) {
    const auto& col = A.columns[j];
    for (std::size_t k = 0; k < col.arcs.size(); ++k)
      at_column[j].add(comp_of_node[std::size_t(col.node[k])], col.arcs[k].length(),
                       integrals ? scan1.q_abs_integral(col.column, col.arcs[k]) : 0.0);
  }
  // the component of arc z of the column at c, inside the panel between scan columns j (at a)
  // and jn (at b): of an arc of theirs it overlaps or is linked to; else of the nearest column
  // beyond them, within one uniform column step of c, with such an arc (a tip whose arcs on the
  // panel's columns were shorter than the sample step, which the scan missed); else -1
  const std::size_t N = A.columns.size();
  const double uniform_step = two_pi / o.columns;
  auto component_of = [&](std::size_t j, double a, std::size_t jn, double b, double c, const Arc& z) {
    // column i at position x (x < c: left of c), by overlap or, with `link`, by linked()
    auto found_in = [&](std::size_t i, double x, bool link) {
      const auto& col = A.columns[i];
      for (std::size_t k = 0; k < col.arcs.size(); ++k)
        if (link ? (x < c ? linked(scan1, x, col.arcs[k], c, z, 6) : linked(scan1, c, z, x, col.arcs[k], 6))
                 : arcs_overlap(col.arcs[k], z))
          return comp_of_node[std::size_t(col.node[k])];
      return -1;
    };
    for (const bool link : {false, true})
      for (const auto& [i, x] : {std::pair{j, a}, std::pair{jn, b}})
        if (const int found = found_in(i, x, link); found >= 0) return found;
    for (std::size_t d = 1; 2 * d < N; ++d) {
      const std::size_t left = (j + N - d) % N, right = (jn + d) % N;
      const double to_left = wrap(c - A.columns[left].column), to_right = wrap(A.columns[right].column - c);
      if (to_left > uniform_step && to_right > uniform_step) break;
      for (const bool left_first : {to_left <= to_right, to_left > to_right}) {
        const double dist = left_first ? to_left : to_right;
        if (dist > uniform_step) continue;
        const std::size_t i = left_first ? left : right;
        const double x = left_first ? c - to_left : c + to_right;
        for (const bool link : {false, true})
          if (const int found = found_in(i, x, link); found >= 0) return found;
      }
    }
    return -1;
  };
  struct Panel {
    double a, b;
    Values fa, fm, fb;
    int depth;
  };
  double area = 0.0, qint = 0.0;
  std::vector<std::array<double, 2>> comp_sum(std::size_t(n_comp) + 1, {0.0, 0.0});  // last: no component
  std::vector<int> present;
  std::vector<std::array<std::array<double, 2>, 2>> parts;
  for (std::size_t j = 0; j < A.columns.size(); ++j) {
    throw_if_stopped("stick set");
    const std::size_t jn = (j + 1) % A.columns.size();
    const double a = A.columns[j].column;
    const double b = jn == 0 ? two_pi : A.columns[jn].column;
    auto column_values = [&](double c) {
      Values v;
      for (const auto& arc : scan1.arcs(wrap(c)))
        v.add(component_of(j, a, jn, b, c, arc), arc.length(), integrals ? scan1.q_abs_integral(wrap(c), arc) : 0.0);
      return v;
    };
    std::vector<Panel> stack{{a, b, at_column[j], column_values(0.5 * (a + b)), at_column[jn], 0}};
    while (!stack.empty()) {
      Panel P = std::move(stack.back());
      stack.pop_back();
      const double h = P.b - P.a;
      const double l = P.a + 0.25 * h, r = P.a + 0.75 * h;
      const Values fl = column_values(l), fr = column_values(r);
      // Simpson on three and on five points, their difference the error estimate
      auto simpson = [&](const std::array<double, 2>& fa, const std::array<double, 2>& f_l,
                         const std::array<double, 2>& fm, const std::array<double, 2>& f_r,
                         const std::array<double, 2>& fb) {
        std::array<std::array<double, 2>, 2> cf{};  // {coarse, fine}
        for (std::size_t k = 0; k < 2; ++k) {
          cf[0][k] = h / 6 * (fa[k] + 4 * fm[k] + fb[k]);
          cf[1][k] = h / 12 * (fa[k] + 4 * f_l[k] + 2 * fm[k] + 4 * f_r[k] + fb[k]);
        }
        return cf;
      };
      const auto total = simpson(P.fa.total, fl.total, P.fm.total, fr.total, P.fb.total);
      present.clear();
      for (const Values* v : {&std::as_const(P.fa), &fl, &std::as_const(P.fm), &fr, &std::as_const(P.fb)})
        for (const auto& part : v->part)
          if (std::find(present.begin(), present.end(), part.first) == present.end()) present.push_back(part.first);
      // the error estimate: of each component's area, not only of their sum (theirs may cancel);
      // with one component present its values are the total's, bit for bit
      double err = std::fabs(total[1][0] - total[0][0]);
      parts.clear();
      if (present.size() > 1) {
        double err_parts = 0.0;
        for (int c : present) {
          parts.push_back(simpson(P.fa.of(c), fl.of(c), P.fm.of(c), fr.of(c), P.fb.of(c)));
          err_parts += std::fabs(parts.back()[1][0] - parts.back()[0][0]);
        }
        err = std::max(err, err_parts);
      }
      if (err <= 15.0 * o.area_tolerance * h || P.depth >= 24) {
        area += total[1][0] + (total[1][0] - total[0][0]) / 15.0;
        qint += total[1][1] + (total[1][1] - total[0][1]) / 15.0;
        for (std::size_t i = 0; i < present.size(); ++i) {
          const auto& cf = parts.empty() ? total : parts[i];
          auto& sum = comp_sum[present[i] < 0 ? std::size_t(n_comp) : std::size_t(present[i])];
          for (std::size_t k = 0; k < 2; ++k) sum[k] += cf[1][k] + (cf[1][k] - cf[0][k]) / 15.0;
        }
      } else {
        stack.push_back({P.a, P.a + 0.5 * h, P.fa, fl, P.fm, P.depth + 1});
        stack.push_back({P.a + 0.5 * h, P.b, std::move(P.fm), fr, std::move(P.fb), P.depth + 1});
      }
    }
  }
  S.area = std::clamp(area, 0.0, two_pi * two_pi);
  S.area_fraction = S.area / (two_pi * two_pi);

  // best column of each component for the maximum
  struct Best {
    double w2 = -1.0;
    int column = -1, arc = -1;
    double along = 0.0;
  };
  std::vector<Best> best(S.components.size());
  for (std::size_t j = 0; j < A.columns.size(); ++j) {
    const auto& col = A.columns[j];
    for (std::size_t k = 0; k < col.arcs.size(); ++k) {
      const int c = comp_of_node[std::size_t(col.node[k])];
      const auto [w2, along] = scan1.max_w2(col.column, col.arcs[k]);
      if (w2 > best[std::size_t(c)].w2) best[std::size_t(c)] = {w2, int(j), int(k), along};
    }
  }

  // refine each component's maximum (stick_set_maxima.cpp)
  const double gabs = std::abs(m.G);
  for (std::size_t c = 0; c < S.components.size(); ++c) {
    throw_if_stopped("stick set");
    auto& comp = S.components[c];
    const Best b0 = best[c];
    const ComponentMaximum top =
        refine_component_maximum(m, scan1, A, b0.column, b0.arc,
                                 {b0.w2, A.columns[std::size_t(b0.column)].column, b0.along},
                                 4.0 * std::max(two_pi / o.samples, S.resolution));
    comp.q_abs_max = gabs * std::sqrt(std::max(0.0, top.w2));
    comp.beta_at_max = {top.column, top.along};
    comp.area = std::clamp(comp_sum[c][0], 0.0, two_pi * two_pi);
    comp.q_abs_integral = std::max(0.0, comp_sum[c][1]);
  }

  // seeds in components
  for (std::size_t k = 0; k < S.seeds.size(); ++k) {
    auto& sd = S.seeds[k];
    const auto [j, arc] = locate(A, sd.beta[0], sd.beta[1]);
    if (j < 0) continue;
    sd.component = comp_of_root[A.uf.find(A.columns[std::size_t(j)].node[std::size_t(arc)])];
    auto& comp = S.components[std::size_t(sd.component)];
    comp.seeds.push_back(int(k));
    if (sd.anchor) comp.balanced_points.push_back(int(k));
  }

  // spreads of the balanced components: beta_1 from these columns, beta_2 from the transposed scan
  const TwoBallScan scan2(m, 1, sample_positions(o.samples, win1));
  AxisAnalysis B = o.verdict_only ? AxisAnalysis{} : analyze_axis(scan2, sample_positions(o.columns, win2));
  for (std::size_t c = 0; c < S.components.size(); ++c) {
    auto& comp = S.components[c];
    if (comp.balanced_points.empty()) continue;
    if (o.verdict_only) {
      comp.spread = {0.0, 0.0};
      continue;
    }
    throw_if_stopped("stick set");
    const double s1 = column_extent(scan1, A, root_of_comp[c]);
    const auto& sd = S.seeds[std::size_t(comp.balanced_points.front())];
    const auto [j, arc] = locate(B, sd.beta[1], sd.beta[0]);
    double s2 = 0.0;
    if (j >= 0) s2 = column_extent(scan2, B, B.uf.find(B.columns[std::size_t(j)].node[std::size_t(arc)]));
    comp.spread = {s1, s2};
  }

  // totals
  S.mean_q_abs = S.area > 0 ? qint / S.area : 0.0;
  S.spread = {0.0, 0.0};
  for (const auto& comp : S.components) {
    if (comp.q_abs_max > S.worst_q_abs_any) S.worst_q_abs_any = comp.q_abs_max, S.worst_beta_any = comp.beta_at_max;
    if (comp.balanced_points.empty()) continue;
    S.balanced_exists = true;
    if (comp.q_abs_max > S.worst_q_abs) S.worst_q_abs = comp.q_abs_max, S.worst_beta = comp.beta_at_max;
    for (int i = 0; i < 2; ++i)
      S.spread[std::size_t(i)] = std::max(S.spread[std::size_t(i)], comp.spread[std::size_t(i)]);
  }
  for (auto& comp : S.components) {
    // a component wraps if its columns cover the whole circle in beta_1 with one arc each
    // reaching around in beta_2, or it covers every column
    comp.wraps = comp.area >= two_pi * two_pi * (1 - 1e-12);
  }
  if (o.trace) S.boundary = trace_boundary(m, A, std::min(0.01, 0.25 * S.resolution * 24.0 / 4.0));
  double mx = 0.0;
  if (!o.verdict_only)
    for (const auto& col : A.columns)
      for (double x : samp2) {
        const double b[2] = {col.column, x};
        mx = std::max(mx, m.excess(b) + 1.0);
      }
  S.max_abs_s = mx;
  if (!S.balanced_exists) S.status = Status{Outcome::not_converged, "no balanced state in the stick set"};
  return S;
}


}  // namespace abu::stick_detail
