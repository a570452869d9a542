// One shift of the shift-invert Arnoldi iteration (shift_invert.hpp; docs/model.md §19.1,
// the residual §19.3, the refinement §19.5), and the cache of its factorizations.
#include "shift_invert.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>

#include <Eigen/SparseLU>
#include <arpack/arpack.hpp>
#include <fmt/format.h>

namespace abu {

namespace {

using shift_invert::cplx;
using shift_invert::SparseComplexMatrix;
using ComplexLU = Eigen::SparseLU<SparseComplexMatrix, Eigen::COLAMDOrdering<int>>;
using RealLU = Eigen::SparseLU<SparseRealMatrix, Eigen::COLAMDOrdering<int>>;

// ARPACK keeps state in Fortran SAVE variables between the calls of one reverse-
// communication loop: two loops at once (threads of a map) would corrupt each other.
std::mutex& arpack_mutex() {
  static std::mutex m;
  return m;
}

// A shift as the cache's key: its exact bits (the same double shift again hits; a shift
// that differs in the last bit is another factorization, as it should be).
struct ShiftKey {
  std::uint64_t re, im;
  auto operator<=>(const ShiftKey&) const = default;
};
ShiftKey key_of(cplx s) {
  ShiftKey k{};
  const double re = s.real(), im = s.imag();
  std::memcpy(&k.re, &re, sizeof re);
  std::memcpy(&k.im, &im, sizeof im);
  return k;
}

}  // namespace

struct ShiftFactorizations::Impl {
  Eigen::Index rows = -1, nonzeros = -1;  // the pencil the entries belong to
  struct Entry {  // one of the two: real shifts take the real path (model.md §19.1)
    std::unique_ptr<ComplexLU> complex;
    std::unique_ptr<RealLU> real;
  };
  std::map<ShiftKey, Entry> lu;
};

ShiftFactorizations::ShiftFactorizations() : impl(std::make_unique<Impl>()) {}
ShiftFactorizations::~ShiftFactorizations() = default;
ShiftFactorizations::ShiftFactorizations(ShiftFactorizations&&) noexcept = default;
ShiftFactorizations& ShiftFactorizations::operator=(ShiftFactorizations&&) noexcept = default;
void ShiftFactorizations::clear() { impl->lu.clear(); }
int ShiftFactorizations::size() const { return int(impl->lu.size()); }

namespace shift_invert {

namespace {
double norm1(const SparseRealMatrix& m) {
  double best = 0.0;
  for (Eigen::Index j = 0; j < m.outerSize(); ++j) {
    double s = 0.0;
    for (SparseRealMatrix::InnerIterator it(m, j); it; ++it) s += std::abs(it.value());
    best = std::max(best, s);
  }
  return best;
}
}  // namespace

Pencil make_pencil(const SparseRealMatrix& A, const SparseRealMatrix& B, int k) {
  if (A.rows() != A.cols()) throw std::invalid_argument("sparse spectrum: A is not square");
  const bool identity_b = B.rows() == 0 && B.cols() == 0;
  if (!identity_b && (B.rows() != A.rows() || B.cols() != A.cols()))
    throw std::invalid_argument("sparse spectrum: B is not of A's size (pass a 0 x 0 B for the identity)");
  if (k < 1 || k >= A.rows() - 1)
    throw std::invalid_argument("sparse spectrum: k must satisfy 1 <= k < n - 1 (ARPACK's limit)");
  Pencil p;
  p.n = A.rows();
  p.identity_b = identity_b;
  p.a = A.cast<cplx>();
  if (identity_b) {
    p.b.resize(p.n, p.n);
    p.b.setIdentity();
    p.identity_real.resize(p.n, p.n);
    p.identity_real.setIdentity();
  } else {
    p.b = B.cast<cplx>();
  }
  p.a.makeCompressed();
  p.b.makeCompressed();
  p.norm1_a = norm1(A);
  p.norm1_b = identity_b ? 1.0 : norm1(B);
  p.a_real = &A;
  p.b_real = identity_b ? nullptr : &B;
  return p;
}

namespace {

// ARPACK's start vector: a fixed sequence (splitmix64), so that the same input gives the
// same bytes; not orthogonal to any eigenvector in practice, unlike a constant vector,
// which is orthogonal to every mode antisymmetric in a symmetric structure.
void start_vector(std::vector<cplx>& resid) {
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  auto next = [&state] {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-53 * 2.0 - 1.0;  // uniform in [-1, 1)
  };
  for (auto& r : resid) {
    const double re = next();
    r = cplx(re, next());
  }
}

// A pair with residual (19.6) and backward error (19.7) above these says the shift's run is
// unsound (finish_shift). Both: a structural zero (|lambda| ~ 1e-16) has a large residual
// relative to its modulus but a backward error at rounding.
constexpr double kUnsoundResidual = 1e-6;
constexpr double kUnsoundBackwardError = 1e-12;
// A pair with residual (19.6) above this is refined even near its shift (§19.5).
constexpr double kRefineResidual = 1e-10;

// Residual (19.6) and backward error (19.7) of (value, vec), computed afresh from A and B.
void pair_errors(const Pencil& p, cplx value, const Eigen::VectorXcd& vec, double& residual, double& backward) {
  const Eigen::VectorXcd bv = p.identity_b ? vec : (p.b * vec).eval();
  const double rn = (p.a * vec - value * bv).norm(), vn = vec.norm(), bn = bv.norm();
  const double lam = std::abs(value);
  residual = lam > 0.0 ? rn / (lam * bn) : rn / (p.norm1_a * vn);
  backward = rn / ((p.norm1_a + lam * p.norm1_b) * vn);
}

// Inverse iteration at the eigenvalue itself (model.md §19.5). With s = ARPACK's value,
// (A - s B)^-1 B has 1/(lambda - s) as its dominant eigenvalue by the factor
// |lambda_j - s| / |lambda - s| over every other (>= 1e3 when ARPACK's value is within 1e-9
// of |lambda| and the next eigenvalue 1e-6 away), so two or three steps give the vector to
// rounding, and lambda = s + 1 / (x^H y) (x unit, y = (A - s B)^-1 B x) carries an error of
// |lambda - s| times the vector's, far below eps |lambda|. A semisimple multiple eigenvalue
// is no obstacle (its eigenspace is amplified as a whole), unlike Newton on a bordered system.
// false: A - s B is singular to the last bit (ARPACK's value is then exact) or a step failed.
bool refine_pair(const Pencil& p, cplx& value, Eigen::VectorXcd& x) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  x /= x.norm();
  Eigen::VectorXcd y(p.n);
  cplx lam = value;
  // A value far off (a run flagged unsound and retried, §19.5: 2e-2 measured) converges
  // slowly at a fixed s: then s moves to the new value (a new LU), at most six times.
  for (int factorization = 0; factorization < 6; ++factorization) {
    const cplx s = lam;
    SparseComplexMatrix shifted = p.a - s * p.b;
    shifted.makeCompressed();
    ComplexLU lu;
    lu.analyzePattern(shifted);
    lu.factorize(shifted);
    if (lu.info() != Eigen::Success) break;  // s is an eigenvalue to the last bit
    bool settled = false;
    for (int it = 0; it < 4 && !settled; ++it) {
      if (p.identity_b)
        y = lu.solve(x);
      else
        y = lu.solve((p.b * x).eval());
      const cplx theta = x.dot(y);  // x^H y
      const double yn = y.norm();
      if (!std::isfinite(yn) || !(yn > 0.0) || theta == cplx(0.0)) return false;
      const cplx next = s + 1.0 / theta;
      x = y / yn;
      settled = it > 0 && std::abs(next - lam) <= 4.0 * eps * std::abs(next);
      lam = next;
    }
    if (settled) break;
  }
  if (!std::isfinite(lam.real()) || !std::isfinite(lam.imag())) return false;
  value = lam;
  return true;
}

// The condition of a simple eigenvalue of the pencil (model.md §19.3): with w the left
// eigenvector, a backward error E (||E|| = residual |lambda| ||B v||, v of unit norm) moves
// lambda by w^H E v / (w^H B v) to first order. w by inverse iteration on the adjoint at
// lambda itself, nudged off it by 1e-12 |lambda| so that the LU exists; 0 if a step fails
// (no bound is then claimed).
double pair_condition(const Pencil& p, cplx value, const Eigen::VectorXcd& vec) {
  const Eigen::VectorXcd x = vec / vec.norm();
  const Eigen::VectorXcd bx = p.identity_b ? x : (p.b * x).eval();
  SparseComplexMatrix shifted = p.a - value * (1.0 + 1e-12) * p.b;
  shifted.makeCompressed();
  ComplexLU lu;
  lu.analyzePattern(shifted);
  lu.factorize(shifted);
  if (lu.info() != Eigen::Success) return 0.0;
  Eigen::VectorXcd w = bx;
  for (int it = 0; it < 3; ++it) {
    w = lu.adjoint().solve(w).eval();
    const double n = w.norm();
    if (!std::isfinite(n) || !(n > 0.0)) return 0.0;
    w /= n;
  }
  const double overlap = std::abs(w.dot(bx));  // w^H B x
  return overlap > 0.0 ? bx.norm() / overlap : 0.0;
}

// The pairs of one shift from ARPACK's converged Ritz values nu (of OP) and vectors
// (columns of `vectors`): lambda = sigma + 1/nu, refined where the shift is far (§19.5),
// the residuals (19.6)-(19.7) from A and B, the k of largest |nu| (a real run may return
// k + 1 to keep a pair whole), the disc (19.3).
void finish_shift(ShiftResult& out, const Pencil& p, cplx sigma, int k, const std::vector<cplx>& nus,
                  const Eigen::MatrixXcd& vectors, bool need_vectors, bool refine) {
  const int m = int(nus.size());
  std::vector<int> order(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) order[std::size_t(i)] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](int l, int r) { return std::abs(nus[std::size_t(l)]) > std::abs(nus[std::size_t(r)]); });
  if (m > k) order.resize(std::size_t(k));
  Eigen::VectorXcd vec;
  for (int i : order) {
    const cplx nu = nus[std::size_t(i)];
    if (nu == cplx(0.0)) continue;  // an infinite eigenvalue (singular B): never nearest
    SparseEigenpair e;
    e.value = sigma + 1.0 / nu;
    e.shift = sigma;
    vec = vectors.col(i);
    pair_errors(p, e.value, vec, e.residual, e.backward_error);
    if (refine && std::isfinite(std::abs(e.value)) &&
        (std::abs(e.value - sigma) > std::abs(e.value) || e.residual > kRefineResidual)) {
      cplx value = e.value;
      Eigen::VectorXcd x = vec;
      if (refine_pair(p, value, x)) {
        double res = 0.0, back = 0.0;
        pair_errors(p, value, x, res, back);
        if (res <= e.residual) {  // never worse than ARPACK's pair
          e.value = value;
          e.residual = res;
          e.backward_error = back;
          e.refined = true;
          vec = x;
          ++out.run.refined;
        }
      }
    }
    if (!std::isfinite(e.value.real()) || !std::isfinite(e.value.imag()) || !std::isfinite(e.residual) ||
        !std::isfinite(e.backward_error)) {
      // Never a NaN in a result: the pair is dropped and the shift says why.
      out.run.status.merge(Outcome::numerical_issue, "a non-finite eigenvalue or residual at a shift");
      continue;
    }
    // Near the axis the sign of Re lambda needs the forward error, not the backward one.
    if (std::abs(e.value.real()) <= 1e4 * e.residual * std::abs(e.value)) e.condition = pair_condition(p, e.value, vec);
    if (need_vectors) e.vector = vec / vec.norm();
    out.pairs.push_back(std::move(e));
  }
  const int nconv = std::min(m, k);
  out.run.converged = nconv;
  // A shift on an eigenvalue (a structural zero of a set of equilibria sits at sigma = 0 to
  // rounding) makes one nu ~ 1/eps dominate the Hessenberg matrix, and rounding of that
  // size wipes out the other Ritz values, which ARPACK still reports as converged (measured
  // on the three-ball rigid reduction: residuals 1.6e-6 .. 0.4, values off by up to 300 1/s,
  // backward errors up to 1e-4, where every sound pair has residual <= 1e-10 after the
  // refinement, or a backward error ~1e-16). No disc is claimed then.
  for (const auto& e : out.pairs)
    if (e.residual > kUnsoundResidual && e.backward_error > kUnsoundBackwardError) {
      out.run.status.merge(Outcome::numerical_issue,
                           "an eigenpair with residual above 1e-6 at a shift: the shift lies on an eigenvalue");
      out.run.radius = 0.0;
      return;
    }
  if (nconv < k || int(out.pairs.size()) < k) {  // short, or a pair dropped: no disc claimed
    out.run.status.merge(Outcome::not_converged, "fewer eigenvalues converged than asked at a shift");
    out.run.radius = 0.0;
  } else {
    double rad = 0.0;
    for (const auto& e : out.pairs) rad = std::max(rad, std::abs(e.value - sigma));
    out.run.radius = rad;
  }
}

