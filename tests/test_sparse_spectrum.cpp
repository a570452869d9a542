// Large sparse spectra by shift-invert ARPACK (linear/sparse_spectrum.hpp, docs/model.md §19)
// against dense eigensolvers on chain pencils that look like rotor dynamics
// (tests/benchmarks/sparse_chain.hpp): masses, springs, dampers, gyroscopic coupling.
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <catch2/catch.hpp>

#include "abu/linear/sparse_spectrum.hpp"
#include "benchmarks/sparse_chain.hpp"

namespace {

using cplx = std::complex<double>;
using cplxl = std::complex<long double>;
using abu::testing::chain_pencil;
using abu::testing::ChainSpec;

// Every eigenvalue of the pencil, by a dense complex QR of B^-1 A in long double: its error
// eps_ld ||B^-1 A|| / |lambda| (eps_ld = 2^-64 = 5.4e-20) stays below 1e-12 of every
// eigenvalue used here (||B^-1 A|| <= 1e7, |lambda| >= 1e-1), far inside the 1e-8 checked.
std::vector<cplx> dense_eigenvalues(const abu::testing::Pencil& p) {
  using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const MatL a = Eigen::MatrixXd(p.A).cast<long double>();
  const MatL b = Eigen::MatrixXd(p.B).cast<long double>();
  const MatL op = b.partialPivLu().solve(a);
  Eigen::ComplexEigenSolver<Eigen::Matrix<cplxl, Eigen::Dynamic, Eigen::Dynamic>> es(op.cast<cplxl>(), false);
  REQUIRE(es.info() == Eigen::Success);
  std::vector<cplx> out;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i)
    out.emplace_back(double(es.eigenvalues()[i].real()), double(es.eigenvalues()[i].imag()));
  return out;
}

double rel(cplx a, cplx b) { return std::abs(a - b) / std::abs(b); }

// The dense eigenvalue nearest z.
cplx nearest(const std::vector<cplx>& ref, cplx z) {
  return *std::min_element(ref.begin(), ref.end(),
                           [&](cplx l, cplx r) { return std::abs(l - z) < std::abs(r - z); });
}

// The k dense eigenvalues nearest sigma must be those found (as a multiset, 1e-8 relative),
// and every eigenvalue strictly inside the run's disc must be one of them.
void check_near(const abu::SparseSpectrum& s, const std::vector<cplx>& ref, cplx sigma, int k) {
  std::vector<cplx> found;
  for (const auto& e : s.eigenpairs)
    if (e.shift == sigma) found.push_back(e.value);
  REQUIRE(int(found.size()) == k);
  std::vector<cplx> want = ref;
  std::sort(want.begin(), want.end(), [&](cplx l, cplx r) { return std::abs(l - sigma) < std::abs(r - sigma); });
  want.resize(std::size_t(k));
  for (cplx w : want) {
    auto it = std::min_element(found.begin(), found.end(),
                               [&](cplx l, cplx r) { return std::abs(l - w) < std::abs(r - w); });
    INFO("sigma " << sigma << " reference " << w << " found " << *it);
    CHECK(rel(*it, w) < 1e-8);
    found.erase(it);  // one-to-one: a double eigenvalue must be found twice
  }
}

}  // namespace

TEST_CASE("sparse spectrum: k nearest each shift match the dense solver on a gyroscopic chain", "[sparse]") {
  ChainSpec spec;
  spec.masses = 50;  // 200 states
  const auto p = chain_pencil(spec);
  const auto ref = dense_eigenvalues(p);
  // A real shift, one on the axis among the modes, one right of the axis, one far up.
  const std::vector<cplx> shifts{cplx(0.0, 0.0), cplx(0.0, 80.0), cplx(5.0, 150.0), cplx(-1.0, 190.0)};
  const int k = 8;
  const auto s = abu::eigenvalues_near(p.A, p.B, shifts, k);
  REQUIRE(s.status.ok());
  REQUIRE(s.shifts.size() == shifts.size());
  CHECK(s.factorizations == 4);
  for (std::size_t j = 0; j < shifts.size(); ++j) {
    CHECK(s.shifts[j].converged == k);
    CHECK(s.shifts[j].radius > 0.0);
    check_near(s, ref, shifts[j], k);
    // The disc claim: no reference eigenvalue strictly inside the disc but the k found.
    int inside = 0;
    for (cplx r : ref) inside += std::abs(r - shifts[j]) < s.shifts[j].radius * (1 - 1e-9);
    CHECK(inside <= k);
  }
  // Residuals: ARPACK's tol 1e-12 on nu = 1/(lambda - sigma) bounds the pencil residual by
  // ~1e-12 x |lambda - sigma| ||(A - sigma B)^-1|| ... ; 1e-9 leaves room for that factor.
  for (const auto& e : s.eigenpairs) {
    CHECK(e.residual < 1e-9);
    CHECK(e.backward_error < 1e-12);
    CHECK(e.residual == e.residual);
  }
  // Sorted by real part descending.
  for (std::size_t i = 1; i < s.eigenpairs.size(); ++i)
    CHECK(s.eigenpairs[i - 1].value.real() >= s.eigenpairs[i].value.real());
}

