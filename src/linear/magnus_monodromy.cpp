// Magnus-4 monodromy of the balanced state's periodic linearization (docs/model.md §10.6).
#include "abu/linear/magnus_monodromy.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

#include "abu/core/cancel.hpp"
#include "abu/linear/floquet_hill.hpp"

namespace abu {

Eigen::MatrixXd magnus_monodromy(const PeriodicJacobian& J, int steps) {
  if (steps < 1) throw std::invalid_argument("magnus_monodromy: steps must be >= 1");
  const double h = J.period() / steps;
  const double c = std::sqrt(3.0) / 6.0;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(J.dimension(), J.dimension());
  for (int k = 0; k < steps; ++k) {
    if (k % 64 == 0) throw_if_stopped("Magnus monodromy");
    const double t0 = k * h;
    const Eigen::MatrixXd A1 = J.at(t0 + (0.5 - c) * h), A2 = J.at(t0 + (0.5 + c) * h);
    const Eigen::MatrixXd Omega = 0.5 * h * (A1 + A2) + (std::sqrt(3.0) / 12.0) * h * h * (A2 * A1 - A1 * A2);
    const Eigen::MatrixXd step = Omega.exp();
    Phi = step * Phi;
  }
  return Phi;
}

std::vector<std::complex<double>> monodromy_multipliers(const Eigen::MatrixXd& monodromy) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(monodromy, false);
  std::vector<std::complex<double>> rho;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) rho.push_back(es.eigenvalues()(i));
  floquet_order(rho);
  return rho;
}

}  // namespace abu
