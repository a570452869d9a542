#include "abu/linear/kappa_sensitivity.hpp"

#include <cmath>
#include <complex>

#include <Eigen/SVD>

namespace abu {

template <int N>
KappaSensitivity<N> kappa_sensitivity(const ParamsT<double, N>& p, const Linearization<long double, N>& lin,
                                      const SpectrumT<N>& spectrum) {
  using ld = long double;
  using cld = std::complex<ld>;
  using Mat = Eigen::Matrix<cld, dof_size<N>, dof_size<N>, Eigen::ColMajor, dof_capacity<N>, dof_capacity<N>>;
  using Vec = Eigen::Matrix<cld, dof_size<N>, 1, Eigen::ColMajor, dof_capacity<N>, 1>;
  using RealVec = Eigen::Matrix<ld, dof_size<N>, 1, Eigen::ColMajor, dof_capacity<N>, 1>;
  KappaSensitivity<N> out;
  if (p.law != FrictionLaw::coulomb && p.law != FrictionLaw::stribeck) return out;
  out.defined = true;
  const int d = int(lin.mass.rows()), n = d - 2;
  const Mat A = lin.mass.template cast<cld>(), C = lin.damping.template cast<cld>(), K = lin.stiffness.template cast<cld>();
  // C_f: the friction slope on the ball diagonal (model.md (6.4): -l_i F_i'(0)), which is
  // proportional to kappa at rest. The rest of C (support damping, Coriolis) does not
  // depend on kappa.
  Mat Cf = Mat::Zero(d, d);
  for (int i = 0; i < n; ++i) Cf(2 + i, 2 + i) = C(2 + i, 2 + i);
  for (int k = 0; k < spectrum.count; ++k) {
    const auto kk = std::size_t(k);
    const cld lambda(spectrum.eigenvalues[kk].real(), spectrum.eigenvalues[kk].imag());
    if (spectrum.structural[kk] || lambda == cld(0)) continue;
    // Both null vectors from one SVD of T(lambda), equilibrated (ball rows and columns can
    // be 1e10 smaller than the rotor's): the last right and left singular vectors. The
    // sensitivity is a ratio of bilinear forms in x and y, invariant under their scaling.
    const Mat T = (lambda * lambda) * A + lambda * C + K;
    RealVec rows(d), cols(d);
    for (int i = 0; i < d; ++i) rows(i) = 1 / std::max(T.row(i).cwiseAbs().maxCoeff(), ld(1e-300L));
    for (int j = 0; j < d; ++j)
      cols(j) = 1 / std::max((rows.asDiagonal() * T).col(j).cwiseAbs().maxCoeff(), ld(1e-300L));
    const Mat Ts = rows.template cast<cld>().asDiagonal() * T * cols.template cast<cld>().asDiagonal();
    if (!Ts.allFinite()) continue;  // no sensitivity rather than an SVD of NaNs
    const Eigen::JacobiSVD<Mat> svd(Ts, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Vec x = cols.template cast<cld>().asDiagonal() * svd.matrixV().col(d - 1);
    const Vec y = rows.template cast<cld>().asDiagonal() * svd.matrixU().col(d - 1).conjugate();  // y^T T = 0
    const cld denominator = y.transpose() * ((ld(2) * lambda) * A + C) * x;
    if (std::abs(denominator) == 0) continue;  // a defective eigenvalue: no first-order sensitivity
    const cld numerator = y.transpose() * Cf * x;
    const double s = double(-(numerator / denominator).real());
    if (!std::isfinite(s)) continue;
    out.log_slope[kk] = s;
    out.computed[kk] = true;
    out.creep[kk] = std::abs(s + 1) <= creep_tolerance;
    out.n_creep += out.creep[kk] ? 1 : 0;
  }
  return out;
}

template KappaSensitivity<2> kappa_sensitivity<2>(const ParamsT<double, 2>&, const Linearization<long double, 2>&,
                                                  const SpectrumT<2>&);
template KappaSensitivity<any_balls> kappa_sensitivity<any_balls>(const ParamsT<double, any_balls>&,
                                                                  const Linearization<long double, any_balls>&,
                                                                  const SpectrumT<any_balls>&);

}  // namespace abu
