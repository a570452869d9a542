// Eigenvalues of a product of matrices by factor-wise orthogonal iteration (floquet.hpp,
// docs/model.md §17.4).
#include "abu/linear/floquet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace abu {
namespace {

// A_k Q_{k-1} = Q_k R_k with diag(R_k) >= 0 (the sign choice makes W = Q_0^T Q_m tend to
// the identity on converged real eigenvalues, so that the test below sees a fixed matrix).
void qr_step(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q_in, Eigen::MatrixXd& q_out, Eigen::MatrixXd& r,
             Eigen::MatrixXd& work) {
  work.noalias() = a * q_in;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(work);
  q_out = qr.householderQ();
  r = qr.matrixQR().triangularView<Eigen::Upper>();
  for (Eigen::Index j = 0; j < r.rows(); ++j)
    if (r(j, j) < 0) {
      r.row(j) *= -1;
      q_out.col(j) *= -1;
    }
}

}  // namespace

ProductEigenvalues product_eigenvalues(const std::vector<Eigen::MatrixXd>& factors,
                                       const ProductEigenvalueOptions& options) {
  ProductEigenvalues out;
  if (factors.empty()) {
    out.status.merge(Outcome::numerical_issue, "no factors");
    return out;
  }
  const Eigen::Index n = factors.front().rows();
  for (const Eigen::MatrixXd& a : factors) {
    if (a.rows() != n || a.cols() != n || n == 0) {
      out.status.merge(Outcome::numerical_issue, "the factors are not square matrices of one size");
      return out;
    }
    if (!a.allFinite()) {
      out.status.merge(Outcome::numerical_issue, "a factor has a non-finite entry");
      return out;
    }
  }
  const std::size_t m = factors.size();
  std::vector<Eigen::MatrixXd> r(m, Eigen::MatrixXd(n, n));
  Eigen::MatrixXd q0 = Eigen::MatrixXd::Identity(n, n), qa(n, n), qb(n, n), work(n, n), w(n, n);
  // history[s][j]: |W_21| at boundary j (leading j + 1 columns) after sweep s.
  std::vector<std::vector<double>> history;
  std::vector<char> kept(std::size_t(std::max<Eigen::Index>(n - 1, 0)), 0);
  const double tol = options.tolerance;
  for (int sweep = 1;; ++sweep) {
    qa = q0;
    for (std::size_t k = 0; k < m; ++k) {
      qr_step(factors[k], qa, qb, r[k], work);
      std::swap(qa, qb);
    }
    w.noalias() = q0.transpose() * qa;
    std::vector<double> b(kept.size());
    for (Eigen::Index j = 1; j < n; ++j) b[std::size_t(j - 1)] = w.bottomLeftCorner(n - j, j).norm();
    history.push_back(b);
    out.sweeps = sweep;
    // A boundary is kept once below the tolerance in two consecutive sweeps (a complex
    // pair's rotation could pass close to 0 once). It is given up, its two sides solved
    // together from their block product, when its observed rate (the moduli ratio across
    // it) is above merge_rate: such a product loses at most about log10(1/merge_rate)
    // digits to the ratio, and iterating it apart would cost ln(tol)/ln(rate) sweeps (47
    // on the viscous cycle branch, whose fast pairs differ by 0.53: a tenth of its cost per
    // orbit, model.md §17.9). It is given up as well when the rate would not bring it to
    // the tolerance within the budget. The rate compares the largest |W_21| of the last
    // four sweeps with that of the four before: inside a complex pair the block rotates
    // instead of decaying, and single sweeps four apart could catch it on its way down.
    const auto window_max = [&](std::size_t j, std::size_t newest) {
      double largest = 0;
      for (std::size_t i = newest - 3; i <= newest; ++i) largest = std::max(largest, history[i][j]);
      return largest;
    };
    bool undecided = false;
    for (std::size_t j = 0; j < kept.size(); ++j) {
      kept[j] = sweep >= 2 && b[j] <= tol && history[history.size() - 2][j] <= tol;
      if (kept[j]) continue;
      if (sweep < 8) {
        undecided = true;
        continue;
      }
      const double before = window_max(j, history.size() - 5);
      const double rate = before > 0 ? std::pow(window_max(j, history.size() - 1) / before, 0.25) : 1.0;
      if (rate >= options.merge_rate) continue;
      const double needed = rate < 1 && b[j] > 0 ? std::log(tol / b[j]) / std::log(rate) + 1 : 1e300;
      if (sweep + needed <= options.max_sweeps) undecided = true;
    }
    if (!undecided || sweep >= options.max_sweeps) break;
    q0 = qa;  // the next sweep starts where this one ended (orthogonal iteration)
  }
  // The last sweep: Q_k^T A_k Q_{k-1} = R_k (k < m), Q_0^T A_m Q_{m-1} = W R_m.
  const Eigen::MatrixXd last = w * r[m - 1];
  std::vector<std::pair<double, std::complex<double>>> found;  // (log modulus, unit-modulus direction or 0)
  Eigen::Index a = 0;
  for (Eigen::Index j = 1; j <= n; ++j) {
    if (j < n && !kept[std::size_t(j - 1)]) continue;
    const Eigen::Index s = j - a;
    if (j < n) out.backward_error = std::max(out.backward_error, history.back()[std::size_t(j - 1)]);
    out.clusters.push_back(int(s));
    // The cluster's block of the product, multiplied out with the running norm factored off.
    Eigen::MatrixXd p = Eigen::MatrixXd::Identity(s, s);
    double log_scale = 0;
    bool singular = false;
    for (std::size_t k = 0; k < m && !singular; ++k) {
      const Eigen::MatrixXd block = k + 1 < m ? Eigen::MatrixXd(r[k].block(a, a, s, s)) : Eigen::MatrixXd(last.block(a, a, s, s));
      p = block * p;
      const double norm = p.norm();
      if (!(norm > 0)) {
        singular = true;
        break;
      }
      p /= norm;
      log_scale += std::log(norm);
    }
    if (singular) {
      for (Eigen::Index i = 0; i < s; ++i) found.emplace_back(-std::numeric_limits<double>::infinity(), 0.0);
    } else if (s == 1) {
      found.emplace_back(log_scale + std::log(std::abs(p(0, 0))), p(0, 0) < 0 ? -1.0 : 1.0);
    } else {
      Eigen::EigenSolver<Eigen::MatrixXd> es(p, false);
      if (es.info() != Eigen::Success) {
        out.status.merge(Outcome::numerical_issue, "the eigenvalues of a cluster's product did not converge");
        return out;
      }
      for (Eigen::Index i = 0; i < s; ++i) {
        const std::complex<double> v = es.eigenvalues()(i);
        const double modulus = std::abs(v);
        if (modulus > 0)
          found.emplace_back(log_scale + std::log(modulus), v / modulus);
        else
          found.emplace_back(-std::numeric_limits<double>::infinity(), 0.0);
      }
    }
    a = j;
  }
  std::stable_sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
    if (x.first != y.first) return x.first > y.first;
    return x.second.imag() > y.second.imag();
  });
  for (const auto& [log_modulus, direction] : found) {
    out.log_moduli.push_back(log_modulus);
    out.arguments.push_back(std::arg(direction));
    out.values.push_back(std::isfinite(log_modulus) ? std::exp(log_modulus) * direction : std::complex<double>(0.0));
  }
  return out;
}

