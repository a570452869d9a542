// Eigenvalues of matrix products (linear/floquet.hpp) against products whose eigenvalues
// are known exactly: A_k = Z_{k+1} D_k Z_k^-1 with Z_{m+1} = Z_1, so that
// A_m ... A_1 = Z_1 (D_m ... D_1) Z_1^-1, with D_k block diagonal (real scalars and
// scaled rotations) and Z_k random, condition number about 10. The multipliers span 1 to
// 1e-300 and below; each factor alone spans only a few orders, as the short-interval
// transition matrices of an orbit do (docs/model.md §17.4).
//
// Tolerance: forming A_k rounds it by a few eps relative to |A_k|; the factor-wise
// backward error of the method is of the same kind, so each multiplier is expected to
// within (m * eps * cond(Z)^2) relative, about 1e-11 for m = 200: asserted 1e-9 on the
// modulus (through its logarithm, so that values below 1e-308 count) and on the argument.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "abu/linear/floquet.hpp"

namespace {

struct Block {
  double log_rate;  // ln of the modulus each factor contributes
  double angle;     // rotation per factor (0: a real block of one; pi: sign flips)
  bool pair;        // a 2 x 2 rotation block
};

Eigen::MatrixXd random_conditioned(std::mt19937_64& rng, int n) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd x(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) x(i, j) = g(rng);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(x);
  Eigen::MatrixXd q = qr.householderQ();
  Eigen::VectorXd sv = Eigen::VectorXd::LinSpaced(n, 1.0, 10.0);
  Eigen::MatrixXd y(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) y(i, j) = g(rng);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr2(y);
  Eigen::MatrixXd v = qr2.householderQ();
  return q * sv.asDiagonal() * v.transpose();
}

struct Case {
  std::vector<Eigen::MatrixXd> factors;
  std::vector<std::complex<double>> directions;  // exact eigenvalues: exp(log_modulus) * direction
  std::vector<double> log_moduli;
  std::vector<Eigen::MatrixXd> bases;  // Z_k: column i is the chain of the i-th diagonal entry
};

Case build(const std::vector<Block>& blocks, int m, unsigned seed) {
  std::mt19937_64 rng(seed);
  int n = 0;
  for (const Block& b : blocks) n += b.pair ? 2 : 1;
  std::vector<Eigen::MatrixXd> z;
  for (int k = 0; k < m; ++k) z.push_back(random_conditioned(rng, n));
  Case c;
  for (int k = 0; k < m; ++k) {
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
    int i = 0;
    for (const Block& b : blocks) {
      const double r = std::exp(b.log_rate);
      if (b.pair) {
        d(i, i) = d(i + 1, i + 1) = r * std::cos(b.angle);
        d(i + 1, i) = r * std::sin(b.angle);
        d(i, i + 1) = -r * std::sin(b.angle);
        i += 2;
      } else {
        d(i, i) = r * std::cos(b.angle);  // angle 0 or pi
        i += 1;
      }
    }
    const Eigen::MatrixXd& next = z[std::size_t((k + 1) % m)];
    c.factors.push_back(next * d * z[std::size_t(k)].inverse());
  }
  c.bases = z;
  for (const Block& b : blocks) {
    const double total = std::remainder(m * b.angle, 2 * std::numbers::pi);
    const std::complex<double> dir = std::polar(1.0, total);
    if (b.pair) {
      c.directions.push_back(std::abs(dir.imag()) > 0 ? std::complex<double>(dir.real(), std::abs(dir.imag())) : dir);
      c.directions.push_back(std::conj(c.directions.back()));
      c.log_moduli.push_back(m * b.log_rate);
      c.log_moduli.push_back(m * b.log_rate);
    } else {
      c.directions.emplace_back(std::round(dir.real()), 0.0);
      c.log_moduli.push_back(m * b.log_rate);
    }
  }
  return c;
}

// Sorted expected values against the computed ones: log modulus and direction to `tol`.
void check(const Case& c, const abu::ProductEigenvalues& e, double tol) {
  REQUIRE(e.status.ok());
  std::vector<std::size_t> order(c.log_moduli.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    if (c.log_moduli[x] != c.log_moduli[y]) return c.log_moduli[x] > c.log_moduli[y];
    return c.directions[x].imag() > c.directions[y].imag();
  });
  REQUIRE(e.values.size() == order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t k = order[i];
    INFO("eigenvalue " << i << ": log modulus " << e.log_moduli[i] << " expected " << c.log_moduli[k]);
    CHECK(std::abs(e.log_moduli[i] - c.log_moduli[k]) <= tol);
    // The argument separately: values below 1e-308 are subnormal doubles, a few digits.
    CHECK(std::abs(std::polar(1.0, e.arguments[i]) - c.directions[k]) <= tol);
  }
}

}  // namespace

TEST_CASE("product eigenvalues: real multipliers from 1 to 1e-2000, each factor spanning 1e-10") {
  // Eight real multipliers, ln|mu| = 0, -2.3, ..., sign flips on two of them; m = 200.
  std::vector<Block> blocks;
  for (int i = 0; i < 8; ++i) blocks.push_back({-0.115 * i * i, i % 3 == 1 ? std::numbers::pi : 0.0, false});
  const Case c = build(blocks, 200, 11);
  const abu::ProductEigenvalues e = abu::product_eigenvalues(c.factors);
  check(c, e, 1e-9);
  CHECK(e.log_moduli.back() < std::log(1e-300));
  // The explicit product loses them: its smallest eigenvalues are rounding noise (the
  // test above could fail; this documents why the method exists).
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(8, 8);
  for (const Eigen::MatrixXd& a : c.factors) p = a * p;
  const Eigen::VectorXcd naive = p.eigenvalues();
  double smallest = 1e300;
  for (Eigen::Index i = 0; i < naive.size(); ++i) smallest = std::min(smallest, std::abs(naive(i)));
  CHECK(smallest > 1e-30);
}

