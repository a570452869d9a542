// The shooting mesh of a cycle (docs/model.md §17.2, §17.9): the points' phases
// theta_0 = 0 < theta_1 < ... < theta_{M-1} < 1 (interval j from theta_j to theta_{j+1},
// theta_M = 1), the weights of the unknowns (sqrt of each interval's fraction, so that the
// arclength of the unknowns is the orbit's L2 norm whatever M), and the choice of a new mesh
// that spreads the transition matrices' growth evenly over the intervals. Internal to
// src/dynamics (cycle_problem.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace abu::detail {

class CycleMesh {
 public:
  CycleMesh() = default;
  /// M equal intervals; weighted: the unknowns of interval j carry sqrt(theta_{j+1} - theta_j)
  /// (else 1: the stiff route keeps its unweighted unknowns).
  static CycleMesh uniform(int m, bool weighted) {
    std::vector<double> theta(std::size_t(std::max(m, 1)));
    for (std::size_t j = 0; j < theta.size(); ++j) theta[j] = double(j) / double(theta.size());
    return CycleMesh(std::move(theta), weighted, true);
  }
  /// Any nodes (theta[0] = 0, ascending, below 1), weighted.
  static CycleMesh nodes(std::vector<double> theta) { return CycleMesh(std::move(theta), true, false); }

  int intervals() const { return int(theta_.size()); }
  double node(int j) const { return j >= intervals() ? 1.0 : theta_[std::size_t(j)]; }
  double fraction(int j) const { return node(j + 1) - node(j); }
  double weight(int j) const { return weight_[std::size_t(j % intervals())]; }
  bool is_uniform() const { return uniform_; }
  bool weighted() const { return weighted_; }

 private:
  CycleMesh(std::vector<double> theta, bool weighted, bool uniform)
      : theta_(std::move(theta)), weighted_(weighted), uniform_(uniform) {
    weight_.resize(theta_.size());
    for (int j = 0; j < intervals(); ++j) weight_[std::size_t(j)] = weighted ? std::sqrt(fraction(j)) : 1.0;
  }
  std::vector<double> theta_{0.0}, weight_{1.0};
  bool weighted_ = true, uniform_ = true;
};

/// A new mesh for an orbit of largest Floquet multiplier e^{log_largest} whose interval j has the
/// growth g_j = ln max(1, |Phi_j|_2) (the transition matrices in the scaled state): M' =
/// clamp(ceil((max(log_largest, 0) + G) / G), m_min, m_max) intervals (G = target, the growth
/// per interval aimed at), over which the contents g_j + G theta-fraction (the second term keeps
/// intervals where the flow does not grow from becoming arbitrarily long) are spread evenly, each
/// taken uniform within its old interval. M' comes from the product's growth, not from the sum
/// of the g_j: that sum also counts each short interval's transient (non-normal) growth, which
/// does not compound, and would ask for ever more intervals as they shrink. Empty if the mesh
/// should stay: M' is M and no interval holds more than 1.5 times the average content
/// (hysteresis: a mesh is not re-chosen for small changes of the orbit).
inline std::vector<double> equidistributed_nodes(const CycleMesh& mesh, const std::vector<double>& growth,
                                                 double log_largest, double target, int m_min, int m_max) {
  const int m = mesh.intervals();
  std::vector<double> content(static_cast<std::size_t>(m));
  double total = 0, largest = 0;
  for (int j = 0; j < m; ++j) {
    content[std::size_t(j)] = std::max(growth[std::size_t(j)], 0.0) + target * mesh.fraction(j);
    total += content[std::size_t(j)];
    largest = std::max(largest, content[std::size_t(j)]);
  }
  const double needed = (std::max(log_largest, 0.0) + target) / target;
  const int wanted = std::clamp(int(std::ceil(needed - 1e-9)), std::max(m_min, 1), std::max(m_max, m_min));
  if (wanted == m && largest <= 1.5 * total / m) return {};
  std::vector<double> theta(std::size_t(wanted), 0.0);
  double below = 0;  // content of the old intervals before j
  int j = 0;
  for (int i = 1; i < wanted; ++i) {
    const double level = total * double(i) / double(wanted);
    while (j < m - 1 && below + content[std::size_t(j)] < level) below += content[std::size_t(j++)];
    const double inside = content[std::size_t(j)] > 0 ? (level - below) / content[std::size_t(j)] : 0.0;
    theta[std::size_t(i)] = mesh.node(j) + std::clamp(inside, 0.0, 1.0) * mesh.fraction(j);
  }
  // Strictly ascending (a node can only coincide with the last after rounding).
  for (int i = 1; i < wanted; ++i)
    if (!(theta[std::size_t(i)] > theta[std::size_t(i - 1)])) return {};
  if (!(theta.back() < 1)) return {};
  return theta;
}

}  // namespace abu::detail