TEST_CASE("sparse spectrum: identity B (a standard problem) and kept eigenvectors", "[sparse]") {
  ChainSpec spec;
  spec.masses = 40;
  spec.mass_coupling = 0.0;
  spec.variation = 0.0;
  spec.mass = 1.0;  // M = I, so B = I and the pencil is the standard problem A v = lambda v
  const auto p = chain_pencil(spec);
  const auto ref = dense_eigenvalues(p);
  abu::SparseSpectrumOptions o;
  o.keep_vectors = true;
  const std::vector<cplx> shifts{cplx(0.0, 60.0)};
  const auto s = abu::eigenvalues_near(p.A, abu::SparseRealMatrix(), shifts, 6, o);
  REQUIRE(s.status.ok());
  check_near(s, ref, shifts[0], 6);
  for (const auto& e : s.eigenpairs) {
    REQUIRE(e.vector.size() == p.A.rows());
    CHECK(std::abs(e.vector.norm() - 1.0) < 1e-12);
    // Independent residual of the returned vector: ||A v - lambda v|| / |lambda|.
    const Eigen::VectorXcd r = p.A.cast<cplx>() * e.vector - e.value * e.vector;
    CHECK(r.norm() / std::abs(e.value) < 1e-9);
  }
}

TEST_CASE("sparse spectrum: rightmost eigenvalues with their coverage against the dense solver", "[sparse]") {
  ChainSpec spec;
  spec.masses = 60;  // 240 states
  spec.ground_damping = 0.5;
  const auto p = chain_pencil(spec);
  const auto ref = dense_eigenvalues(p);
  abu::RightmostOptions o;
  o.max_frequency = 120.0;
  const int k = 10;
  const auto s = abu::rightmost_eigenvalues(p.A, p.B, k, o);
  INFO(s.status.reason << " / " << s.coverage.how);
  REQUIRE(s.status.ok());
  REQUIRE(!s.coverage.empty());
  CHECK(s.coverage.imag_max >= 120.0 * (1 - 1e-9));
  CHECK(s.coverage.real_min < 0.0);
  CHECK(s.shifts.size() >= 2);
  REQUIRE(int(s.eigenpairs.size()) >= k);
  // Every returned value is an eigenvalue (1e-8 relative).
  for (const auto& e : s.eigenpairs) CHECK(rel(e.value, nearest(ref, e.value)) < 1e-8);
  // The coverage claim: every reference eigenvalue in the rectangle right of the k-th
  // returned value is returned.
  const double xk = s.eigenpairs.back().value.real();
  CHECK(xk >= s.coverage.real_min);
  std::vector<cplx> in_region;
  for (cplx r : ref)
    if (r.real() >= xk * (1 + 1e-9) && r.real() <= s.coverage.real_max && std::abs(r.imag()) <= s.coverage.imag_max)
      in_region.push_back(r);
  for (cplx r : in_region) {
    bool hit = false;
    for (const auto& e : s.eigenpairs) hit = hit || rel(e.value, r) < 1e-8;
    INFO("reference eigenvalue " << r << " in the covered region");
    CHECK(hit);
  }
  // And they are the k rightmost of the band |Im| <= imag_max of the dense spectrum.
  std::vector<cplx> band;
  for (cplx r : ref)
    if (std::abs(r.imag()) <= s.coverage.imag_max) band.push_back(r);
  std::sort(band.begin(), band.end(), [](cplx l, cplx r) { return l.real() > r.real(); });
  for (int i = 0; i < k; ++i) {
    INFO("band's rightmost #" << i << " " << band[std::size_t(i)]);
    bool hit = false;
    for (const auto& e : s.eigenpairs) hit = hit || rel(e.value, band[std::size_t(i)]) < 1e-8;
    CHECK(hit);
  }
  // Closed under conjugation (a real pencil).
  for (const auto& e : s.eigenpairs) {
    bool hit = false;
    for (const auto& f : s.eigenpairs) hit = hit || std::abs(f.value - std::conj(e.value)) <= 1e-9 * std::abs(e.value);
    CHECK(hit);
  }
}