TEST_CASE("product eigenvalues: a trivial multiplier 1, a real one 0.98 next to it and complex pairs") {
  // Like the Floquet multipliers of an orbit near a Hopf point: 1 (the flow direction),
  // 0.98, a slow complex pair, and fast pairs far inside the unit circle.
  const int m = 150;
  const std::vector<Block> blocks = {
      {0.0, 0.0, false},
      {std::log(0.98) / m, 0.0, false},
      {std::log(0.3) / m, 0.013, true},
      {std::log(1e-40) / m, 0.2, true},
      {std::log(1e-320) / m, 2.5, true},
  };
  const Case c = build(blocks, m, 5);
  const abu::ProductEigenvalues e = abu::product_eigenvalues(c.factors);
  check(c, e, 1e-9);
  CHECK(std::abs(e.values[0] - 1.0) < 1e-12);
  // The pairs stay clusters of two; 1 and 0.98 separate or share one (either is right).
  CHECK(e.clusters.back() == 2);
}

TEST_CASE("product eigenvalues: one factor is an ordinary eigenvalue problem") {
  Eigen::MatrixXd a(3, 3);
  a << 2, 1, 0, 0, 3, 1, 0, 0, -1;
  const abu::ProductEigenvalues e = abu::product_eigenvalues({a});
  REQUIRE(e.status.ok());
  REQUIRE(e.values.size() == 3);
  CHECK(std::abs(e.values[0] - 3.0) < 1e-14);
  CHECK(std::abs(e.values[1] - 2.0) < 1e-14);
  CHECK(std::abs(e.values[2] + 1.0) < 1e-14);
}

TEST_CASE("product eigenvalues: bad factors are refused with a reason") {
  CHECK_FALSE(abu::product_eigenvalues({}).status.ok());
  CHECK_FALSE(abu::product_eigenvalues({Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Identity(3, 3)}).status.ok());
  Eigen::MatrixXd bad = Eigen::MatrixXd::Identity(2, 2);
  bad(0, 1) = std::nan("");
  const abu::ProductEigenvalues e = abu::product_eigenvalues({bad});
  CHECK(e.status.outcome == abu::Outcome::numerical_issue);
  CHECK_FALSE(e.status.reason.empty());
}

TEST_CASE("deflated product eigenvalues: the known chain's multiplier apart, the others as the product's") {
  // The products of the first test case's kind with a trivial multiplier 1 whose eigenvector
  // chain Z_k e_0 is given (an orbit's flow direction at its shooting points), beside e^60, a
  // complex pair and small ones. Deflated along the exact chain, every eigenvalue comes out as
  // product_eigenvalues gets it (1e-9 in log modulus and direction), the trivial one at its
  // index after e^60, and the dropped part (the chain's mismatch) is at rounding.
  const int m = 30;
  const std::vector<Block> blocks = {
      {0.0, 0.0, false},
      {60.0 / m, 0.0, false},
      {std::log(0.5) / m, 0.07, true},
      {std::log(1e-3) / m, 0.0, false},
      {std::log(1e-12) / m, 1.1, true},
  };
  const Case c = build(blocks, m, 17);
  // The chain: A_k (Z_k e_0) = Z_{k+1} D_k e_0 = Z_{k+1} e_0 (the first block is 1 per factor),
  // exact by construction (an explicit product could not give it: its rounding, eps e^60, is
  // larger than the eigenvalue).
  const Eigen::Index n = c.factors.front().rows();
  std::vector<Eigen::VectorXd> chain;
  for (int k = 0; k < m; ++k) chain.push_back(c.bases[std::size_t(k)].col(0).normalized());
  const abu::DeflatedProductEigenvalues d = abu::deflated_product_eigenvalues(c.factors, chain);
  check(c, d.eigen, 1e-9);
  CHECK(d.trivial == 1);
  CHECK(std::abs(d.eigen.values[d.trivial] - 1.0) < 1e-9);
  CHECK(d.chain_error < 1e-12);
  // A chain vector off by 1e-6 rad (the flow vector at a point of an orbit with a residual):
  // that much is dropped, reported as chain_error, and the eigenvalues move by about as much.
  std::vector<Eigen::VectorXd> off = chain;
  Eigen::VectorXd tilt = Eigen::VectorXd::Unit(n, 2);
  tilt -= tilt.dot(off[5]) * off[5];
  off[5] = (off[5] + 1e-6 * tilt.normalized()).normalized();
  const abu::DeflatedProductEigenvalues e = abu::deflated_product_eigenvalues(c.factors, off);
  CHECK(e.chain_error > 1e-8);
  CHECK(e.chain_error < 1e-4);
  check(c, e.eigen, 1e-4);
}

TEST_CASE("deflated product eigenvalues: bad chains are refused with a reason") {
  const std::vector<Eigen::MatrixXd> f(2, Eigen::MatrixXd::Identity(3, 3));
  CHECK_FALSE(abu::deflated_product_eigenvalues(f, {Eigen::VectorXd::Ones(3)}).eigen.status.ok());
  CHECK_FALSE(abu::deflated_product_eigenvalues(f, {Eigen::VectorXd::Ones(3), Eigen::VectorXd::Zero(3)}).eigen.status.ok());
  const abu::DeflatedProductEigenvalues ok = abu::deflated_product_eigenvalues(f, {Eigen::VectorXd::Ones(3), Eigen::VectorXd::Ones(3)});
  REQUIRE(ok.eigen.status.ok());
  for (const auto& v : ok.eigen.values) CHECK(std::abs(v - 1.0) < 1e-14);
}