// What ARPACK's info after the iteration means for the status; false: stop (error).
bool iteration_status(ShiftResult& out, a_int info) {
  if (info < 0) {
    out.run.status.merge(Outcome::numerical_issue, "ARPACK's naupd reported an error");
    return false;
  }
  // Both end the iteration short; what did converge is still extracted and reported.
  if (info == 1)
    out.run.status.merge(Outcome::not_converged,
                         "ARPACK reached max_iterations with fewer eigenvalues converged than asked");
  if (info == 3)
    out.run.status.merge(Outcome::not_converged,
                         "ARPACK could not apply shifts during a restart (naupd info = 3): raise ncv");
  return true;
}

int basis_size(int n, int k, const SparseSpectrumOptions& o) {
  return std::min(n, o.ncv > 0 ? std::max(o.ncv, k + 2) : std::max(2 * k + 1, 20));
}

// Complex shift: znaupd on OP = (A - sigma B)^-1 B with the complex LU.
void arnoldi_complex(ShiftResult& out, const Pencil& p, ComplexLU& lu, int k, const SparseSpectrumOptions& o,
                     std::vector<cplx>& nus, Eigen::MatrixXcd& vectors) {
  const int n = int(p.n);
  const int ncv = basis_size(n, k, o);
  const int lworkl = 3 * ncv * ncv + 5 * ncv;
  const auto un = static_cast<std::size_t>(n), uncv = static_cast<std::size_t>(ncv);
  std::vector<cplx> resid(un), v(un * uncv), workd(3 * un), workl(static_cast<std::size_t>(lworkl)),
      workev(2 * uncv);
  std::vector<double> rwork(uncv);
  start_vector(resid);
  a_int iparam[11] = {}, ipntr[14] = {};
  iparam[0] = 1;                 // exact shifts
  iparam[2] = o.max_iterations;  // restarts
  iparam[6] = 1;                 // mode 1: we apply OP ourselves (bmat 'I', see header)
  a_int ido = 0, info = 1;       // info = 1: use resid as the start vector
  Eigen::VectorXcd bx(n);
  std::lock_guard<std::mutex> hold(arpack_mutex());
  for (;;) {
    arpack::naupd(ido, arpack::bmat::identity, n, arpack::which::largest_magnitude, k, o.tol, resid.data(), ncv,
                  v.data(), n, iparam, ipntr, workd.data(), workl.data(), lworkl, rwork.data(), info);
    if (ido != -1 && ido != 1) break;
    Eigen::Map<const Eigen::VectorXcd> x(workd.data() + ipntr[0] - 1, n);
    Eigen::Map<Eigen::VectorXcd> y(workd.data() + ipntr[1] - 1, n);
    if (p.identity_b)
      y = lu.solve(x);
    else {
      bx.noalias() = p.b * x;
      y = lu.solve(bx);
    }
  }
  out.run.iterations = int(iparam[2]);
  out.run.operator_applications = int(iparam[8]);
  if (!iteration_status(out, info)) return;
  std::vector<a_int> select(uncv, 0);
  std::vector<cplx> d(static_cast<std::size_t>(k) + 1), z(un * static_cast<std::size_t>(k));
  a_int info2 = 0;
  if (iparam[4] > 0)  // nothing converged: zneupd would only report that (info -14)
    arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), d.data(), z.data(), n, cplx(0.0), workev.data(),
                  arpack::bmat::identity, n, arpack::which::largest_magnitude, k, o.tol, resid.data(), ncv, v.data(),
                  n, iparam, ipntr, workd.data(), workl.data(), lworkl, rwork.data(), info2);
  // After a short iteration zneupd's complaint (-14: no Ritz value met tol) is that same
  // shortfall, already in the status: nothing to extract.
  if (iparam[4] <= 0 || (info2 != 0 && info != 0)) return;
  if (info2 != 0) {
    out.run.status.merge(Outcome::numerical_issue, "ARPACK's zneupd reported an error");
    return;
  }
  const int m = std::min(int(iparam[4]), k);
  nus.assign(d.begin(), d.begin() + m);
  vectors = Eigen::Map<const Eigen::MatrixXcd>(z.data(), n, k).leftCols(m);
}

