#include "abu/linear/spectrum_counts.hpp"

#include "abu/linear/characteristic.hpp"

namespace abu {

bool certify_counts(Spectrum& sp, const Linearization<long double, 2>& lin) {
  if (sp.n_marginal == 0 || sp.n_structural > 0) return false;
  return certify_counts(sp, to_double(characteristic_polynomial(lin)));
}

bool certify_counts(Spectrum& sp, const Polynomial& p) {
  if (sp.n_marginal == 0 || sp.n_structural > 0) return false;
  const RouthCount rc = routh_count(p);
  if (!rc.decided || rc.n_unstable < sp.n_unstable || rc.n_unstable > sp.n_unstable + sp.n_marginal) return false;
  // The rightmost root, polished from each eigenvalue in turn and from 0, until one is
  // certified (no root right of it) on the side of the axis the count says.
  for (int i = 0; i <= sp.count; ++i) {
    std::complex<double> rightmost = i < sp.count ? sp.eigenvalues[std::size_t(i)] : std::complex<double>{};
    if (!certified_abscissa(p, rightmost) || (rightmost.real() > 0) != (rc.n_unstable > 0)) continue;
    sp.certified_count = sp.n_marginal;
    sp.n_unstable = rc.n_unstable;
    sp.n_marginal = 0;
    sp.abscissa = rightmost.real();
    sp.stability = rc.n_unstable > 0 ? Stability::unstable : Stability::stable;
    return true;
  }
  return false;
}

}  // namespace abu