DeflatedProductEigenvalues deflated_product_eigenvalues(const std::vector<Eigen::MatrixXd>& factors,
                                                        const std::vector<Eigen::VectorXd>& chain,
                                                        const ProductEigenvalueOptions& options) {
  DeflatedProductEigenvalues out;
  const std::size_t m = factors.size();
  if (m == 0 || chain.size() != m) {
    out.eigen.status.merge(Outcome::numerical_issue, "no factors, or a chain of another length");
    return out;
  }
  const Eigen::Index n = factors.front().rows();
  std::vector<Eigen::MatrixXd> bases(m);
  for (std::size_t k = 0; k < m; ++k) {
    if (chain[k].size() != n || !(chain[k].norm() > 0) || !chain[k].allFinite() || factors[k].rows() != n ||
        factors[k].cols() != n || !factors[k].allFinite()) {
      out.eigen.status.merge(Outcome::numerical_issue, "a chain vector is zero or of the wrong size, or a factor is not "
                                                        "square of the chain's size and finite");
      return out;
    }
    // An orthonormal basis whose first vector is +- v_k (the sign cancels in prod c_k: each
    // basis enters one factor and its inverse the next).
    bases[k] = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd(chain[k])).householderQ();
  }
  std::vector<Eigen::MatrixXd> reduced(m);
  double log_c = 0;
  bool negative = false;
  for (std::size_t k = 0; k < m; ++k) {
    const Eigen::MatrixXd f = bases[(k + 1) % m].transpose() * factors[k] * bases[k];
    log_c += std::log(std::abs(f(0, 0)));
    negative = negative != (f(0, 0) < 0);
    out.chain_error = std::max(out.chain_error, f.col(0).tail(n - 1).norm() / factors[k].norm());
    reduced[k] = f.bottomRightCorner(n - 1, n - 1);
  }
  if (n > 1) {
    out.eigen = product_eigenvalues(reduced, options);
    if (!out.eigen.status.ok()) return out;
  }
  // The trivial multiplier in the descending order (after any of equal modulus).
  std::size_t at = 0;
  while (at < out.eigen.log_moduli.size() && out.eigen.log_moduli[at] >= log_c) ++at;
  const double direction = negative ? -1.0 : 1.0;
  out.trivial = at;
  out.eigen.log_moduli.insert(out.eigen.log_moduli.begin() + long(at), log_c);
  out.eigen.arguments.insert(out.eigen.arguments.begin() + long(at), negative ? std::acos(-1.0) : 0.0);
  out.eigen.values.insert(out.eigen.values.begin() + long(at),
                          std::isfinite(log_c) ? std::complex<double>(direction * std::exp(log_c)) : 0.0);
  // Its cluster (of one) after the clusters of the values before it.
  std::size_t before = 0, c = 0;
  while (c < out.eigen.clusters.size() && before + std::size_t(out.eigen.clusters[c]) <= at)
    before += std::size_t(out.eigen.clusters[c++]);
  out.eigen.clusters.insert(out.eigen.clusters.begin() + long(c), 1);
  out.eigen.backward_error = std::max(out.eigen.backward_error, out.chain_error);
  return out;
}