TEST_CASE("sparse spectrum: hard cases, clustered and repeated eigenvalues and a spectrum over decades", "[sparse]") {
  SECTION("clustered: identical masses, coupling 1e-6 of the springs") {
    // Nearly uncoupled identical oscillators: the modes cluster within ~1e-6 relative of each
    // other around sqrt(k/m) = 100 1/s.
    ChainSpec spec;
    spec.masses = 30;
    spec.variation = 1e-5;  // splits the cluster at ~1e-6 .. 1e-5 relative
    spec.mass_coupling = 0.0;
    spec.gyroscopic = 0.0;
    const auto p0 = chain_pencil(spec);
    // Re-ground every mass so that the chain's springs are weak couplings.
    abu::testing::Pencil p = p0;
    const int q = int(p.A.rows()) / 2;
    for (int i = 2; i < q; ++i) p.A.coeffRef(q + i, i) -= 1e4;  // a 1e4 N/m ground spring each
    for (int k = 0; k < p.A.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(p.A, k); it; ++it)
        if (it.row() >= q && it.col() < q && std::abs(int(it.row()) - q - int(it.col())) == 2)
          it.valueRef() *= 1e-6;  // the chain springs to 1e-6 of themselves
    const auto ref = dense_eigenvalues(p);
    abu::SparseSpectrumOptions o;
    o.ncv = 60;  // a cluster of 2 x 29 values near the shift: the basis must hold it
    const std::vector<cplx> shifts{cplx(0.0, 100.0)};
    const auto s = abu::eigenvalues_near(p.A, p.B, shifts, 20, o);
    INFO(s.status.reason);
    REQUIRE(s.status.ok());
    check_near(s, ref, shifts[0], 20);
  }
  SECTION("repeated: identical uncoupled oscillators, a 2-fold eigenvalue per direction") {
    // No gyroscopic coupling, no variation: x and y of one mass have the same modes, every
    // eigenvalue is double (semisimple). One-to-one matching asks for both copies.
    ChainSpec spec;
    spec.masses = 25;
    spec.variation = 0.0;
    spec.gyroscopic = 0.0;
    const auto p = chain_pencil(spec);
    const auto ref = dense_eigenvalues(p);
    const std::vector<cplx> shifts{cplx(0.0, 50.0)};
    const auto s = abu::eigenvalues_near(p.A, p.B, shifts, 8, {});
    REQUIRE(s.status.ok());
    check_near(s, ref, shifts[0], 8);
  }
  SECTION("spectrum over six decades: stiffness 1e-2 .. 1e6 along the chain") {
    ChainSpec spec;
    spec.masses = 50;
    spec.stiffness = 1e-2;
    spec.stiffness_ratio = 1e8;
    spec.damping = 1e-3;
    spec.gyroscopic = 0.5;
    const auto p = chain_pencil(spec);
    const auto ref = dense_eigenvalues(p);
    double lo = 1e300, hi = 0.0;
    for (cplx r : ref) lo = std::min(lo, std::abs(r)), hi = std::max(hi, std::abs(r));
    INFO("|lambda| from " << lo << " to " << hi);
    CHECK(hi / lo > 1e4);
    // The smallest near 0, some in the middle decades, the largest far up.
    const std::vector<cplx> shifts{cplx(0.0, 0.0), cplx(0.0, 10.0), cplx(0.0, 1000.0)};
    const auto s = abu::eigenvalues_near(p.A, p.B, shifts, 6, {});
    INFO(s.status.reason);
    REQUIRE(s.status.ok());
    for (cplx sigma : shifts) check_near(s, ref, sigma, 6);
  }
}

