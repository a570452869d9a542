// One shift of the shift-invert Arnoldi iteration on a sparse pencil A v = lambda B v
// (include/abu/linear/sparse_spectrum.hpp, docs/model.md §19.1, §19.3, §19.5): the pencil in
// complex form, the LU of A - sigma B (or the cached one), ARPACK on OP = (A - sigma B)^-1 B,
// and the pairs it returns, refined and checked. Internal to src/linear (sparse_spectrum.cpp
// builds the nearest-shifts and rightmost searches on it).
#pragma once

#include <complex>
#include <vector>

#include <Eigen/SparseCore>

#include "abu/linear/sparse_spectrum.hpp"

namespace abu::shift_invert {

using cplx = std::complex<double>;
using SparseComplexMatrix = Eigen::SparseMatrix<cplx>;

// The pencil in complex form, with what every shift needs: the pattern of A - sigma B (the
// union of A's and B's, explicit zeros kept) is the same for every sigma, so COLAMD's
// ordering is computed once.
struct Pencil {
  Eigen::Index n = 0;
  bool identity_b = false;
  SparseComplexMatrix a, b;  // b: the identity when identity_b
  double norm1_a = 0.0, norm1_b = 1.0;
  const SparseRealMatrix* a_real = nullptr;
  const SparseRealMatrix* b_real = nullptr;
  SparseRealMatrix identity_real;  // B when identity_b, for the real path
};

// The pencil (A, B) checked and put in complex form; B of size 0 x 0 is the identity. Throws
// std::invalid_argument for a non-square A, a B of another size, or k outside ARPACK's
// 1 <= k < n - 1.
Pencil make_pencil(const SparseRealMatrix& A, const SparseRealMatrix& B, int k);

// What one shift gave: its run (status, radius, counts) and its eigenpairs.
struct ShiftResult {
  ShiftRun run;
  std::vector<SparseEigenpair> pairs;
  bool factorized = false;
};

// One shift: factorize (or reuse) A - sigma B, run the Arnoldi iteration on OP, extract and
// check the pairs. A real shift takes the real path.
// `cache` (may be null) keeps the factorization for a shift that comes again; the pairs carry
// their vectors when `need_vectors`.
ShiftResult run_shift(const Pencil& p, cplx sigma, int k, const SparseSpectrumOptions& o,
                      ShiftFactorizations* cache, bool need_vectors);

}  // namespace abu::shift_invert