// Real shift: dnaupd on the real OP = (A - sigma B)^-1 B with the real LU (a quarter of the
// complex flops, half the memory; model.md §19.1). Complex Ritz values come in conjugate
// pairs, their vectors packed as (Re, Im) in two columns.
void arnoldi_real(ShiftResult& out, const Pencil& p, RealLU& lu, int k, const SparseSpectrumOptions& o,
                  std::vector<cplx>& nus, Eigen::MatrixXcd& vectors) {
  const int n = int(p.n);
  const int ncv = basis_size(n, k + 1, o);  // dnaupd needs ncv >= nev + 2
  const int lworkl = 3 * ncv * ncv + 6 * ncv;
  const auto un = static_cast<std::size_t>(n), uncv = static_cast<std::size_t>(ncv);
  std::vector<cplx> start(un);
  start_vector(start);
  std::vector<double> resid(un), v(un * uncv), workd(3 * un), workl(static_cast<std::size_t>(lworkl)),
      workev(3 * uncv);
  for (std::size_t i = 0; i < un; ++i) resid[i] = start[i].real();
  a_int iparam[11] = {}, ipntr[14] = {};
  iparam[0] = 1;
  iparam[2] = o.max_iterations;
  iparam[6] = 1;
  a_int ido = 0, info = 1;
  Eigen::VectorXd bx(n);
  std::lock_guard<std::mutex> hold(arpack_mutex());
  for (;;) {
    arpack::naupd(ido, arpack::bmat::identity, n, arpack::which::largest_magnitude, k, o.tol, resid.data(), ncv,
                  v.data(), n, iparam, ipntr, workd.data(), workl.data(), lworkl, info);
    if (ido != -1 && ido != 1) break;
    Eigen::Map<const Eigen::VectorXd> x(workd.data() + ipntr[0] - 1, n);
    Eigen::Map<Eigen::VectorXd> y(workd.data() + ipntr[1] - 1, n);
    if (p.identity_b)
      y = lu.solve(x);
    else {
      bx.noalias() = *p.b_real * x;
      y = lu.solve(bx);
    }
  }
  out.run.iterations = int(iparam[2]);
  out.run.operator_applications = int(iparam[8]);
  if (!iteration_status(out, info)) return;
  std::vector<a_int> select(uncv, 0);
  std::vector<double> dr(static_cast<std::size_t>(k) + 1), di(static_cast<std::size_t>(k) + 1),
      z(un * (static_cast<std::size_t>(k) + 1));
  a_int info2 = 0;
  if (iparam[4] > 0)
    arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), dr.data(), di.data(), z.data(), n, 0.0, 0.0,
                  workev.data(), arpack::bmat::identity, n, arpack::which::largest_magnitude, k, o.tol,
                  resid.data(), ncv, v.data(), n, iparam, ipntr, workd.data(), workl.data(), lworkl, info2);
  if (iparam[4] <= 0 || (info2 != 0 && info != 0)) return;
  if (info2 != 0) {
    out.run.status.merge(Outcome::numerical_issue, "ARPACK's dneupd reported an error");
    return;
  }
  const int m = std::min(int(iparam[4]), k + 1);
  Eigen::Map<const Eigen::MatrixXd> zr(z.data(), n, k + 1);
  vectors.resize(n, m);
  nus.clear();
  for (int j = 0; j < m; ++j) {
    const cplx nu(dr[std::size_t(j)], di[std::size_t(j)]);
    if (nu.imag() == 0.0) {
      vectors.col(j) = zr.col(j).cast<cplx>();
    } else if (nu.imag() > 0.0 && j + 1 < k + 1) {
      // (j, j + 1): Re and Im of the vector of the value with Im > 0; its conjugate next.
      vectors.col(j) = zr.col(j).cast<cplx>() + cplx(0.0, 1.0) * zr.col(j + 1).cast<cplx>();
      if (j + 1 < m) vectors.col(j + 1) = vectors.col(j).conjugate();
    } else if (nu.imag() < 0.0 && j > 0 && di[std::size_t(j - 1)] > 0.0) {
      // second member of a pair: set above
    } else {
      break;  // a pair split at the end of ARPACK's list: its vector is not stored
    }
    nus.push_back(nu);
  }
  vectors.conservativeResize(n, int(nus.size()));
}

}  // namespace