TEST_CASE("sparse spectrum: a shortfall is reported, never silent", "[sparse]") {
  ChainSpec spec;
  spec.masses = 100;
  const auto p = chain_pencil(spec);
  abu::SparseSpectrumOptions o;
  o.max_iterations = 1;
  o.ncv = 12;
  const std::vector<cplx> shifts{cplx(0.0, 100.0)};
  const auto s = abu::eigenvalues_near(p.A, p.B, shifts, 10, o);
  INFO(s.status.reason);
  CHECK_FALSE(s.status.ok());
  CHECK(s.status.outcome == abu::Outcome::not_converged);
  CHECK(!s.status.reason.empty());
  REQUIRE(s.shifts.size() == 1);
  CHECK(s.shifts[0].converged < 10);
  CHECK(s.shifts[0].radius == 0.0);  // no disc claimed
  CHECK(int(s.eigenpairs.size()) == s.shifts[0].converged);

  // The rightmost search says so too, and claims no coverage it does not have.
  abu::RightmostOptions r;
  r.arpack = o;
  r.max_frequency = 100.0;
  const auto t = abu::rightmost_eigenvalues(p.A, p.B, 10, r);
  CHECK_FALSE(t.status.ok());
  CHECK(t.coverage.empty());
  for (const auto& e : t.eigenpairs) CHECK_FALSE(e.covered);

  // And a ladder stopped by max_shifts below its band.
  abu::RightmostOptions short_ladder;
  short_ladder.max_frequency = 1e4;
  short_ladder.max_shifts = 2;
  const auto u = abu::rightmost_eigenvalues(p.A, p.B, 6, short_ladder);
  CHECK_FALSE(u.status.ok());
  CHECK(u.shifts.size() == 2);
  CHECK(u.coverage.imag_max < 1e4);
}

TEST_CASE("sparse spectrum: same bytes on a rerun, factorizations reused from the cache", "[sparse]") {
  ChainSpec spec;
  spec.masses = 80;
  const auto p = chain_pencil(spec);
  const std::vector<cplx> shifts{cplx(0.0, 40.0), cplx(0.0, 40.0), cplx(1.0, 0.0)};
  abu::ShiftFactorizations cache;
  const auto a = abu::eigenvalues_near(p.A, p.B, shifts, 6, {}, &cache);
  REQUIRE(a.status.ok());
  CHECK(a.factorizations == 2);  // the repeated shift reuses its LU
  CHECK(a.shifts[1].reused_factorization);
  CHECK(cache.size() == 2);
  const auto b = abu::eigenvalues_near(p.A, p.B, shifts, 6, {}, &cache);
  CHECK(b.factorizations == 0);
  const auto c = abu::eigenvalues_near(p.A, p.B, shifts, 6, {});
  REQUIRE(a.eigenpairs.size() == c.eigenpairs.size());
  for (std::size_t i = 0; i < a.eigenpairs.size(); ++i) {
    // Bit-identical: the start vector is fixed and the arithmetic is sequential.
    CHECK(a.eigenpairs[i].value == c.eigenpairs[i].value);
    CHECK(a.eigenpairs[i].value == b.eigenpairs[i].value);
    CHECK(a.eigenpairs[i].residual == c.eigenpairs[i].residual);
  }
}

TEST_CASE("sparse spectrum: bad arguments are refused", "[sparse]") {
  ChainSpec spec;
  spec.masses = 5;
  const auto p = chain_pencil(spec);
  const std::vector<cplx> shifts{cplx(0.0)};
  CHECK_THROWS_AS(abu::eigenvalues_near(p.A, p.B, shifts, 0), std::invalid_argument);
  CHECK_THROWS_AS(abu::eigenvalues_near(p.A, p.B, shifts, int(p.A.rows()) - 1), std::invalid_argument);
  const abu::SparseRealMatrix wrong(3, 3);
  CHECK_THROWS_AS(abu::eigenvalues_near(p.A, wrong, shifts, 2), std::invalid_argument);
  abu::RightmostOptions o;
  o.spacing = 2.5;
  CHECK_THROWS_AS(abu::rightmost_eigenvalues(p.A, p.B, 2, o), std::invalid_argument);
}
