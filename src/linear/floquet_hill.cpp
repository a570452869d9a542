// Hill's method for the balanced state's Floquet multipliers (docs/model.md §10.6).
#include "abu/linear/floquet_hill.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include <Eigen/Eigenvalues>

#include "abu/core/cancel.hpp"

namespace abu {

namespace {

using cd = std::complex<double>;
// Hill's eigenproblem in double or long double (HillOptions::extended): the stiff coulomb
// rates (1e8 1/s) set |H|, and the slow ball exponents (1e-7 1/s there) drown in double's
// eps |H|; long double costs ~20 times more.

struct Selection {
  std::vector<cd> exponents;
  std::vector<Eigen::MatrixXcd> vectors;  // with keep_vectors: dim x (2N + 1), harmonic first[i] + j
  std::vector<int> first;
  bool ok = false;
};

template <class R>
Selection solve_hill(const Eigen::Matrix<std::complex<R>, Eigen::Dynamic, Eigen::Dynamic>& J0,
                     const Eigen::Matrix<std::complex<R>, Eigen::Dynamic, Eigen::Dynamic>& Jp,
                     const Eigen::Matrix<std::complex<R>, Eigen::Dynamic, Eigen::Dynamic>& Jm, double omega, int N,
                     bool keep_vectors) {
  using cl = std::complex<R>;
  using MatrixXcl = Eigen::Matrix<cl, Eigen::Dynamic, Eigen::Dynamic>;
  const Eigen::Index n = J0.rows();
  const Eigen::Index blocks = 2 * N + 1;
  MatrixXcl H = MatrixXcl::Zero(blocks * n, blocks * n);
  for (Eigen::Index b = 0; b < blocks; ++b) {
    const double k = double(b - N);
    H.block(b * n, b * n, n, n) = J0;
    H.block(b * n, b * n, n, n).diagonal().array() -= cl(R(0), R(2) * R(omega) * R(k));
    if (b > 0) H.block(b * n, (b - 1) * n, n, n) = Jp;           // x_{k-1}
    if (b + 1 < blocks) H.block(b * n, (b + 1) * n, n, n) = Jm;  // x_{k+1}
  }
  Eigen::ComplexEigenSolver<MatrixXcl> es(H, true);
  Selection sel;
  if (es.info() != Eigen::Success) return sel;
  const Eigen::Index total = blocks * n;
  std::vector<double> centroid(std::size_t(total), 0.0);
  for (Eigen::Index e = 0; e < total; ++e) {
    double w = 0.0, wk = 0.0;
    for (Eigen::Index b = 0; b < blocks; ++b) {
      const double m = double(es.eigenvectors().col(e).segment(b * n, n).squaredNorm());
      w += m;
      wk += m * double(b - N);
    }
    centroid[std::size_t(e)] = w > 0.0 ? wk / w : 1e300;
  }
  std::vector<Eigen::Index> order(static_cast<std::size_t>(total));
  std::iota(order.begin(), order.end(), Eigen::Index(0));
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return centroid[std::size_t(a)] < centroid[std::size_t(b)];
  });
  // The run of n consecutive centroids spanning < 1 that lies closest to the middle.
  double best = 1e300;
  std::size_t first = 0;
  for (std::size_t i = 0; i + std::size_t(n) <= order.size(); ++i) {
    const double lo = centroid[std::size_t(order[i])], hi = centroid[std::size_t(order[i + std::size_t(n) - 1])];
    if (!(hi - lo < 1.0)) continue;
    const double off = std::max(std::abs(lo), std::abs(hi));
    if (off < best) best = off, first = i;
  }
  if (best == 1e300) return sel;
  for (std::size_t i = first; i < first + std::size_t(n); ++i) {
    const cd lambda(double(es.eigenvalues()(order[i]).real()), double(es.eigenvalues()(order[i]).imag()));
    // Im lambda modulo 2 omega into (-omega, omega].
    const double shift = std::ceil((lambda.imag() - omega) / (2.0 * omega));
    const double im = lambda.imag() - 2.0 * omega * shift;
    sel.exponents.push_back({lambda.real(), im});
    if (keep_vectors) {
      // lambda - 2 i omega m carries the same motion with every harmonic index raised by m.
      Eigen::MatrixXcd x(n, blocks);
      for (Eigen::Index b = 0; b < blocks; ++b)
        for (Eigen::Index r = 0; r < n; ++r) {
          const auto& c = es.eigenvectors()(b * n + r, order[i]);
          x(r, b) = cd(double(c.real()), double(c.imag()));
        }
      sel.vectors.push_back(std::move(x));
      sel.first.push_back(-N + int(shift));
    }
  }
  sel.ok = true;
  return sel;
}

std::vector<cd> multipliers_of(const std::vector<cd>& exponents, double period) {
  std::vector<cd> rho;
  for (const cd& l : exponents) rho.push_back(std::exp(l * period));
  return rho;
}

}  // namespace