ShiftResult run_shift(const Pencil& p, cplx sigma, int k, const SparseSpectrumOptions& o,
                      ShiftFactorizations* cache, bool need_vectors) {
  ShiftResult out;
  out.run.shift = sigma;
  out.run.requested = k;
  const bool real_shift = sigma.imag() == 0.0;

  // The factorization: from the cache, or new.
  ShiftFactorizations::Impl::Entry* entry = nullptr;
  ShiftFactorizations::Impl::Entry owned;
  if (cache) {
    auto& c = *cache->impl;
    if (c.rows != p.n || c.nonzeros != p.a.nonZeros() + p.b.nonZeros()) {
      c.lu.clear();
      c.rows = p.n;
      c.nonzeros = p.a.nonZeros() + p.b.nonZeros();
    }
    auto it = c.lu.find(key_of(sigma));
    if (it != c.lu.end()) {
      entry = &it->second;
      out.run.reused_factorization = true;
    }
  }
  if (!entry) {
    bool ok = false;
    if (real_shift) {
      SparseRealMatrix shifted = *p.a_real - sigma.real() * (p.identity_b ? p.identity_real : *p.b_real);
      shifted.makeCompressed();
      owned.real = std::make_unique<RealLU>();
      owned.real->analyzePattern(shifted);
      owned.real->factorize(shifted);
      ok = owned.real->info() == Eigen::Success;
    } else {
      SparseComplexMatrix shifted = p.a - sigma * p.b;
      shifted.makeCompressed();
      owned.complex = std::make_unique<ComplexLU>();
      owned.complex->analyzePattern(shifted);
      owned.complex->factorize(shifted);
      ok = owned.complex->info() == Eigen::Success;
    }
    out.factorized = true;
    if (!ok) {
      out.run.status.merge(Outcome::numerical_issue,
                           "the sparse LU of A - sigma B failed: the shift is an eigenvalue or the pencil is singular");
      return out;
    }
    entry = &owned;
  }

  std::vector<cplx> nus;
  Eigen::MatrixXcd vectors;
  if (real_shift)
    arnoldi_real(out, p, *entry->real, k, o, nus, vectors);
  else
    arnoldi_complex(out, p, *entry->complex, k, o, nus, vectors);
  if (out.run.status.outcome == Outcome::numerical_issue) return out;
  finish_shift(out, p, sigma, k, nus, vectors, need_vectors, o.refine);
  if (cache && entry == &owned) cache->impl->lu.emplace(key_of(sigma), std::move(owned));
  return out;
}

}  // namespace shift_invert

}  // namespace abu