CycleTestValues cycle_test_values(const std::vector<std::complex<double>>& multipliers,
                                  const std::vector<double>& log_moduli) {
  std::size_t trivial = 0;
  for (std::size_t i = 1; i < multipliers.size(); ++i)
    if (std::abs(multipliers[i] - 1.0) < std::abs(multipliers[trivial] - 1.0)) trivial = i;
  return cycle_test_values(multipliers, log_moduli, trivial);
}

CycleTestValues cycle_test_values(const std::vector<std::complex<double>>& multipliers,
                                  const std::vector<double>& log_moduli, std::size_t trivial) {
  CycleTestValues out;
  const std::size_t n = multipliers.size();
  if (n == 0 || log_moduli.size() != n || trivial >= n) return out;
  out.trivial = trivial;
  out.trivial_distance = std::abs(multipliers[out.trivial] - 1.0);
  std::complex<double> pd = 1, ns = 1;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == out.trivial) continue;
    if (log_moduli[i] > 0) ++out.unstable;
    if (std::abs(log_moduli[i]) < 0.05 && multipliers[i].imag() != 0) out.complex_pair_near_circle = true;
    pd *= 1.0 + multipliers[i];
    for (std::size_t j = i + 1; j < n; ++j)
      if (j != out.trivial) ns *= multipliers[i] * multipliers[j] - 1.0;
  }
  out.period_doubling = pd.real();
  out.neimark_sacker = ns.real();
  return out;
}

double multiplier_jump(const std::vector<std::complex<double>>& before, const std::vector<std::complex<double>>& after) {
  if (before.size() != after.size()) return std::numeric_limits<double>::infinity();
  const auto clamp2 = [](std::complex<double> z) { return std::abs(z) > 2 ? 2.0 * z / std::abs(z) : z; };
  std::vector<char> used(before.size(), 0);
  double jump = 0;
  for (const std::complex<double>& a : after) {
    std::size_t best = before.size();
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < before.size(); ++i)
      if (!used[i] && std::abs(clamp2(before[i]) - clamp2(a)) < d) d = std::abs(clamp2(before[i]) - clamp2(a)), best = i;
    if (best < before.size()) used[best] = 1;
    jump = std::max(jump, d);
  }
  return jump;
}

}  // namespace abu
