#include "abu/linear/modes.hpp"

#include <cmath>
#include <numbers>

namespace abu {

std::string_view to_string(ModeKind kind) {
  switch (kind) {
    case ModeKind::rotor_forward: return "rotor forward whirl";
    case ModeKind::rotor_backward: return "rotor backward whirl";
    case ModeKind::ball: return "ball mode";
    case ModeKind::ball_relative: return "ball relative mode";
    case ModeKind::set_direction: return "along the balanced set";
  }
  return "?";
}

namespace {

// The conjugate partner of eigenvalue k in the sorted spectrum: the refinement stores
// conjugate pairs exactly (spectrum.cpp), so an exact match is expected; the nearest is
// taken otherwise (tracked spectra).
template <int N>
int conjugate_of(const SpectrumT<N>& sp, int k) {
  const auto target = std::conj(sp.eigenvalues[std::size_t(k)]);
  int best = -1;
  double best_distance = 0;
  for (int j = 0; j < sp.count; ++j) {
    if (j == k || sp.structural[std::size_t(j)]) continue;
    const double d = std::abs(sp.eigenvalues[std::size_t(j)] - target);
    if (best < 0 || d < best_distance) best = j, best_distance = d;
  }
  return best;
}

// Circular components (16.1.1) of a planar displacement amplitude (x, y) of the rotating
// frame: w+ rides on exp((lambda + i omega) t), w- on exp((conj lambda + i omega) t).
struct Circular {
  double forward = 0, backward = 0;  // |w+|^2, |w-|^2
};
Circular circular(std::complex<double> x, std::complex<double> y) {
  const std::complex<double> i(0, 1);
  return {std::norm((x + i * y) / 2.0), std::norm((std::conj(x) + i * std::conj(y)) / 2.0)};
}

}  // namespace

template <int N>
std::vector<ModeView> mode_views(const ParamsT<double, N>& p, const Coordinates<long double, N>& position,
                                 const SpectrumT<N>& sp) {
  const std::complex<double> i(0, 1);
  const int n = ball_count(p);
  const double M = p.total_mass();
  std::vector<ModeView> modes;
  for (int k = 0; k < sp.count; ++k) {
    const auto lambda = sp.eigenvalues[std::size_t(k)];
    const bool structural = sp.structural[std::size_t(k)];
    if (!structural && lambda.imag() < 0) continue;  // the partner with Im > 0 represents the pair
    ModeView m;
    m.index = k;
    m.rotating = lambda;
    m.conjugate = (!structural && lambda.imag() > 0) ? conjugate_of(sp, k) : -1;
    const auto& v = sp.vectors[std::size_t(k)];

    // Mass-weighted circular components over the bodies (16.2.1): the rotor (M_r) and each
    // ball (m_i) at its absolute displacement q + i l_i e^{i beta_i} dbeta_i, rotating frame.
    Circular total{};
    const Circular rotor = circular(v(0), v(1));
    total.forward += p.rotor.mass * rotor.forward;
    total.backward += p.rotor.mass * rotor.backward;
    // Inertia measure (16.3.1): the diagonal of A (3.8), M |dq|^2 and j_i m_i l_i^2 |dbeta_i|^2.
    const double rotor_energy = M * (std::norm(v(0)) + std::norm(v(1)));
    double ball_energy = 0, common_norm = 0;
    std::complex<double> common{};
    for (int b = 0; b < n; ++b) {
      const auto& ball = p.balls[std::size_t(b)];
      const double beta = double(position(2 + b));
      const std::complex<double> db = v(2 + b);
      const Circular c = circular(v(0) - ball.race_radius * std::sin(beta) * db,
                                  v(1) + ball.race_radius * std::cos(beta) * db);
      total.forward += ball.mass * c.forward;
      total.backward += ball.mass * c.backward;
      const double weight = std::sqrt(ball.inertia_factor * ball.mass) * ball.race_radius;  // y_i = weight v_i
      ball_energy += weight * weight * std::norm(db);
      common += weight * weight * db;  // u . y with u_i = weight, y_i = weight v_i
      common_norm += weight * weight;
    }
    const double energy = rotor_energy + ball_energy;
    m.rotor_share = energy > 0 ? rotor_energy / energy : 0;
    m.common_share = ball_energy > 0 ? std::norm(common) / (common_norm * ball_energy) : 0;
    const double weighted = total.forward + total.backward;
    m.plus_share = weighted > 0 ? total.forward / weighted : 0.5;

    // (16.1.2), (16.1.3): the forward component's fixed-frame eigenvalue is lambda + i omega, the
    // backward one's conj(lambda) + i omega. A tie (a real eigenvalue, where both are the
    // same, or a pure ball oscillation) is resolved toward forward.
    const std::complex<double> plus = lambda + i * p.omega, minus = std::conj(lambda) + i * p.omega;
    const bool forward_dominant = m.plus_share >= 0.5;
    m.fixed = forward_dominant ? plus : minus;
    m.fixed_minor = forward_dominant ? minus : plus;
    if (structural) m.fixed = m.fixed_minor = i * p.omega;  // exactly 0 in the rotating frame
    m.whirl_frequency = m.fixed.imag();
    // The share of the motion whirling forward: w+ always (Omega+ > 0), w- when Omega- > 0.
    m.forward_share = weighted > 0 ? (total.forward + (minus.imag() > 0 ? total.backward : 0.0)) / weighted : 1.0;
    const double modulus = std::abs(m.fixed);
    m.damping_ratio = modulus > 0 ? -m.fixed.real() / modulus : 0;
    m.has_log_decrement = m.whirl_frequency != 0;
    m.log_decrement = m.has_log_decrement ? -2 * std::numbers::pi * m.fixed.real() / std::abs(m.whirl_frequency) : 0;

    if (structural) {
      m.kind = ModeKind::set_direction;
    } else if (m.rotor_share >= 0.5) {
      m.kind = m.whirl_frequency >= 0 ? ModeKind::rotor_forward : ModeKind::rotor_backward;
    } else {
      m.kind = m.common_share >= 0.5 ? ModeKind::ball : ModeKind::ball_relative;
    }
    modes.push_back(m);
  }
  return modes;
}

std::vector<int> mode_of_eigenvalue(const std::vector<ModeView>& modes, int count) {
  std::vector<int> of(std::size_t(count), -1);
  for (std::size_t m = 0; m < modes.size(); ++m) {
    of[std::size_t(modes[m].index)] = int(m);
    if (modes[m].conjugate >= 0) of[std::size_t(modes[m].conjugate)] = int(m);
  }
  return of;
}

template <int N>
double natural_frequency(const ParamsT<double, N>& p) {
  return std::sqrt(p.rotor.stiffness / p.total_mass());
}

template <int N>
double ball_capacity_of(const ParamsT<double, N>& p) {
  double a = 0;
  for (const auto& b : p.balls) a += b.mass * b.race_radius;
  return a;
}

template <int N>
double unbalanced_amplitude(const ParamsT<double, N>& p, double mass) {
  const double w = p.omega;
  return p.rotor.unbalance * w * w / std::abs(std::complex<double>(p.rotor.stiffness - mass * w * w, p.rotor.damping * w));
}

template std::vector<ModeView> mode_views<2>(const ParamsT<double, 2>&, const Coordinates<long double, 2>&,
                                             const SpectrumT<2>&);
template std::vector<ModeView> mode_views<any_balls>(const ParamsT<double, any_balls>&,
                                                     const Coordinates<long double, any_balls>&,
                                                     const SpectrumT<any_balls>&);
template double natural_frequency<2>(const ParamsT<double, 2>&);
template double natural_frequency<any_balls>(const ParamsT<double, any_balls>&);
template double ball_capacity_of<2>(const ParamsT<double, 2>&);
template double ball_capacity_of<any_balls>(const ParamsT<double, any_balls>&);
template double unbalanced_amplitude<2>(const ParamsT<double, 2>&, double);
template double unbalanced_amplitude<any_balls>(const ParamsT<double, any_balls>&, double);

}  // namespace abu