void floquet_order(std::vector<std::complex<double>>& rho, double rel) {
  // Pair each multiplier off the real axis with its conjugate partner and make them exact.
  std::vector<bool> done(rho.size(), false);
  for (std::size_t i = 0; i < rho.size(); ++i) {
    if (done[i]) continue;
    done[i] = true;
    const double scale = std::abs(rho[i]);
    if (std::abs(rho[i].imag()) <= rel * scale) {
      rho[i] = {rho[i].real(), 0.0};
      continue;
    }
    std::size_t partner = rho.size();
    double dist = rel * scale;
    for (std::size_t j = 0; j < rho.size(); ++j)
      if (!done[j] && std::abs(rho[j] - std::conj(rho[i])) <= dist) dist = std::abs(rho[j] - std::conj(rho[i])), partner = j;
    if (partner == rho.size()) continue;
    done[partner] = true;
    const cd mean = 0.5 * (rho[i] + std::conj(rho[partner]));
    rho[i] = mean;
    rho[partner] = std::conj(mean);
  }
  std::sort(rho.begin(), rho.end(), [](const cd& a, const cd& b) {
    const double ma = std::abs(a), mb = std::abs(b);
    if (ma != mb) return ma > mb;
    return a.imag() > b.imag();
  });
}

PeriodicJacobian restricted(const PeriodicJacobian& J, const Eigen::MatrixXd& V) {
  PeriodicJacobian R;
  R.omega = J.omega;
  R.mean = V.transpose() * J.mean * V;
  R.cos2 = V.transpose() * J.cos2 * V;
  R.sin2 = V.transpose() * J.sin2 * V;
  return R;
}

template <class R>
HillResult hill_in(const PeriodicJacobian& J, const HillOptions& options);

HillResult hill_multipliers(const PeriodicJacobian& J, const HillOptions& options) {
  // J comes scaled (anisotropic_support.hpp): no further balancing here.
  return options.extended ? hill_in<long double>(J, options) : hill_in<double>(J, options);
}

template <class R>
HillResult hill_in(const PeriodicJacobian& J, const HillOptions& options) {
  using cl = std::complex<R>;
  using MatrixXcl = Eigen::Matrix<cl, Eigen::Dynamic, Eigen::Dynamic>;
  const MatrixXcl J0 = J.mean.cast<R>().template cast<cl>();
  const MatrixXcl Jc = J.cos2.cast<R>().template cast<cl>(), Js = J.sin2.cast<R>().template cast<cl>();
  const MatrixXcl Jp = cl(R(0.5)) * (Jc - cl(R(0), R(1)) * Js);  // multiplies x_{k-1}
  const MatrixXcl Jm = cl(R(0.5)) * (Jc + cl(R(0), R(1)) * Js);  // multiplies x_{k+1}
  const double T = J.period();

  HillResult r;
  std::vector<cd> previous;
  for (int N = options.first_harmonics; N <= options.max_harmonics; N += options.harmonics_step) {
    throw_if_stopped("Hill's method (Floquet multipliers)");
    Selection s = solve_hill<R>(J0, Jp, Jm, J.omega, N, options.keep_vectors);
    r.harmonics = N;
    if (!s.ok) {
      r.status = {Outcome::numerical_issue,
                  "Hill's method: no run of eigenvectors centred in the harmonic range (ladder selection failed)"};
      continue;
    }
    std::vector<std::size_t> idx(s.exponents.size());
    std::iota(idx.begin(), idx.end(), std::size_t(0));
    std::vector<cd> rho = multipliers_of(s.exponents, T);
    // Sort exponents with their multipliers.
    std::vector<std::pair<cd, cd>> both;
    for (std::size_t i = 0; i < rho.size(); ++i) both.push_back({rho[i], s.exponents[i]});
    floquet_order(rho);
    std::vector<cd> lam;
    r.vectors.clear();
    r.first_harmonic.clear();
    for (const cd& x : rho) {
      auto it = std::min_element(both.begin(), both.end(), [&](const auto& a, const auto& b) {
        return std::abs(a.first - x) < std::abs(b.first - x);
      });
      cd l = it->second;
      if (x.imag() == 0.0) l = {l.real(), x.real() >= 0.0 ? 0.0 : J.omega};  // a real multiplier: Im exact
      lam.push_back(l);
      if (options.keep_vectors) {
        const std::size_t at = std::size_t(it - both.begin());
        r.vectors.push_back(s.vectors[at]);
        // Im moved from it->second's to l's by 2 omega m: the harmonics move by -m.
        r.first_harmonic.push_back(s.first[at] + int(std::lround((it->second.imag() - l.imag()) / (2.0 * J.omega))));
      }
    }
    r.multipliers = rho;
    r.exponents = lam;
    if (!previous.empty() && previous.size() == rho.size()) {
      double change = 0.0;
      for (std::size_t i = 0; i < rho.size(); ++i)
        change = std::max(change, std::abs(rho[i] - previous[i]) / (std::abs(rho[i]) + options.tolerance));
      r.truncation_change = change;
      // Double rounding leaves ~1e-11 of noise in the multipliers (|H| eps times pi/omega),
      // so double stops at 100 times the tolerance; long double at the tolerance.
      if (change <= (options.extended ? 1.0 : 100.0) * options.tolerance) {
        r.status = {};
        return r;
      }
    }
    r.status = {Outcome::not_converged, "Hill's method: the multipliers still change with the truncation"};
    previous = rho;
  }
  return r;
}

}  // namespace abu
