// Fixed-frame whirl of the Floquet modes on an anisotropic support (docs/model.md §10.15).
#include "abu/linear/floquet_modes.hpp"

#include <cmath>
#include <numbers>

#include "abu/linear/balanced_floquet.hpp"

namespace abu {

namespace {
using cd = std::complex<double>;

// The two lines of one harmonic pair (10.15.2): `plus` at f = Im lambda + omega + 2 omega k
// (the w+ of harmonic k), `minus` at -f (the w- of harmonic k + 1), mass-weighted.
struct LinePair {
  double plus = 0, minus = 0;
};
}  // namespace

HillOptions campbell_hill_options() {
  HillOptions o;
  o.max_harmonics = 48;
  o.keep_vectors = true;
  return o;
}

FloquetModes floquet_mode_views(const ParamsN& p, const AnisotropicSupport& support, const EquilibriumN& e,
                                const HillOptions& options) {
  const cd i(0, 1);
  const PeriodicJacobian full = balanced_periodic_jacobian(p, support, e.position);
  PeriodicJacobian J = full;
  const Eigen::VectorXd& scale = full.scale;  // of the full state (restricted() keeps none)
  Eigen::MatrixXd normal;  // V_N of the balanced set (n >= 3), else none
  if (e.on_balanced_set) {
    normal = balanced_normal_basis(p, e);
    J = restricted(J, normal);
  }
  HillOptions o = options;
  o.keep_vectors = true;
  HillResult h = hill_multipliers(J, o);
  if (!h.status.ok() && !o.extended) {  // the stiff coulomb rates: long double (§10.5)
    o.extended = true;
    h = hill_multipliers(J, o);
  }
  FloquetModes out;
  out.status = h.status;
  out.harmonics = h.harmonics;
  out.multipliers = h.multipliers;
  if (!h.status.ok()) return out;

  const int n = ball_count(p);
  const Eigen::Index d = 2 + n;
  const double w = p.omega;
  const double M = p.total_mass();
  for (std::size_t k = 0; k < h.multipliers.size(); ++k) {
    const cd rho = h.multipliers[k];
    if (rho.imag() < 0) continue;  // the partner with Im rho > 0 (Im lambda in (0, omega)) represents the pair
    const cd lambda = h.exponents[k];
    ModeView m;
    m.index = int(k);
    m.rotating = lambda;
    if (rho.imag() > 0)
      for (std::size_t j = 0; j < h.multipliers.size(); ++j)
        if (j != k && h.multipliers[j] == std::conj(rho)) m.conjugate = int(j);

    // The harmonics in the state space: x = V_N y + z (V_N: the balanced set's normal basis).
    // J(t) V_T = 0, so the tangent part z (P_T = I - V_N V_N^T) follows from z' = P_T J(t) V_N y:
    // harmonic by harmonic (lambda + 2 i omega k) z_k = P_T (J0 X_k + Jp X_{k-1} + Jm X_{k+1}),
    // lambda != 2 i omega k off the structural zeros (§10.4). Then SI: times `scale`.
    const int first = h.first_harmonic[k];
    Eigen::MatrixXcd X = h.vectors[k];
    if (normal.size()) {
      const Eigen::MatrixXcd Y = normal.cast<cd>() * h.vectors[k];
      const Eigen::MatrixXcd PT = Eigen::MatrixXcd::Identity(Y.rows(), Y.rows()) - normal.cast<cd>() * normal.transpose().cast<cd>();
      const Eigen::MatrixXcd J0 = full.mean.cast<cd>();
      const Eigen::MatrixXcd Jp = 0.5 * (full.cos2.cast<cd>() - i * full.sin2.cast<cd>());  // multiplies x_{k-1}
      const Eigen::MatrixXcd Jm = 0.5 * (full.cos2.cast<cd>() + i * full.sin2.cast<cd>());  // multiplies x_{k+1}
      X = Y;
      for (Eigen::Index c = 0; c < Y.cols(); ++c) {
        Eigen::VectorXcd rhs = J0 * Y.col(c);
        if (c > 0) rhs += Jp * Y.col(c - 1);
        if (c + 1 < Y.cols()) rhs += Jm * Y.col(c + 1);
        X.col(c) += PT * rhs / (lambda + i * (2.0 * w * double(first + int(c))));
      }
    }
    const Eigen::Index blocks = X.cols();
    // Pair g holds harmonic k_g = first - 1 + g: its w+ comes from column g - 1, its w- from column g.
    std::vector<LinePair> pairs(std::size_t(blocks + 1));
    double rotor_energy = 0, ball_energy = 0, common_norm = 0, common_sum = 0;
    for (Eigen::Index c = 0; c < blocks; ++c) {
      Eigen::VectorXcd v(d);
      for (Eigen::Index r = 0; r < d; ++r) v(r) = X(r, c) * scale(r);
      // Circular components (16.1.1) of each body's displacement, mass-weighted as (16.2.1): the
      // rotor (M_r) and each ball (m_i) at q + i l_i e^{i beta_i} dbeta_i, rotating frame.
      auto add = [&](double mass, cd x, cd y) {
        pairs[std::size_t(c) + 1].plus += mass * std::norm((x + i * y) / 2.0);
        pairs[std::size_t(c)].minus += mass * std::norm((std::conj(x) + i * std::conj(y)) / 2.0);
      };
      add(p.rotor.mass, v(0), v(1));
      rotor_energy += M * (std::norm(v(0)) + std::norm(v(1)));  // (16.3.1), summed over harmonics (Parseval)
      cd common{};
      double norm = 0;
      for (int b = 0; b < n; ++b) {
        const auto& ball = p.balls[std::size_t(b)];
        const double beta = double(e.position(2 + b));
        const cd db = v(2 + b);
        add(ball.mass, v(0) - ball.race_radius * std::sin(beta) * db, v(1) + ball.race_radius * std::cos(beta) * db);
        const double weight = std::sqrt(ball.inertia_factor * ball.mass) * ball.race_radius;
        ball_energy += weight * weight * std::norm(db);
        common += weight * weight * db;
        norm += weight * weight;
      }
      common_sum += std::norm(common);
      common_norm = norm;
    }
    const double energy = rotor_energy + ball_energy;
    m.rotor_share = energy > 0 ? rotor_energy / energy : 0;
    m.common_share = ball_energy > 0 ? common_sum / (common_norm * ball_energy) : 0;

    // The dominant line pair; a tie goes to the pair with the larger w+ line (so that an
    // isotropic mode takes lambda + i omega when f+ >= 1/2, as mode_views).
    double total = 0, plus_total = 0, forward = 0;
    std::size_t best = 0;
    for (std::size_t g = 0; g < pairs.size(); ++g) {
      const LinePair& q = pairs[g];
      const double f = lambda.imag() + w + 2.0 * w * double(first - 1 + int(g));
      total += q.plus + q.minus;
      plus_total += q.plus;
      forward += (f >= 0 ? q.plus : 0.0) + (f < 0 ? q.minus : 0.0);  // the line at a positive frequency
      const LinePair& b = pairs[best];
      if (q.plus + q.minus > b.plus + b.minus || (q.plus + q.minus == b.plus + b.minus && q.plus > b.plus)) best = g;
    }
    const int harmonic = first - 1 + int(best);
    const double f = lambda.imag() + w + 2.0 * w * double(harmonic);
    const double positive = f >= 0 ? pairs[best].plus : pairs[best].minus;
    const double negative = f >= 0 ? pairs[best].minus : pairs[best].plus;
    const double whirl = positive >= negative ? std::abs(f) : -std::abs(f);  // a tie counts forward (§16.2)
    m.fixed = {lambda.real(), whirl};
    m.fixed_minor = {lambda.real(), -whirl};
    m.whirl_frequency = whirl;
    m.plus_share = total > 0 ? plus_total / total : 0.5;
    m.forward_share = total > 0 ? forward / total : 1.0;
    const double modulus = std::abs(m.fixed);
    m.damping_ratio = modulus > 0 ? -m.fixed.real() / modulus : 0;
    m.has_log_decrement = whirl != 0;
    m.log_decrement = m.has_log_decrement ? -2 * std::numbers::pi * m.fixed.real() / std::abs(whirl) : 0;
    if (m.rotor_share >= 0.5)
      m.kind = whirl >= 0 ? ModeKind::rotor_forward : ModeKind::rotor_backward;
    else
      m.kind = m.common_share >= 0.5 ? ModeKind::ball : ModeKind::ball_relative;
    out.modes.push_back(m);
    out.harmonic.push_back(harmonic);
    out.line_share.push_back(total > 0 ? (pairs[best].plus + pairs[best].minus) / total : 0);
  }
  return out;
}

}  // namespace abu
