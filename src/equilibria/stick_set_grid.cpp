// n >= 3 balls: the stick set on a grid of G points per angle (the stated resolution) and
// its components by a flood fill with the torus wrap in every angle (model.md §14.3).
#include "stick_set_model.hpp"

#include <algorithm>
#include <deque>

#include "abu/core/cancel.hpp"

namespace abu::stick_detail {

StickSet sampled_set(const StickModel& m, const StickSetOptions& o, std::vector<StickSeed> seeds) {
  StickSet S;
  const int n = m.n;
  S.n_balls = n;
  S.sampled = true;
  S.seeds = std::move(seeds);
  int G = int(std::floor(std::pow(double(o.grid_budget), 1.0 / n) + 1e-9));
  G = std::max(G, 4);
  S.grid_points_per_angle = G;
  S.resolution = two_pi / G;
  long total = 1;
  for (int i = 0; i < n; ++i) total *= G;
  std::vector<int> label(std::size_t(total), -2);  // -2 outside, -1 inside unlabelled
  std::vector<double> qabs(std::size_t(total), 0.0);
  
  std::vector<double> beta(static_cast<std::size_t>(n), 0.0);
  long inside_count = 0;
  double qsum = 0.0, mx = 0.0;
  for (long cell = 0; cell < total; ++cell) {
    if ((cell & 0xffff) == 0) throw_if_stopped("stick set");
    long r = cell;
    for (int i = 0; i < n; ++i) {
      beta[std::size_t(i)] = two_pi * double(r % G) / G;
      r /= G;
    }
    const double e = m.excess(beta.data());
    mx = std::max(mx, e + 1.0);
    if (e <= 0.0) {
      label[std::size_t(cell)] = -1;
      ++inside_count;
      qabs[std::size_t(cell)] = std::abs(m.q(beta.data()));
      qsum += qabs[std::size_t(cell)];
    }
  }
  S.max_abs_s = mx;
  const double cell_volume = std::pow(S.resolution, n);
  S.area = double(inside_count) * cell_volume;
  S.area_fraction = double(inside_count) / double(total);
  S.whole_torus = inside_count == total;
  S.mean_q_abs = inside_count ? qsum / double(inside_count) : 0.0;
  // flood fill with the torus wrap in every angle
  std::vector<long> stride;
  for (long st = 1; int(stride.size()) < n; st *= G) stride.push_back(st);
  std::vector<std::vector<std::vector<char>>> proj;  // per component, per ball: occupied grid values
  for (long cell = 0; cell < total; ++cell) {
    if (label[std::size_t(cell)] != -1) continue;
    const int c = int(S.components.size());
    S.components.emplace_back();
    auto& comp = S.components.back();
    std::vector<std::vector<char>> occ(std::size_t(n), std::vector<char>(std::size_t(G), 0));
    std::deque<long> queue{cell};
    label[std::size_t(cell)] = c;
    long count = 0;
    double best = -1.0;
    long best_cell = cell;
    while (!queue.empty()) {
      const long x = queue.front();
      queue.pop_front();
      ++count;
      comp.q_abs_integral += qabs[std::size_t(x)] * cell_volume;
      if (qabs[std::size_t(x)] > best) best = qabs[std::size_t(x)], best_cell = x;
      for (int i = 0; i < n; ++i) {
        const long coord = (x / stride[std::size_t(i)]) % G;
        occ[std::size_t(i)][std::size_t(coord)] = 1;
        for (int d : {-1, 1}) {
          const long nc = (coord + d + G) % G;
          const long y = x + (nc - coord) * stride[std::size_t(i)];
          if (label[std::size_t(y)] == -1) {
            label[std::size_t(y)] = c;
            queue.push_back(y);
          }
        }
      }
    }
    comp.area = double(count) * cell_volume;
    comp.q_abs_max = best;
    comp.beta_at_max.resize(std::size_t(n));
    for (int i = 0; i < n; ++i)
      comp.beta_at_max[std::size_t(i)] = two_pi * double((best_cell / stride[std::size_t(i)]) % G) / G;
    comp.spread.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) {
      // shortest covering arc of the occupied grid values (each value stands for its cell)
      const auto& v = occ[std::size_t(i)];
      int gap = 0, run = 0, first_run = -1;
      for (int k = 0; k < 2 * G; ++k) {
        if (!v[std::size_t(k % G)]) {
          ++run;
        } else {
          if (first_run < 0) first_run = run;
          gap = std::max(gap, run);
          run = 0;
        }
      }
      gap = std::max(gap, std::min(run, G));
      comp.spread[std::size_t(i)] = two_pi * double(G - gap) / G;
    }
  }
  // seeds: nearest grid point
  for (std::size_t k = 0; k < S.seeds.size(); ++k) {
    auto& sd = S.seeds[k];
    long cell = 0;
    for (int i = 0; i < n; ++i) {
      const long g = std::lround(wrap(sd.beta[std::size_t(i)]) / S.resolution) % G;
      cell += g * stride[std::size_t(i)];
    }
    const int c = label[std::size_t(cell)];
    if (c < 0) continue;
    sd.component = c;
    S.components[std::size_t(c)].seeds.push_back(int(k));
    if (sd.anchor) S.components[std::size_t(c)].balanced_points.push_back(int(k));
  }
  S.spread.assign(std::size_t(n), 0.0);
  for (const auto& comp : S.components) {
    if (comp.q_abs_max > S.worst_q_abs_any) S.worst_q_abs_any = comp.q_abs_max, S.worst_beta_any = comp.beta_at_max;
    if (comp.balanced_points.empty()) continue;
    S.balanced_exists = true;
    if (comp.q_abs_max > S.worst_q_abs) S.worst_q_abs = comp.q_abs_max, S.worst_beta = comp.beta_at_max;
    for (int i = 0; i < n; ++i)
      S.spread[std::size_t(i)] = std::max(S.spread[std::size_t(i)], comp.spread[std::size_t(i)]);
  }
  const bool any_anchor = std::any_of(S.seeds.begin(), S.seeds.end(), [](const StickSeed& s) { return s.anchor; });
  if (!S.balanced_exists && !m.race)
    S.status = Status{Outcome::not_converged, any_anchor
                                                  ? Reason("the grid does not resolve the stick set around the balanced set")
                                                  : Reason("no balanced state in the stick set")};
  if (!S.balanced_exists && m.race)
    S.status = Status{Outcome::not_converged,
                      any_anchor ? Reason("the grid does not resolve the stick set around the race's least-|q| stable equilibrium")
                                 : Reason("the unround race has no stable equilibrium (model.md §11.4)")};
  return S;
}

}  // namespace abu::stick_detail
