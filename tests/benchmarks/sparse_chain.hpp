// A rotor-dynamics-like test pencil for the sparse spectra (docs/model.md §19): a chain of
// N masses, each moving in two directions (x, y), joined by springs and dampers, the first
// grounded, with gyroscopic coupling of each mass's x and y, written in first order as
//     A = [[0, I], [-K, -(C + G)]],   B = blkdiag(I, M),    state (u, u'), 4 N states,
// dofs interleaved (x_0, y_0, x_1, y_1, ...) so that K, C, M are banded. M (consistent:
// neighbours coupled), K and C symmetric positive definite, G skew. Used by
// tests/test_sparse_spectrum.cpp and bench_sparse_spectrum.cpp.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/SparseCore>

namespace abu::testing {

struct ChainSpec {
  int masses = 50;
  /// Per-mass values are base x (1 + variation x a fixed irregular sequence), so that no
  /// two modes are exactly equal unless variation = 0.
  double mass = 1.0, stiffness = 1e4, damping = 2.0, gyroscopic = 50.0;
  double mass_coupling = 0.1;  ///< consistent-mass off-diagonal, fraction of the mass
  double variation = 0.3;
  /// Stiffness of mass i multiplied by stiffness_ratio^(i / (N - 1)) (spread over decades).
  double stiffness_ratio = 1.0;
  double ground_damping = 0.0;  ///< viscous damper from every mass to ground [N s/m]
};

struct Pencil {
  Eigen::SparseMatrix<double> A, B;
};

inline double chain_wiggle(int i) { return std::sin(1.7 * i + 0.3) * std::cos(0.37 * i); }

inline Pencil chain_pencil(const ChainSpec& s) {
  const int N = s.masses, q = 2 * N, n = 2 * q;
  std::vector<Eigen::Triplet<double>> ta, tb;
  ta.reserve(std::size_t(q) * 12);
  tb.reserve(std::size_t(q) * 4);
  // Per-dof stiffness and damping of the spring/damper below mass i (between i - 1 and i,
  // or ground for i = 0); K and C are assembled into A's lower blocks with a minus sign.
  auto kval = [&](int i) {
    const double spread = N > 1 ? std::pow(s.stiffness_ratio, double(i) / (N - 1)) : 1.0;
    return s.stiffness * spread * (1.0 + s.variation * chain_wiggle(i));
  };
  auto cval = [&](int i) { return s.damping * (1.0 + s.variation * chain_wiggle(i + 11)); };
  auto mval = [&](int i) { return s.mass * (1.0 + s.variation * chain_wiggle(i + 5)); };
  for (int i = 0; i < q; ++i) {
    ta.emplace_back(i, q + i, 1.0);  // u' = v
    tb.emplace_back(i, i, 1.0);
  }
  auto add_element = [&](int i, int j, double k, double c) {  // between dof i and dof j (-1: ground)
    ta.emplace_back(q + i, i, -k);
    ta.emplace_back(q + i, q + i, -c);
    if (j >= 0) {
      ta.emplace_back(q + j, j, -k);
      ta.emplace_back(q + j, q + j, -c);
      ta.emplace_back(q + i, j, k);
      ta.emplace_back(q + j, i, k);
      ta.emplace_back(q + i, q + j, c);
      ta.emplace_back(q + j, q + i, c);
    }
  };
  for (int i = 0; i < N; ++i) {
    for (int d = 0; d < 2; ++d) {
      const int dof = 2 * i + d;
      add_element(dof, i == 0 ? -1 : dof - 2, kval(i), cval(i));
      if (s.ground_damping != 0.0) ta.emplace_back(q + dof, q + dof, -s.ground_damping);
      // Consistent mass: m_i on the diagonal plus the coupling to the next mass.
      const double m = mval(i);
      tb.emplace_back(q + dof, q + dof, m);
      if (i + 1 < N) {
        const double mc = s.mass_coupling * std::min(m, mval(i + 1));
        tb.emplace_back(q + dof, q + dof + 2, mc);
        tb.emplace_back(q + dof + 2, q + dof, mc);
        tb.emplace_back(q + dof, q + dof, mc);  // keeps M diagonally dominant (SPD)
        tb.emplace_back(q + dof + 2, q + dof + 2, mc);
      }
    }
    // Gyroscopic coupling of x_i and y_i: -(G u')  with G = g [[0, 1], [-1, 0]].
    const double g = s.gyroscopic * (1.0 + s.variation * chain_wiggle(i + 23));
    ta.emplace_back(q + 2 * i, q + 2 * i + 1, -g);
    ta.emplace_back(q + 2 * i + 1, q + 2 * i, g);
  }
  Pencil p;
  p.A.resize(n, n);
  p.B.resize(n, n);
  p.A.setFromTriplets(ta.begin(), ta.end());
  p.B.setFromTriplets(tb.begin(), tb.end());
  p.A.makeCompressed();
  p.B.makeCompressed();
  return p;
}

}  // namespace abu::testing
