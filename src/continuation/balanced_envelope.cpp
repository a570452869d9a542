#include "balanced_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace abu::n_balls {

using ld = long double;

// The envelope of the Hopf points of all samples: the parameter interval cut at every
// located HB and LP of any sample (and at the ends of every sample's branch); in each
// piece a sample counts as normally stable if every part of its branch over the piece
// is (a part: the points between two consecutive special points, all of one stability,
// as no test function changed sign between them).
BalancedEnvelope envelope_of(const std::vector<BranchN>& branches, ld from, ld to) {
  struct Part {
    ld lo, hi;
    bool stable;
  };
  BalancedEnvelope env;
  std::vector<ld> cuts{std::min(from, to), std::max(from, to)};
  std::vector<std::vector<Part>> parts;
  std::vector<int> weights;  // samples each branch stands for
  for (const auto& b : branches) {
    if (b.family != Family::balanced || b.points.empty()) continue;
    const int weight = 1 + b.images;
    env.samples += weight;
    bool hopf = false;
    std::vector<Part>& mine = parts.emplace_back();
    std::size_t next = 0;  // the next special along the branch
    for (std::size_t k = 0; k < b.points.size(); ++k) {
      const BranchPointN& pt = b.points[k];
      const bool stable = pt.spectrum.stability == Stability::stable;
      bool fresh = mine.empty();
      while (next < b.specials.size() && b.specials[next].next_point <= int(k)) {
        const SpecialPointN& sp = b.specials[next++];
        if (sp.label != Label::HB && sp.label != Label::LP) continue;
        hopf = hopf || sp.label == Label::HB;
        cuts.push_back(sp.parameter);
        if (!mine.empty()) mine.back().lo = std::min(mine.back().lo, sp.parameter), mine.back().hi = std::max(mine.back().hi, sp.parameter);
        mine.push_back({sp.parameter, sp.parameter, stable});
        fresh = false;
      }
      if (fresh) mine.push_back({pt.parameter, pt.parameter, stable});
      Part& part = mine.back();
      part.lo = std::min(part.lo, pt.parameter), part.hi = std::max(part.hi, pt.parameter);
      part.stable = part.stable && stable;
    }
    env.samples_with_hopf += hopf ? weight : 0;
    weights.push_back(weight);
    cuts.push_back(b.points.front().parameter), cuts.push_back(b.points.back().parameter);
  }
  std::sort(cuts.begin(), cuts.end());
  const auto same = [](ld x, ld y) { return std::abs(x - y) <= 1e-12L * std::max(std::abs(x), std::abs(y)); };
  cuts.erase(std::unique(cuts.begin(), cuts.end(), same), cuts.end());
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    BalancedEnvelope::Interval iv{cuts[k], cuts[k + 1], 0, 0};
    const ld mid = (iv.from + iv.to) / 2;
    for (std::size_t b = 0; b < parts.size(); ++b) {
      bool covered = false, stable = true;
      for (const Part& part : parts[b])
        if (part.lo <= mid && mid <= part.hi) covered = true, stable = stable && part.stable;
      iv.samples += covered ? weights[b] : 0;
      iv.stable += covered && stable ? weights[b] : 0;
    }
    env.intervals.push_back(iv);
  }
  return env;
}

}  // namespace abu::n_balls
